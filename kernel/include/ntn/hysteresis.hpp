// Hysteretic hinge directions (HingeBehaviour::kPlastic, DESIGN §7). A direction of elastic
// stiffness k carries f = k (d - d_p) (+ its dashpot, bilinear only); its law (laws/table.hpp)
// decides, once per step, how the plastic deformation d_p moves. d_p, the energy dissipated (the
// plastic work integral f dd_p), the largest |d_p| and the law's own values are the direction's
// history in State: a checkpoint restores them. The rules shared by every law (acceptance
// limits, the slip stage's friction and fixed_if) are here; each law's own are in its header.
#pragma once

#include <array>

#include "ntn/laws/law.hpp"
#include "ntn/laws/table.hpp"
#include "ntn/model_spec.hpp"

namespace ntn {

// The most slip directions (rigid-plastic, slip.hpp) of one rigid tree solved together; a tree's
// mobility matrix between them is kept in Model::slip_mobility, one row of this length per
// direction.
inline constexpr int kSlipBlock = 16;

// A law the kernel takes for a direction of elastic stiffness k and dashpot c: acceptance limits
// none or 0 < io <= ls <= cp (finite); friction: mu, cohesion >= 0 and finite, a circle partner
// other than the normal; fixed_if: -1 or +1 with a controlling direction and nothing else;
// otherwise its law's own rule (its check(), laws/).
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
  return law_valid(s, k, c);
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
  with_law<bool>(s.rule, false, [&](auto l) {
    decltype(l)::make(s, k, h);
    return true;
  });
  return h;
}

// A hysteretic direction's history brought to deformation d (once per step, the hinge-spring
// stage, integrator.hpp). True the step it breaks (a law with kBreaks; the stage records when).
inline bool hysteresis_update(const HysteresisData& h, double d, double& dp, double& dissipated,
                              double& peak, LawState& x) {
  return with_law<bool>(h.rule, false,
                        [&](auto l) { return decltype(l)::update(h, d, dp, dissipated, peak, x); });
}

}  // namespace ntn
