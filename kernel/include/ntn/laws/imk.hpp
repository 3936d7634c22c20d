// The modified Ibarra-Medina-Krawinkler law, bilinear (HysteresisRule::kImk): the standard
// component model for the collapse of steel and concrete members (Ibarra, Medina and Krawinkler
// 2005, "Hysteretic models that incorporate strength and stiffness deterioration", EESD
// 34(12):1489-1511; Lignos and Krawinkler 2011, J. Struct. Eng. 137(11):1291-1302). Its
// parameters are those of the literature (and of OpenSees' IMKBilin) per sense:
//   k            elastic stiffness (the direction's)
//   F_y          yield force or moment (yield_pos, yield_neg)
//   theta_p      pre-capping plastic deformation, yield to capping
//   theta_pc     post-capping deformation, capping to zero strength
//   theta_u      ultimate deformation (total): past it the direction has no strength left
//   F_c / F_y    capping-to-yield strength ratio (>= 1)
//   F_r / F_y    residual-to-yield strength ratio
//   Lambda_s,c,k the reference cumulative deformation of each deterioration (E_t = Lambda F_y+;
//                0: none), c_s,c,k their exponents, D+ and D- their rates in each sense.
// The backbone of a sense, in its deformation x (a magnitude): the hardening line through the
// yield point (F_y / k, F_y) of slope K_s = (F_c - F_y) / theta_p to the capping point
// (F_y / k + theta_p, F_c); the post-capping line of slope -K_c = -F_c / theta_pc; the residual
// F_r once the post-capping line falls below it; no strength past theta_u.
// Hysteresis (bilinear): the force stays between the two senses' bounds, fixed lines in d as in
// kinematic hardening (the hardening line extended across the origin; in the post-capping
// range the lower of the hardening and post-capping lines; the residual under the latter);
// between them it moves at the unloading stiffness K_u.
// Cyclic deterioration (Ibarra et al. 2005, eq. 3-7): an excursion ends when the force changes
// sign; with E_i the energy it dissipated and sum E_j the energy dissipated so far (this one
// included), beta_i = (E_i / (E_t - sum E_j))^c (1 when E_t - sum E_j <= E_i: the capacity is
// spent, and the direction breaks). Then in the sense the new excursion loads (the force's new
// sign), with D that sense's rate:
//   F_y,i = (1 - D beta_s) F_y,i-1 and K_s,i = (1 - D beta_s) K_s,i-1  (basic strength)
//   the post-capping line's intercept at d = 0, (1 - D beta_c) of its last  (post-capping)
// and, shared by both senses, with beta_k against 2 E_t (it deteriorates twice a cycle; the
// capacity is still spent at E_t),
//   K_u,i = (1 - beta_k) K_u,i-1                                          (unloading stiffness)
// Deteriorating the loaded sense only is what OpenSees' IMKBilin does and what Lignos and
// Krawinkler's calibrated Lambda assume: under a symmetric protocol each sense loses strength
// once per cycle. (IMKBilin takes K_u's step at the reversal of d before the force changes sign,
// with the energy of the excursion so far less the elastic energy it will release; here it is at
// the sign change, with the excursion's energy: the same beta, one branch later.)
// A force on a bound of slope s at or above K_u would not be reached by the elastic line; every
// slope here is below k, and K_s and K_u deteriorate alike when Lambda_s = Lambda_k.
// The force is k (d - d_p) like every law's (law.hpp): d_p = d - f / k, and the plastic work
// integral f dd_p (State::dissipated) is exact along each straight piece of the step's path
// (the elastic line at K_u, then the bound), so that the energy books close; where the force is
// zero it is the energy the hysteresis dissipated. The peak plastic deformation (the acceptance
// limits' measure) is |d - f / K_u| on a bound. Past theta_u, or when the capacity is spent, the
// direction breaks like a backbone past E: no force from then on, its elastic energy dissipated,
// State::first_slip the step (kBreaks).
// The exponents c are multiples of 1/4 from 1/4 to 4 (the step raises to them without libm).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "ntn/laws/backbone.hpp"
#include "ntn/laws/law.hpp"
#include "ntn/model_spec.hpp"
#include "ntn/root.hpp"

namespace ntn {

namespace imk {
// HysteresisSpec::parameters: by sense (+0 positive, +1 negative), or by deterioration
// (+0 strength, +1 post-capping, +2 unloading stiffness).
inline constexpr std::size_t kPreCapping = 0;     // theta_p, m or rad
inline constexpr std::size_t kPostCapping = 2;    // theta_pc, m or rad
inline constexpr std::size_t kUltimate = 4;       // theta_u, m or rad
inline constexpr std::size_t kCappingRatio = 6;   // F_c / F_y
inline constexpr std::size_t kResidualRatio = 8;  // F_r / F_y
inline constexpr std::size_t kLambda = 10;        // Lambda_s, Lambda_c, Lambda_k, m or rad
inline constexpr std::size_t kExponent = 13;      // c_s, c_c, c_k
inline constexpr std::size_t kRate = 16;          // D+, D-
// HysteresisData::p, from them
inline constexpr std::size_t kHardeningSlope = 0;    // K_s, N/m or N m/rad
inline constexpr std::size_t kPostSlope = 2;         // K_c (a magnitude)
inline constexpr std::size_t kPostIntercept = 4;     // the post-capping line at d = 0
inline constexpr std::size_t kResidualForce = 6;     // F_r
inline constexpr std::size_t kUltimateLimit = 8;     // theta_u
inline constexpr std::size_t kReferenceEnergy = 10;  // E_t = Lambda F_y+ (0: none), J
inline constexpr std::size_t kExponentOf = 13;       // c
inline constexpr std::size_t kRateOf = 16;           // D
// State::law_state
inline constexpr std::size_t kBroken = 0;         // 1 once broken
inline constexpr std::size_t kLastD = 1;          // d at the last step
inline constexpr std::size_t kSign = 2;           // the current excursion's sign (0: none yet)
inline constexpr std::size_t kEnergyAt = 3;       // State::dissipated when it began
inline constexpr std::size_t kLostStrength = 4;   // 1 - F_y,i / F_y, by sense
inline constexpr std::size_t kLostCapping = 6;    // 1 - intercept_i / intercept, by sense
inline constexpr std::size_t kLostUnloading = 8;  // 1 - K_u,i / k
}  // namespace imk

// What is wrong with an IMK direction's values (the model compiler words it at the key).
enum class ImkFault : std::uint8_t {
  kNone,
  kStiffness,     // k > 0 and finite, no dashpot, no hardening or backbone of another law
  kYield,         // F_y > 0 and finite
  kPreCapping,    // theta_p > 0 and finite
  kPostCapping,   // theta_pc > 0 and finite
  kCappingRatio,  // F_c / F_y >= 1 and finite
  kSteeperThanK,  // K_s < k
  kResidual,      // 0 <= F_r / F_y <= F_c / F_y
  kUltimate,      // theta_u beyond the capping point F_y / k + theta_p, finite
  kLambda,        // Lambda >= 0 and finite
  kExponent,      // c a multiple of 1/4 from 1/4 to 4
  kRate,          // 0 < D <= 1
  kLimits,        // cp within the plastic deformation at theta_u
};
struct ImkCheck {
  ImkFault fault = ImkFault::kNone;
  int index = -1;  // the parameter's place in its group: the sense (0, 1) or deterioration (0-2)
};

constexpr ImkCheck imk_check(const HysteresisSpec& s, double k, double c) {
  using F = ImkFault;
  namespace P = imk;
  const auto& v = s.parameters;
  const auto finite_positive = [](double x) { return x > 0 && law_value_ok(x); };
  if (!finite_positive(k) || c != 0 || s.hardening != 0 || s.backbone_pos[0].d != 0 ||
      s.backbone_neg[0].d != 0)
    return {F::kStiffness, -1};
  for (int i = 0; i < 2; ++i) {
    const auto u = static_cast<std::size_t>(i);
    const double fy = i == 0 ? s.yield_pos : s.yield_neg;
    if (!finite_positive(fy)) return {F::kYield, i};
    if (!finite_positive(v[P::kPreCapping + u])) return {F::kPreCapping, i};
    if (!finite_positive(v[P::kPostCapping + u])) return {F::kPostCapping, i};
    const double ratio = v[P::kCappingRatio + u];
    if (!(ratio >= 1 && law_value_ok(ratio))) return {F::kCappingRatio, i};
    if (!((ratio - 1) * fy < k * v[P::kPreCapping + u])) return {F::kSteeperThanK, i};
    const double res = v[P::kResidualRatio + u];
    if (!(res >= 0 && res <= ratio)) return {F::kResidual, i};
    const double ult = v[P::kUltimate + u];
    if (!(ult > fy / k + v[P::kPreCapping + u] && law_value_ok(ult))) return {F::kUltimate, i};
    const double rate = v[P::kRate + u];
    if (!(rate > 0 && rate <= 1)) return {F::kRate, i};
  }
  for (int j = 0; j < 3; ++j) {
    const auto u = static_cast<std::size_t>(j);
    const double lambda = v[P::kLambda + u];
    if (!(lambda >= 0 && law_value_ok(lambda))) return {F::kLambda, j};
    const double q = v[P::kExponent + u] * 4;
    if (!(q >= 1 && q <= 16 && q == static_cast<double>(static_cast<int>(q))))
      return {F::kExponent, j};
  }
  const auto& l = s.limits;
  if (l[2] > v[P::kUltimate] - s.yield_pos / k || l[2] > v[P::kUltimate + 1] - s.yield_neg / k)
    return {F::kLimits, -1};
  return {};
}

// r^c for 0 <= r < 1 and c a multiple of 1/4 in [1/4, 4], arithmetic only (c = 1: r exactly).
inline double imk_power(double r, double c) {
  const int q = static_cast<int>(c * 4.0 + 0.5);
  double out = 1.0;
  for (int i = 0; i < q / 4; ++i)
    out *= r;
  if (q % 4 != 0) {
    const double quarter = root(root(r));
    for (int i = 0; i < q % 4; ++i)
      out *= quarter;
  }
  return out;
}

// beta of one deterioration after an excursion that dissipated e, with `total` dissipated so
// far: 0 without one (E_t = 0), 1 when the capacity is spent.
inline double imk_beta(double e, double reference, double total, double c) {
  if (!(reference > 0)) return 0.0;
  const double left = reference - total;
  if (!(left > e)) return 1.0;
  return imk_power(e / left, c);
}

struct Imk {
  static constexpr HysteresisRule kRule = HysteresisRule::kImk;
  static constexpr const char* kName = "imk";
  static constexpr const char* kEnum = "kImk";
  static constexpr const char* kSummary = "imk (deteriorating)";
  static constexpr LawAccount kAccount = LawAccount::kHysteretic;
  static constexpr bool kSlip = false;
  static constexpr bool kBreaks = true;
  static constexpr bool kEnvelope = true;

  static constexpr bool check(const HysteresisSpec& s, double k, double c) {
    return imk_check(s, k, c).fault == ImkFault::kNone;
  }

  static void make(const HysteresisSpec& s, double k, HysteresisData& h) {
    namespace P = imk;
    const auto& v = s.parameters;
    for (std::size_t i = 0; i < 2; ++i) {
      const double fy = i == 0 ? s.yield_pos : s.yield_neg;
      const double fc = v[P::kCappingRatio + i] * fy;
      const double post = fc / v[P::kPostCapping + i];
      h.p[P::kHardeningSlope + i] = (fc - fy) / v[P::kPreCapping + i];
      h.p[P::kPostSlope + i] = post;
      h.p[P::kPostIntercept + i] = fc + post * (fy / k + v[P::kPreCapping + i]);
      h.p[P::kResidualForce + i] = v[P::kResidualRatio + i] * fy;
      h.p[P::kUltimateLimit + i] = v[P::kUltimate + i];
      h.p[P::kRateOf + i] = v[P::kRate + i];
    }
    for (std::size_t j = 0; j < 3; ++j) {
      h.p[P::kReferenceEnergy + j] = v[P::kLambda + j] * s.yield_pos;
      h.p[P::kExponentOf + j] = v[P::kExponent + j];
    }
  }

  // The bound of sense i (0 positive, 1 negative) at deformation x in that sense (a magnitude;
  // negative across the origin), as its history has deteriorated it.
  static BoundLine bound(const HysteresisData& h, const LawState& x, double at, std::size_t i) {
    namespace P = imk;
    const double keep = 1.0 - x[P::kLostStrength + i];
    const double fy = (i == 0 ? h.yield_pos : h.yield_neg) * keep;
    const double ks = h.p[P::kHardeningSlope + i] * keep;
    const double hardening = fy + ks * (at - fy / h.k);
    const double post =
        h.p[P::kPostIntercept + i] * (1.0 - x[P::kLostCapping + i]) - h.p[P::kPostSlope + i] * at;
    if (hardening <= post) return {hardening, ks};
    const double residual = h.p[P::kResidualForce + i];
    if (post >= residual) return {post, -h.p[P::kPostSlope + i]};
    return {residual, 0.0};
  }

  static bool update(const HysteresisData& h, double d, double& dp, double& dissipated,
                     double& peak, LawState& x) {
    namespace P = imk;
    if (x[P::kBroken] != 0) {  // no strength left: the force stays 0
      dp = d;
      x[P::kLastD] = d;
      return false;
    }
    const double k = h.k;
    if (d > h.p[P::kUltimateLimit] || -d > h.p[P::kUltimateLimit + 1])
      return fail(k, d, dp, dissipated, peak, x);
    const double ku = k * (1.0 - x[P::kLostUnloading]);
    const double d0 = x[P::kLastD];
    const double f0 = k * (d0 - dp);
    const double trial = f0 + ku * (d - d0);
    const BoundLine up = bound(h, x, d, 0);
    BoundLine lo = bound(h, x, -d, 1);
    lo.f = -lo.f;              // as a force in the positive sense; its slope in d stays the same
    if (lo.f > up.f) lo = up;  // deep in a deteriorated range the two cannot cross
    const BoundLine* on = trial > up.f ? &up : trial < lo.f ? &lo : nullptr;
    const double f = on != nullptr ? on->f : trial;
    const double dp_new = d - f / k;
    double work = 0.5 * (f0 + f) * (dp_new - dp);
    if (on != nullptr) {
      // The step's path: the elastic line at K_u to the bound's line, then along it.
      const double s = on->slope;
      if (ku != s) {
        const double at = (f - s * d - f0 + ku * d0) / (ku - s);
        if ((at - d0) * (d - at) >= 0) {
          const double fm = f0 + ku * (at - d0);
          const double dpm = at - fm / k;
          work = 0.5 * (f0 + fm) * (dpm - dp) + 0.5 * (fm + f) * (dp_new - dpm);
        }
      }
      const double plastic = d - f / ku;
      const double size = plastic < 0 ? -plastic : plastic;
      if (size > peak) peak = size;
    }
    dissipated += work;
    dp = dp_new;
    x[P::kLastD] = d;
    if (f == 0) return false;
    const double sign = f > 0 ? 1.0 : -1.0;
    if (x[P::kSign] == 0) {  // the first excursion begins
      x[P::kSign] = sign;
    } else if (sign != x[P::kSign]) {  // an excursion ended: deteriorate by its energy
      x[P::kSign] = sign;
      const double e = dissipated - x[P::kEnergyAt];
      x[P::kEnergyAt] = dissipated;
      double beta[3];
      for (std::size_t j = 0; j < 3; ++j) {
        // K_u deteriorates at both ends of a cycle: against 2 E_t, spent at E_t (imk_beta's 1)
        const double et = h.p[P::kReferenceEnergy + j];
        const double against = j == 2 && dissipated < et ? 2.0 * et : et;
        beta[j] = imk_beta(e > 0 ? e : 0.0, against, dissipated, h.p[P::kExponentOf + j]);
        if (beta[j] >= 1.0) return fail(k, d, dp, dissipated, peak, x);  // capacity spent
      }
      const std::size_t i = sign > 0 ? 0 : 1;  // the sense the next excursion loads
      const double rate = h.p[P::kRateOf + i];
      x[P::kLostStrength + i] = 1.0 - (1.0 - rate * beta[0]) * (1.0 - x[P::kLostStrength + i]);
      x[P::kLostCapping + i] = 1.0 - (1.0 - rate * beta[1]) * (1.0 - x[P::kLostCapping + i]);
      x[P::kLostUnloading] = 1.0 - (1.0 - beta[2]) * (1.0 - x[P::kLostUnloading]);
    }
    return false;
  }

  // Breaks at deformation d: the elastic energy it held is dissipated, no force from now on.
  static bool fail(double k, double d, double& dp, double& dissipated, double& peak, LawState& x) {
    const double f = k * (d - dp);
    dissipated += 0.5 * f * (d - dp);
    dp = d;
    const double size = d < 0 ? -d : d;
    if (size > peak) peak = size;
    x[imk::kBroken] = 1;
    x[imk::kLastD] = d;
    return true;
  }

  // The monotonic backbone of one sense (+1, -1) as magnitudes B (yield), C (capping), D (the
  // residual reached, or zero strength at theta_u first), E (theta_u).
  static std::array<CurvePoint, 4> envelope(const HysteresisSpec& s, double k, int sense) {
    namespace P = imk;
    const std::size_t i = sense > 0 ? 0 : 1;
    const auto& v = s.parameters;
    const double fy = i == 0 ? s.yield_pos : s.yield_neg;
    const double fc = v[P::kCappingRatio + i] * fy;
    const double dc = fy / k + v[P::kPreCapping + i];
    const double post = fc / v[P::kPostCapping + i];
    const double fr = v[P::kResidualRatio + i] * fy;
    const double du = v[P::kUltimate + i];
    double dr = dc + (fc - fr) / post;  // where the post-capping line meets the residual
    double f_end = fr;
    if (dr > du) {
      dr = du;
      f_end = fc - post * (du - dc);
    }
    return {CurvePoint{fy / k, fy}, CurvePoint{dc, fc}, CurvePoint{dr, f_end},
            CurvePoint{du, f_end}};
  }
};

}  // namespace ntn
