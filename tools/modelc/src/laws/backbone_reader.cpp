// The reader of the backbone laws (ntn/laws/backbone.hpp): { backbone = [B, C, D, E],
// backbone_negative = [...], rule = "kinematic" | "peak_oriented", io, ls, cp }.
#include <cmath>
#include <string>
#include <utility>

#include "../messages.hpp"
#include "law_reader.hpp"
#include "ntn/hysteresis.hpp"

namespace ntn::modelc::compile {

const std::array<std::string_view, 2> kBackboneKeys = {"backbone_negative", "rule"};

namespace {

constexpr const char* kPointName[4] = {"B (yield)", "C (capping)", "D (residual)", "E (ultimate)"};

// The kernel's envelope rule (ntn/laws/backbone.hpp envelope_check) in words.
std::string envelope_fault(const std::array<CurvePoint, 4>& p, double k, EnvelopeCheck c) {
  const auto i = static_cast<std::size_t>(c.point);
  const std::string name = kPointName[i];
  switch (c.fault) {
    case EnvelopeFault::kNone:
      break;
    case EnvelopeFault::kYield:
      return "point " + name + " needs a positive deformation and force (got [" + num(p[0].d) +
             ", " + num(p[0].force) + "]); the elastic stiffness is its force over its deformation";
    case EnvelopeFault::kOffElastic:
      return "point " + name + " [" + num(p[0].d) + ", " + num(p[0].force) +
             "] is not on the elastic line of the positive sense (k = " + num(k) +
             "): both senses unload at the same k; give its deformation as force / k = " +
             num(p[0].force / k);
    case EnvelopeFault::kOrder:
      return "points out of order: " + name + " at deformation " + num(p[i].d) +
             (i == 1 ? " must lie beyond " : " must not lie before ") + kPointName[i - 1] + " at " +
             num(p[i - 1].d) + (i == 1 ? "" : " (equal deformations: a vertical drop)");
    case EnvelopeFault::kCappingBelow:
      return "point " + name + " has force " + num(p[1].force) + ", below the yield force " +
             num(p[0].force) + " at B: the capping strength is the envelope's largest";
    case EnvelopeFault::kResidualAbove:
      return "point " + name + " has force " + num(p[2].force) +
             ": the residual strength must lie between 0 and the capping strength " +
             num(p[1].force) + " at C";
    case EnvelopeFault::kNegativeForce:
      return "point " + name + " has force " + num(p[3].force) + ": strengths are magnitudes, >= 0";
    case EnvelopeFault::kSteeperThanK: {
      const std::size_t a = i == 1 ? 0 : 2;
      return "the segment from " + std::string(kPointName[a]) + " to " + name + " rises at " +
             num((p[i].force - p[a].force) / (p[i].d - p[a].d)) +
             ", not below the elastic stiffness k = " + num(k) +
             ": a backbone hardens less steeply than it loads elastically";
    }
  }
  return {};
}

// A backbone's four points B, C, D, E as [deformation, force] pairs (magnitudes; A is the
// origin). Each pair is read here; their order is the kernel's rule (envelope_check).
std::optional<std::array<CurvePoint, 4>> read_backbone_points(Reader& L, Table& tb,
                                                              std::string_view k) {
  const toml::node* n = tb.get(k, Need::kRequired);
  if (n == nullptr) return std::nullopt;
  const std::string key = tb.key(k);
  const auto* a = n->as_array();
  if (a == nullptr || a->size() != 4) {
    L.error(n->source(), key,
            "expected the 4 points B, C, D, E of an ASCE 41 backbone as [deformation, force] "
            "pairs (A is the origin), got " +
                (a != nullptr ? std::to_string(a->size()) + " points" : type_name(*n)));
    return std::nullopt;
  }
  std::array<CurvePoint, 4> p{};
  bool ok = true;
  for (std::size_t i = 0; i < 4; ++i) {
    const auto v = L.array_of<double>(
        (*a)[i], key + "[" + std::to_string(i) + "]", 2,
        [&L](const toml::node& e, const std::string& ek) { return L.non_negative(e, ek); });
    if (v) {
      p[i] = {(*v)[0], (*v)[1]};
    } else {
      ok = false;
    }
  }
  if (!ok) return std::nullopt;
  return p;
}

// The place of point i of backbone key k (for the envelope rule's message).
Where point_place(Table& tb, std::string_view k, int i) {
  const toml::node* n = tb.raw().get(k);
  const auto* a = n != nullptr ? n->as_array() : nullptr;
  if (a == nullptr || i < 0 || static_cast<std::size_t>(i) >= a->size()) return tb.where(k);
  return place((*a)[static_cast<std::size_t>(i)].source(),
               tb.key(k) + "[" + std::to_string(i) + "]");
}

}  // namespace

// { backbone = [B, C, D, E], backbone_negative = [...], rule = "kinematic" | "peak_oriented",
// io, ls, cp }: the elastic stiffness is B's force over its deformation.
std::optional<BehaviourIn> read_backbone(Reader& L, Table& tb, const toml::table& t,
                                         BehaviourIn b) {
  const auto pos = read_backbone_points(L, tb, "backbone");
  std::optional<std::array<CurvePoint, 4>> neg;
  if (tb.has("backbone_negative")) neg = read_backbone_points(L, tb, "backbone_negative");
  const auto rule = tb.choice("rule", Need::kRequired, {"kinematic", "peak_oriented"});
  std::array<double, 3> limits{};
  bool ok = read_limits(L, tb, t, limits) && pos && rule && (neg || !tb.has("backbone_negative"));
  ok = no_dashpot(L, tb, "a backbone",
                  "its force must be able to drop to zero (damp the frame with [model.damping])") &&
       ok;
  if (!pos) return std::nullopt;
  const double k = (*pos)[0].d > 0 ? (*pos)[0].force / (*pos)[0].d : 0.0;
  std::array<CurvePoint, 4> neg_points = neg.value_or(*pos);
  // Within 1e-6 of the elastic line counts as on it (a yield point typed from a table); the
  // kernel then gets B's deformation as force / k.
  if (neg && k > 0 && (*neg)[0].d > 0 && std::fabs((*neg)[0].force / (*neg)[0].d - k) <= 1e-6 * k)
    neg_points[0].d = neg_points[0].force / k;
  for (const auto& [key, p] :
       {std::pair<std::string_view, const std::array<CurvePoint, 4>*>{"backbone", &*pos},
        {"backbone_negative", &neg_points}}) {
    if (key == "backbone_negative" && !neg) continue;
    const EnvelopeCheck c = envelope_check(*p, k);
    if (c.fault != EnvelopeFault::kNone) {
      L.error(point_place(tb, key, c.point), envelope_fault(*p, k, c));
      ok = false;
    }
  }
  if (!ok) return std::nullopt;
  for (const auto& [sense, p] :
       {std::pair<const char*, const std::array<CurvePoint, 4>*>{"positive", &*pos},
        {"negative", &neg_points}}) {
    const double last = backbone_last_plastic(*p, k);
    if (limits[2] > last) {
      L.error(tb.where("cp"), "cp = " + num(limits[2]) +
                                  " lies beyond the backbone's last point: "
                                  "the plastic deformation at E in the " +
                                  sense + " sense is d_E - f_E / k = " + num(last));
      return std::nullopt;
    }
  }
  b.kind = HingeBehaviour::kPlastic;
  b.k = k;
  b.c = 0;
  b.law.rule = *rule == 0 ? HysteresisRule::kKinematic : HysteresisRule::kPeakOriented;
  b.law.backbone_pos = *pos;
  b.law.backbone_neg = neg_points;
  b.law.yield_pos = (*pos)[0].force;
  b.law.yield_neg = neg_points[0].force;
  b.law.hardening = 0;
  b.law.limits = limits;
  return b;
}

}  // namespace ntn::modelc::compile
