// The stop joint (DESIGN §7.1, the momentum clamp), shared by tests/validation/hinge_stops_test
// (the whole model run) and tests/kernel/clamp_test (clamp.hpp alone on it): a column with two
// beams hinged to its top, each with rotational play of +-kPlay about its own y axis and rigid
// stops beyond it (a curve with steep ends), free about z, rigid otherwise.
#pragma once

#include <cstddef>
#include <cstdint>

#include "ntn/model_spec.hpp"
#include "support/builders.hpp"
#include "support/hinges.hpp"

namespace ntn_test::stop_joint {

constexpr double kPlay = 1e-3;  // rad
constexpr double kH = 3.0, kSpan = 4.0;
// Column 0 (base, fixed) - 8 - 1 (top, the joint). Left beam 3 (fixed) - 6 - 2, right beam
// 4 - 7 - 5 (fixed); nodes 2 and 4 sit at the joint and are hinged to it.
constexpr int kJoint = 1, kLeftEnd = 2, kRightEnd = 4;
constexpr ntn::Sizes kSizes{.nodes = 9, .elements = 6, .hinges = 2, .curves = 1, .curve_points = 4};

// Writes the joint's nodes, members, curve and hinges into `s` (cleared first) under `method`
// (penalty springs 1e12 N/m and 1e11 N m/rad); loads, time functions and dt are the caller's.
template <ntn::Sizes S>
void build(ntn::ModelSpec<S>& s, ntn::HingeMethod method) {
  static_assert(S.nodes >= kSizes.nodes && S.elements >= kSizes.elements &&
                S.hinges >= kSizes.hinges && S.curves >= 1 && S.curve_points == 4);
  s = {};
  auto node = [&](int n, double x, double z, std::uint8_t fixed) {
    s.nodes[static_cast<std::size_t>(n)] = ntn::NodeSpec{};
    s.nodes[static_cast<std::size_t>(n)].x = x;
    s.nodes[static_cast<std::size_t>(n)].z = z;
    s.nodes[static_cast<std::size_t>(n)].fixed = fixed;
  };
  node(0, 0, 0, kFixedAll);
  node(8, 0, kH / 2, 0);
  node(kJoint, 0, kH, 0);
  node(3, -kSpan, kH, kFixedAll);
  node(6, -kSpan / 2, kH, 0);
  node(kLeftEnd, 0, kH, 0);
  node(kRightEnd, 0, kH, 0);
  node(7, kSpan / 2, kH, 0);
  node(5, kSpan, kH, kFixedAll);
  const int members[6][2] = {{0, 8}, {8, kJoint}, {3, 6}, {6, kLeftEnd}, {kRightEnd, 7}, {7, 5}};
  for (int e = 0; e < 6; ++e) {
    s.elements[static_cast<std::size_t>(e)] =
        element(members[e][0], members[e][1], kSteel, rectangle(0.15, 0.3),
                e < 2 ? Vec3{1, 0, 0} : Vec3{0, 0, 1});
  }
  // Beam frames: x along +x, z up, y = z x x = +y. Rigid but for ry (the curve) and rz (free).
  s.curve_points = {{{-1.1 * kPlay, -1e9}, {-kPlay, 0.0}, {kPlay, 0.0}, {1.1 * kPlay, 1e9}}};
  s.curves[0] = {0, 4};
  s.settings.limit_stiffness = 1e12;
  s.settings.limit_rotational_stiffness = 1e11;
  for (int h = 0; h < 2; ++h) {
    ntn::HingeSpec& hs = s.hinges[static_cast<std::size_t>(h)];
    hs = hinge(h == 0 ? kLeftEnd : kRightEnd, kJoint, kIdentity3);
    hs.behaviour[ntn::kRy] = ntn::HingeBehaviour::kCurve;
    hs.curve[ntn::kRy] = 0;
    hs.behaviour[ntn::kRz] = ntn::HingeBehaviour::kFree;
  }
  s.settings.hinge_method = method;
  s.settings.penalty_stiffness = 1e12;
  s.settings.penalty_rotational_stiffness = 1e11;
}

}  // namespace ntn_test::stop_joint
