// ntn_paper.hpp alone (seed S 17-37): its three passes on hand-made hinges and node vectors,
// without a model or a step. What each must do:
// - paper_masses (S 22-26): in a rigid direction both nodes get the sum of their hinge-frame
//   masses, a free direction keeps each node's own; with the hinge frame aligned with the global
//   axes the round trip is products by 1 and 0, so the sums are exact (compared bit for bit);
//   turned, the result is the diagonal of T^T diag(l) T with l the diagonal of T diag(m) T^T,
//   summed in the rigid rows (computed here from the definition, to 1e-15 relative: a few
//   roundings of sums of three products);
// - paper_forces (S 17-21): the same sums for the forces, so that with both the two nodes of a
//   rigid direction get the same acceleration, bit for bit in the aligned case;
// - paper_after_update (S 27-37): a hinge to a supported node copies the supported node's rigid
//   components (S 30-31); a curve direction past its rigid branch is scaled back onto it (S 33,
//   d lands on the limit to 1e-15 relative); v and a of a changed DOF follow as du / dt and
//   du / dt^2 (S 35-37, to rounding: 1e-15 relative); an unchanged DOF keeps its bits.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>

#include "ntn/ntn_paper.hpp"
#include "support/hinges.hpp"

namespace ntn_paper_test {

using ntn_test::Mat3;

// A hinge between nodes 0 and 1, rigid in ux, uy, uz, rx and free in ry, rz (a pinned beam end).
ntn::HingeData pinned(const Mat3& frame) {
  ntn::HingeData h;
  h.node1 = 0, h.node2 = 1;
  h.frame = frame;
  h.rigid = 0x0f;
  for (std::size_t k = 0; k < 6; ++k)
    h.branch_lower[k] = -1e300, h.branch_upper[k] = 1e300;
  return h;
}

// Node 0's and node 1's masses (or forces), different in every DOF.
constexpr std::array<double, 12> kMass{2.0, 3.0,  5.0,  0.7, 1.1, 1.3,
                                       7.0, 11.0, 13.0, 1.7, 1.9, 2.3};

TEST(NtnPaper, MassesAlignedSumExactlyInRigidDirectionsOnly) {
  const std::array<ntn::HingeData, 1> h{pinned(ntn_test::kIdentity3)};
  std::array<double, 12> m = kMass;
  ntn::paper_masses(h, m);
  for (std::size_t k = 0; k < 6; ++k) {
    const bool rigid = k < 4;
    EXPECT_EQ(m[k], rigid ? kMass[k] + kMass[6 + k] : kMass[k]) << "node 0, direction " << k;
    EXPECT_EQ(m[6 + k], rigid ? kMass[6 + k] + kMass[k] : kMass[6 + k]) << "node 1, " << k;
  }
}

// diag(T^T diag(l) T) with l = diag(T diag(m) T^T) summed over both nodes in the rigid rows.
std::array<double, 12> turned_masses_by_definition(const Mat3& t, std::uint8_t rigid) {
  std::array<double, 12> out{};
  for (std::size_t block = 0; block < 6; block += 3) {
    double l[2][3];
    for (std::size_t n = 0; n < 2; ++n) {
      for (std::size_t r = 0; r < 3; ++r) {
        l[n][r] = 0;
        for (std::size_t c = 0; c < 3; ++c)
          l[n][r] += t[3 * r + c] * t[3 * r + c] * kMass[6 * n + block + c];
      }
    }
    for (std::size_t r = 0; r < 3; ++r) {
      if (!((rigid >> (block + r)) & 1U)) continue;
      const double sum = l[0][r] + l[1][r];
      l[0][r] = l[1][r] = sum;
    }
    for (std::size_t n = 0; n < 2; ++n) {
      for (std::size_t c = 0; c < 3; ++c) {
        double g = 0;
        for (std::size_t r = 0; r < 3; ++r)
          g += t[3 * r + c] * t[3 * r + c] * l[n][r];
        out[6 * n + block + c] = g;
      }
    }
  }
  return out;
}

TEST(NtnPaper, MassesTurnedAreTheDiagonalOfTheSummedHingeFrameMasses) {
  const Mat3 t = ntn_test::skewed_frame(ntn_test::kIdentity3);
  const std::array<ntn::HingeData, 1> h{pinned(t)};
  std::array<double, 12> m = kMass;
  ntn::paper_masses(h, m);
  const std::array<double, 12> want = turned_masses_by_definition(t, 0x0f);
  for (std::size_t j = 0; j < 12; ++j)
    EXPECT_NEAR(m[j], want[j], 1e-15 * want[j]) << "DOF " << j;
  // The turned frame mixes the axes: the result differs from the aligned one.
  EXPECT_NE(m[0], kMass[0] + kMass[6]);
}

TEST(NtnPaper, ForcesAndMassesGiveBothNodesOneAccelerationInRigidDirections) {
  const std::array<ntn::HingeData, 1> h{pinned(ntn_test::kIdentity3)};
  std::array<double, 12> m = kMass;
  std::array<double, 12> r{1.5, -2.5, 3.5, 0.25, -0.75, 0.5, -4.0, 6.0, 1.0, -0.5, 2.0, -1.0};
  const std::array<double, 12> r0 = r;
  ntn::paper_masses(h, m);
  ntn::paper_forces(h, r.data());
  for (std::size_t k = 0; k < 6; ++k) {
    if (k < 4) {
      EXPECT_EQ(r[k], r0[k] + r0[6 + k]) << k;  // S 20: the sum, on both nodes
      EXPECT_EQ(r[6 + k], r0[6 + k] + r0[k]) << k;
      EXPECT_EQ(r[k] / m[k], r[6 + k] / m[6 + k]) << "one acceleration in rigid direction " << k;
    } else {
      EXPECT_EQ(r[k], r0[k]) << k;  // free: each node keeps its own
      EXPECT_EQ(r[6 + k], r0[6 + k]) << k;
    }
  }
}

TEST(NtnPaper, AfterUpdateCopiesTheSupportedNodesRigidComponents) {
  // Node 1 is held in every DOF (S 30): node 0 takes its rigid components (zero), keeps ry, rz.
  const std::array<ntn::HingeData, 1> h{pinned(ntn_test::kIdentity3)};
  const std::array<std::uint8_t, 2> fixed{0, ntn_test::kFixedAll};
  std::array<double, 12> u{1e-3, -2e-3, 3e-3, 4e-4, 5e-4, -6e-4, 0, 0, 0, 0, 0, 0};
  std::array<double, 12> v{}, a{};
  const std::array<double, 12> u0 = u;
  const double inv_dt = 1e3;
  ntn::paper_after_update(h, fixed, u.data(), v.data(), a.data(), inv_dt);
  for (std::size_t k = 0; k < 6; ++k) {
    if (k < 4) {
      EXPECT_EQ(u[k], 0.0) << k;
      const double du = -u0[k];
      EXPECT_NEAR(v[k], du * inv_dt, 1e-15 * std::abs(du * inv_dt)) << k;  // S 35-36
      EXPECT_NEAR(a[k], du * inv_dt * inv_dt, 1e-15 * std::abs(du * inv_dt * inv_dt)) << k;
    } else {
      EXPECT_EQ(u[k], u0[k]) << k;  // free: untouched, bit for bit
      EXPECT_EQ(v[k], 0.0) << k;
    }
    EXPECT_EQ(u[6 + k], 0.0) << "the supported node does not move, " << k;
  }
  // Node 0 held instead (S 31): node 1 takes node 0's rigid components.
  const std::array<std::uint8_t, 2> fixed0{ntn_test::kFixedAll, 0};
  std::array<double, 12> u2{0, 0, 0, 0, 0, 0, 1e-3, -2e-3, 3e-3, 4e-4, 5e-4, -6e-4};
  v = {}, a = {};
  ntn::paper_after_update(h, fixed0, u2.data(), v.data(), a.data(), inv_dt);
  for (std::size_t k = 0; k < 4; ++k)
    EXPECT_EQ(u2[6 + k], 0.0) << k;
  EXPECT_EQ(u2[6 + 4], 5e-4);
}

TEST(NtnPaper, AfterUpdateScalesAPairPastItsRigidBranchOntoIt) {
  // A free pair with a rigid branch in ry at +-1e-3 rad (S 32-33): d = phi1 - phi0 = 1.5e-3.
  ntn::HingeData hd = pinned(ntn_test::kIdentity3);
  hd.rigid = 0;
  hd.branches = 1U << ntn::kRy;
  hd.branch_lower[ntn::kRy] = -1e-3, hd.branch_upper[ntn::kRy] = 1e-3;
  const std::array<ntn::HingeData, 1> h{hd};
  const std::array<std::uint8_t, 2> fixed{0, 0};
  std::array<double, 12> u{}, v{}, a{};
  u[ntn::kRy] = -0.5e-3, u[6 + ntn::kRy] = 1.0e-3, u[ntn::kUx] = 2e-3;
  const std::array<double, 12> u0 = u;
  const double inv_dt = 1e3;
  // couple = false: the clamp alone, as clamp = "paper" runs it under the other methods.
  ntn::paper_after_update(h, fixed, u.data(), v.data(), a.data(), inv_dt, false);
  const double d = u[6 + ntn::kRy] - u[ntn::kRy];
  EXPECT_NEAR(d, 1e-3, 1e-15 * 1e-3);
  // S 33 scales both absolute rotations by d_lim / d.
  EXPECT_NEAR(u[ntn::kRy], u0[ntn::kRy] * (1e-3 / 1.5e-3), 1e-15 * 1e-3);
  EXPECT_NEAR(u[6 + ntn::kRy], u0[6 + ntn::kRy] * (1e-3 / 1.5e-3), 1e-15 * 1e-3);
  for (std::size_t j : {std::size_t{ntn::kRy}, std::size_t{6 + ntn::kRy}}) {
    const double du = u[j] - u0[j];
    EXPECT_NEAR(v[j], du * inv_dt, 1e-12 * std::abs(du * inv_dt)) << j;
    EXPECT_NEAR(a[j], du * inv_dt * inv_dt, 1e-12 * std::abs(du * inv_dt * inv_dt)) << j;
  }
  EXPECT_EQ(u[ntn::kUx], u0[ntn::kUx]);  // not a branch direction: its bits stay
  // Inside the branch nothing moves.
  const std::array<double, 12> inside = u;
  ntn::paper_after_update(h, fixed, u.data(), v.data(), a.data(), inv_dt, false);
  for (std::size_t j = 0; j < 12; ++j)
    EXPECT_EQ(u[j], inside[j]) << j;
}

}  // namespace ntn_paper_test
