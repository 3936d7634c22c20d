// The bilinear law (HysteresisRule::kBilinear): elasto-plastic with kinematic hardening. The
// elastic range is q - yield_neg <= f <= q + yield_pos around the back force q = H d_p, with
// H = b k / (1 - b) so that the tangent after yield is k H / (k + H) = b k. A rigid-plastic
// direction takes it too (slip.hpp: perfectly plastic, or hardening with the slip).
#pragma once

#include <array>

#include "ntn/laws/law.hpp"
#include "ntn/model_spec.hpp"

namespace ntn {

// The bilinear return mapping at deformation d: when the trial force k (d - d_p) leaves the
// elastic range by x, d_p moves by x / (k + H), which puts the force back on its edge (exact for
// the bilinear law). `dissipated` grows by the plastic work along the edge, integral of
// (H d_p + yield) dd_p from the old d_p to the new one (exact on that path). `peak` keeps the
// largest |d_p|.
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

// Yields > 0 and finite, hardening in [0, 1).
struct Bilinear {
  static constexpr HysteresisRule kRule = HysteresisRule::kBilinear;
  static constexpr const char* kName = "bilinear";
  static constexpr const char* kEnum = "kBilinear";
  static constexpr const char* kSummary = "plastic (bilinear, kinematic hardening)";
  static constexpr LawAccount kAccount = LawAccount::kHysteretic;
  static constexpr bool kSlip = true;
  static constexpr bool kBreaks = false;
  static constexpr bool kEnvelope = false;
  static constexpr bool check(const HysteresisSpec& s, double, double) {
    return s.yield_pos > 0 && law_value_ok(s.yield_pos) && s.yield_neg > 0 &&
           law_value_ok(s.yield_neg) && s.hardening >= 0 && s.hardening < 1;
  }
  static void make(const HysteresisSpec&, double, HysteresisData&) {}
  static bool update(const HysteresisData& h, double d, double& dp, double& dissipated,
                     double& peak, LawState&) {
    bilinear_update(h, d, dp, dissipated, peak);
    return false;
  }
  static std::array<CurvePoint, 4> envelope(const HysteresisSpec&, double, int) { return {}; }
};

}  // namespace ntn
