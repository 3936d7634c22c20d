// Backbone hysteresis rules (HysteresisRule::kKinematic, kPeakOriented; DESIGN §7): a
// multi-linear monotonic envelope per sense in the form of ASCE 41 / FEMA 356 (A at the origin,
// B yield, C capping, D the drop to the residual strength, E the ultimate deformation) and a rule
// for unloading and reloading. Both rules unload at the elastic stiffness k, so the force is
// k (d - d_p) on the elastic line through the current plastic deformation d_p (the zero-force
// point of that line), and each step only decides whether the trial force k (d - d_p) crosses
// the bound of its sense; if it does, the force is put on the bound and d_p moves.
//   kinematic (steel): the bound of a sense is its envelope, with the B-C segment extended back
//     across the origin, as bilinear kinematic hardening has it (the same law when C, D, E are
//     far); past C the strength at the largest excursion so far caps the bound (degradation
//     along the envelope never comes back).
//   peak_oriented (concrete, timber): the bound of a sense is the line from the zero-force point
//     of the last unloading from the other sense (State::law_state anchor) to the envelope at
//     the largest excursion so far in this sense (B before any), then the envelope past it.
// Past E in either sense the direction has no strength left: it transmits no force for the
// rest of the run (d_p follows d), and the elastic energy it held counts as dissipated.
// The stable step uses k, the largest tangent the rules reach (every bound's slope is below k).
#pragma once

#include <array>
#include <cstdint>

#include "ntn/laws/law.hpp"
#include "ntn/model_spec.hpp"

namespace ntn {

// A point of a bound and its slope there (N/m or N m/rad).
struct BoundLine {
  double f = 0;
  double slope = 0;
};

// The envelope's line at a deformation magnitude x (x < d_C: the B-C segment, extended below B;
// x > d_E: no strength).
inline BoundLine envelope_line(const Envelope& e, double x) {
  if (x > e.d[3]) return {0.0, 0.0};
  std::size_t i = 0;  // the segment that starts at point i
  if (x >= e.d[1]) i = x >= e.d[2] ? 2 : 1;
  return {e.f[i] + e.slope[i] * (x - e.d[i]), e.slope[i]};
}

// What is wrong with an envelope (the model compiler words it): the rule the kernel holds it to.
enum class EnvelopeFault : std::uint8_t {
  kNone,
  kYield,          // B: deformation and force positive and finite
  kOffElastic,     // B off the elastic line: |f_B - k d_B| > 1e-12 f_B
  kOrder,          // deformations: d_B < d_C <= d_D <= d_E (finite)
  kCappingBelow,   // f_C < f_B (or not finite)
  kResidualAbove,  // f_D > f_C or f_D < 0
  kNegativeForce,  // f_E < 0
  kSteeperThanK,   // a rising segment (B-C or D-E) not below k: the stable step would not hold
};
struct EnvelopeCheck {
  EnvelopeFault fault = EnvelopeFault::kNone;
  int point = -1;  // 0..3: B, C, D, E (the later point of a bad segment)
};

// An envelope the kernel takes, for elastic stiffness k: 0 < d_B < d_C <= d_D <= d_E (finite),
// B on the elastic line, f_B <= f_C, 0 <= f_D <= f_C, 0 <= f_E, every rising slope below k.
constexpr EnvelopeCheck envelope_check(const std::array<CurvePoint, 4>& p, double k) {
  const CurvePoint &B = p[0], &C = p[1], &D = p[2], &E = p[3];
  using F = EnvelopeFault;
  if (!(B.d > 0 && B.d < 1e300 && B.force > 0 && B.force < 1e300)) return {F::kYield, 0};
  const double off = B.force - k * B.d;
  if (!((off < 0 ? -off : off) <= 1e-12 * B.force)) return {F::kOffElastic, 0};
  if (!(B.d < C.d)) return {F::kOrder, 1};
  if (!(C.d <= D.d)) return {F::kOrder, 2};
  if (!(D.d <= E.d && E.d < 1e300)) return {F::kOrder, 3};
  if (!(B.force <= C.force && C.force < 1e300)) return {F::kCappingBelow, 1};
  if (!(D.force >= 0 && D.force <= C.force)) return {F::kResidualAbove, 2};
  if (!(E.force >= 0 && E.force < 1e300)) return {F::kNegativeForce, 3};
  if (!(C.force - B.force < k * (C.d - B.d))) return {F::kSteeperThanK, 1};
  if (E.d > D.d && !(E.force - D.force < k * (E.d - D.d))) return {F::kSteeperThanK, 3};
  return {};
}

constexpr bool envelope_valid(const std::array<CurvePoint, 4>& p, double k) {
  return envelope_check(p, k).fault == EnvelopeFault::kNone;
}

inline Envelope make_envelope(const std::array<CurvePoint, 4>& p) {
  Envelope e;
  for (std::size_t i = 0; i < 4; ++i)
    e.d[i] = p[i].d, e.f[i] = p[i].force;
  for (std::size_t i = 0; i < 3; ++i) {
    const double len = e.d[i + 1] - e.d[i];
    e.slope[i] = len > 0 ? (e.f[i + 1] - e.f[i]) / len : 0.0;
  }
  return e;
}

// Indices into State::law_state.
inline constexpr std::size_t kPeakPos = 0, kPeakNeg = 1, kAnchorPos = 2, kAnchorNeg = 3;

// kinematic: the bound of the sense whose envelope is `e`, at deformation magnitude x (negative
// on the other side of the origin), capped past C by the strength at the largest excursion.
inline BoundLine kinematic_bound(const Envelope& e, double x, double peak) {
  BoundLine b = envelope_line(e, x);
  if (peak >= e.d[1]) {
    const double cap = envelope_line(e, peak).f;
    if (b.f > cap) b = {cap, 0.0};
  }
  return b;
}

// peak_oriented: the bound at deformation magnitude x of the sense whose reloading line starts
// at `anchor` (as a magnitude in that sense) and aims at the envelope at the largest excursion.
inline BoundLine peak_oriented_bound(const Envelope& e, double x, double peak, double anchor) {
  const double target = peak > e.d[0] ? peak : e.d[0];
  if (x >= target) return envelope_line(e, x);
  const double ft = envelope_line(e, target).f;
  const double run = target - anchor;
  if (!(run > 0)) return {ft, 0.0};
  const double slope = ft / run;
  return {slope * (x - anchor), slope};
}

// One step of a backbone direction at deformation d: `dp` its plastic deformation, `dissipated`
// the plastic work integral f dd_p (exact along a straight bound: the force on a bound of slope
// s is linear in d_p with slope k s / (k - s)), `peak` the largest |d_p|, `x` its excursions.
inline void backbone_update(HysteresisRule rule, double k, const Envelope& pos, const Envelope& neg,
                            double d, double& dp, double& dissipated, double& peak, LawState& x) {
  const bool was_broken = x[kPeakPos] > pos.d[3] || x[kPeakNeg] > neg.d[3];
  if (d > x[kPeakPos]) x[kPeakPos] = d;
  if (-d > x[kPeakNeg]) x[kPeakNeg] = -d;
  if (was_broken) {  // no strength left: the force stays 0
    dp = d;
    return;
  }
  if (x[kPeakPos] > pos.d[3] || x[kPeakNeg] > neg.d[3]) {  // breaks now: its elastic energy goes
    const double f = k * (d - dp);
    dissipated += 0.5 * f * (d - dp);
    dp = d;
    const double size = d < 0 ? -d : d;
    if (size > peak) peak = size;
    return;
  }
  const double trial = k * (d - dp);
  BoundLine b;
  bool upper = false;
  if (rule == HysteresisRule::kKinematic) {
    const BoundLine up = kinematic_bound(pos, d, x[kPeakPos]);
    BoundLine lo = kinematic_bound(neg, -d, x[kPeakNeg]);
    lo.f = -lo.f;              // as a force in the positive sense; its slope in d stays the same
    if (lo.f > up.f) lo = up;  // deep in a degraded range the translated range cannot invert
    if (trial > up.f) {
      b = up, upper = true;
    } else if (trial < lo.f) {
      b = lo;
    } else {
      return;
    }
  } else {
    if (trial > 0) {
      b = peak_oriented_bound(pos, d, x[kPeakPos], x[kAnchorPos]);
      if (!(trial > b.f)) return;
      upper = true;
    } else if (trial < 0) {
      b = peak_oriented_bound(neg, -d, x[kPeakNeg], -x[kAnchorNeg]);
      b.f = -b.f;
      if (!(trial < b.f)) return;
    } else {
      return;
    }
  }
  const double dp_new = d - b.f / k;
  // The force on this bound's line where the plastic deformation was dp: where the step left
  // the elastic line (or the last step's force when it was on the same line).
  const double f_start = b.slope < k ? (b.f + b.slope * (dp - d)) * k / (k - b.slope) : b.f;
  dissipated += 0.5 * (f_start + b.f) * (dp_new - dp);
  dp = dp_new;
  if (upper) {
    x[kAnchorNeg] = dp_new;  // an unloading from here reaches zero force at dp_new
  } else {
    x[kAnchorPos] = dp_new;
  }
  const double size = dp_new < 0 ? -dp_new : dp_new;
  if (size > peak) peak = size;
}

// The plastic deformation at a backbone's point E, d_E - f_E / k: how far the acceptance limits
// may reach.
constexpr double backbone_last_plastic(const std::array<CurvePoint, 4>& p, double k) {
  return p[3].d - p[3].force / k;
}

// The rule both backbone laws share: both envelopes valid, yields equal to their B forces, no
// dashpot (its force must be able to drop to zero), cp within the plastic deformation at E in
// both senses.
constexpr bool backbone_valid(const HysteresisSpec& s, double k, double c) {
  const auto& l = s.limits;
  const bool none = l[0] == 0 && l[1] == 0 && l[2] == 0;
  if (!(k > 0) || c != 0 || s.hardening != 0 || !envelope_valid(s.backbone_pos, k) ||
      !envelope_valid(s.backbone_neg, k) || s.yield_pos != s.backbone_pos[0].force ||
      s.yield_neg != s.backbone_neg[0].force)
    return false;
  const double last_pos = backbone_last_plastic(s.backbone_pos, k);
  const double last_neg = backbone_last_plastic(s.backbone_neg, k);
  return none || (l[2] <= last_pos && l[2] <= last_neg);
}

// The two backbone laws, the same but for their rule.
template <HysteresisRule R>
struct BackboneLaw {
  static constexpr HysteresisRule kRule = R;
  static constexpr LawAccount kAccount = LawAccount::kHysteretic;
  static constexpr bool kSlip = false;
  static constexpr bool kBreaks = false;
  static constexpr bool kEnvelope = true;
  static constexpr bool check(const HysteresisSpec& s, double k, double c) {
    return backbone_valid(s, k, c);
  }
  static void make(const HysteresisSpec& s, double, HysteresisData& h) {
    h.pos = make_envelope(s.backbone_pos);
    h.neg = make_envelope(s.backbone_neg);
  }
  static bool update(const HysteresisData& h, double d, double& dp, double& dissipated,
                     double& peak, LawState& x) {
    backbone_update(R, h.k, h.pos, h.neg, d, dp, dissipated, peak, x);
    return false;
  }
  // The envelope of one sense (+1, -1) as magnitudes B, C, D, E (A at the origin).
  static std::array<CurvePoint, 4> envelope(const HysteresisSpec& s, double, int sense) {
    return sense > 0 ? s.backbone_pos : s.backbone_neg;
  }
};

struct Kinematic : BackboneLaw<HysteresisRule::kKinematic> {
  static constexpr const char* kName = "kinematic";
  static constexpr const char* kEnum = "kKinematic";
  static constexpr const char* kSummary = "backbone kinematic";
};

struct PeakOriented : BackboneLaw<HysteresisRule::kPeakOriented> {
  static constexpr const char* kName = "peak_oriented";
  static constexpr const char* kEnum = "kPeakOriented";
  static constexpr const char* kSummary = "backbone peak_oriented";
};

}  // namespace ntn
