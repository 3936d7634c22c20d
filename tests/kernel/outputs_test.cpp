// Output channels (sample_outputs in step(), DESIGN §8): values at t_n, and support reaction and
// element end forces of a statically loaded cantilever against equilibrium (with stiffness-
// proportional damping, the reaction's damping part).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ntn/kernel.hpp"
#include "support/builders.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"
#include "support/relaxation.hpp"

namespace outputs_test {

using ntn_test::dof;
using K = ntn::OutputKind;

constexpr int kN = 8;
constexpr ntn::Sizes kS{.nodes = kN + 1, .elements = kN, .loads = 2, .outputs = 10};
constexpr double kL = 2.0, kP = 500.0, kT = 30.0;  // m, N, N m

ntn::ModelSpec<kS> spec;
ntn::Model<kS> model;
ntn::State<kS> state;
ntn::Scratch<kS> scratch;

void build() {
  spec = {};
  ntn_test::straight_beam(spec, kL, ntn_test::kSteel, ntn_test::rectangle(0.05, 0.1));
  spec.loads[0] = {kN, ntn::kUz, kP, ntn::kConstant};
  spec.loads[1] = {kN, ntn::kRx, kT, ntn::kConstant};
  spec.outputs[0] = {K::kDisplacement, kN, 0, 0, 0, ntn::kUz, 1000.0};  // mm
  spec.outputs[1] = {K::kVelocity, kN, 0, 0, 0, ntn::kUz, 1.0};
  spec.outputs[2] = {K::kAcceleration, kN / 2, 0, 0, 0, ntn::kUz, 1.0};
  spec.outputs[3] = {K::kDrift, 2, 6, 0, 0, ntn::kUz, 1.0 / 1.0};  // nodes 1 m apart
  spec.outputs[4] = {K::kReaction, 0, 0, 0, 0, ntn::kUz, 1.0};
  spec.outputs[5] = {K::kReaction, 0, 0, 0, 0, ntn::kRy, 1.0};
  spec.outputs[6] = {K::kElementForce, 0, 0, 0, 0, 2, 1.0};           // Vz at the clamped end
  spec.outputs[7] = {K::kElementForce, 0, 0, 0, 0, 4, 1.0};           // My at the clamped end
  spec.outputs[8] = {K::kElementForce, 0, 0, kN / 2 - 1, 1, 4, 1.0};  // My at mid-span, end j
  spec.outputs[9] = {K::kElementForce, 0, 0, kN - 1, 1, 3, 1.0};      // torque near the tip
  const double w1 = 3.516 / (kL * kL) * std::sqrt(210e9 * 0.05 * 1e-3 / 12 / (7850 * 5e-3));
  spec.settings.alpha = 2 * w1;  // near critical for the first x-z mode: relaxes quickly
  spec.settings.dt = 0.9 * ntn::stable_time_step(ntn::view(spec)).dt_stable;
}

// Channels are sampled at t_n inside step(n): displacement u_n (scaled), velocity
// v_n = v_{n-1/2} + dt/2 a_n (= the average of the two half-step velocities), acceleration a_n,
// drift u[node2] - u[node] times 1/height. Rounding tolerance 1e-13.
TEST(Outputs, KinematicChannelsAreTheStateAtTn) {
  build();
  const ntn_test::EigenNoMalloc guard;
  ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
  state = {};
  ASSERT_EQ(ntn::start(model, state, scratch, {}), ntn::StepStatus::kOk);
  for (int n = 0; n < 500; ++n) {
    const ntn::State<kS> before = state;
    ASSERT_EQ(ntn::step(model, state, scratch, {}), ntn::StepStatus::kOk);
    const std::size_t tip = dof(kN, ntn::kUz);
    EXPECT_EQ(scratch.outputs[0], 1000.0 * before.u[tip]);
    const double vn = 0.5 * (before.v[tip] + state.v[tip]);
    EXPECT_NEAR(scratch.outputs[1], vn, 1e-13 * std::abs(state.v[tip]) + 1e-300);
    EXPECT_EQ(scratch.outputs[2], scratch.a[dof(kN / 2, ntn::kUz)]);
    EXPECT_EQ(scratch.outputs[3], before.u[dof(6, ntn::kUz)] - before.u[dof(2, ntn::kUz)]);
  }
}

// After dynamic relaxation under a tip force P (z) and torque T: the support reaction is -P
// in z and +P L about y (the support holds the beam against the load's moment -P L about y);
// the first element's end forces at the clamp (forces the node exerts on the element) are the
// same reaction, Vz = -P, My = P L; at mid-span the outer half acts on the element through its
// end j with My = -P L / 2 (the moment of P about that point), and the tip node on the last
// element with the torque T. Statics, exact for the converged solution: tolerance 1e-8 (relaxation
// converged to 1e-10).
TEST(Outputs, ReactionAndEndForcesSatisfyStatics) {
  build();
  ntn_test::RelaxationResult r;
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
    state = {};
    r = ntn_test::relax(model, state, scratch, 1e-10, 1'000'000);
  }
  ASSERT_TRUE(r.converged);
  const auto& o = scratch.outputs;
  EXPECT_NEAR(o[4] / -kP, 1.0, 1e-8);
  EXPECT_NEAR(o[5] / (kP * kL), 1.0, 1e-8);
  EXPECT_NEAR(o[6] / -kP, 1.0, 1e-8);
  EXPECT_NEAR(o[7] / (kP * kL), 1.0, 1e-8);
  EXPECT_NEAR(o[8] / (-kP * kL / 2), 1.0, 1e-8);
  EXPECT_NEAR(o[9] / kT, 1.0, 1e-8);
}

// With stiffness-proportional damping the reaction is the support's share of F_n, which holds the
// elements' damping forces beta K v_{n-1/2} as well (kernel/README.md): Newton's law for the whole
// beam. The elements' forces sum to zero over all nodes (K has the rigid translations in its null
// space), so at every step of the transient from rest under the tip load, with alpha = 0,
//   reaction_z = sum over supported DOFs of (F - P) = -sum_all P_z + sum_free m a_z.
// Rounding tolerance 1e-9 of the largest term. The element force channel Vz at the clamp is the
// elastic K_L T u alone: it differs from the reaction by the damping force there (checked to be
// a sizeable part of it, so the comparison can tell the two apart).
TEST(Outputs, ReactionIncludesTheElementsDampingForces) {
  build();
  const double w1 = 3.516 / (kL * kL) * std::sqrt(210e9 * 0.05 * 1e-3 / 12 / (7850 * 5e-3));
  spec.settings.alpha = 0;
  spec.settings.beta = 2 * 0.3 / w1;  // 30 % of critical at the first x-z mode
  spec.settings.dt = 0.9 * ntn::stable_time_step(ntn::view(spec)).dt_stable;
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
  }
  state = {};
  ASSERT_EQ(ntn::start(model, state, scratch, {}), ntn::StepStatus::kOk);
  double damping_share = 0;
  for (int n = 0; n < 20'000; ++n) {
    ASSERT_EQ(ntn::step(model, state, scratch, {}), ntn::StepStatus::kOk);
    double inertia = 0, scale = kP;
    for (int k = 1; k <= kN; ++k) {
      const std::size_t j = dof(k, ntn::kUz);
      inertia += model.mass[j] * scratch.a[j];
      scale = std::max(scale, std::abs(model.mass[j] * scratch.a[j]));
    }
    const double reaction = scratch.outputs[4];
    ASSERT_NEAR(reaction, -kP + inertia, 1e-9 * scale) << "step " << n;
    damping_share = std::max(damping_share, std::abs(reaction - scratch.outputs[6]) / kP);
  }
  std::printf("  largest |reaction - elastic Vz at the clamp| / P = %.3f\n", damping_share);
  EXPECT_GT(damping_share, 0.05);
}

// Under a constant ground acceleration a_g (input in g, scaled), once relaxed the structure moves
// with the ground: relative acceleration 0, absolute acceleration a_g at every node (exactly at
// the support, where the relative acceleration is held at 0), and the support pushes the whole
// mass along: reaction = total mass x a_g (sum over all DOFs of the internal forces is zero, so
// the support's F - P balances -sum P = M a_g). Tolerance 1e-8 (relaxation converged to 1e-10).
TEST(Outputs, AbsoluteAccelerationAndReactionUnderGroundAcceleration) {
  constexpr ntn::Sizes S{.nodes = 5, .elements = 4, .inputs = 1, .outputs = 4};
  static ntn::ModelSpec<S> sp;
  static ntn::Model<S> mo;
  static ntn::State<S> st;
  static ntn::Scratch<S> sc;
  const double ag = 0.2, g = 9.80665;  // input in g
  sp = {};
  ntn_test::straight_beam(sp, kL, ntn_test::kSteel, ntn_test::rectangle(0.05, 0.1));
  sp.nodes[4].added = {50, 50, 50, 0, 0, 0};
  sp.inputs[0] = {ntn::InputKind::kGroundAcceleration, 0, ntn::kUz, g};
  sp.outputs[0] = {K::kAbsoluteAcceleration, 4, 0, 0, 0, ntn::kUz, 1.0};
  sp.outputs[1] = {K::kAbsoluteAcceleration, 0, 0, 0, 0, ntn::kUz, 1.0};
  sp.outputs[2] = {K::kAcceleration, 4, 0, 0, 0, ntn::kUz, 1.0};
  sp.outputs[3] = {K::kReaction, 0, 0, 0, 0, ntn::kUz, 1.0};
  sp.settings.alpha = 2 * 20.0;  // near critical for the first x-z mode (~20 rad/s with the mass)
  sp.settings.dt = 0.9 * ntn::stable_time_step(ntn::view(sp)).dt_stable;
  ntn_test::RelaxationResult r;
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(sp, mo).ok());
    st = {};
    r = ntn_test::relax(mo, st, sc, 1e-10, 1'000'000, {ag});
  }
  ASSERT_TRUE(r.converged);
  double total_mass = 0;
  for (std::size_t n = 0; n < S.nodes; ++n)
    total_mass += mo.mass[dof(n, ntn::kUz)];
  EXPECT_NEAR(sc.outputs[0] / (ag * g), 1.0, 1e-8);
  EXPECT_EQ(sc.outputs[1], ag * g);
  EXPECT_NEAR(sc.outputs[2] / (ag * g), 0.0, 1e-8);
  EXPECT_NEAR(sc.outputs[3] / (total_mass * ag * g), 1.0, 1e-8);
}

}  // namespace outputs_test
