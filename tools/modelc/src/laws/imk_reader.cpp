// The reader of the IMK law (ntn/laws/imk.hpp): { imk = k, yield = F_y, yield_negative,
// capping_ratio = F_c / F_y, pre_capping = theta_p, post_capping = theta_pc, ultimate = theta_u,
// residual_ratio = F_r / F_y, lambda = Lambda, exponent = c, rate = D, io, ls, cp }. A value
// of each sense is a number (both senses) or [positive, negative]; lambda and exponent a number
// (every deterioration) or [strength, post-capping, unloading stiffness].
#include <string>
#include <vector>

#include "../messages.hpp"
#include "law_reader.hpp"
#include "ntn/laws/imk.hpp"

namespace ntn::modelc::compile {

const std::array<std::string_view, 8> kImkKeys = {
    "capping_ratio",  "pre_capping", "post_capping", "ultimate",
    "residual_ratio", "lambda",      "exponent",     "rate"};
const std::array<std::string_view, 2> kImkSharedKeys = {"yield", "yield_negative"};

namespace {

// A number for every entry of a group of n, or n numbers; `fallback` when absent (optional).
std::optional<std::vector<double>> read_group(Reader& L, Table& tb, std::string_view k,
                                              std::size_t n, std::optional<double> fallback) {
  const toml::node* node = tb.get(k, fallback ? Need::kOptional : Need::kRequired);
  if (node == nullptr) {
    if (!fallback) return std::nullopt;
    return std::vector<double>(n, *fallback);
  }
  if (node->as_array() != nullptr) return tb.numbers(k, Need::kRequired, n);
  const auto v = L.number(*node, tb.key(k));
  if (!v) return std::nullopt;
  return std::vector<double>(n, *v);
}

// The key of a fault, and the rule in words (imk_check is the kernel's rule).
std::pair<std::string_view, std::string> imk_fault(const HysteresisSpec& s, double k, ImkCheck c) {
  namespace P = imk;
  const auto& v = s.parameters;
  const auto i = static_cast<std::size_t>(c.index < 0 ? 0 : c.index);
  const char* const sense = i == 0 ? "positive" : "negative";
  const std::string in = std::string(" (") + sense + " sense)";
  switch (c.fault) {
    case ImkFault::kNone:
    case ImkFault::kStiffness:
      break;
    case ImkFault::kYield:
      return {i == 0 ? "yield" : "yield_negative", "must be positive and finite"};
    case ImkFault::kPreCapping:
      return {"pre_capping",
              "must be positive and finite: the plastic deformation from yield to "
              "the capping point" +
                  in};
    case ImkFault::kPostCapping:
      return {"post_capping",
              "must be positive and finite: the deformation from the capping "
              "point to zero strength" +
                  in};
    case ImkFault::kCappingRatio:
      return {"capping_ratio",
              "must be at least 1 (the capping strength F_c is at least the "
              "yield F_y; got " +
                  num(v[P::kCappingRatio + i]) + in + ")"};
    case ImkFault::kSteeperThanK: {
      const double fy = i == 0 ? s.yield_pos : s.yield_neg;
      return {"capping_ratio", "the hardening slope (F_c - F_y) / theta_p = " +
                                   num((v[P::kCappingRatio + i] - 1) * fy / v[P::kPreCapping + i]) +
                                   in + " is not below the elastic stiffness k = " + num(k) +
                                   ": lower capping_ratio or raise pre_capping"};
    }
    case ImkFault::kResidual:
      return {"residual_ratio",
              "must lie between 0 and capping_ratio = " + num(v[P::kCappingRatio + i]) + " (got " +
                  num(v[P::kResidualRatio + i]) + in + ")"};
    case ImkFault::kUltimate: {
      const double fy = i == 0 ? s.yield_pos : s.yield_neg;
      return {"ultimate", "must lie beyond the capping point F_y / k + theta_p = " +
                              num(fy / k + v[P::kPreCapping + i]) + " (got " +
                              num(v[P::kUltimate + i]) + in + ")"};
    }
    case ImkFault::kLambda:
      return {"lambda", "must be at least 0 and finite (0: no such deterioration; got " +
                            num(v[P::kLambda + i]) + ")"};
    case ImkFault::kExponent:
      return {"exponent",
              "must be a multiple of 0.25 from 0.25 to 4 (got " + num(v[P::kExponent + i]) + ")"};
    case ImkFault::kRate:
      return {"rate", "must be above 0 and at most 1 (got " + num(v[P::kRate + i]) + in + ")"};
    case ImkFault::kLimits: {
      const double last =
          std::min(v[P::kUltimate] - s.yield_pos / k, v[P::kUltimate + 1] - s.yield_neg / k);
      return {"cp", "cp = " + num(s.limits[2]) +
                        " lies beyond the plastic deformation at the ultimate deformation, "
                        "theta_u - F_y / k = " +
                        num(last)};
    }
  }
  return {"imk", "must be positive and finite"};
}

}  // namespace

std::optional<BehaviourIn> read_imk(Reader& L, Table& tb, const toml::table& t, BehaviourIn b) {
  namespace P = imk;
  if (!no_dashpot(L, tb, "an imk",
                  "its force must be able to drop to zero (damp the frame with [model.damping])"))
    return std::nullopt;
  const auto k = tb.positive("imk", Need::kRequired);
  const auto fy = tb.positive("yield", Need::kRequired);
  const auto fn = tb.positive("yield_negative", Need::kOptional);
  struct Group {
    std::string_view key;
    std::size_t at, n;
    std::optional<double> fallback;
  };
  const Group groups[] = {
      {"pre_capping", P::kPreCapping, 2, std::nullopt},
      {"post_capping", P::kPostCapping, 2, std::nullopt},
      {"ultimate", P::kUltimate, 2, std::nullopt},
      {"capping_ratio", P::kCappingRatio, 2, std::nullopt},
      {"residual_ratio", P::kResidualRatio, 2, 0.0},
      {"lambda", P::kLambda, 3, 0.0},
      {"exponent", P::kExponent, 3, 1.0},
      {"rate", P::kRate, 2, 1.0},
  };
  BehaviourIn out = b;
  HysteresisSpec& law = out.law;
  bool ok = k && fy && (fn || !tb.has("yield_negative"));
  for (const Group& g : groups) {
    const auto v = read_group(L, tb, g.key, g.n, g.fallback);
    if (!v) {
      ok = false;
      continue;
    }
    for (std::size_t j = 0; j < g.n; ++j)
      law.parameters[g.at + j] = (*v)[j];
  }
  ok = read_limits(L, tb, t, law.limits) && ok;
  if (!ok) return std::nullopt;
  law.rule = HysteresisRule::kImk;
  law.yield_pos = *fy;
  law.yield_neg = fn.value_or(*fy);
  const ImkCheck c = imk_check(law, *k, 0.0);
  if (c.fault != ImkFault::kNone) {
    const auto [key, words] = imk_fault(law, *k, c);
    L.error(tb.where(key), words);
    return std::nullopt;
  }
  out.kind = HingeBehaviour::kPlastic;
  out.k = *k;
  out.c = 0;
  return out;
}

}  // namespace ntn::modelc::compile
