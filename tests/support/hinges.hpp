// Builders for models with NTN hinges (DESIGN §7): hinge frames from rotations, a member's own
// local frame, hinge specs, and a straight beam split at one node by a hinge. No heap, no
// exceptions. Frames are built here from first principles (Rodrigues' formula, DESIGN §3's
// member axes), not with the kernel's functions.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "ntn/modal/assembly.hpp"
#include "ntn/model.hpp"
#include "ntn/model_spec.hpp"
#include "ntn/time_step.hpp"
#include "support/builders.hpp"

namespace ntn_test {

using Mat3 = std::array<double, 9>;  // row-major

inline constexpr Mat3 kIdentity3{1, 0, 0, 0, 1, 0, 0, 0, 1};
inline constexpr double kDegree = 3.14159265358979323846 / 180.0;

inline Mat3 mat3_mul(const Mat3& a, const Mat3& b) {
  Mat3 c{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      double s = 0;
      for (int k = 0; k < 3; ++k)
        s += a[static_cast<std::size_t>(3 * i + k)] * b[static_cast<std::size_t>(3 * k + j)];
      c[static_cast<std::size_t>(3 * i + j)] = s;
    }
  }
  return c;
}

inline Mat3 transpose(const Mat3& a) {
  return {a[0], a[3], a[6], a[1], a[4], a[7], a[2], a[5], a[8]};
}

// Rotation by `angle` (rad) about the unit vector `axis` (Rodrigues): R v rotates v.
inline Mat3 rotation(const Vec3& axis, double angle) {
  const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  const double x = axis[0] / n, y = axis[1] / n, z = axis[2] / n;
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  return {t * x * x + c,     t * x * y - s * z, t * x * z + s * y, t * x * y + s * z, t * y * y + c,
          t * y * z - s * x, t * x * z - s * y, t * y * z + s * x, t * z * z + c};
}

// A member's local frame (DESIGN §3), rows x, y, z in global: x from a to b, z in the plane of
// x and `ref`, y = z x x.
inline Mat3 member_frame(const Vec3& a, const Vec3& b, const Vec3& ref) {
  Vec3 x{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double lx = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  for (double& c : x)
    c /= lx;
  const double along = ref[0] * x[0] + ref[1] * x[1] + ref[2] * x[2];
  Vec3 z{ref[0] - along * x[0], ref[1] - along * x[1], ref[2] - along * x[2]};
  const double lz = std::sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
  for (double& c : z)
    c /= lz;
  const Vec3 y{z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]};
  return {x[0], x[1], x[2], y[0], y[1], y[2], z[0], z[1], z[2]};
}

// A frame (rows = axes in global) whose axes are those of `frame` turned by the rotation Q
// (given in global): new axis i = Q (old axis i), so new rows = old rows Q^T.
inline Mat3 rotate_frame(const Mat3& frame, const Mat3& Q) {
  return mat3_mul(frame, transpose(Q));
}

// The skewed hinge frame: the member frame turned 30 degrees about the member axis, then
// 20 degrees about the (turned) local z axis.
inline Mat3 skewed_frame(const Mat3& member) {
  const Vec3 x{member[0], member[1], member[2]};
  const Mat3 f1 = rotate_frame(member, rotation(x, 30 * kDegree));
  const Vec3 z1{f1[6], f1[7], f1[8]};
  return rotate_frame(f1, rotation(z1, 20 * kDegree));
}

using Behaviour = ntn::HingeBehaviour;
inline constexpr std::array<Behaviour, 6> kAllRigid{};  // kRigid is the enum's zero

// Rigid in every direction except `released` (bits), which are free.
inline std::array<Behaviour, 6> released(std::uint8_t bits) {
  std::array<Behaviour, 6> b{};
  for (std::size_t k = 0; k < 6; ++k)
    b[k] = ((bits >> k) & 1U) ? Behaviour::kFree : Behaviour::kRigid;
  return b;
}

inline ntn::HingeSpec hinge(int node1, int node2, const Mat3& frame,
                            const std::array<Behaviour, 6>& behaviour = kAllRigid,
                            const Vec3& eccentricity = {0, 0, 0}) {
  ntn::HingeSpec h;
  h.node1 = node1, h.node2 = node2;
  h.frame = frame;
  h.behaviour = behaviour;
  h.eccentricity = eccentricity;
  return h;
}

// A straight beam of S.elements equal elements (see straight_beam) cut at node `cut`: node
// `extra` (an index >= S.elements + 1) is placed at node `cut`, and the elements after the cut
// start from it. The caller adds the hinge between `extra` (node 1, the right member's end) and
// `cut` (node 2, the joint).
template <ntn::Sizes S>
void split_beam(ntn::ModelSpec<S>& spec, double length, const Material& m, const Section& s,
                int cut, int extra, std::uint8_t fixed_first, std::uint8_t fixed_last,
                const Vec3& axis = {1, 0, 0}, const Vec3& ref = {0, 0, 1}) {
  straight_beam(spec, length, m, s, fixed_first, fixed_last, axis, ref);
  spec.nodes[static_cast<std::size_t>(extra)] = spec.nodes[static_cast<std::size_t>(cut)];
  spec.nodes[static_cast<std::size_t>(extra)].fixed = 0;
  spec.elements[static_cast<std::size_t>(cut)].node_i = extra;
}

inline Vec3 position(const ntn::NodeSpec& n) {
  return {n.x, n.y, n.z};
}

// A triangular load pulse 0 -> 1 -> 0 over [0, duration] (time-function points).
inline std::array<ntn::TimePoint, 3> triangle_pulse(double duration) {
  return {{{0.0, 0.0}, {0.5 * duration, 1.0}, {duration, 0.0}}};
}

// The stable-step report of a hinged model as init computes it: the elements' bound and the
// hinges' springs with the lumped masses (DESIGN §6).
template <ntn::Sizes S>
ntn::StableStepReport hinged_stable_step(const ntn::ModelSpec<S>& spec) {
  return ntn::stable_time_step(ntn::view(spec), ntn::modal::lumped_mass(ntn::view(spec)));
}

}  // namespace ntn_test
