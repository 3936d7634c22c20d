// Brittle hinge directions (HysteresisRule::kBrittle): a connection that carries its
// force until that force first passes its limit, then breaks and carries nothing for the rest
// of the run (a bolt, a weld, a tie). On a spring (a `linear` direction that fails, or a
// `failure` direction under `penalty`, whose spring is the penalty stiffness) the force is
// k (d - d_p): d_p stays 0 while it holds; the step its trial force k d leaves
// [-yield_neg, yield_pos] it breaks, the force is 0 from that step on (d_p follows d), and the
// elastic energy it held, (k d)^2 / 2k, counts as dissipated. Under ntn_exact a rigid `failure`
// direction is the slip stage's (slip.hpp): it slides at its limit once and is free after.
// The broken flag is the first entry of State::law_state; the event's tick is State::first_slip
// (brittle_update returns true the step it breaks).
#pragma once

#include <array>

#include "ntn/laws/law.hpp"

namespace ntn {

inline constexpr std::size_t kBroken = 0;  // State::law_state entry of a brittle direction

inline bool brittle_update(double k, double yield_pos, double yield_neg, double d, double& dp,
                           double& dissipated, double& peak, LawState& x) {
  if (x[kBroken] != 0) {  // broken: no force
    dp = d;
    return false;
  }
  const double f = k * d;  // d_p is 0 until it breaks
  if (f <= yield_pos && f >= -yield_neg) return false;
  x[kBroken] = 1;
  dissipated += 0.5 * f * d;  // the elastic energy it held, (k d)^2 / 2k
  dp = d;
  peak = d < 0 ? -d : d;
  return true;
}

// Linear until it breaks: yields > 0 and finite, no hardening, no dashpot (its force must drop
// to zero when it breaks). A rigid-plastic direction may take it (it breaks at its first slide).
struct Brittle {
  static constexpr HysteresisRule kRule = HysteresisRule::kBrittle;
  static constexpr const char* kName = "brittle";
  static constexpr const char* kEnum = "kBrittle";
  static constexpr const char* kSummary = "springs that break";
  static constexpr LawAccount kAccount = LawAccount::kBreaking;
  static constexpr bool kSlip = true;
  static constexpr bool kBreaks = true;
  static constexpr bool kEnvelope = false;
  static constexpr bool check(const HysteresisSpec& s, double, double c) {
    return s.yield_pos > 0 && law_value_ok(s.yield_pos) && s.yield_neg > 0 &&
           law_value_ok(s.yield_neg) && s.hardening == 0 && c == 0;
  }
  static void make(const HysteresisSpec&, double, HysteresisData&) {}
  static bool update(const HysteresisData& h, double d, double& dp, double& dissipated,
                     double& peak, LawState& x) {
    return brittle_update(h.k, h.yield_pos, h.yield_neg, d, dp, dissipated, peak, x);
  }
  static std::array<CurvePoint, 4> envelope(const HysteresisSpec&, double, int) { return {}; }
};

}  // namespace ntn
