// NTN hinges (DESIGN §7, seed S 11-16): hinge geometry, relative displacement d_L = B u,
// spring and dashpot forces B^T f_L, force-deformation curves with rigid branches.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>

#include "ntn/hysteresis.hpp"
#include "ntn/model_spec.hpp"
#include "ntn/rotation.hpp"

namespace ntn {

// Where a curve stops being a spring: outside [lower, upper] the curve is a rigid branch.
struct CurveBranches {
  double lower = -1e300;  // m or rad; -1e300: no rigid branch below
  double upper = 1e300;   // m or rad; +1e300: no rigid branch above
  double max_slope = 0;   // N/m or N m/rad, steepest non-rigid segment (for the stable step)
  bool valid = false;     // at least one non-rigid segment, rigid branches only at the ends
  // Why, by segment (segment s joins points s and s + 1): the first and last non-rigid segment
  // (-1: none), and the first rigid segment found between non-rigid ones (-1: none).
  int first = -1;
  int last = -1;
  int inner = -1;
};

// Splits a curve into its spring part and its rigid end branches: segments whose slope is at
// least k_lim are rigid (seed Fig. 2). Rigid segments between spring segments are not valid.
inline CurveBranches curve_branches(std::span<const CurvePoint> points, const CurveSpec& c,
                                    double k_lim) {
  CurveBranches b;
  if (c.count < 2) return b;
  const CurvePoint* p = points.data() + c.first;
  int& first = b.first;
  int& last = b.last;
  for (int s = 0; s + 1 < c.count; ++s) {
    const double dd = p[s + 1].d - p[s].d;
    if (!(dd > 0)) return b;
    const double slope = (p[s + 1].force - p[s].force) / dd;
    if (slope < k_lim) {
      if (first < 0) first = s;
      if (last >= 0 && last != s - 1) {  // a rigid segment between spring segments
        b.inner = last + 1;
        return b;
      }
      last = s;
      if (slope > b.max_slope) b.max_slope = slope;
    }
  }
  if (first < 0) return b;
  if (first > 0) b.lower = p[first].d;
  if (last < c.count - 2) b.upper = p[last + 1].d;
  b.valid = true;
  return b;
}

// Force of a curve at deformation d inside its spring part; the end segments extrapolate.
inline double curve_force(const CurvePoint* p, int count, double d) {
  int s = 0;
  while (s + 2 < count && d > p[s + 1].d)
    ++s;
  const double t = (d - p[s].d) / (p[s + 1].d - p[s].d);
  return p[s].force + t * (p[s + 1].force - p[s].force);
}

// The hinge-axes rule: rows x, y, z of R (global axes) orthonormal to kAxesTolerance (every entry
// of |R R^T - I| below it) and right-handed (det R > 0). The kernel refuses a hinge that breaks it;
// the model compiler names the largest entry or the determinant in its message.
inline constexpr double kAxesTolerance = 1e-9;

struct AxesCheck {
  double worst = 0;  // the largest entry of |R R^T - I| (a NaN entry is passed over, but fails
                     // `orthonormal`)
  double det = 0;    // det R
  bool orthonormal = false;
  bool right_handed = false;
  constexpr bool ok() const { return orthonormal && right_handed; }
};

inline AxesCheck check_axes(const std::array<double, 9>& R) {
  AxesCheck c;
  c.orthonormal = true;
  for (std::size_t a = 0; a < 3; ++a) {
    for (std::size_t b = 0; b < 3; ++b) {
      const double dot =
          R[3 * a] * R[3 * b] + R[3 * a + 1] * R[3 * b + 1] + R[3 * a + 2] * R[3 * b + 2];
      const double want = a == b ? 1.0 : 0.0;
      const double dev = dot > want ? dot - want : want - dot;
      if (!(dev < kAxesTolerance)) c.orthonormal = false;
      if (dev > c.worst) c.worst = dev;
    }
  }
  c.det = R[0] * (R[4] * R[8] - R[5] * R[7]) - R[1] * (R[3] * R[8] - R[5] * R[6]) +
          R[2] * (R[3] * R[7] - R[4] * R[6]);
  c.right_handed = c.det > 0;
  return c;
}

// What step() needs of a hinge: its nodes, frame, eccentricity and per-direction behaviour.
struct HingeData {
  std::int32_t node1 = 0;
  std::int32_t node2 = kGround;
  std::array<double, 9> frame{};         // T_R, rows = hinge axes in global
  std::array<double, 3> eccentricity{};  // m, e = x2 - x1
  std::array<HingeBehaviour, kDofsPerNode> behaviour{};
  std::array<double, kDofsPerNode> stiffness{};          // N/m or N m/rad: linear k, or penalty k_p
  std::array<double, kDofsPerNode> dashpot{};            // N s/m or N m s/rad
  std::array<std::int32_t, kDofsPerNode> curve_first{};  // first point of the curve
  std::array<std::int32_t, kDofsPerNode> curve_count{};
  std::array<double, kDofsPerNode> branch_lower{};  // rigid branch starts (curve directions)
  std::array<double, kDofsPerNode> branch_upper{};
  std::uint8_t springs = 0;   // bit d: direction d carries a spring force (linear, curve, penalty)
  std::uint8_t rigid = 0;     // bit d: a coupled direction, held by the NTN coupling (not penalty)
  std::uint8_t branches = 0;  // bit d: direction d is a curve with a rigid branch (a stop)
  std::uint8_t plastic = 0;   // bit d: direction d is hysteretic (kPlastic; kRigidPlastic
                              // under penalty: a bilinear spring of the penalty stiffness)
  std::uint8_t slip = 0;      // bit d: a rigid-plastic direction held by the slip stage (slip.hpp)
  bool turns = false;         // it turns with its nodes (hinge_turns, model_spec.hpp)
  std::array<std::int32_t, kDofsPerNode> history{};  // kPlastic, kRigidPlastic: its history slot
};

// A hinge's geometry as the step uses it: `frame` maps the nodes' translations to the hinge's
// (rows: hinge axes x, y, z in global), `spin` their rotations, and `arm` is the lever arm from
// node 1 to node 2's point. In linear kinematics spin = frame and arm = e (hinge_pose); a hinge
// that turns with its nodes has them from its nodes' motion now (hinge_turned).
struct HingePose {
  Matrix3 frame{};
  Matrix3 spin{};
  Vector3 arm{};
};

inline HingePose hinge_pose(const HingeData& h) {
  return {h.frame, h.frame, h.eccentricity};
}

// The rows of a turning hinge (corotational geometry) and its relative displacement d, from its
// nodes' translations u1, u2 and total rotations q1, q2 (State::rotation). Node 1's rotation Q1
// carries the hinge's axes and offset: T = T0 Q1^T, e = Q1 e0 (T0, e0 the reference's, e0 =
// X2 - X1). The translations are measured from node 1's rigid link, d_t = T (e0 + u2 - u1 -
// Q1 e0), and the rotations are node 2's relative to node 1 in node 1's axes, d_r = T0 psi with
// psi = log(Q1^T Q2). Their variations over the nodes' velocities and spins w (spatial) are
// d_t' = T (u2' - u1' - w1 x r), r = e0 + u2 - u1 the arm now (the frame's own turning moves
// the gap with it), and d_r' = T0 T_s^-1(psi) Q1^T (w2 - w1) (rotation.hpp's T_s: the relative
// rotation's spin in node 1's axes is Q1^T (w2 - w1)). So the pose is frame = T, spin =
// T0 T_s^-1(psi) Q1^T, arm = r, and hinge_scatter's B^T f is the forces' exact virtual work:
// the energy of a spring is a function of d alone, and a rigid motion of both nodes leaves d
// unchanged (objective). At the reference (Q = 1, u = 0) it is hinge_pose's.
inline HingePose hinge_turned(const HingeData& h, const Quaternion& q1, const Quaternion& q2,
                              const double* u1, const double* u2, double* d) {
  const Vector3& e0 = h.eccentricity;
  const Vector3 r{e0[0] + (u2[0] - u1[0]), e0[1] + (u2[1] - u1[1]), e0[2] + (u2[2] - u1[2])};
  const Vector3 e = rotate(q1, e0);
  const Vector3 gap{r[0] - e[0], r[1] - e[1], r[2] - e[2]};
  const Vector3 psi = log_rotation(product(conjugate(q1), q2));
  HingePose p;
  p.arm = r;
  for (std::size_t k = 0; k < 3; ++k) {
    const Vector3 t0{h.frame[3 * k], h.frame[3 * k + 1], h.frame[3 * k + 2]};
    const Vector3 t = rotate(q1, t0);
    const Vector3 s = rotate(q1, log_tangent_inverse_transpose(psi, t0));
    for (std::size_t c = 0; c < 3; ++c)
      p.frame[3 * k + c] = t[c], p.spin[3 * k + c] = s[c];
    d[k] = dot(t, gap);
    d[k + 3] = dot(t0, psi);
  }
  return p;
}

// Relative displacement in the hinge frame (DESIGN §7):
// d_L = T [u2 - u1 - phi1 x e ; phi2 - phi1]; the ground has u2 = phi2 = 0. With a pose, the
// same rows at the pose's frame, spin and arm (a turning hinge's rates, hinge_turned).
inline void hinge_relative(const HingePose& p, const double* x1, const double* x2, double* d) {
  const auto& R = p.frame;
  const auto& S = p.spin;
  const auto& e = p.arm;
  // the motion of node 1's rigid link at node 2's point: u1 + phi1 x e
  const double w[3] = {x1[0] + (x1[4] * e[2] - x1[5] * e[1]), x1[1] + (x1[5] * e[0] - x1[3] * e[2]),
                       x1[2] + (x1[3] * e[1] - x1[4] * e[0])};
  double g[6];
  for (int k = 0; k < 3; ++k) {
    g[k] = (x2 != nullptr ? x2[k] : 0.0) - w[k];
    g[k + 3] = (x2 != nullptr ? x2[k + 3] : 0.0) - x1[k + 3];
  }
  for (int r = 0; r < 3; ++r) {
    d[r] = R[static_cast<std::size_t>(3 * r)] * g[0] +
           R[static_cast<std::size_t>(3 * r + 1)] * g[1] +
           R[static_cast<std::size_t>(3 * r + 2)] * g[2];
    d[r + 3] = S[static_cast<std::size_t>(3 * r)] * g[3] +
               S[static_cast<std::size_t>(3 * r + 1)] * g[4] +
               S[static_cast<std::size_t>(3 * r + 2)] * g[5];
  }
}

inline void hinge_relative(const HingeData& h, const double* x1, const double* x2, double* d) {
  hinge_relative(hinge_pose(h), x1, x2, d);
}

// Adds the internal force B^T f_L of a hinge force f_L (force on node 1, hinge frame) to the
// nodes' internal force vectors: node 1 gets -[F ; e x F + M], node 2 gets [F ; M] with
// F = T^T f_t, M = T^T f_r (so the force acting on node 1 is +F, on node 2 -F). With a pose,
// M = spin^T f_r and the arm for e.
inline void hinge_scatter(const HingePose& p, const double* f_local, double* f1, double* f2) {
  const auto& R = p.frame;
  const auto& S = p.spin;
  const auto& e = p.arm;
  double F[3], M[3];
  for (int c = 0; c < 3; ++c) {
    F[c] = R[static_cast<std::size_t>(c)] * f_local[0] +
           R[static_cast<std::size_t>(3 + c)] * f_local[1] +
           R[static_cast<std::size_t>(6 + c)] * f_local[2];
    M[c] = S[static_cast<std::size_t>(c)] * f_local[3] +
           S[static_cast<std::size_t>(3 + c)] * f_local[4] +
           S[static_cast<std::size_t>(6 + c)] * f_local[5];
  }
  const double exF[3] = {e[1] * F[2] - e[2] * F[1], e[2] * F[0] - e[0] * F[2],
                         e[0] * F[1] - e[1] * F[0]};
  for (int c = 0; c < 3; ++c) {
    f1[c] -= F[c];
    f1[c + 3] -= exF[c] + M[c];
  }
  if (f2 != nullptr) {
    for (int c = 0; c < 3; ++c) {
      f2[c] += F[c];
      f2[c + 3] += M[c];
    }
  }
}

inline void hinge_scatter(const HingeData& h, const double* f_local, double* f1, double* f2) {
  hinge_scatter(hinge_pose(h), f_local, f1, f2);
}

// Spring and dashpot force on node 1 in the hinge frame, for the directions in `springs`:
// f = k d + c d_dot (linear, penalty), f = F(d) (curve: its spring part; on a rigid branch the
// force at the branch start), f = k (d - d_p) + c d_dot (plastic, d_p its plastic deformation in
// `plastic`, hysteresis.hpp). d_dot from the half-step velocities (explicit, like C v_{n-1/2}).
inline void hinge_spring_force(const HingeData& h, std::span<const CurvePoint> points,
                               std::span<const double> plastic, const double* d,
                               const double* d_dot, double* f) {
  for (std::size_t k = 0; k < kDofsPerNode; ++k) {
    f[k] = 0;
    if (!((h.springs >> k) & 1U)) continue;
    if ((h.plastic >> k) & 1U) {
      const double dp = plastic[static_cast<std::size_t>(h.history[k])];
      f[k] = h.stiffness[k] * (d[k] - dp) + h.dashpot[k] * d_dot[k];
    } else if (h.behaviour[k] == HingeBehaviour::kCurve) {
      double x = d[k];
      if (x < h.branch_lower[k]) x = h.branch_lower[k];
      if (x > h.branch_upper[k]) x = h.branch_upper[k];
      f[k] = curve_force(points.data() + h.curve_first[k], h.curve_count[k], x);
    } else {
      f[k] = h.stiffness[k] * d[k] + h.dashpot[k] * d_dot[k];
    }
  }
}

// Resolves a hinge spec: which directions carry a spring force (`springs`), where curves have
// rigid branches, and, through `rigid_direction(k)`, what the hinge method makes of a rigid
// direction k (make_hinge_data in hinge_methods.hpp: NTN-coupled, `rigid`, or a penalty
// spring). False for a bad spec: node out of range, a frame that is not orthonormal and
// right-handed (to 1e-9), a bad curve, a negative stiffness or dashpot, an eccentric ground
// hinge, a rigid direction the method refuses.
template <class RigidDirection, class SlipDirection>
bool resolve_hinge(const HingeSpec& spec, const Settings& settings, std::size_t node_count,
                   std::span<const CurveSpec> curves, std::span<const CurvePoint> points,
                   HingeData& h, RigidDirection&& rigid_direction, SlipDirection&& slip_direction) {
  h = HingeData{};
  h.node1 = spec.node1, h.node2 = spec.node2;
  h.frame = spec.frame;
  h.eccentricity = spec.eccentricity;
  h.behaviour = spec.behaviour;
  if (spec.node1 < 0 || std::cmp_greater_equal(spec.node1, node_count)) return false;
  if (spec.node2 != kGround && (spec.node2 < 0 || std::cmp_greater_equal(spec.node2, node_count)))
    return false;
  if (spec.node2 == spec.node1) return false;
  if (spec.node2 == kGround &&
      (spec.eccentricity[0] != 0 || spec.eccentricity[1] != 0 || spec.eccentricity[2] != 0))
    return false;
  if (!check_axes(spec.frame).ok()) return false;

  for (std::size_t k = 0; k < kDofsPerNode; ++k) {
    const auto bit = static_cast<std::uint8_t>(1U << k);
    h.branch_lower[k] = -1e300, h.branch_upper[k] = 1e300;
    switch (spec.behaviour[k]) {
      case HingeBehaviour::kRigid:
        if (!rigid_direction(k)) return false;
        break;
      case HingeBehaviour::kFree:
        break;
      case HingeBehaviour::kLinear:
        h.stiffness[k] = spec.stiffness[k];
        h.dashpot[k] = spec.dashpot[k];
        if (!(h.stiffness[k] >= 0) || !(h.dashpot[k] >= 0)) return false;
        h.springs |= bit;
        break;
      case HingeBehaviour::kCurve: {
        const int c = spec.curve[k];
        if (c < 0 || c >= static_cast<int>(curves.size())) return false;
        const CurveSpec& cs = curves[static_cast<std::size_t>(c)];
        if (cs.first < 0 || cs.count < 2 || cs.first + cs.count > static_cast<int>(points.size()))
          return false;
        const CurveBranches b = curve_branches(points, cs, branch_slope_limit(settings, k));
        if (!b.valid) return false;
        h.curve_first[k] = cs.first, h.curve_count[k] = cs.count;
        h.stiffness[k] = b.max_slope;  // for the stable step
        h.branch_lower[k] = b.lower, h.branch_upper[k] = b.upper;
        if (b.lower > -1e300 || b.upper < 1e300) h.branches |= bit;
        h.springs |= bit;
        break;
      }
      case HingeBehaviour::kPlastic:  // its law is checked against the model's (check_references)
        h.stiffness[k] = spec.stiffness[k];
        h.dashpot[k] = spec.dashpot[k];
        if (!(h.stiffness[k] > 0) || !(h.dashpot[k] >= 0) || spec.hysteresis[k] < 0) return false;
        h.history[k] = spec.hysteresis[k];
        h.springs |= bit;
        h.plastic |= bit;
        break;
      case HingeBehaviour::kRigidPlastic:  // what the method makes of it (slip_direction)
        if (spec.hysteresis[k] < 0 || spec.dashpot[k] != 0 || !(spec.stiffness[k] >= 0) ||
            !law_value_ok(spec.stiffness[k]))
          return false;
        h.history[k] = spec.hysteresis[k];
        h.stiffness[k] = spec.stiffness[k];  // its hardening with the slip, if any
        if (!slip_direction(k)) return false;
        break;
    }
  }
  return true;
}

// The generalized direction b of hinge direction k (d_k = b1 . x1 + b2 . x2): for a
// translation b1 = -[t ; e x t], b2 = [t ; 0]; for a rotation b1 = -[0 ; t], b2 = [0 ; t],
// t = row k of the frame.
// The model compiler's and modal analysis' rows of B are this function too (the overload on a
// frame and eccentricity, for a HingeSpec).
inline void hinge_direction(const std::array<double, 9>& frame, const std::array<double, 3>& e,
                            std::size_t k, double* b1, double* b2) {
  const std::size_t row = k % 3;
  const double t[3] = {frame[3 * row], frame[3 * row + 1], frame[3 * row + 2]};
  for (int c = 0; c < 6; ++c)
    b1[c] = 0, b2[c] = 0;
  if (k < 3) {
    const double ext[3] = {e[1] * t[2] - e[2] * t[1], e[2] * t[0] - e[0] * t[2],
                           e[0] * t[1] - e[1] * t[0]};
    for (int c = 0; c < 3; ++c)
      b1[c] = -t[c], b1[c + 3] = -ext[c], b2[c] = t[c];
  } else {
    for (int c = 0; c < 3; ++c)
      b1[c + 3] = -t[c], b2[c + 3] = t[c];
  }
}

inline void hinge_direction(const HingeData& h, std::size_t k, double* b1, double* b2) {
  hinge_direction(h.frame, h.eccentricity, k, b1, b2);
}

// b^T M^-1 b over both nodes for direction k with diagonal masses (0 where a mass is zero and b
// is not: returns +inf then, an infinitely fast mode).
inline double hinge_inverse_mass(const HingeData& h, std::size_t k, const double* m1,
                                 const double* m2) {
  double b1[6], b2[6], w = 0;
  hinge_direction(h, k, b1, b2);
  for (int c = 0; c < 6; ++c) {
    if (b1[c] != 0) w += b1[c] * b1[c] / m1[c];
    if (m2 != nullptr && b2[c] != 0) w += b2[c] * b2[c] / m2[c];
  }
  return w;
}

}  // namespace ntn
