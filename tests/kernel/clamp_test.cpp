// clamp.hpp alone (DESIGN §7.1, clamp = "momentum"): the momentum clamp called on a State set by
// hand, without a step. Two beam ends hinged to one joint, each with rotational play about y
// and rigid stops beyond it (support/stop_joint.hpp, shared with hinge_stops_test). What must
// hold:
// - one stop between two lone nodes (penalty: no rigid tree): d lands on its limit (to 1e-14
//   relative: the excess is removed by one product and one division), only the two nodes move,
//   and the moment pair is equal and opposite, so sum I dphi over the two nodes stays zero (to
//   1e-12 of one node's share: two roundings of products of the same size);
// - two stops squeezing one joint from both sides, in one rigid tree (ntn_exact): the tree solve
//   lands both on their limits at once (to 1e-14 relative), the rigid directions of the tree stay
//   exact (1e-15 of the play) and the momentum is kept (1e-12, as above);
// - v and a follow a move as du / dt and du / dt^2 (S 35-37, to 1e-12 relative: du is recovered
//   as a difference of u);
// - a stop inside its play moves nothing (every bit of the State stays);
// - the clamp works in its own workspace (Scratch::clamp): F_n and the coupled R in the scratch
//   keep their bits (the outputs of the step read them).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "ntn/kernel.hpp"
#include "support/builders.hpp"
#include "support/hinges.hpp"
#include "support/init_model.hpp"
#include "support/stop_joint.hpp"

namespace clamp_test {

using ntn_test::dof;
using B = ntn::HingeBehaviour;
using ntn_test::stop_joint::kJoint;
using ntn_test::stop_joint::kLeftEnd;
using ntn_test::stop_joint::kPlay;
using ntn_test::stop_joint::kRightEnd;
using ntn_test::stop_joint::kSizes;

ntn_test::Sim<kSizes> sim;

void build(ntn::HingeMethod method) {
  auto& s = sim.spec;
  ntn_test::stop_joint::build(s, method);
  s.settings.dt = 1e-5;
  s.settings.allow_unstable = true;  // the step is never taken here
}

// d of direction k of hinge h (node 1 = the beam end, node 2 = the joint): phi_joint - phi_end.
double hinge_d(int h, int k) {
  const ntn::HingeData& hd = sim.model.hinges[static_cast<std::size_t>(h)];
  double d[6];
  hinge_relative(hd, &sim.state.u[dof(hd.node1, 0)], &sim.state.u[dof(hd.node2, 0)], d);
  return d[k];
}

// The scratch as a step leaves it before the stops: F_n and R set to recognizable values.
void fill_scratch() {
  auto& w = sim.scratch;
  ntn::detail::step_weights(sim.model, w);  // the moves of a step
  for (std::size_t j = 0; j < w.f.size(); ++j) {
    w.f[j] = 1.0 + static_cast<double>(j);
    w.r[j] = -2.0 - static_cast<double>(j);
    w.a[j] = 0.0;
  }
  sim.state.v = {};
}

void expect_scratch_forces_kept() {
  const auto& w = sim.scratch;
  for (std::size_t j = 0; j < w.f.size(); ++j) {
    EXPECT_EQ(w.f[j], 1.0 + static_cast<double>(j)) << "F_n at DOF " << j;
    EXPECT_EQ(w.r[j], -2.0 - static_cast<double>(j)) << "R at DOF " << j;
  }
}

// v and a of every DOF follow the move of u (S 35-37): du / dt and du / dt^2 (v, a zero
// before). Several moves add up at a DOF, so the tolerance is relative to the largest move.
void expect_follow(const std::array<double, ntn::State<kSizes>::kDofs>& u0) {
  const double inv_dt = sim.model.inv_dt;
  double largest = 0;
  for (std::size_t j = 0; j < u0.size(); ++j)
    largest = std::max(largest, std::abs(sim.state.u[j] - u0[j]));
  ASSERT_GT(largest, 0.0);
  for (std::size_t j = 0; j < u0.size(); ++j) {
    const double du = sim.state.u[j] - u0[j];
    EXPECT_NEAR(sim.state.v[j], du * inv_dt, 1e-12 * largest * inv_dt) << j;
    EXPECT_NEAR(sim.scratch.a[j], du * inv_dt * inv_dt, 1e-12 * largest * inv_dt * inv_dt) << j;
  }
}

double total_ry_momentum(const std::array<double, ntn::State<kSizes>::kDofs>& v) {
  double sum = 0;
  for (std::size_t n = 0; n < kSizes.nodes; ++n)
    sum += sim.model.mass[dof(n, ntn::kRy)] * v[dof(n, ntn::kRy)];
  return sum;
}

TEST(Clamp, OneStopBetweenLoneNodesLandsOnItsLimitAndKeepsMomentum) {
  build(ntn::HingeMethod::kPenalty);
  ASSERT_TRUE(ntn_test::init_model(sim.spec, sim.model).ok());
  ASSERT_EQ(sim.model.num_trees, 0);  // penalty: every node is a part of its own
  sim.state = {};
  fill_scratch();
  // The left end turned past its upper stop: d = 0 - (-1.5 play); the right one inside.
  sim.state.u[dof(kLeftEnd, ntn::kRy)] = -1.5 * kPlay;
  sim.state.u[dof(kRightEnd, ntn::kRy)] = -0.5 * kPlay;
  const auto u0 = sim.state.u;
  ntn::detail::momentum_clamp(sim.model, sim.state, sim.scratch);

  EXPECT_NEAR(hinge_d(0, ntn::kRy), kPlay, 1e-14 * kPlay);
  EXPECT_LT(std::abs(hinge_d(1, ntn::kRy)), kPlay);  // the right stop stays inside its play
  EXPECT_EQ(sim.state.u[dof(kRightEnd, ntn::kRy)], u0[dof(kRightEnd, ntn::kRy)]);
  for (std::size_t n = 0; n < kSizes.nodes; ++n) {
    if (n == kLeftEnd || n == kJoint) continue;
    for (int d = 0; d < 6; ++d)
      EXPECT_EQ(sim.state.u[dof(n, d)], u0[dof(n, d)]) << "node " << n << " DOF " << d;
  }
  // The moment pair: I_end dphi_end = -I_joint dphi_joint, both nonzero.
  const double share =
      sim.model.mass[dof(kLeftEnd, ntn::kRy)] * sim.state.v[dof(kLeftEnd, ntn::kRy)];
  EXPECT_NE(share, 0.0);
  EXPECT_NE(sim.state.v[dof(kJoint, ntn::kRy)], 0.0);
  EXPECT_NEAR(total_ry_momentum(sim.state.v), 0.0, 1e-12 * std::abs(share));
  expect_follow(u0);
  expect_scratch_forces_kept();
}

TEST(Clamp, TwoStopsSqueezingOneJointInOneTreeLandTogether) {
  build(ntn::HingeMethod::kNtnExact);
  ASSERT_TRUE(ntn_test::init_model(sim.spec, sim.model).ok());
  ASSERT_EQ(sim.model.num_trees, 1);  // the joint and both beam ends
  ASSERT_EQ(sim.model.trees[0].end_stop - sim.model.trees[0].first_stop, 2);
  sim.state = {};
  fill_scratch();
  // Left past its upper stop, right past its lower one: each push turns the joint into the
  // other stop, so clamped one at a time they reopen each other.
  sim.state.u[dof(kLeftEnd, ntn::kRy)] = -1.5 * kPlay;
  sim.state.u[dof(kRightEnd, ntn::kRy)] = 1.2 * kPlay;
  const auto u0 = sim.state.u;
  const std::int64_t events = sim.scratch.clamp.events;
  ntn::detail::momentum_clamp(sim.model, sim.state, sim.scratch);

  EXPECT_NEAR(hinge_d(0, ntn::kRy), kPlay, 1e-14 * kPlay);
  EXPECT_NEAR(hinge_d(1, ntn::kRy), -kPlay, 1e-14 * kPlay);
  // One tree solve: one clamp event (clamped one at a time, each clamp is an event, and stops
  // that squeeze one joint take many).
  EXPECT_EQ(sim.scratch.clamp.events - events, 1);
  // The rigid directions of both hinges (ux, uy, uz, rx) stay exact.
  for (int h = 0; h < 2; ++h) {
    for (int k = 0; k < 4; ++k)
      EXPECT_NEAR(hinge_d(h, k), 0.0, 1e-15 * kPlay) << "hinge " << h << " direction " << k;
  }
  double largest = 0;
  for (int n : {kLeftEnd, kRightEnd, kJoint}) {
    largest = std::max(largest,
                       std::abs(sim.model.mass[dof(n, ntn::kRy)] * sim.state.v[dof(n, ntn::kRy)]));
  }
  EXPECT_GT(largest, 0.0);
  EXPECT_NEAR(total_ry_momentum(sim.state.v), 0.0, 1e-12 * largest);
  expect_follow(u0);
  expect_scratch_forces_kept();
}

TEST(Clamp, StopsInsideTheirPlayMoveNothing) {
  for (ntn::HingeMethod method : {ntn::HingeMethod::kNtnExact, ntn::HingeMethod::kPenalty}) {
    build(method);
    ASSERT_TRUE(ntn_test::init_model(sim.spec, sim.model).ok());
    sim.state = {};
    fill_scratch();
    sim.state.u[dof(kLeftEnd, ntn::kRy)] = -0.999 * kPlay;
    sim.state.u[dof(kRightEnd, ntn::kRy)] = 0.999 * kPlay;
    sim.state.u[dof(kJoint, ntn::kUx)] = 1e-3;  // rigid directions moved alike
    sim.state.u[dof(kLeftEnd, ntn::kUx)] = 1e-3;
    sim.state.u[dof(kRightEnd, ntn::kUx)] = 1e-3;
    const ntn::State<kSizes> before = sim.state;
    ntn::detail::momentum_clamp(sim.model, sim.state, sim.scratch);
    EXPECT_EQ(std::memcmp(&before.u, &sim.state.u, sizeof(before.u)), 0);
    EXPECT_EQ(std::memcmp(&before.v, &sim.state.v, sizeof(before.v)), 0);
    expect_scratch_forces_kept();
  }
}

// Two beams, each of two elements hinged in the middle with a stop in ry: two rigid trees, one
// stop each. init() into a Model that held a model before must give the same stop ranges: the
// counts once started from the old ones, so the second tree's range ran past Model::tree_stops
// and the writes corrupted the memory after it.
constexpr ntn::Sizes kTwoTrees{
    .nodes = 8, .elements = 4, .hinges = 2, .curves = 1, .curve_points = 4};

TEST(Clamp, StopRangesOfTwoTreesAreTheSameWhenAModelIsBuiltAgain) {
  static ntn::ModelSpec<kTwoTrees> spec;
  static ntn::Model<kTwoTrees> model;
  for (int b = 0; b < 2; ++b) {
    const double y = 5.0 * b;
    const int n = 4 * b;
    auto node = [&](int i, double x, std::uint8_t fixed) {
      spec.nodes[static_cast<std::size_t>(n + i)] = ntn::NodeSpec{};
      spec.nodes[static_cast<std::size_t>(n + i)].x = x;
      spec.nodes[static_cast<std::size_t>(n + i)].y = y;
      spec.nodes[static_cast<std::size_t>(n + i)].fixed = fixed;
    };
    node(0, 0.0, ntn_test::kFixedAll);
    node(1, 3.0, 0);
    node(2, 3.0, 0);  // the second element's end, hinged to node 1
    node(3, 6.0, ntn_test::kFixedAll);
    for (int e = 0; e < 2; ++e) {
      spec.elements[static_cast<std::size_t>(2 * b + e)] =
          ntn_test::element(n + 2 * e, n + 2 * e + 1, ntn_test::kSteel,
                            ntn_test::rectangle(0.15, 0.3), ntn_test::Vec3{0, 0, 1});
    }
    ntn::HingeSpec& hs = spec.hinges[static_cast<std::size_t>(b)];
    hs = ntn_test::hinge(n + 2, n + 1, ntn_test::kIdentity3);
    hs.behaviour[ntn::kRy] = B::kCurve;
    hs.curve[ntn::kRy] = 0;
    hs.behaviour[ntn::kRz] = B::kFree;
  }
  spec.curve_points = {{{-1.1 * kPlay, -1e9}, {-kPlay, 0.0}, {kPlay, 0.0}, {1.1 * kPlay, 1e9}}};
  spec.curves[0] = {0, 4};
  spec.settings.limit_rotational_stiffness = 1e11;
  spec.settings.dt = 1e-5;
  spec.settings.allow_unstable = true;
  for (int build = 0; build < 2; ++build) {
    ASSERT_TRUE(ntn_test::init_model(spec, model).ok()) << "build " << build;
    ASSERT_EQ(model.num_trees, 2);
    for (int t = 0; t < 2; ++t) {
      EXPECT_EQ(model.trees[static_cast<std::size_t>(t)].first_stop, t) << "build " << build;
      EXPECT_EQ(model.trees[static_cast<std::size_t>(t)].end_stop, t + 1) << "build " << build;
    }
  }
}

}  // namespace clamp_test
