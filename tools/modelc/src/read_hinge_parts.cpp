#include "read_hinge_parts.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "messages.hpp"
#include "ntn/hinge.hpp"
#include "ntn/hysteresis.hpp"

namespace ntn::modelc::compile {

namespace {

// Acceptance criteria io, ls, cp on the peak plastic deformation: all three or none,
// io <= ls <= cp. False (reported) when they are not.
bool read_limits(Reader& L, Table& tb, const toml::table& t, std::array<double, 3>& limits) {
  const char* const kLimit[3] = {"io", "ls", "cp"};
  const int given = static_cast<int>(tb.has("io")) + static_cast<int>(tb.has("ls")) +
                    static_cast<int>(tb.has("cp"));
  limits = {};
  bool ok = true;
  if (given > 0 && given < 3) {
    for (const char* l : kLimit) {
      if (!tb.has(l)) {
        L.error(t.source(), tb.key(l),
                "missing: give all three acceptance limits io, ls and cp, or none");
        ok = false;
      }
    }
  } else if (given == 3) {
    for (std::size_t i = 0; i < 3; ++i) {
      const auto v = tb.positive(kLimit[i], Need::kRequired);
      if (!v) {
        ok = false;
      } else {
        limits[i] = *v;
      }
    }
    for (std::size_t i = 1; i < 3 && ok; ++i) {
      if (limits[i] < limits[i - 1]) {
        L.error(tb.where(kLimit[i]), std::string(kLimit[i]) + " = " + num(limits[i]) +
                                         " is below " + kLimit[i - 1] + " = " + num(limits[i - 1]) +
                                         ": the limits must not decrease (io <= ls <= cp)");
        ok = false;
      }
    }
  }
  return ok;
}

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
  if (tb.has("dashpot")) {
    L.error(tb.where("dashpot"),
            "a backbone direction takes no dashpot: its force must be able to drop to zero "
            "(damp the frame with [model.damping])");
    ok = false;
  }
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

}  // namespace

// One hinge direction: "rigid", "free", { linear = k, dashpot = c }, { curve = "id" },
// { plastic = k, yield = F, yield_negative = F, hardening = b, dashpot = c, io, ls, cp } or
// { backbone = [B, C, D, E], backbone_negative = [...], rule = "...", io, ls, cp }.
std::optional<BehaviourIn> read_behaviour(Reader& L, const toml::node& n, const std::string& key) {
  BehaviourIn b;
  b.at = place(n.source(), key);
  const std::string what =
      "must be \"rigid\", \"free\", { linear = k, dashpot = c }, { curve = \"id\" }, "
      "{ plastic = k, yield = F }, { backbone = [B, C, D, E], rule = \"kinematic\" }, "
      "{ rigid_plastic = F }, { friction = mu, normal = \"ux\" }, { fixed_if = \"negative\" } "
      "or { failure = F }";
  if (const auto* s = n.as_string()) {
    if (s->get() == "rigid" || s->get() == "free") {
      b.kind = s->get() == "rigid" ? HingeBehaviour::kRigid : HingeBehaviour::kFree;
      return b;
    }
    L.error(n.source(), key, what + " (got \"" + s->get() + "\")");
    return std::nullopt;
  }
  const auto* t = n.as_table();
  if (t == nullptr) {
    L.error(n.source(), key, what + ", got " + type_name(n));
    return std::nullopt;
  }
  Table tb(L, *t, key,
           {"linear",
            "dashpot",
            "curve",
            "plastic",
            "yield",
            "yield_negative",
            "hardening",
            "backbone",
            "backbone_negative",
            "rule",
            "rigid_plastic",
            "hardening_stiffness",
            "friction",
            "cohesion",
            "normal",
            "circle",
            "fixed_if",
            "control",
            "failure",
            "io",
            "ls",
            "cp"});
  tb.check_unknown();
  // The kernel's bound on a law's values (ntn::kLawValueLimit), at the key that breaks it: a
  // value the kernel would refuse far from its cause ("hinge with a bad node, frame, curve or
  // stiffness") or overflow with.
  for (const char* k : {"yield", "yield_negative", "rigid_plastic", "hardening_stiffness",
                        "friction", "cohesion", "failure", "io", "ls", "cp"}) {
    const toml::node* v = t->get(k);
    if (v == nullptr || !(v->is_floating_point() || v->is_integer())) continue;
    const double x = v->is_integer() ? static_cast<double>(v->as_integer()->get())
                                     : v->as_floating_point()->get();
    if (std::isfinite(x) && !ntn::law_value_ok(std::fabs(x))) {
      L.error(tb.where(k), "must be below " + num(ntn::kLawValueLimit) +
                               " in magnitude (the kernel's bound on a hinge law's values; got " +
                               num(x) + ")");
      return std::nullopt;
    }
  }
  const char* const kKinds[8] = {"linear",        "curve",    "plastic",  "backbone",
                                 "rigid_plastic", "friction", "fixed_if", "failure"};
  for (std::size_t i = 0; i < 8; ++i) {
    for (std::size_t j = i + 1; j < 8; ++j) {
      if (i == 0 && j == 7) continue;  // { linear = k, failure = F }: a spring that breaks
      if (tb.conflict(kKinds[i], kKinds[j])) return std::nullopt;
    }
  }
  const std::pair<std::string_view, std::string_view> kOnlyWith[] = {
      {"hardening_stiffness", "rigid_plastic"}, {"control", "fixed_if"}, {"circle", "friction"}};
  for (const auto& [k, with] : kOnlyWith) {
    if (tb.has(k) && !tb.has(with)) {
      L.error(tb.where(k), "only applies with '" + std::string(with) + "'");
      return std::nullopt;
    }
  }
  for (std::string_view k : {"yield", "hardening"}) {
    if (tb.has(k) && !tb.has("plastic")) {
      L.error(tb.where(k), "only applies with 'plastic'");
      return std::nullopt;
    }
  }
  for (std::string_view k : {"cohesion", "normal"}) {
    if (tb.has(k) && !tb.has("friction")) {
      L.error(tb.where(k), "only applies with 'friction'");
      return std::nullopt;
    }
  }
  if (tb.has("yield_negative") && !tb.has("plastic") && !tb.has("rigid_plastic")) {
    L.error(tb.where("yield_negative"), "only applies with 'plastic' or 'rigid_plastic'");
    return std::nullopt;
  }
  for (std::string_view k : {"backbone_negative", "rule"}) {
    if (tb.has(k) && !tb.has("backbone")) {
      L.error(tb.where(k), "only applies with 'backbone'");
      return std::nullopt;
    }
  }
  for (std::string_view k : {"io", "ls", "cp"}) {
    if (tb.has(k) && !tb.has("plastic") && !tb.has("backbone") && !tb.has("rigid_plastic") &&
        !tb.has("friction")) {
      L.error(tb.where(k),
              "only applies with 'plastic', 'backbone', 'rigid_plastic' or 'friction'");
      return std::nullopt;
    }
  }
  if (tb.has("backbone")) return read_backbone(L, tb, *t, b);
  if (tb.has("friction")) {
    // Coulomb friction: rigid while |f| < mu max(0, -N) + cohesion, N the force of direction
    // `normal` of the same hinge (ntn/slip.hpp).
    const auto mu = tb.non_negative("friction", Need::kOptional);
    const auto c = tb.non_negative("cohesion", Need::kOptional);
    const auto normal = tb.choice("normal", Need::kOptional, {"ux", "uy", "uz", "rx", "ry", "rz"});
    const auto circle = tb.choice("circle", Need::kOptional, {"ux", "uy", "uz", "rx", "ry", "rz"});
    std::array<double, 3> limits{};
    bool ok = mu && (c || !tb.has("cohesion")) && (normal || !tb.has("normal")) &&
              (circle || !tb.has("circle"));
    ok = read_limits(L, tb, *t, limits) && ok;
    if (tb.has("dashpot")) {
      L.error(tb.where("dashpot"),
              "a friction direction takes no dashpot: it is rigid while it sticks");
      ok = false;
    }
    if (!ok) return std::nullopt;
    b.kind = HingeBehaviour::kRigidPlastic;
    b.law.normal = normal.value_or(0);
    b.law.mu = *mu;
    b.law.cohesion = c.value_or(0.0);
    b.law.limits = limits;
    b.normal_at = tb.has("normal") ? tb.where("normal") : b.at;
    b.law.circle = circle.value_or(-1);
    if (circle) b.circle_at = tb.where("circle");
    return b;
  }
  if (tb.has("fixed_if")) {
    // Rigid while the force of its control (itself by default) has the sign, free otherwise
    // (ntn/slip.hpp; on its own force a stop at d = 0).
    const auto sign = tb.choice("fixed_if", Need::kRequired, {"negative", "positive"});
    const auto control =
        tb.choice("control", Need::kOptional, {"ux", "uy", "uz", "rx", "ry", "rz"});
    if (tb.has("dashpot")) {
      L.error(tb.where("dashpot"), "a fixed_if direction takes no dashpot: it is rigid or free");
      return std::nullopt;
    }
    if (!sign || (!control && tb.has("control"))) return std::nullopt;
    const int s_ = *sign == 0 ? -1 : 1;
    b.normal_at = tb.has("control") ? tb.where("control") : b.at;
    if (control) {
      b.kind = HingeBehaviour::kRigidPlastic;
      b.law.fixed_if = s_;
      b.law.normal = *control;
    } else {
      b.kind = HingeBehaviour::kCurve;
      b.stop = s_;
    }
    return b;
  }
  if (tb.has("failure")) {
    // Rigid (or a linear spring) until its force first passes the limit, free from then on
    // (ntn/laws/brittle.hpp; rigid under ntn_exact: ntn/slip.hpp).
    const auto fy = tb.positive("failure", Need::kRequired);
    const auto k = tb.has("linear") ? tb.positive("linear", Need::kRequired) : std::nullopt;
    if (tb.has("dashpot")) {
      L.error(tb.where("dashpot"),
              "a failure direction takes no dashpot: its force must drop "
              "to zero when it breaks");
      return std::nullopt;
    }
    if (!fy || (!k && tb.has("linear"))) return std::nullopt;
    b.kind = k ? HingeBehaviour::kPlastic : HingeBehaviour::kRigidPlastic;
    b.k = k.value_or(0.0);
    b.law.rule = HysteresisRule::kBrittle;
    b.law.yield_pos = b.law.yield_neg = *fy;
    return b;
  }
  if (tb.has("rigid_plastic")) {
    // Rigid until its force reaches the yield, then sliding at it (ntn/slip.hpp).
    const auto fy = tb.positive("rigid_plastic", Need::kRequired);
    const auto fn = tb.positive("yield_negative", Need::kOptional);
    const auto hard = tb.non_negative("hardening_stiffness", Need::kOptional);
    std::array<double, 3> limits{};
    bool ok = fy && (fn || !tb.has("yield_negative")) && (hard || !tb.has("hardening_stiffness"));
    ok = read_limits(L, tb, *t, limits) && ok;
    if (tb.has("dashpot")) {
      L.error(tb.where("dashpot"),
              "a rigid_plastic direction takes no dashpot: it is rigid while it sticks");
      ok = false;
    }
    if (!ok) return std::nullopt;
    b.kind = HingeBehaviour::kRigidPlastic;
    b.k = hard.value_or(0.0);  // hardening with the slip: a parallel spring (ntn/slip.hpp)
    b.c = 0;
    b.law.yield_pos = *fy;
    b.law.yield_neg = fn.value_or(*fy);
    b.law.limits = limits;
    return b;
  }
  if (tb.has("plastic")) {
    // Bilinear elasto-plastic with kinematic hardening (ntn/hysteresis.hpp).
    const auto k = tb.positive("plastic", Need::kRequired);
    const auto fy = tb.positive("yield", Need::kRequired);
    const auto fn = tb.positive("yield_negative", Need::kOptional);
    const auto hard = tb.number("hardening", Need::kOptional);
    const auto c = tb.non_negative("dashpot", Need::kOptional);
    bool ok = k && fy && (fn || !tb.has("yield_negative")) && (hard || !tb.has("hardening")) &&
              (c || !tb.has("dashpot"));
    if (hard && !(*hard >= 0 && *hard < 1)) {
      L.error(tb.where("hardening"),
              "must be at least 0 and less than 1: the tangent after yield is hardening x k (got " +
                  num(*hard) + ")");
      ok = false;
    }
    std::array<double, 3> limits{};
    ok = read_limits(L, tb, *t, limits) && ok;
    if (!ok) return std::nullopt;
    b.law.limits = limits;
    b.kind = HingeBehaviour::kPlastic;
    b.k = *k;
    b.c = c.value_or(0.0);
    b.law.yield_pos = *fy;
    b.law.yield_neg = fn.value_or(*fy);
    b.law.hardening = hard.value_or(0.0);
    return b;
  }
  if (tb.has("curve")) {
    if (tb.has("dashpot")) {
      L.error(tb.where("dashpot"), "only applies with 'linear'");
      return std::nullopt;
    }
    auto c = read_id(L, tb, "curve");
    if (!c) return std::nullopt;
    b.kind = HingeBehaviour::kCurve;
    b.curve = *c;
    return b;
  }
  const toml::node* k = tb.get("linear", Need::kRequired, " (or give curve = \"id\")");
  if (k == nullptr) return std::nullopt;
  const auto kv = L.non_negative(*k, tb.key("linear"));
  const auto cv = tb.non_negative("dashpot", Need::kOptional);
  if (!kv || (!cv && tb.has("dashpot"))) return std::nullopt;
  b.kind = HingeBehaviour::kLinear;
  b.k = *kv;
  b.c = cv.value_or(0.0);
  return b;
}

// release_start / release_end: an array of DOF names (those free, the rest rigid), or a table
// of behaviours per direction (those not named rigid).
std::optional<Release> read_release(Reader& L, const toml::node& n, const std::string& key) {
  Release r;
  r.at = place(n.source(), key);
  for (BehaviourIn& d : r.dirs)
    d.at = r.at;
  if (const auto* a = n.as_array()) {
    if (a->empty()) {
      L.error(n.source(), key,
              "expected at least one DOF name to release (" + quoted_list(kDofNames) + ")");
      return std::nullopt;
    }
    bool ok = true;
    unsigned seen = 0;
    for (std::size_t i = 0; i < a->size(); ++i) {
      const std::string ik = key + "[" + std::to_string(i) + "]";
      const auto d = L.choice((*a)[i], ik, kDofNames);
      if (!d) {
        ok = false;
      } else if ((seen >> *d) & 1U) {
        L.error(
            (*a)[i].source(), ik,
            "\"" + std::string(kDofNames[static_cast<std::size_t>(*d)]) + "\" is released twice");
        ok = false;
      } else {
        seen |= 1U << *d;
        r.dirs[static_cast<std::size_t>(*d)].kind = HingeBehaviour::kFree;
        r.dirs[static_cast<std::size_t>(*d)].at = place((*a)[i].source(), ik);
      }
    }
    if (!ok) return std::nullopt;
    return r;
  }
  if (const auto* t = n.as_table()) {
    Table tb(L, *t, key, kDofNames);
    tb.check_unknown();
    if (t->empty()) {
      L.error(n.source(), key, "expected at least one direction (" + plain_list(kDofNames) + ")");
      return std::nullopt;
    }
    bool ok = true;
    for (std::size_t d = 0; d < kDofNames.size(); ++d) {
      const toml::node* v = tb.get(kDofNames[d], Need::kOptional);
      if (v == nullptr) continue;
      auto b = read_behaviour(L, *v, tb.key(kDofNames[d]));
      if (b) {
        r.dirs[d] = *b;
      } else {
        ok = false;
      }
    }
    if (!ok) return std::nullopt;
    return r;
  }
  L.error(n.source(), key,
          "must be an array of DOF names (released: free) or a table of behaviours per "
          "direction, got " +
              type_name(n));
  return std::nullopt;
}

// Hinge axes: rows x, y, z in global axes, orthonormal and right-handed to 1e-9.
std::optional<std::array<double, 9>> read_axes(Reader& L, const toml::node& n,
                                               const std::string& key) {
  auto rows =
      L.array_of<std::vector<double>>(n, key, 3, [&L](const toml::node& e, const std::string& ek) {
        return L.array_of<double>(
            e, ek, 3, [&L](const toml::node& x, const std::string& xk) { return L.number(x, xk); });
      });
  if (!rows) return std::nullopt;
  std::array<double, 9> R{};
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t c = 0; c < 3; ++c)
      R[3 * r + c] = (*rows)[r][c];
  const AxesCheck c = check_axes(R);  // the kernel's rule (make_hinge_data refuses the same)
  if (!c.orthonormal) {
    L.error(n.source(), key,
            "axes must be orthonormal to 1e-9 (rows x, y, z of unit length, at right angles): "
            "the largest entry of |R R^T - I| is " +
                num(c.worst));
    return std::nullopt;
  }
  if (!c.right_handed) {
    L.error(n.source(), key,
            "axes must be right-handed (z = x cross y); these have det = " + num(c.det) +
                ": turn the z row round");
    return std::nullopt;
  }
  return R;
}

}  // namespace ntn::modelc::compile
