// Hysteretic hinge directions (HingeBehaviour::kPlastic, DESIGN §7). A direction of elastic
// stiffness k carries f = k (d - d_p) (+ its dashpot, bilinear only); its law decides, once per
// step, how the plastic deformation d_p moves. d_p, the energy dissipated (the plastic work
// integral f dd_p), the largest |d_p| and the backbone rules' excursions are the direction's
// history in State: a checkpoint restores them.
// kBilinear: elasto-plastic with kinematic hardening. The elastic range is
// q - yield_neg <= f <= q + yield_pos around the back force q = H d_p, with H = b k / (1 - b) so
// that the tangent after yield is k H / (k + H) = b k.
// kKinematic, kPeakOriented: a backbone and its rule (backbone.hpp). kBrittle: linear until it
// breaks (brittle.hpp).
#pragma once

#include <array>

#include "ntn/backbone.hpp"
#include "ntn/brittle.hpp"
#include "ntn/model_spec.hpp"

namespace ntn {

// The most slip directions (rigid-plastic, slip.hpp) of one rigid tree solved together; a tree's
// mobility matrix between them is kept in Model::slip_mobility, one row of this length per
// direction.
inline constexpr int kSlipBlock = 16;

// What the step needs of one hysteretic direction (Model::hystereses).
struct HysteresisData {
  HysteresisRule rule = HysteresisRule::kBilinear;  // first: the step reads rule to inv_kH
  double k = 0;                                     // N/m or N m/rad, elastic stiffness
  double yield_pos = 0;                             // N or N m
  double yield_neg = 0;                             // N or N m, as a magnitude
  double H = 0;                                     // kinematic hardening modulus b k / (1 - b)
  double inv_kH = 0;                                // 1 / (k + H)
  std::array<double, 3> limits{};                   // io, ls, cp on the peak |d_p| (0, 0, 0: none)
  Envelope pos, neg;  // the backbone of each sense (kKinematic, kPeakOriented)
  int normal = -1;    // friction, fixed_if (slip.hpp): the direction whose force N sets the
                      // limit, or -1
  double mu = 0;
  double cohesion = 0;
  int fixed_if = 0;  // -1 (+1): held while N < 0 (N > 0), free otherwise (slip.hpp)
  int circle = -1;   // friction circle: the other direction of the pair, or -1 (slip.hpp)
};

// The bound on a hinge law's values (forces, moments, deformations, stiffnesses, mu, cohesion,
// acceptance limits): each must be below it, so that the law's products (mu N + c, k d, H d_p)
// stay finite. The model compiler refuses a value at or above it at its key.
inline constexpr double kLawValueLimit = 1e300;
constexpr bool law_value_ok(double v) {
  return v < kLawValueLimit;
}

// A law the kernel takes for a direction of elastic stiffness k and dashpot c: acceptance limits
// none or 0 < io <= ls <= cp (finite); bilinear: yields > 0 and finite, hardening in [0, 1);
// backbone: both envelopes valid (backbone.hpp), yields equal to their B forces, no dashpot (its
// force must be able to drop to zero), cp within the plastic deformation at E in both senses;
// brittle: yields > 0 and finite, no hardening, no dashpot; friction: mu, cohesion >= 0 and
// finite, a circle partner other than the normal; fixed_if: -1 or +1 with a controlling
// direction and nothing else.
constexpr bool hysteresis_valid(const HysteresisSpec& s, double k, double c) {
  const auto& l = s.limits;
  const bool none = l[0] == 0 && l[1] == 0 && l[2] == 0;
  const bool ordered = l[0] > 0 && l[0] <= l[1] && l[1] <= l[2] && law_value_ok(l[2]);
  if (!(none || ordered)) return false;
  if (s.fixed_if != 0)  // held by the sign of another direction's force: no limits of its own
    return (s.fixed_if == 1 || s.fixed_if == -1) && s.rule == HysteresisRule::kBilinear &&
           s.normal >= 0 && s.normal < 6 && s.mu == 0 && s.cohesion == 0 && s.hardening == 0;
  if (s.normal >= 0)  // friction: the yields are not used
    return s.rule == HysteresisRule::kBilinear && s.normal < 6 && s.mu >= 0 && law_value_ok(s.mu) &&
           s.cohesion >= 0 && law_value_ok(s.cohesion) && s.hardening == 0 && s.circle >= -1 &&
           s.circle < 6 && s.circle != s.normal;
  if (s.normal != -1 || s.circle != -1) return false;
  if (s.rule == HysteresisRule::kBilinear || s.rule == HysteresisRule::kBrittle)
    return s.yield_pos > 0 && law_value_ok(s.yield_pos) && s.yield_neg > 0 &&
           law_value_ok(s.yield_neg) && s.hardening >= 0 && s.hardening < 1 &&
           (s.rule == HysteresisRule::kBilinear || (s.hardening == 0 && c == 0));
  if (s.rule != HysteresisRule::kKinematic && s.rule != HysteresisRule::kPeakOriented) return false;
  if (!(k > 0) || c != 0 || s.hardening != 0 || !envelope_valid(s.backbone_pos, k) ||
      !envelope_valid(s.backbone_neg, k) || s.yield_pos != s.backbone_pos[0].force ||
      s.yield_neg != s.backbone_neg[0].force)
    return false;
  const double last_pos = s.backbone_pos[3].d - s.backbone_pos[3].force / k;
  const double last_neg = s.backbone_neg[3].d - s.backbone_neg[3].force / k;
  return none || (l[2] <= last_pos && l[2] <= last_neg);
}

// The plastic deformation at a backbone's point E, d_E - f_E / k: how far the acceptance limits
// may reach.
constexpr double backbone_last_plastic(const std::array<CurvePoint, 4>& p, double k) {
  return p[3].d - p[3].force / k;
}

// Performance level of a direction whose largest plastic deformation so far is `peak`: 0 below
// yield (no plastic deformation), 1 within IO (peak <= io), 2 within LS, 3 within CP, 4 beyond
// CP; without limits 0 or 1 (yielded).
constexpr int performance_level(const std::array<double, 3>& limits, double peak) {
  if (!(peak > 0)) return 0;
  int level = 1;
  if (limits[0] > 0) {
    for (const double lim : limits)
      level += peak > lim ? 1 : 0;
  }
  return level;
}

inline HysteresisData make_hysteresis(const HysteresisSpec& s, double k) {
  HysteresisData h;
  h.k = k;
  h.yield_pos = s.yield_pos;
  h.yield_neg = s.yield_neg;
  h.H = s.hardening * k / (1.0 - s.hardening);
  h.inv_kH = 1.0 / (k + h.H);
  h.limits = s.limits;
  h.rule = s.rule;
  h.normal = s.normal, h.mu = s.mu, h.cohesion = s.cohesion;
  h.fixed_if = s.fixed_if;
  h.circle = s.circle;
  if (s.rule == HysteresisRule::kKinematic || s.rule == HysteresisRule::kPeakOriented) {
    h.pos = make_envelope(s.backbone_pos);
    h.neg = make_envelope(s.backbone_neg);
  }
  return h;
}

// The bilinear return mapping at deformation d: when the trial
// force k (d - d_p) leaves the elastic range by x, d_p moves by x / (k + H), which puts the force
// back on its edge (exact for the bilinear law). `dissipated` grows by the plastic work along the
// edge, integral of (H d_p + yield) dd_p from the old d_p to the new one (exact on that path).
// `peak` keeps the largest |d_p|.
inline void bilinear_update(const HysteresisData& h, double d, double& dp, double& dissipated,
                            double& peak) {
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
  const double size = dp_new < 0 ? -dp_new : dp_new;
  if (size > peak) peak = size;
}

// A hysteretic direction's history brought to deformation d (once per step, the hinge-spring
// stage, integrator.hpp). True the step a brittle direction breaks (the stage records when).
inline bool hysteresis_update(const HysteresisData& h, double d, double& dp, double& dissipated,
                              double& peak, std::array<double, 4>& excursion) {
  switch (h.rule) {
    case HysteresisRule::kBilinear:
      bilinear_update(h, d, dp, dissipated, peak);
      return false;
    case HysteresisRule::kBrittle:
      return brittle_update(h.k, h.yield_pos, h.yield_neg, d, dp, dissipated, peak, excursion);
    case HysteresisRule::kKinematic:
    case HysteresisRule::kPeakOriented:
      break;
  }
  backbone_update(h.rule, h.k, h.pos, h.neg, d, dp, dissipated, peak, excursion);
  return false;
}

}  // namespace ntn
