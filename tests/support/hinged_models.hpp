// Small hinged models that several test folders build (tests/kernel against `penalty`,
// tests/modal against the exact condensation): the geometry, members and hinges only, so that
// each test adds its own loads, section and settings. Sizes: `star_joint_sizes` and
// `hinge_chain_sizes` plus whatever the test adds (time functions, loads).
#pragma once

#include "ntn/model_spec.hpp"
#include "support/builders.hpp"
#include "support/hinges.hpp"

namespace ntn_test {

// ---- Star joint: node 0 is the joint (a point mass with rotary inertia: the penalty springs
// need a mass on both sides), members along +x, +y, -x and +z, each from its own end node at the
// joint to a clamped far end, two elements each; node 3 is the middle of member 1. Four hinge
// frames, four sets of behaviours:
//   1: rigid in all six, member frame;
//   2: pinned about local y, frame turned 25 degrees about the member axis;
//   3: free about local z, a torsion spring about local x, frame turned -40 degrees about the
//      member axis and 15 about global z;
//   4: free about local x and y, the skewed frame (30 + 20 degrees).
constexpr ntn::Sizes star_joint_sizes(ntn::Sizes extra = {}) {
  extra.nodes = 13, extra.elements = 8, extra.hinges = 4;
  return extra;
}

// Resets `s` and builds the star; returns the builder's complete().
template <ntn::Sizes S>
bool star_joint(ntn::ModelSpec<S>& s, const Section& member) {
  using B = ntn::HingeBehaviour;
  s = {};
  FrameBuilder<S> f(s);
  const int joint = f.add_node({0, 0, 0});
  s.nodes[static_cast<std::size_t>(joint)].added = {20, 20, 20, 0.2, 0.2, 0.2};
  const Vec3 far[4] = {{2, 0, 0}, {0, 1.8, 0}, {-2.2, 0, 0}, {0, 0, 2}};
  const Vec3 ref[4] = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {1, 0, 0}};
  int end[4];
  for (int m = 0; m < 4; ++m) {
    end[m] = f.add_node({0, 0, 0});
    const int tip = f.add_node(far[m], kFixedAll);
    f.add_member(end[m], tip, 2, kSteel, member, ref[m]);
  }
  Mat3 frame[4];
  for (int m = 0; m < 4; ++m)
    frame[m] = member_frame({0, 0, 0}, far[m], ref[m]);
  s.hinges[0] = hinge(end[0], joint, frame[0]);
  s.hinges[1] = hinge(end[1], joint, rotate_frame(frame[1], rotation(far[1], 25 * kDegree)),
                      released(1U << ntn::kRy));
  Mat3 f3 = rotate_frame(frame[2], rotation(far[2], -40 * kDegree));
  f3 = rotate_frame(f3, rotation({0, 0, 1}, 15 * kDegree));
  s.hinges[2] = hinge(end[2], joint, f3, released(1U << ntn::kRz));
  s.hinges[2].behaviour[ntn::kRx] = B::kLinear;
  s.hinges[2].stiffness[ntn::kRx] = 2e5;  // N m/rad
  s.hinges[3] =
      hinge(end[3], joint, skewed_frame(frame[3]), released((1U << ntn::kRx) | (1U << ntn::kRy)));
  return f.complete();
}

// ---- Chain of three hinges on four coincident nodes at (2, 0, 0): A (node 1, the end of a beam
// from the clamped origin), plates B (node 2) and C (node 3) with point masses, D (node 4, the
// end of a beam to the clamped (4, 0, 0)). Hinges A-B pinned about local y, C-B free about a
// local z turned 35 degrees about the axis, D-C a torsion spring about local x in the skewed
// frame, rigid otherwise. B is the root (most rigid hinges, heavier than C), so D hangs two
// hinges below it.
constexpr ntn::Sizes hinge_chain_sizes(ntn::Sizes extra = {}) {
  extra.nodes = 8, extra.elements = 4, extra.hinges = 3;
  return extra;
}

// Resets `s` and builds the chain; returns the builder's complete().
template <ntn::Sizes S>
bool hinge_chain(ntn::ModelSpec<S>& s, const Section& member) {
  using B = ntn::HingeBehaviour;
  s = {};
  FrameBuilder<S> f(s);
  const int left = f.add_node({0, 0, 0}, kFixedAll);
  const int a = f.add_node({2, 0, 0});
  const int b = f.add_node({2, 0, 0});
  const int c = f.add_node({2, 0, 0});
  const int d = f.add_node({2, 0, 0});
  const int right = f.add_node({4, 0, 0}, kFixedAll);
  s.nodes[static_cast<std::size_t>(b)].added = {30, 30, 30, 0.3, 0.3, 0.3};
  s.nodes[static_cast<std::size_t>(c)].added = {15, 15, 15, 0.15, 0.15, 0.15};
  f.add_member(left, a, 2, kSteel, member, {0, 0, 1});
  f.add_member(d, right, 2, kSteel, member, {0.3, 0, 1});
  const Mat3 axes = member_frame({0, 0, 0}, {1, 0, 0}, {0, 0, 1});
  s.hinges[0] = hinge(a, b, axes, released(1U << ntn::kRy));
  s.hinges[1] =
      hinge(c, b, rotate_frame(axes, rotation({1, 0, 0}, 35 * kDegree)), released(1U << ntn::kRz));
  s.hinges[2] = hinge(d, c, skewed_frame(axes));
  s.hinges[2].behaviour[ntn::kRx] = B::kLinear;
  s.hinges[2].stiffness[ntn::kRx] = 5e4;  // N m/rad
  return f.complete();
}

}  // namespace ntn_test
