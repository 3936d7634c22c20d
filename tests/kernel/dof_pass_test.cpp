// The fused DOF pass of models without hinges (dof_pass.hpp): its SIMD path
// gives the scalar reference's bits on every instruction set this CPU has, for any node range
// (odd counts, odd starts), signed zeros and a non-finite velocity; and residual_update(), the
// pass with the load slots, gives the bits of the unfused stages it replaced (residual(), then
// update()) on a model whose slots were declared out of DOF order, whole or in any two parts.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "ntn/dof_pass.hpp"
#include "ntn/integrator.hpp"
#include "support/every_target.hpp"
#include "support/frames.hpp"
#include "support/init_model.hpp"

namespace dof_pass_test {

// Random DOF arrays for `nodes` nodes: masses over orders of magnitude, forces and velocities
// with exact and negative zeros mixed in.
struct Dofs {
  std::vector<double> mass, inv_mass, f, a, v, u;
  std::array<double, ntn::kDofsPerNode> g{};
  double alpha = 0.3, dt = 1e-4;

  std::vector<ntn::MassBlock> table;
  std::vector<std::int32_t> entry;

  ntn::DofPassData data() {
    const std::size_t nodes = mass.size() / ntn::kDofsPerNode;
    table.assign(ntn::mass_groups(nodes), {});
    entry.assign(ntn::mass_groups(nodes), -1);
    ntn::fill_mass_table(mass.data(), inv_mass.data(), nodes, table.data(), entry.data());
    return {mass.data(), inv_mass.data(), f.data(), g.data(),     alpha,       dt,
            a.data(),    v.data(),        u.data(), table.data(), entry.data()};
  }
};

Dofs random_dofs(std::size_t nodes, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> x(-1.0, 1.0), e(0.0, 6.0);
  auto value = [&] {
    switch (rng() % 8) {
      case 0:
        return 0.0;
      case 1:
        return -0.0;
      default:
        return x(rng) * std::pow(10.0, e(rng));
    }
  };
  Dofs d;
  const std::size_t n = ntn::kDofsPerNode * nodes;
  for (std::size_t j = 0; j < n; ++j) {
    d.mass.push_back(std::pow(10.0, e(rng)));
    d.inv_mass.push_back(1.0 / d.mass.back());
    d.f.push_back(value());
    d.v.push_back(value());
    d.u.push_back(value());
  }
  d.a.assign(n, 7.0);  // overwritten by the pass
  d.g = {0.98, -0.0, -9.81, 0.0, 0.0, 0.0};
  return d;
}

bool same_bits(const std::vector<double>& x, const std::vector<double>& y) {
  return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0;
}

// The pass over nodes [first, last) by one path: the returned flag and the arrays after it.
struct Pass {
  double bad;
  Dofs after;
};

Pass run(Dofs d, ntn::ElementPass path, std::size_t first, std::size_t last) {
  const double bad = ntn::dof_pass_nodes(path, d.data(), first, last);
  return {bad, d};
}

void expect_same(const Pass& x, const Pass& y, const char* what) {
  EXPECT_EQ(x.bad, y.bad) << what;
  EXPECT_TRUE(same_bits(x.after.a, y.after.a)) << what;
  EXPECT_TRUE(same_bits(x.after.v, y.after.v)) << what;
  EXPECT_TRUE(same_bits(x.after.u, y.after.u)) << what;
}

// The scalar reference is the formula, DOF by DOF (written out here once more, by hand).
TEST(DofPass, ScalarPathIsTheCentralDifferenceUpdate) {
  const Dofs d = random_dofs(3, 1);
  const Pass p = run(d, ntn::ElementPass::kScalar, 0, 3);
  EXPECT_EQ(p.bad, 0.0);
  for (std::size_t j = 0; j < d.mass.size(); ++j) {
    const double a =
        ((d.mass[j] * d.g[j % 6] - d.f[j]) - (d.alpha * d.mass[j]) * d.v[j]) * d.inv_mass[j];
    const double v = d.v[j] + d.dt * a;
    EXPECT_EQ(p.after.a[j], a) << j;
    EXPECT_EQ(p.after.v[j], v) << j;
    EXPECT_EQ(p.after.u[j], d.u[j] + d.dt * v) << j;
  }
}

// A non-finite velocity anywhere in the range, first node to last, is reported by both paths.
TEST(DofPass, NonFiniteVelocityIsReported) {
  for (const ntn::ElementPass path : {ntn::ElementPass::kScalar, ntn::ElementPass::kSimd}) {
    for (std::size_t node = 0; node < 5; ++node) {
      Dofs d = random_dofs(5, 2);
      d.f[6 * node + node % 6] = std::numeric_limits<double>::infinity();
      EXPECT_EQ(run(d, path, 0, 5).bad, 1.0) << "node " << node;
      EXPECT_EQ(run(d, path, 0, node).bad, 0.0) << "node " << node;
    }
  }
}

#if defined(NTN_SIMD)

using ntn_test::EveryTarget;

TEST_F(EveryTarget, DofPassGivesTheScalarBits) {
  each_target([&](std::int64_t t) {
    for (const std::size_t nodes : {1, 2, 3, 4, 5, 7, 64, 65}) {  // groups of 4 and the rest
      const Dofs d = random_dofs(nodes, 10 + nodes);
      for (const std::size_t first : {std::size_t{0}, std::size_t{1}}) {
        if (first >= nodes) continue;
        expect_same(run(d, ntn::ElementPass::kSimd, first, nodes),
                    run(d, ntn::ElementPass::kScalar, first, nodes), hwy::TargetName(t));
      }
    }
  });
}

// A structure whose floors repeat: groups 1-15 copy group 0's masses, group 16 too but for the
// sign of one zero inverse mass (a supported DOF). The shared groups point at one entry, the
// signed zero makes its own, and the SIMD pass, which reads the masses there, gives the scalar
// bits on every target.
TEST_F(EveryTarget, SharedMassesGiveTheScalarBits) {
  constexpr std::size_t kGroupDofs = ntn::kMassGroup * ntn::kDofsPerNode;
  Dofs d = random_dofs(17 * ntn::kMassGroup + 3, 11);
  d.inv_mass[0] = 0.0;
  for (std::size_t j = kGroupDofs; j < 17 * kGroupDofs; ++j)
    d.mass[j] = d.mass[j % kGroupDofs], d.inv_mass[j] = d.inv_mass[j % kGroupDofs];
  d.inv_mass[16 * kGroupDofs] = -0.0;
  (void)d.data();  // builds d.table and d.entry by fill_mass_table
  for (std::size_t k = 0; k < 17; ++k)
    EXPECT_EQ(d.entry[k], k < 16 ? 0 : 1) << "group " << k;
  for (std::size_t k = 0; k < 17; ++k) {
    const ntn::MassBlock& e = d.table[static_cast<std::size_t>(d.entry[k])];
    EXPECT_EQ(std::memcmp(e.mass.data(), &d.mass[kGroupDofs * k], sizeof e.mass), 0) << k;
    EXPECT_EQ(std::memcmp(e.inv_mass.data(), &d.inv_mass[kGroupDofs * k], sizeof e.inv_mass), 0)
        << k;
  }
  each_target([&](std::int64_t t) {
    for (const std::size_t first : {std::size_t{0}, std::size_t{3}, std::size_t{5}}) {
      expect_same(run(d, ntn::ElementPass::kSimd, first, d.mass.size() / ntn::kDofsPerNode),
                  run(d, ntn::ElementPass::kScalar, first, d.mass.size() / ntn::kDofsPerNode),
                  hwy::TargetName(t));
    }
  });
}

#endif  // NTN_SIMD

constexpr auto S = ntn_test::kFeatureSizes;

// The feature frame with its slots declared out of DOF order, two of them on one node.
bool slotted_frame(ntn::ModelSpec<S>& spec) {
  if (!ntn_test::feature_frame(spec)) return false;
  spec.loads[0] = {7, ntn::kUx, 2e4, 0};  // DOF 42, then 35 (load 1), then 43 (input 2)
  return true;
}

TEST(DofPass, SlotsAreInDofOrder) {
  static ntn_test::Sim<S> sim;
  ASSERT_TRUE(slotted_frame(sim.spec));
  ASSERT_TRUE(ntn_test::init_model(sim.spec, sim.model).ok());
  ASSERT_EQ(sim.model.num_slots, 3);
  for (int k = 1; k < sim.model.num_slots; ++k)
    EXPECT_LT(sim.model.slot_dof[static_cast<std::size_t>(k - 1)],
              sim.model.slot_dof[static_cast<std::size_t>(k)]);
  for (std::size_t i = 0; i < S.loads; ++i) {
    const ntn::LoadSpec& l = sim.spec.loads[i];
    EXPECT_EQ(sim.model.slot_dof[static_cast<std::size_t>(sim.model.load_slot[i])],
              ntn::kDofsPerNode * l.node + l.dof);
  }
  EXPECT_EQ(sim.model.slot_dof[static_cast<std::size_t>(sim.model.input_slot[2])],
            ntn::kDofsPerNode * 7 + ntn::kUy);
}

// residual_update() against the unfused stages, at many states of a run with loads and inputs.
TEST(DofPass, FusedPassIsTheUnfusedStages) {
  static ntn_test::Sim<S> sim;
  static ntn::State<S> fused, unfused;
  static ntn::Scratch<S> w_fused, w_unfused;
  ASSERT_TRUE(slotted_frame(sim.spec));
  ASSERT_TRUE(ntn_test::init_model(sim.spec, sim.model).ok());
  const ntn::Model<S>& m = sim.model;
  ntn::initial_state(m, sim.state);
  std::array<double, S.inputs> in{};
  (void)ntn::start(m, sim.state, sim.scratch, in);
  for (long n = 0; n < 400; ++n) {
    for (std::size_t c = 0; c < S.inputs; ++c)
      in[c] = ntn_test::input_sample(static_cast<int>(c), n);
    (void)ntn::step(m, sim.state, sim.scratch, in);
    if (n % 40 != 0) continue;
    // F_n and P_n at this state, then the two ways to a_n, v_{n+1/2}, u_{n+1}
    ntn::Scratch<S>& w = sim.scratch;
    (void)ntn::detail::accept_inputs(m, sim.state, in);
    ntn::detail::apply_loads(m, sim.state, w, static_cast<double>(sim.state.tick) * m.dt);
    ntn::detail::element_forces(m, sim.state, w);
    unfused = sim.state, w_unfused = w;
    ntn::detail::residual(m, unfused, w_unfused, m.inv_mass.data(), w_unfused.a.data());
    ASSERT_TRUE(ntn::detail::update(m, unfused, w_unfused));
    for (std::size_t split = 0; split <= S.nodes; ++split) {  // whole, and in two parts
      fused = sim.state, w_fused = w;
      ASSERT_TRUE(ntn::detail::residual_update(m, fused, w_fused, 0, split));
      ASSERT_TRUE(ntn::detail::residual_update(m, fused, w_fused, split, S.nodes));
      ASSERT_EQ(std::memcmp(fused.u.data(), unfused.u.data(), sizeof(fused.u)), 0) << n << split;
      ASSERT_EQ(std::memcmp(fused.v.data(), unfused.v.data(), sizeof(fused.v)), 0) << n << split;
      ASSERT_EQ(std::memcmp(w_fused.a.data(), w_unfused.a.data(), sizeof(w_fused.a)), 0) << n;
      // and the outputs' a_n, computed before the pass, are the pass's
      for (std::size_t j = 0; j < ntn::Model<S>::kDofs; ++j)
        ASSERT_EQ(ntn::detail::acceleration_at(m, sim.state, w, j), w_fused.a[j]) << j;
    }
  }
}

}  // namespace dof_pass_test
