// Hinged models for the modal analysis tests: each joint kind the constraint transformation
// u = T q must handle (tools/modal/include/ntn/modal/constraints.hpp), built with the tests'
// builders (tests/support), and helpers to compare frequencies.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "ntn/modal/modal.hpp"
#include "support/assemble.hpp"
#include "support/builders.hpp"
#include "support/hinged_models.hpp"
#include "support/hinges.hpp"

namespace modal_test {

using ntn_test::Mat3;
using ntn_test::Vec3;
using B = ntn::HingeBehaviour;

inline constexpr ntn_test::Section kMember = ntn_test::rectangle(0.1, 0.15);
inline constexpr ntn_test::Section kColumn = ntn_test::rectangle(0.2, 0.2);

// Largest relative difference of the first `count` frequencies: omega_a / omega_b - 1.
inline double max_relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                                      int count) {
  double d = 0;
  for (int i = 0; i < count; ++i)
    d = std::max(d, std::abs(a(i) / b(i) - 1.0));
  return d;
}

// The library's first `count` frequencies against an independent reference (the tests' dense
// null-space condensation, support/assemble.hpp): prints both and returns the largest relative
// difference.
inline double compare_with_reference(const char* name, const ntn::modal::ModalResult& r,
                                     const ntn_test::Modes& ref, int count) {
  EXPECT_TRUE(r.ok()) << name << ": " << r.error;
  if (!r.ok() || r.modes() < count || ref.omega.size() < count) return 1.0;
  const double d = max_relative_difference(r.omega, ref.omega, count);
  std::printf("  %s: %d coordinates, %d trees; f1..f%d =", name, r.coordinates, r.trees, count);
  for (int i = 0; i < count; ++i)
    std::printf(" %.5f", r.frequency(i));
  std::printf(" Hz; max |lib / ref - 1| = %.2e\n", d);
  return d;
}

// ---- Star joint (support/hinged_models.hpp): four members, four hinge frames on one node.
inline constexpr ntn::Sizes kStar = ntn_test::star_joint_sizes();

inline void build_star(ntn::ModelSpec<kStar>& s) {
  EXPECT_TRUE(ntn_test::star_joint(s, kMember));
}

// ---- Eccentric chain: a connector plate P (point mass and inertia) at (2.1, 0, 0.05) between
// the end A of a beam from the clamped origin to (2, 0, 0) and the end C of a beam from
// (2.2, 0, 0) to the clamped (4.2, 0, 0). Both hinges have the plate as node 1 (e = x_end - x_P),
// so the plate is the root (two rigid hinges) and both beam ends hang below it as node 2: the
// child-is-node-2 form of the elimination, with eccentricity and released rotations. P-A is
// free about a turned local y; P-C is free about local z with a spring about local x, in the
// skewed frame.
inline constexpr ntn::Sizes kEccentricChain{.nodes = 9, .elements = 6, .hinges = 2};

inline void build_eccentric_chain(ntn::ModelSpec<kEccentricChain>& s) {
  s = {};
  ntn_test::FrameBuilder<kEccentricChain> f(s);
  const int left = f.add_node({0, 0, 0}, ntn_test::kFixedAll);
  const int a = f.add_node({2, 0, 0});
  const int p = f.add_node({2.1, 0, 0.05});
  const int c = f.add_node({2.2, 0, 0});
  const int right = f.add_node({4.2, 0, 0}, ntn_test::kFixedAll);
  s.nodes[static_cast<std::size_t>(p)].added = {25, 25, 25, 0.25, 0.3, 0.2};
  f.add_member(left, a, 3, ntn_test::kSteel, kMember, {0, 0, 1});
  f.add_member(c, right, 3, ntn_test::kSteel, kMember, {0.3, 0, 1});
  EXPECT_TRUE(f.complete());
  const Mat3 member = ntn_test::member_frame({0, 0, 0}, {1, 0, 0}, {0, 0, 1});
  const auto at = [&s](int n) { return ntn_test::position(s.nodes[static_cast<std::size_t>(n)]); };
  auto ecc = [&at](int n1, int n2) {
    const Vec3 x1 = at(n1), x2 = at(n2);
    return Vec3{x2[0] - x1[0], x2[1] - x1[1], x2[2] - x1[2]};
  };
  s.hinges[0] = ntn_test::hinge(
      p, a, ntn_test::rotate_frame(member, ntn_test::rotation({1, 0, 0}, 35 * ntn_test::kDegree)),
      ntn_test::released(1U << ntn::kRy), ecc(p, a));
  s.hinges[1] = ntn_test::hinge(p, c, ntn_test::skewed_frame(member),
                                ntn_test::released(1U << ntn::kRz), ecc(p, c));
  s.hinges[1].behaviour[ntn::kRx] = B::kLinear;
  s.hinges[1].stiffness[ntn::kRx] = 5e4;  // N m/rad
}

// ---- Chain of three hinges on coincident nodes (support/hinged_models.hpp): B is the root; D
// hangs two hinges below it.
inline constexpr ntn::Sizes kChain = ntn_test::hinge_chain_sizes();

inline void build_chain(ntn::ModelSpec<kChain>& s) {
  EXPECT_TRUE(ntn_test::hinge_chain(s, kMember));
}

// ---- Supports through hinges: a column (3 m, 3 elements) on an inclined roller, and a beam
// (3 m, 3 elements) from the column top to a pinned support. The column base is tied to the
// ground by a hinge whose frame is the global frame turned 30 degrees about y and 20 about the
// new z, rigid in its local x and z, free along its local y and in rotation: an inclined support
// (a tree rooted at the ground). The beam's start E is pinned to the column top (free about the
// beam's local y); its end F is joined to a clamped node N, rigid except about the beam's local y
// (= global y): a pinned support made of a hinge, a tree rooted at the supported node.
inline constexpr ntn::Sizes kSupported{.nodes = 9, .elements = 6, .hinges = 3};

inline Mat3 inclined_frame() {
  const Mat3 f = ntn_test::rotate_frame(ntn_test::kIdentity3,
                                        ntn_test::rotation({0, 1, 0}, 30 * ntn_test::kDegree));
  return ntn_test::rotate_frame(f, ntn_test::rotation({f[6], f[7], f[8]}, 20 * ntn_test::kDegree));
}

inline void build_supported(ntn::ModelSpec<kSupported>& s) {
  s = {};
  ntn_test::FrameBuilder<kSupported> f(s);
  const int base = f.add_node({0, 0, 0});
  const int top = f.add_node({0, 0, 3});
  const int e = f.add_node({0, 0, 3});
  const int end = f.add_node({3, 0, 3});
  const int pin = f.add_node({3, 0, 3}, ntn_test::kFixedAll);
  f.add_member(base, top, 3, ntn_test::kSteel, kColumn, {1, 0, 0});
  f.add_member(e, end, 3, ntn_test::kSteel, kMember, {0, 0, 1});
  EXPECT_TRUE(f.complete());
  ntn::HingeSpec ground;
  ground.node1 = base, ground.node2 = ntn::kGround;
  ground.frame = inclined_frame();
  ground.behaviour = {B::kRigid, B::kFree, B::kRigid, B::kFree, B::kFree, B::kFree};
  s.hinges[0] = ground;
  const Mat3 beam = ntn_test::member_frame({0, 0, 3}, {3, 0, 3}, {0, 0, 1});
  s.hinges[1] = ntn_test::hinge(e, top, beam, ntn_test::released(1U << ntn::kRy));
  s.hinges[2] = ntn_test::hinge(end, pin, beam, ntn_test::released(1U << ntn::kRy));
}

}  // namespace modal_test
