// Hysteretic hinge directions (HingeBehaviour::kPlastic, DESIGN §7): bilinear elasto-plastic with
// kinematic hardening. A direction of elastic stiffness k carries f = k (d - d_p) (+ its dashpot);
// the elastic range is q - yield_neg <= f <= q + yield_pos around the back force q = H d_p, with
// H = b k / (1 - b) so that the tangent after yield is k H / (k + H) = b k. d_p (the plastic
// deformation) and the energy dissipated, the plastic work integral f dd_p, are the direction's
// history in State (State::plastic, State::dissipated): a checkpoint restores them.
#pragma once

#include "ntn/model_spec.hpp"

namespace ntn {

// What the step needs of one hysteretic direction (Model::hystereses).
struct HysteresisData {
  double k = 0;          // N/m or N m/rad, elastic stiffness
  double yield_pos = 0;  // N or N m
  double yield_neg = 0;  // N or N m, as a magnitude
  double H = 0;          // kinematic hardening modulus b k / (1 - b)
  double inv_kH = 0;     // 1 / (k + H)
};

// A law the kernel takes: yields > 0 and finite, hardening in [0, 1).
constexpr bool hysteresis_valid(const HysteresisSpec& s) {
  return s.yield_pos > 0 && s.yield_pos < 1e300 && s.yield_neg > 0 && s.yield_neg < 1e300 &&
         s.hardening >= 0 && s.hardening < 1;
}

inline HysteresisData make_hysteresis(const HysteresisSpec& s, double k) {
  HysteresisData h;
  h.k = k;
  h.yield_pos = s.yield_pos;
  h.yield_neg = s.yield_neg;
  h.H = s.hardening * k / (1.0 - s.hardening);
  h.inv_kH = 1.0 / (k + h.H);
  return h;
}

// The return mapping at deformation d (once per step, the hinge-spring stage): when the trial
// force k (d - d_p) leaves the elastic range by x, d_p moves by x / (k + H), which puts the force
// back on its edge (exact for the bilinear law). `dissipated` grows by the plastic work along the
// edge, integral of (H d_p + yield) dd_p from the old d_p to the new one (exact on that path).
inline void hysteresis_update(const HysteresisData& h, double d, double& dp, double& dissipated) {
  const double xi = h.k * (d - dp) - h.H * dp;  // the trial force relative to the back force
  double edge = 0, delta = 0;
  if (xi > h.yield_pos) {
    edge = h.yield_pos;
    delta = (xi - h.yield_pos) * h.inv_kH;
  } else if (xi < -h.yield_neg) {
    edge = -h.yield_neg;
    delta = (xi + h.yield_neg) * h.inv_kH;
  } else {
    return;
  }
  const double dp_new = dp + delta;
  dissipated += (h.H * (0.5 * (dp + dp_new)) + edge) * delta;
  dp = dp_new;
}

}  // namespace ntn
