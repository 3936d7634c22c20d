#include "read_hinge_parts.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "laws/law_reader.hpp"
#include "messages.hpp"
#include "ntn/hinge.hpp"
#include "ntn/hysteresis.hpp"

namespace ntn::modelc::compile {

namespace {

// Whether a law reader that shares key k (yield, ...) selects this table.
bool taken_by_law(const Table& tb, std::string_view k) {
  for (const LawReader& r : law_readers()) {
    if (!tb.has(r.key)) continue;
    for (std::string_view s : r.shared)
      if (s == k) return true;
  }
  return false;
}

// " or 'imk'" for the readers that share key k.
std::string also_with(std::string_view k) {
  std::string s;
  for (const LawReader& r : law_readers()) {
    for (std::string_view x : r.shared)
      if (x == k) s += " or '" + std::string(r.key) + "'";
  }
  return s;
}

bool law_values_ok(Reader& L, Table& tb, const toml::table& t) {
  // The kernel's bound on a law's values (ntn::kLawValueLimit), at the key that breaks it: a
  // value the kernel would refuse far from its cause ("hinge with a bad node, frame, curve or
  // stiffness") or overflow with.
  for (const char* k : {"yield", "yield_negative", "rigid_plastic", "hardening_stiffness",
                        "friction", "cohesion", "failure", "io", "ls", "cp"}) {
    const toml::node* v = t.get(k);
    if (v == nullptr || !(v->is_floating_point() || v->is_integer())) continue;
    const double x = v->is_integer() ? static_cast<double>(v->as_integer()->get())
                                     : v->as_floating_point()->get();
    if (std::isfinite(x) && !ntn::law_value_ok(std::fabs(x))) {
      L.error(tb.where(k), "must be below " + num(ntn::kLawValueLimit) +
                               " in magnitude (the kernel's bound on a hinge law's values; got " +
                               num(x) + ")");
      return false;
    }
  }
  return true;
}

// Which keys go together: one kind of direction, each key with the kind it belongs to.
bool combination_ok(Reader& L, Table& tb, const std::vector<std::string_view>& kinds) {
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    for (std::size_t j = i + 1; j < kinds.size(); ++j) {
      if (kinds[i] == "linear" && kinds[j] == "failure") continue;  // a spring that breaks
      if (tb.conflict(kinds[i], kinds[j])) return false;
    }
  }
  const std::pair<std::string_view, std::string_view> kOnlyWith[] = {
      {"hardening_stiffness", "rigid_plastic"}, {"control", "fixed_if"}, {"circle", "friction"}};
  for (const auto& [k, with] : kOnlyWith) {
    if (tb.has(k) && !tb.has(with)) {
      L.error(tb.where(k), "only applies with '" + std::string(with) + "'");
      return false;
    }
  }
  for (std::string_view k : {"yield", "hardening"}) {
    if (tb.has(k) && !tb.has("plastic") && !taken_by_law(tb, k)) {
      L.error(tb.where(k), "only applies with 'plastic'" + also_with(k));
      return false;
    }
  }
  for (std::string_view k : {"cohesion", "normal"}) {
    if (tb.has(k) && !tb.has("friction")) {
      L.error(tb.where(k), "only applies with 'friction'");
      return false;
    }
  }
  if (tb.has("yield_negative") && !tb.has("plastic") && !tb.has("rigid_plastic") &&
      !taken_by_law(tb, "yield_negative")) {
    L.error(tb.where("yield_negative"),
            "only applies with 'plastic' or 'rigid_plastic'" + also_with("yield_negative"));
    return false;
  }
  for (const LawReader& r : law_readers()) {
    for (std::string_view k : r.own) {
      if (tb.has(k) && !tb.has(r.key)) {
        L.error(tb.where(k), "only applies with '" + std::string(r.key) + "'");
        return false;
      }
    }
  }
  bool limits_apply = tb.has("plastic") || tb.has("rigid_plastic") || tb.has("friction");
  std::string laws;
  for (const LawReader& r : law_readers()) {
    limits_apply = limits_apply || tb.has(r.key);
    laws += ", '" + std::string(r.key) + "'";
  }
  for (std::string_view k : {"io", "ls", "cp"}) {
    if (tb.has(k) && !limits_apply) {
      L.error(tb.where(k),
              "only applies with 'plastic'" + laws + ", 'rigid_plastic' or 'friction'");
      return false;
    }
  }
  return true;
}

// Coulomb friction: rigid while |f| < mu max(0, -N) + cohesion (ntn/slip.hpp).
std::optional<BehaviourIn> read_friction(Reader& L, Table& tb, const toml::table& t,
                                         BehaviourIn b) {
  // Coulomb friction: rigid while |f| < mu max(0, -N) + cohesion, N the force of direction
  // `normal` of the same hinge (ntn/slip.hpp).
  const auto mu = tb.non_negative("friction", Need::kOptional);
  const auto c = tb.non_negative("cohesion", Need::kOptional);
  const auto normal = tb.choice("normal", Need::kOptional, {"ux", "uy", "uz", "rx", "ry", "rz"});
  const auto circle = tb.choice("circle", Need::kOptional, {"ux", "uy", "uz", "rx", "ry", "rz"});
  std::array<double, 3> limits{};
  bool ok = mu && (c || !tb.has("cohesion")) && (normal || !tb.has("normal")) &&
            (circle || !tb.has("circle"));
  ok = read_limits(L, tb, t, limits) && ok;
  ok = no_dashpot(L, tb, "a friction", "it is rigid while it sticks") && ok;
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

// Rigid while the force of its control has the sign, free otherwise (ntn/slip.hpp).
std::optional<BehaviourIn> read_fixed_if(Reader& L, Table& tb, BehaviourIn b) {
  // Rigid while the force of its control (itself by default) has the sign, free otherwise
  // (ntn/slip.hpp; on its own force a stop at d = 0).
  const auto sign = tb.choice("fixed_if", Need::kRequired, {"negative", "positive"});
  const auto control = tb.choice("control", Need::kOptional, {"ux", "uy", "uz", "rx", "ry", "rz"});
  if (!no_dashpot(L, tb, "a fixed_if", "it is rigid or free")) return std::nullopt;
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

// Rigid or a linear spring until its force first passes the limit (ntn/laws/brittle.hpp).
std::optional<BehaviourIn> read_failure(Reader& L, Table& tb, BehaviourIn b) {
  // Rigid (or a linear spring) until its force first passes the limit, free from then on
  // (ntn/laws/brittle.hpp; rigid under ntn_exact: ntn/slip.hpp).
  const auto fy = tb.positive("failure", Need::kRequired);
  const auto k = tb.has("linear") ? tb.positive("linear", Need::kRequired) : std::nullopt;
  if (!no_dashpot(L, tb, "a failure", "its force must drop to zero when it breaks"))
    return std::nullopt;
  if (!fy || (!k && tb.has("linear"))) return std::nullopt;
  b.kind = k ? HingeBehaviour::kPlastic : HingeBehaviour::kRigidPlastic;
  b.k = k.value_or(0.0);
  b.law.rule = HysteresisRule::kBrittle;
  b.law.yield_pos = b.law.yield_neg = *fy;
  return b;
}

// Rigid until its force reaches the yield, then sliding at it (ntn/slip.hpp).
std::optional<BehaviourIn> read_rigid_plastic(Reader& L, Table& tb, const toml::table& t,
                                              BehaviourIn b) {
  // Rigid until its force reaches the yield, then sliding at it (ntn/slip.hpp).
  const auto fy = tb.positive("rigid_plastic", Need::kRequired);
  const auto fn = tb.positive("yield_negative", Need::kOptional);
  const auto hard = tb.non_negative("hardening_stiffness", Need::kOptional);
  std::array<double, 3> limits{};
  bool ok = fy && (fn || !tb.has("yield_negative")) && (hard || !tb.has("hardening_stiffness"));
  ok = read_limits(L, tb, t, limits) && ok;
  ok = no_dashpot(L, tb, "a rigid_plastic", "it is rigid while it sticks") && ok;
  if (!ok) return std::nullopt;
  b.kind = HingeBehaviour::kRigidPlastic;
  b.k = hard.value_or(0.0);  // hardening with the slip: a parallel spring (ntn/slip.hpp)
  b.c = 0;
  b.law.yield_pos = *fy;
  b.law.yield_neg = fn.value_or(*fy);
  b.law.limits = limits;
  return b;
}

// Bilinear elasto-plastic with kinematic hardening (ntn/laws/bilinear.hpp).
std::optional<BehaviourIn> read_plastic(Reader& L, Table& tb, const toml::table& t, BehaviourIn b) {
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
  ok = read_limits(L, tb, t, limits) && ok;
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

}  // namespace

// One hinge direction: "rigid", "free", { linear = k, dashpot = c }, { curve = "id" },
// { plastic = k, yield = F, yield_negative = F, hardening = b, dashpot = c, io, ls, cp }, a law
// of the law readers' table (laws/law_readers.cpp: backbone, imk), { rigid_plastic = F },
// { friction = mu, ... }, { fixed_if = "..." } or { failure = F }.
std::optional<BehaviourIn> read_behaviour(Reader& L, const toml::node& n, const std::string& key) {
  BehaviourIn b;
  b.at = place(n.source(), key);
  std::string what =
      "must be \"rigid\", \"free\", { linear = k, dashpot = c }, { curve = \"id\" }, "
      "{ plastic = k, yield = F }, ";
  for (const LawReader& r : law_readers())
    what += std::string(r.form) + ", ";
  what +=
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
  // The keys: plastic's, each law reader's (its key and its own keys), the slip laws'.
  std::vector<std::string_view> keys = {"linear", "dashpot",        "curve",    "plastic",
                                        "yield",  "yield_negative", "hardening"};
  std::vector<std::string_view> kinds = {"linear", "curve", "plastic"};
  for (const LawReader& r : law_readers()) {
    keys.push_back(r.key);
    keys.insert(keys.end(), r.own.begin(), r.own.end());
    kinds.push_back(r.key);
  }
  for (std::string_view k :
       {"rigid_plastic", "hardening_stiffness", "friction", "cohesion", "normal", "circle",
        "fixed_if", "control", "failure", "io", "ls", "cp"})
    keys.push_back(k);
  for (std::string_view k : {"rigid_plastic", "friction", "fixed_if", "failure"})
    kinds.push_back(k);
  Table tb(L, *t, key, keys);
  tb.check_unknown();
  if (!law_values_ok(L, tb, *t)) return std::nullopt;
  if (!combination_ok(L, tb, kinds)) return std::nullopt;
  for (const LawReader& r : law_readers())
    if (tb.has(r.key)) return r.read(L, tb, *t, b);
  if (tb.has("friction")) return read_friction(L, tb, *t, b);
  if (tb.has("fixed_if")) return read_fixed_if(L, tb, b);
  if (tb.has("failure")) return read_failure(L, tb, b);
  if (tb.has("rigid_plastic")) return read_rigid_plastic(L, tb, *t, b);
  if (tb.has("plastic")) return read_plastic(L, tb, *t, b);
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
