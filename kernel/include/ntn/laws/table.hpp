// The table of hysteretic hinge laws: every layer that does something per law (the step's
// hinge-spring stage, the kernel's checks, the model compiler's header and reports, the energy
// books, the yield report, the plots) visits this list instead of switching on the rule.
// A new law is its header in this folder (law.hpp says what it holds) and one entry here.
#pragma once

#include <array>

#include "ntn/laws/backbone.hpp"
#include "ntn/laws/bilinear.hpp"
#include "ntn/laws/brittle.hpp"
#include "ntn/laws/imk.hpp"
#include "ntn/laws/law.hpp"
#include "ntn/model_spec.hpp"

namespace ntn {

template <class... L>
struct LawList {
  static constexpr std::size_t size = sizeof...(L);
};

using HysteresisLaws = LawList<Bilinear, Kinematic, PeakOriented, Brittle, Imk>;

namespace detail {
template <class R, class F, class... L>
constexpr R with_law(LawList<L...>, HysteresisRule rule, R otherwise, F&& f) {
  R out = otherwise;
  (void)((L::kRule == rule ? (out = f(L{}), true) : false) || ...);
  return out;
}
template <class F, class... L>
constexpr void each_law(LawList<L...>, F&& f) {
  (f(L{}), ...);
}
}  // namespace detail

// f(Law{}) for the law of `rule`; `otherwise` for a rule no law has.
template <class R, class F>
constexpr R with_law(HysteresisRule rule, R otherwise, F&& f) {
  return detail::with_law<R>(HysteresisLaws{}, rule, otherwise, static_cast<F&&>(f));
}

// f(Law{}) for every law, in the table's order.
template <class F>
constexpr void each_law(F&& f) {
  detail::each_law(HysteresisLaws{}, static_cast<F&&>(f));
}

// The law's place in the table (-1 for a rule no law has).
constexpr int law_index(HysteresisRule r) {
  int i = 0, at = -1;
  each_law([&](auto l) {
    if (decltype(l)::kRule == r) at = i;
    ++i;
  });
  return at;
}

// The traits of a law by its rule (false, "" for a rule no law has).
constexpr const char* law_name(HysteresisRule r) {
  return with_law<const char*>(r, "", [](auto l) { return decltype(l)::kName; });
}
constexpr const char* law_enum(HysteresisRule r) {
  return with_law<const char*>(r, "", [](auto l) { return decltype(l)::kEnum; });
}
constexpr LawAccount law_account(HysteresisRule r) {
  return with_law<LawAccount>(r, LawAccount::kHysteretic,
                              [](auto l) { return decltype(l)::kAccount; });
}
constexpr bool law_breaks(HysteresisRule r) {
  return with_law<bool>(r, false, [](auto l) { return decltype(l)::kBreaks; });
}
constexpr bool law_slips(HysteresisRule r) {
  return with_law<bool>(r, false, [](auto l) { return decltype(l)::kSlip; });
}
constexpr bool law_has_envelope(HysteresisRule r) {
  return with_law<bool>(r, false, [](auto l) { return decltype(l)::kEnvelope; });
}

// The law's own rule for its values (law.hpp: check).
constexpr bool law_valid(const HysteresisSpec& s, double k, double c) {
  return with_law<bool>(s.rule, false, [&](auto l) { return decltype(l)::check(s, k, c); });
}

// The monotonic envelope of one sense (+1, -1) as magnitudes B, C, D, E (laws with kEnvelope).
inline std::array<CurvePoint, 4> law_envelope(const HysteresisSpec& s, double k, int sense) {
  return with_law<std::array<CurvePoint, 4>>(
      s.rule, {}, [&](auto l) { return decltype(l)::envelope(s, k, sense); });
}

}  // namespace ntn
