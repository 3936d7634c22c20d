// The element pass's two paths (element_pass.hpp): the SIMD path gives the scalar
// reference's bits on every instruction set this CPU has, for any element count (partial last
// blocks), shared nodes (the sums' order), stiffness-proportional damping, and exact and negative
// zeros (the sign of zero is part of the bits); and both give beam_force()'s forces element by
// element. The second-order chord forces likewise (geometry.hpp). Then whole runs: the same states
// step after step.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "ntn/element_pass.hpp"
#include "ntn/geometry.hpp"
#include "ntn/integrator.hpp"
#include "support/every_target.hpp"
#include "support/frames.hpp"
#include "support/init_model.hpp"
#include "support/signed_order.hpp"

#if defined(NTN_SIMD)
#include <hwy/highway.h>
#include <hwy/targets.h>
#endif

namespace element_pass_test {

using ntn::BeamBlock;
using ntn::BeamData;
using ntn::BeamRotations;

// A random element set, in runs of 1 to 9 elements of one kind so that blocks come uniform, with
// lanes of different AxisMaps and with aligned and general lanes mixed: rotations either random
// entries with exact zeros and -0.0 mixed in (general: the full products), or one of the 48
// signed orders of the axes, zeros of either sign (aligned: picks, beam.hpp); stiffness across
// orders of magnitude, nodes drawn from a few so that elements share them.
struct Elements {
  std::vector<BeamData> beams;
  std::vector<BeamBlock> blocks;
  std::vector<BeamRotations> rotations;
  std::vector<ntn::BeamStiffnessBlock> stiffness;
  std::vector<double> u, v;

  ntn::BeamArrays arrays() const { return {blocks.data(), rotations.data(), stiffness.data()}; }
  void set(std::size_t k) {
    ntn::set_lane(blocks.data(), rotations.data(), stiffness.data(), k / ntn::kBeamLanes,
                  k % ntn::kBeamLanes, beams[k]);
  }
};

double pick(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> x(-1.0, 1.0);
  switch (rng() % 8) {
    case 0:
      return 0.0;
    case 1:
      return -0.0;
    case 2:
      return 1.0;
    default:
      return x(rng);
  }
}

Elements random_elements(std::size_t count, int nodes, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mag(3.0, 9.0);
  Elements e;
  std::size_t run = 0;
  std::uint64_t kind = 0;  // 48: general, else a signed order
  for (std::size_t k = 0; k < count; ++k) {
    if (run == 0) run = 1 + rng() % 9, kind = rng() % 3 == 0 ? 48 : rng() % 48;
    --run;
    BeamData b;
    b.node_i = static_cast<std::int32_t>(rng() % static_cast<std::uint64_t>(nodes));
    do {
      b.node_j = static_cast<std::int32_t>(rng() % static_cast<std::uint64_t>(nodes));
    } while (b.node_j == b.node_i);
    if (kind == 48) {
      for (double& r : b.rotation)
        r = pick(rng);
    } else {
      b.rotation = ntn_test::signed_order(static_cast<std::size_t>(kind),
                                          [&](std::size_t) { return rng() % 2 == 0 ? 0.0 : -0.0; });
    }
    b.axes = ntn::axis_map(b.rotation);
    auto stiff = [&] { return std::pow(10.0, mag(rng)); };
    b.k.axial = stiff(), b.k.torsion = stiff();
    for (std::size_t c = 0; c < 4; ++c)
      b.k.xy[c] = stiff(), b.k.xz[c] = stiff();
    e.beams.push_back(b);
  }
  e.blocks.resize(ntn::beam_blocks(count));
  e.rotations.resize(ntn::beam_blocks(count));
  e.stiffness.resize(ntn::beam_blocks(count));
  for (std::size_t k = 0; k < count; ++k)
    e.set(k);
  const auto dofs = static_cast<std::size_t>(ntn::kDofsPerNode * nodes);
  e.u.resize(dofs), e.v.resize(dofs);
  for (std::size_t j = 0; j < dofs; ++j)
    e.u[j] = 1e-3 * pick(rng), e.v[j] = pick(rng);
  return e;
}

// f starts at `f0`: the pass adds to it (the kernel's starts at +0.0, which turns every -0.0 sum
// into +0.0; -0.0 keeps the signs visible).
std::vector<double> forces(const Elements& e, ntn::ElementPass path, double beta, double f0 = 0.0) {
  std::vector<double> f(e.u.size(), f0);
  ntn::element_forces(path, e.arrays(), e.beams.size(), e.u.data(), e.v.data(), beta, f.data());
  return f;
}

// The multi-core pass (element_forces_split) over every block with random `direct` masks: f
// after it (from f0) and the stored end forces (from a sentinel), one after the other.
std::vector<double> split_forces(const Elements& e, ntn::ElementPass path, double beta,
                                 const std::vector<std::uint8_t>& direct) {
  std::vector<double> out(e.u.size(), 0.5);
  out.resize(e.u.size() + 12 * ntn::kBeamLanes * e.blocks.size(), 7.0);
  ntn::element_forces_split(path, e.arrays(), 0, e.blocks.size(), direct.data(), e.u.data(),
                            e.v.data(), beta, out.data(), out.data() + e.u.size());
  return out;
}

// beam_force() on the BeamData themselves, element by element (the kernel's pass before blocks).
std::vector<double> reference(const Elements& e, double beta) {
  std::vector<double> f(e.u.size(), 0.0);
  for (const BeamData& b : e.beams) {
    const auto i = static_cast<std::size_t>(6 * b.node_i),
               j = static_cast<std::size_t>(6 * b.node_j);
    double ui[6], uj[6], fi[6], fj[6];
    for (std::size_t d = 0; d < 6; ++d) {
      ui[d] = beta != 0.0 ? e.u[i + d] + beta * e.v[i + d] : e.u[i + d];
      uj[d] = beta != 0.0 ? e.u[j + d] + beta * e.v[j + d] : e.u[j + d];
    }
    ntn::beam_force(b, ui, uj, fi, fj);
    for (std::size_t d = 0; d < 6; ++d)
      f[i + d] += fi[d], f[j + d] += fj[d];
  }
  return f;
}

// Bit for bit, the sign of zero included (== would call -0.0 and 0.0 equal).
::testing::AssertionResult same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  for (std::size_t j = 0; j < a.size(); ++j) {
    if (std::bit_cast<std::uint64_t>(a[j]) != std::bit_cast<std::uint64_t>(b[j])) {
      return ::testing::AssertionFailure() << "DOF " << j << ": " << a[j] << " vs " << b[j];
    }
  }
  return ::testing::AssertionSuccess();
}

constexpr std::size_t kCounts[] = {1, 2, 3, 4, 5, 7, 8, 9, 63, 64, 65, 400};

TEST(ElementPass, ScalarPathIsBeamForceInOrder) {
  for (const std::size_t n : kCounts) {
    const Elements e = random_elements(n, 6, 100 + n);
    for (const double beta : {0.0, 2e-3}) {
      EXPECT_TRUE(same_bits(forces(e, ntn::ElementPass::kScalar, beta), reference(e, beta)))
          << n << " elements, beta " << beta;
    }
  }
}

// `count` elements on their own nodes (2k, 2k + 1), displacements -0.0, rotations with -0.0 off
// the diagonal (a product with +-0 keeps a sign): even elements the identity (aligned: picks, one
// negated axis), odd ones a rotation about y (general: products).
Elements own_node_zeros(std::size_t count) {
  Elements e = random_elements(count, static_cast<int>(2 * count), 7);
  for (std::size_t k = 0; k < e.beams.size(); ++k) {
    e.beams[k].node_i = static_cast<std::int32_t>(2 * k);
    e.beams[k].node_j = static_cast<std::int32_t>(2 * k + 1);
    e.beams[k].rotation =
        k % 2 == 0 ? std::array<double, 9>{1.0, -0.0, -0.0, -0.0, -1.0, -0.0, -0.0, -0.0, -1.0}
                   : std::array<double, 9>{0.6, -0.0, -0.8, -0.0, 1.0, -0.0, 0.8, -0.0, 0.6};
    e.set(k);
  }
  for (double& x : e.u)
    x = -0.0;
  return e;
}

TEST(ElementPass, ZerosKeepTheirSign) {
  // Displacements +-0 and forces summed onto -0.0: every product is +-0, and each sum's sign
  // depends on the operations and their order.
  // Five elements on their own nodes, displacements -0.0, rotations with -0.0 off the diagonal
  // (a product with +-0 keeps a sign): elements 0, 2, 4 the identity (aligned: picks, one
  // negated axis), 1 and 3 a rotation about y (general: products), so one block of each kind.
  Elements e = own_node_zeros(5);
  for (std::size_t k = 0; k < e.beams.size(); ++k) {
    ASSERT_EQ(e.blocks[k / ntn::kBeamLanes].axes[k % ntn::kBeamLanes] != ntn::kGeneralAxes,
              k % 2 == 0);
  }
  const std::vector<double> f = forces(e, ntn::ElementPass::kScalar, 0.0, -0.0);
  int negative = 0, positive = 0;
  for (double x : f)
    (std::signbit(x) ? negative : positive) += 1;
  ASSERT_GT(negative, 0) << "the case must have both signs of zero to mean anything";
  ASSERT_GT(positive, 0);
  EXPECT_TRUE(same_bits(forces(e, ntn::ElementPass::kSimd, 0.0, -0.0), f));
}

// Elements of `types` stiffness kinds in runs (members of a few sections meshed in place): the
// random set of random_elements with each element's stiffness replaced by its kind's.
Elements typed_elements(std::size_t count, std::size_t types, std::uint64_t seed) {
  Elements e = random_elements(count, 40, seed);
  const Elements kinds = random_elements(types, 40, seed + 1);
  std::mt19937_64 rng(seed);
  std::size_t kind = 0;
  for (std::size_t k = 0; k < count; ++k) {
    if (k % 4 == 0 && rng() % 3 == 0) kind = rng() % types;  // mostly whole blocks of one kind
    e.beams[k].k = kinds.beams[kind].k;
    e.set(k);
  }
  return e;
}

// dedupe_stiffness moves where a block reads its stiffness, never what it reads: every element's
// data (lane()) and the forces of both paths keep their bits, the table keeps only distinct
// entries, and a frame of a few kinds shares them.
TEST(ElementPass, SharedStiffnessKeepsTheBits) {
  for (const std::size_t types : {std::size_t{1}, std::size_t{3}, std::size_t{200}}) {
    const Elements before = typed_elements(401, types, 50 + types);
    Elements after = before;
    const std::size_t distinct =
        ntn::dedupe_stiffness(after.blocks.data(), after.stiffness.data(), after.blocks.size());
    for (std::size_t k = 0; k < before.beams.size(); ++k) {
      const BeamData a = ntn::lane(before.arrays(), k / ntn::kBeamLanes, k % ntn::kBeamLanes);
      const BeamData b = ntn::lane(after.arrays(), k / ntn::kBeamLanes, k % ntn::kBeamLanes);
      ASSERT_EQ(std::memcmp(&a.k, &b.k, sizeof a.k), 0) << types << " kinds, element " << k;
    }
    for (const ntn::ElementPass path : {ntn::ElementPass::kScalar, ntn::ElementPass::kSimd}) {
      EXPECT_TRUE(same_bits(forces(after, path, 2e-3), forces(before, path, 2e-3)))
          << types << " kinds";
    }
    for (std::size_t i = 0; i < distinct; ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        EXPECT_NE(
            std::memcmp(&after.stiffness[i], &after.stiffness[j], sizeof(ntn::BeamStiffnessBlock)),
            0)
            << types << " kinds: entries " << j << " and " << i;
      }
    }
    // Fewer distinct blocks than the window: every repeat is shared, so the table holds exactly
    // the distinct blocks (counted here pair by pair).
    std::size_t unique = 0;
    for (std::size_t i = 0; i < before.blocks.size(); ++i) {
      bool repeat = false;
      for (std::size_t j = 0; j < i && !repeat; ++j) {
        repeat = std::memcmp(&before.stiffness[i], &before.stiffness[j],
                             sizeof(ntn::BeamStiffnessBlock)) == 0;
      }
      unique += repeat ? 0 : 1;
    }
    ASSERT_LE(unique, ntn::kShareWindow);
    EXPECT_EQ(distinct, unique) << types << " kinds";
    // One kind: the whole blocks and the last one (one element, three empty lanes); three: at
    // most one entry per kind and the last block; 200 in runs: more than that.
    const std::size_t least = types == 200 ? 5 : 2, most = types == 1 ? 2 : types == 3 ? 4 : 64;
    EXPECT_GE(distinct, least) << types << " kinds";
    EXPECT_LE(distinct, most) << types << " kinds";
  }
}

// An entry repeated after more than kShareWindow distinct ones is kept, not shared (the
// bounded search), and its block still reads its own bits.
TEST(ElementPass, SharedStiffnessSearchIsBounded) {
  const std::size_t w = ntn::kShareWindow;
  Elements e = random_elements(4 * (w + 3), 40, 9);  // w + 3 blocks, all different
  for (std::size_t l = 0; l < ntn::kBeamLanes; ++l) {
    e.beams[4 * (w + 1) + l].k = e.beams[l].k;          // block w + 1 repeats block 0: too far back
    e.beams[4 * (w + 2) + l].k = e.beams[4 * w + l].k;  // block w + 2 repeats block w
    e.set(4 * (w + 1) + l), e.set(4 * (w + 2) + l);
  }
  const Elements before = e;
  EXPECT_EQ(ntn::dedupe_stiffness(e.blocks.data(), e.stiffness.data(), e.blocks.size()), w + 2);
  EXPECT_EQ(e.blocks[w + 1].stiffness, static_cast<std::int32_t>(w + 1));
  EXPECT_EQ(e.blocks[w + 2].stiffness, static_cast<std::int32_t>(w));
  EXPECT_TRUE(same_bits(forces(e, ntn::ElementPass::kSimd, 0.0),
                        forces(before, ntn::ElementPass::kSimd, 0.0)));
}

// mark_first_ends: every node with an element end has exactly one first bit, on its earliest end
// in the model's order; a node with none leaves `every` false.
TEST(ElementPass, FirstEndsAreEachNodesEarliest) {
  for (const std::size_t n : kCounts) {
    Elements e = random_elements(n, 12, 300 + n);
    std::vector<std::uint8_t> touched(12);
    const bool every = ntn::mark_first_ends(e.blocks.data(), n, 12, touched.data());
    std::vector<int> firsts(12, 0);
    std::vector<bool> seen(12, false);
    for (std::size_t k = 0; k < n; ++k) {
      const int nodes[2] = {e.beams[k].node_i, e.beams[k].node_j};
      for (std::size_t end = 0; end < 2; ++end) {
        const auto node = static_cast<std::size_t>(nodes[end]);
        const bool first =
            ntn::direct_end(e.blocks[k / ntn::kBeamLanes].first, k % ntn::kBeamLanes, end);
        EXPECT_EQ(first, !seen[node]) << n << " elements: element " << k << ", end " << end;
        firsts[node] += first ? 1 : 0;
        seen[node] = true;
      }
    }
    bool all = true;
    for (std::size_t node = 0; node < 12; ++node) {
      EXPECT_EQ(firsts[node], seen[node] ? 1 : 0) << node;
      all = all && seen[node];
    }
    EXPECT_EQ(every, all) << n << " elements";
  }
}

#if defined(NTN_SIMD)

using ntn_test::EveryTarget;

TEST_F(EveryTarget, SimdPathGivesTheScalarBits) {
  // The sets hold the three kinds of block the SIMD pass tells apart: all lanes general, all one
  // AxisMap, and lanes that differ (maps, or aligned and general).
  int general = 0, uniform = 0, mixed = 0;
  for (const BeamBlock& blk : random_elements(400, 40, 400).blocks) {
    bool same = true;
    for (const ntn::AxisMap m : blk.axes)
      same = same && m == blk.axes[0];
    (!same ? mixed : blk.axes[0] == ntn::kGeneralAxes ? general : uniform) += 1;
  }
  ASSERT_GT(general, 0);
  ASSERT_GT(uniform, 0);
  ASSERT_GT(mixed, 0);
  each_target([&](std::int64_t t) {
    for (const std::size_t n : kCounts) {
      const Elements e = random_elements(n, n < 8 ? 3 : 40, n);
      for (const double beta : {0.0, 2e-3}) {
        EXPECT_TRUE(same_bits(forces(e, ntn::ElementPass::kSimd, beta),
                              forces(e, ntn::ElementPass::kScalar, beta)))
            << hwy::TargetName(t) << ", " << n << " elements, beta " << beta;
      }
    }
  });
}

// The multi-core pass: each end added or stored as its bit says, the scalar bits on every target;
// with every bit set it is the single-core pass (on whole blocks).
TEST_F(EveryTarget, SplitPassGivesTheScalarBits) {
  each_target([&](std::int64_t t) {
    for (const std::size_t n : {std::size_t{4}, std::size_t{8}, std::size_t{64}}) {
      const Elements e = random_elements(n, 40, 100 + n);
      std::mt19937_64 rng(n);
      std::vector<std::uint8_t> direct(e.blocks.size());
      for (std::uint8_t& d : direct)
        d = static_cast<std::uint8_t>(rng() % 4 == 0 ? 0xFF : rng() & 0xFF);
      for (const double beta : {0.0, 2e-3}) {
        EXPECT_TRUE(same_bits(split_forces(e, ntn::ElementPass::kSimd, beta, direct),
                              split_forces(e, ntn::ElementPass::kScalar, beta, direct)))
            << hwy::TargetName(t) << ", " << n << " elements, beta " << beta;
        const std::vector<std::uint8_t> all(e.blocks.size(), 0xFF);
        std::vector<double> f = split_forces(e, ntn::ElementPass::kSimd, beta, all);
        f.resize(e.u.size());
        EXPECT_TRUE(same_bits(f, forces(e, ntn::ElementPass::kScalar, beta, 0.5)))
            << hwy::TargetName(t) << ", " << n << " elements, beta " << beta;
      }
    }
  });
}

// Each of the 48 signed orders of the axes as whole blocks of one AxisMap, zeros of both signs in
// the rotations and the displacements: the uniform picks (the 24 right-handed orders each by code
// of its own, element_pass.cpp; the 24 left-handed by the lane-by-lane picks) give the scalar bits
// on every target, in the single-core pass (adds, and first writes) and the multi-core one.
TEST_F(EveryTarget, EachSignedOrderGivesTheScalarBits) {
  int right_handed = 0;
  each_target([&](std::int64_t t) {
    for (std::size_t which = 0; which < 48; ++which) {
      Elements e = random_elements(8, 5, 900 + which);
      for (std::size_t k = 0; k < e.beams.size(); ++k) {
        e.beams[k].rotation = ntn_test::signed_order(
            which, [&](std::size_t c) { return (c + k) % 3 == 0 ? -0.0 : 0.0; });
        e.beams[k].axes = ntn::axis_map(e.beams[k].rotation);
        e.set(k);
      }
      for (const BeamBlock& blk : e.blocks)
        ASSERT_EQ(std::count(blk.axes.begin(), blk.axes.end(), blk.axes[0]), 4) << which;
      right_handed += ntn::right_handed(e.blocks[0].axes[0]) ? 1 : 0;
      for (std::size_t j = 0; j < e.u.size(); j += 4)
        e.u[j] = j % 8 == 0 ? -0.0 : 0.0, e.v[j] = -0.0;
      std::vector<std::uint8_t> touched(5);
      const bool every = ntn::mark_first_ends(e.blocks.data(), 8, 5, touched.data());
      const std::vector<std::uint8_t> direct = {0x5A, 0xFF};
      const auto where = [&](double beta) {
        return ::testing::Message()
               << hwy::TargetName(t) << ", signed order " << which << ", beta " << beta;
      };
      for (const double beta : {0.0, 2e-3}) {
        for (const double f0 : {0.0, -0.0}) {
          EXPECT_TRUE(same_bits(forces(e, ntn::ElementPass::kSimd, beta, f0),
                                forces(e, ntn::ElementPass::kScalar, beta, f0)))
              << where(beta) << ", F from " << f0;
        }
        std::vector<double> simd(e.u.size(), std::numeric_limits<double>::quiet_NaN());
        std::vector<double> scalar(e.u.size(), 1.0);
        ntn::element_forces_into(ntn::ElementPass::kSimd, e.arrays(), 8, every, e.u.size(),
                                 e.u.data(), e.v.data(), beta, simd.data());
        ntn::element_forces_into(ntn::ElementPass::kScalar, e.arrays(), 8, every, e.u.size(),
                                 e.u.data(), e.v.data(), beta, scalar.data());
        EXPECT_TRUE(same_bits(simd, scalar)) << where(beta) << ", first writes";
        EXPECT_TRUE(same_bits(split_forces(e, ntn::ElementPass::kSimd, beta, direct),
                              split_forces(e, ntn::ElementPass::kScalar, beta, direct)))
            << where(beta) << ", split";
      }
    }
  });
  EXPECT_EQ(right_handed % 24, 0);  // 24 per target
  EXPECT_GT(right_handed, 0);
}

// F = the forces (element_forces_into): the SIMD path's first writes, from an F of NaNs that no
// DOF may keep, give the bits of the scalar path's zeroed F plus adds, with displacements of
// -0.0 too (forces of -0.0: a first write stores 0.0 + f, +0.0, as the zeroed F does); where a
// node has no element (every_node false) F is zeroed first.
TEST_F(EveryTarget, ForcesIntoGiveTheScalarBits) {
  int with_every = 0, without = 0;
  each_target([&](std::int64_t t) {
    for (const std::size_t n : kCounts) {
      Elements e = random_elements(n, n < 8 ? 3 : 12, 500 + n);
      std::vector<std::uint8_t> touched(e.u.size() / 6);
      const bool every = ntn::mark_first_ends(e.blocks.data(), n, touched.size(), touched.data());
      (every ? with_every : without) += 1;
      if (n % 2 == 1) {
        for (std::size_t j = 0; j < e.u.size(); ++j)
          e.u[j] = -0.0, e.v[j] = -0.0;
      }
      for (const double beta : {0.0, 2e-3}) {
        std::vector<double> simd(e.u.size(), std::numeric_limits<double>::quiet_NaN());
        std::vector<double> scalar(e.u.size(), 1.0);
        ntn::element_forces_into(ntn::ElementPass::kSimd, e.arrays(), n, every, e.u.size(),
                                 e.u.data(), e.v.data(), beta, simd.data());
        ntn::element_forces_into(ntn::ElementPass::kScalar, e.arrays(), n, every, e.u.size(),
                                 e.u.data(), e.v.data(), beta, scalar.data());
        EXPECT_TRUE(same_bits(simd, scalar))
            << hwy::TargetName(t) << ", " << n << " elements, beta " << beta
            << (every ? "" : ", a node without elements");
        EXPECT_TRUE(same_bits(scalar, forces(e, ntn::ElementPass::kScalar, beta)));
      }
    }
  });
  EXPECT_GT(with_every, 0);
  EXPECT_GT(without, 0);
  // Every node met once, its forces +-0: each DOF is one first write, 0.0 + f = +0.0.
  each_target([&](std::int64_t t) {
    for (const std::size_t n : {std::size_t{5}, std::size_t{8}}) {
      Elements e = own_node_zeros(n);
      std::vector<std::uint8_t> touched(2 * n);
      ASSERT_TRUE(ntn::mark_first_ends(e.blocks.data(), n, 2 * n, touched.data()));
      ASSERT_GT(std::count_if(e.u.begin(), e.u.end(), [](double x) { return std::signbit(x); }), 0);
      std::vector<double> simd(e.u.size(), std::numeric_limits<double>::quiet_NaN());
      std::vector<double> scalar(e.u.size(), 1.0);
      ntn::element_forces_into(ntn::ElementPass::kSimd, e.arrays(), n, true, e.u.size(), e.u.data(),
                               e.v.data(), 0.0, simd.data());
      ntn::element_forces_into(ntn::ElementPass::kScalar, e.arrays(), n, true, e.u.size(),
                               e.u.data(), e.v.data(), 0.0, scalar.data());
      EXPECT_TRUE(same_bits(simd, scalar)) << hwy::TargetName(t) << ", " << n << " elements";
      // The forces themselves have -0.0 (so the case means something).
      const std::vector<double> raw = forces(e, ntn::ElementPass::kScalar, 0.0, -0.0);
      EXPECT_GT(std::count_if(raw.begin(), raw.end(), [](double x) { return std::signbit(x); }), 0);
    }
  });
}

// The second-order chord forces (geometry.hpp) of random elements: the lanes of the SIMD pass
// (uniform, general and mixed blocks, partial last blocks, in element order or another) give
// geometric_forces' bits and count,
// from an F of +0.0, -0.0 (the rotational DOFs' -0.0 untouched) or random values, with
// displacements of -0.0 and a NaN at node 0 (the padded lanes read it, and count nothing). A NaN's
// sign is the compiler's, not the source's (it may swap a product's operands: the scalar reference
// built for SSE4 differs from the test's own there), so NaNs compare as NaN, all else by its bits.
struct Chords {
  std::vector<ntn::GeometricElement> elements;
  std::vector<ntn::GeometricBlock> blocks;
  std::vector<BeamRotations> rotations;
  std::vector<double> u;
};

Chords random_chords(std::size_t count, int nodes, std::uint64_t seed) {
  const Elements e = random_elements(count, nodes, seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mag(5.0, 10.0);
  Chords c;
  for (std::size_t k = 0; k < count; ++k) {
    const BeamData& b = e.beams[k];
    ntn::GeometricElement g;
    g.dof_i = ntn::kDofsPerNode * b.node_i, g.dof_j = ntn::kDofsPerNode * b.node_j;
    g.element = static_cast<std::int32_t>(k);
    g.rotation = b.rotation, g.axes = b.axes;
    g.axial = std::pow(10.0, mag(rng));
    g.inv_length = 1.0 / (0.5 + static_cast<double>(rng() % 8));
    g.limit = rng() % 4 == 0 ? 0.0 : 1e-2 * g.axial;  // some past it
    c.elements.push_back(g);
  }
  // The blocks in another order than the elements (the model's, in a model): here a random one.
  std::vector<std::int32_t> order(count);
  for (std::size_t k = 0; k < count; ++k)
    order[k] = static_cast<std::int32_t>(k);
  std::shuffle(order.begin(), order.end(), rng);
  if (seed % 2 == 0) std::sort(order.begin(), order.end());
  c.blocks.resize(ntn::beam_blocks(count));
  c.rotations.resize(ntn::beam_blocks(count));
  ntn::fill_geometric_blocks(c.elements.data(), count, order, c.blocks.data(), c.rotations.data());
  c.u = e.u;
  return c;
}

::testing::AssertionResult same_bits_or_nan(const std::vector<double>& a,
                                            const std::vector<double>& b) {
  for (std::size_t j = 0; j < a.size(); ++j) {
    if (std::isnan(a[j]) && std::isnan(b[j])) continue;
    if (std::bit_cast<std::uint64_t>(a[j]) != std::bit_cast<std::uint64_t>(b[j])) {
      return ::testing::AssertionFailure() << "DOF " << j << ": " << a[j] << " vs " << b[j];
    }
  }
  return ::testing::AssertionSuccess();
}

struct ChordForces {
  std::vector<double> f;
  std::size_t over = 0;
};

ChordForces chord_forces(const Chords& c, ntn::ElementPass path, const std::vector<double>& f0) {
  ChordForces out{f0, 0};
  std::vector<double> rows(4 * c.elements.size());
  out.over = ntn::geometric_forces(path, {c.blocks.data(), c.rotations.data()}, c.elements.data(),
                                   c.elements.size(), c.u.data(), out.f.data(), rows.data());
  return out;
}

TEST_F(EveryTarget, GeometricPassGivesTheScalarBits) {
  int general = 0, uniform = 0, mixed = 0, past = 0;
  each_target([&](std::int64_t t) {
    for (const std::size_t n : kCounts) {
      Chords c = random_chords(n, n < 8 ? 3 : 40, 700 + n);
      for (const ntn::GeometricBlock& blk : c.blocks) {
        const bool same = std::count(blk.axes.begin(), blk.axes.end(), blk.axes[0]) == 4;
        (!same ? mixed : blk.axes[0] == ntn::kGeneralAxes ? general : uniform) += 1;
      }
      std::mt19937_64 rng(n);
      std::vector<double> noise(c.u.size());
      for (double& x : noise)
        x = pick(rng);
      for (int variant = 0; variant < 3; ++variant) {
        if (variant == 1) {
          for (std::size_t j = 0; j < c.u.size(); j += 3)
            c.u[j] = -0.0;
        }
        if (variant == 2) c.u[1] = std::numeric_limits<double>::quiet_NaN();
        for (const std::vector<double>& f0 :
             {std::vector<double>(c.u.size(), 0.0), std::vector<double>(c.u.size(), -0.0), noise}) {
          const ChordForces simd = chord_forces(c, ntn::ElementPass::kSimd, f0);
          const ChordForces scalar = chord_forces(c, ntn::ElementPass::kScalar, f0);
          EXPECT_TRUE(same_bits_or_nan(simd.f, scalar.f))
              << hwy::TargetName(t) << ", " << n << " elements, variant " << variant;
          if (variant < 2) {
            EXPECT_TRUE(same_bits(simd.f, scalar.f));
          }
          EXPECT_EQ(simd.over, scalar.over)
              << hwy::TargetName(t) << ", " << n << " elements, variant " << variant;
          past += scalar.over > 0 ? 1 : 0;
        }
      }
    }
  });
  EXPECT_GT(general, 0);
  EXPECT_GT(uniform, 0);
  EXPECT_GT(mixed, 0);
  EXPECT_GT(past, 0);
}

TEST(ElementPass, DispatchTakesAVectorSetWhereTheCpuHasOne) {
  const std::string name = ntn::element_pass_target();
  RecordProperty("element_pass", name);
#if HWY_ARCH_X86_64
  // x86-64 has SSE2 at least: Highway's 128-bit or wider sets, never the scalar fallback
  EXPECT_NE(name, "SCALAR");
  EXPECT_NE(name, "EMU128");
#endif
}

#endif  // NTN_SIMD

// The feature frame (every load and channel kind) with Rayleigh damping beta K: runs by the two
// paths have the same states at every step.
TEST(ElementPass, RunsHaveTheSameStatesStepByStep) {
  constexpr auto S = ntn_test::kFeatureSizes;
  static ntn_test::Sim<S> a, b;
  for (const double beta : {0.0, 1e-4}) {
    ASSERT_TRUE(ntn_test::feature_frame(a.spec));
    a.spec.settings.beta = beta;
    a.spec.settings.dt = 0.5 * ntn::stable_time_step(ntn::view(a.spec)).dt_stable;
    ASSERT_TRUE(ntn_test::init_model(a.spec, a.model).ok());
    ASSERT_TRUE(ntn_test::init_model(a.spec, b.model).ok());
    a.model.element_pass = ntn::ElementPass::kSimd;
    b.model.element_pass = ntn::ElementPass::kScalar;
    ntn::initial_state(a.model, a.state), ntn::initial_state(b.model, b.state);
    std::array<double, S.inputs> in{};
    (void)ntn::start(a.model, a.state, a.scratch, in);
    (void)ntn::start(b.model, b.state, b.scratch, in);
    for (long n = 0; n < 3000; ++n) {
      for (std::size_t c = 0; c < S.inputs; ++c)
        in[c] = ntn_test::input_sample(static_cast<int>(c), n);
      (void)ntn::step(a.model, a.state, a.scratch, in);
      (void)ntn::step(b.model, b.state, b.scratch, in);
      ASSERT_EQ(std::memcmp(a.state.u.data(), b.state.u.data(), sizeof(a.state.u)), 0)
          << "step " << n << ", beta " << beta;
      ASSERT_EQ(std::memcmp(a.state.v.data(), b.state.v.data(), sizeof(a.state.v)), 0);
    }
  }
}

}  // namespace element_pass_test
