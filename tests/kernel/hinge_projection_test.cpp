// ntn_exact re-projects only the trees that round (DESIGN §7.1, kernel/README.md "Hinges").
//
// In a tree of centric hinges aligned with the global axes the forest's matrices are 0/1
// diagonals, so the downward pass gives every child exactly its parent's rigid accelerations
// and the update moves both alike: the rigid components stay equal with no projection at all.
// The step therefore skips those trees. These tests hold that claim to exact equality, with no
// tolerance, because it is a statement about floating-point operations (a product by 1 plus a
// product by 0), not about an approximation:
// - a beam with two aligned hinges and an aligned support hinge to the ground, under loads in
//   every direction for 20 000 steps: every rigid component of every child equals its parent's
//   (or zero, at the ground) after every step, and a twin run that also projects every edge
//   after every step has the same u and v (as numbers: a projection may turn -0 into +0);
// - a tree with a rotated hinge is re-projected by the step, and so is every tree when the
//   S 33 clamp meets a rigid branch;
// - start() puts initial displacements and velocities that violate the constraints onto them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "ntn/kernel.hpp"
#include "support/builders.hpp"
#include "support/hinges.hpp"
#include "support/init_model.hpp"

namespace hinge_projection_test {

using ntn_test::dof;

constexpr int kN = 8;  // elements along x, nodes 0..8
constexpr int kCutA = 4, kExtraA = 9;
constexpr int kCutB = 2, kExtraB = 10;
constexpr ntn::Sizes kSizes{.nodes = kN + 3,
                            .elements = kN,
                            .time_functions = 1,
                            .time_points = 3,
                            .loads = 8,
                            .hinges = 3,
                            .curves = 1,
                            .curve_points = 4};
constexpr long kSteps = 20000;

ntn::ModelSpec<kSizes> spec;
ntn::Model<kSizes> model, twin;
ntn::State<kSizes> state, twin_state;
ntn::Scratch<kSizes> scratch, twin_scratch;

// Beam along x on a support hinge at node 0 (to the ground, rigid but for ry) and fixed at node 8;
// cut at node 4 by a hinge free in ry and rz (node 9 = the right member's end) and at node 2 by a
// hinge free in rx (node 10). `frame_a` is hinge A's frame.
void build(const ntn_test::Mat3& frame_a) {
  spec = {};
  ntn_test::straight_beam(spec, 4.0, ntn_test::kSteel, ntn_test::rectangle(0.1, 0.15), 0,
                          ntn_test::kFixedAll);
  for (auto [cut, extra] : {std::pair{kCutA, kExtraA}, std::pair{kCutB, kExtraB}}) {
    spec.nodes[static_cast<std::size_t>(extra)] = spec.nodes[static_cast<std::size_t>(cut)];
    spec.elements[static_cast<std::size_t>(cut)].node_i = extra;
  }
  using ntn::kRx, ntn::kRy, ntn::kRz;
  spec.hinges[0] =
      ntn_test::hinge(kExtraA, kCutA, frame_a, ntn_test::released((1U << kRy) | (1U << kRz)));
  spec.hinges[1] =
      ntn_test::hinge(kExtraB, kCutB, ntn_test::kIdentity3, ntn_test::released(1U << kRx));
  spec.hinges[2] =
      ntn_test::hinge(0, ntn::kGround, ntn_test::kIdentity3, ntn_test::released(1U << kRy));
  spec.time_points = ntn_test::triangle_pulse(0.004);
  spec.time_functions[0] = {0, 3};
  for (int d = 0; d < 6; ++d) {
    spec.loads[static_cast<std::size_t>(d)] = {d % 2 == 0 ? 3 : 6, d, d < 3 ? 4e4 : 2e3, 0};
  }
  spec.loads[6] = {kCutA, ntn::kUy, -2e4, 0};
  spec.loads[7] = {kExtraB, ntn::kRx, 1e3, 0};
  spec.settings.dt = 0.9 * ntn_test::hinged_stable_step(spec).dt_stable;
}

// Child minus parent in global components, for aligned hinges: zero in every rigid direction.
double rigid_gap(const ntn::State<kSizes>& s, const ntn::HingeData& h, int d, bool velocity) {
  const auto& x = velocity ? s.v : s.u;
  const double child = x[dof(h.node1, d)];
  const double parent = h.node2 == ntn::kGround ? 0.0 : x[dof(h.node2, d)];
  return child - parent;
}

TEST(HingeProjection, AlignedTreesStayExactWithoutProjection) {
  build(ntn_test::kIdentity3);
  ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
  ASSERT_TRUE(ntn_test::init_model(spec, twin).ok());
  EXPECT_EQ(model.num_edges, 3);
  EXPECT_EQ(model.num_project_edges, 0) << "every tree is aligned: the step projects nothing";
  state = {}, twin_state = {};
  ASSERT_EQ(ntn::start(model, state, scratch, {}), ntn::StepStatus::kOk);
  ASSERT_EQ(ntn::start(twin, twin_state, twin_scratch, {}), ntn::StepStatus::kOk);
  double peak = 0, worst_gap = 0, worst_twin = 0;
  for (long n = 0; n < kSteps; ++n) {
    ASSERT_EQ(ntn::step(model, state, scratch, {}), ntn::StepStatus::kOk);
    ASSERT_EQ(ntn::step(twin, twin_state, twin_scratch, {}), ntn::StepStatus::kOk);
    ntn::forest_project_initial(twin.edges, twin.edge_matrices, twin.num_edges, twin_state.u.data(),
                                twin_state.v.data());  // every edge, u and v
    for (const ntn::HingeData& h : model.hinges) {
      for (int d = 0; d < 6; ++d) {
        if (!((h.rigid >> d) & 1U)) continue;
        worst_gap = std::max({worst_gap, std::abs(rigid_gap(state, h, d, false)),
                              std::abs(rigid_gap(state, h, d, true))});
      }
    }
    for (std::size_t j = 0; j < state.u.size(); ++j) {
      peak = std::max(peak, std::abs(state.u[j]));
      worst_twin = std::max({worst_twin, std::abs(state.u[j] - twin_state.u[j]),
                             std::abs(state.v[j] - twin_state.v[j])});
    }
  }
  std::printf(
      "  %ld steps, peak |u| %.3e: max rigid gap %.1e, max |unprojected - projected| %.1e\n",
      kSteps, peak, worst_gap, worst_twin);
  EXPECT_GT(peak, 1e-6) << "the loads must move the beam";
  EXPECT_EQ(worst_gap, 0.0);
  EXPECT_EQ(worst_twin, 0.0);
}

TEST(HingeProjection, TreesThatRoundAreReprojected) {
  // Hinge A turned 20 degrees about z: its rigid torsion axis is no longer a global axis, so its
  // tree is re-projected and the others not. (A turn about the member axis x would not do: the
  // rigid subspace, all translations and rx, would be the same, and so the matrices.)
  build(ntn_test::rotation({0, 0, 1}, 20 * ntn_test::kDegree));
  ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
  ASSERT_EQ(model.num_project_edges, 1);
  const int e = model.project_edges[0];
  EXPECT_EQ(model.edges[static_cast<std::size_t>(e)].hinge, 0);
  EXPECT_FALSE(model.edges[static_cast<std::size_t>(e)].aligned);

  // A rigid branch under clamp = "paper" (S 33 moves single nodes): every tree is re-projected.
  build(ntn_test::kIdentity3);
  spec.curves[0] = {0, 4};
  spec.curve_points = {{{-2e-3, -1e9}, {-1e-3, -1e2}, {1e-3, 1e2}, {2e-3, 1e9}}};
  spec.hinges[1].behaviour[ntn::kRx] = ntn::HingeBehaviour::kCurve;
  spec.hinges[1].curve[ntn::kRx] = 0;
  spec.settings.limit_rotational_stiffness = 1e8;
  spec.settings.dt = 0.9 * ntn_test::hinged_stable_step(spec).dt_stable;
  spec.settings.clamp = ntn::ClampRule::kMomentum;
  ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
  EXPECT_EQ(model.num_branch_hinges, 1);
  EXPECT_EQ(model.num_project_edges, 0) << "the momentum clamp moves the trees as trees";
  spec.settings.clamp = ntn::ClampRule::kPaper;
  ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
  EXPECT_EQ(model.num_project_edges, model.num_edges);
}

TEST(HingeProjection, StartPutsInitialConditionsOnTheConstraints) {
  build(ntn_test::kIdentity3);
  ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
  state = {};
  for (int d = 0; d < 6; ++d) {  // every direction of node 9 off its joint, and node 0 off ground
    state.u[dof(kExtraA, d)] = 1e-3 * (d + 1);
    state.v[dof(kExtraA, d)] = -2e-2 * (d + 1);
    state.u[dof(0, d)] = 5e-4;
  }
  ASSERT_EQ(ntn::start(model, state, scratch, {}), ntn::StepStatus::kOk);
  const ntn::HingeData& a = model.hinges[0];
  const ntn::HingeData& g = model.hinges[2];
  for (int d = 0; d < 6; ++d) {
    const bool free_a = d == ntn::kRy || d == ntn::kRz;
    // u_0 exact: set from the parent. (v here is v_{-1/2} = v_0 - dt/2 a_0, with a_0 from the
    // forest, so its rigid components are equal too.)
    EXPECT_EQ(rigid_gap(state, a, d, false), free_a ? 1e-3 * (d + 1) : 0.0) << "direction " << d;
    if (!free_a) {
      EXPECT_EQ(rigid_gap(state, a, d, true), 0.0) << "direction " << d;
    }
    EXPECT_EQ(state.u[dof(0, d)], d == ntn::kRy ? 5e-4 : 0.0) << "direction " << d;
  }
  EXPECT_EQ(g.node2, ntn::kGround);
}

}  // namespace hinge_projection_test
