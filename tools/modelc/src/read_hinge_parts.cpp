#include "read_hinge_parts.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "messages.hpp"
#include "ntn/hinge.hpp"

namespace ntn::modelc::compile {

// One hinge direction: "rigid", "free", { linear = k, dashpot = c }, { curve = "id" } or
// { plastic = k, yield = F, yield_negative = F, hardening = b, dashpot = c }.
std::optional<BehaviourIn> read_behaviour(Reader& L, const toml::node& n, const std::string& key) {
  BehaviourIn b;
  b.at = place(n.source(), key);
  const std::string what =
      "must be \"rigid\", \"free\", { linear = k, dashpot = c }, { curve = \"id\" } or "
      "{ plastic = k, yield = F }";
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
           {"linear", "dashpot", "curve", "plastic", "yield", "yield_negative", "hardening", "io",
            "ls", "cp"});
  tb.check_unknown();
  if (tb.conflict("linear", "curve") || tb.conflict("linear", "plastic") ||
      tb.conflict("curve", "plastic"))
    return std::nullopt;
  if (!tb.has("plastic")) {
    for (std::string_view k : {"yield", "yield_negative", "hardening", "io", "ls", "cp"}) {
      if (tb.has(k)) {
        L.error(tb.where(k), "only applies with 'plastic'");
        return std::nullopt;
      }
    }
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
    // Acceptance criteria on the peak plastic deformation: all three or none, io <= ls <= cp.
    const char* const kLimit[3] = {"io", "ls", "cp"};
    const int given = static_cast<int>(tb.has("io")) + static_cast<int>(tb.has("ls")) +
                      static_cast<int>(tb.has("cp"));
    std::array<double, 3> limits{};
    if (given > 0 && given < 3) {
      for (const char* l : kLimit) {
        if (!tb.has(l)) {
          L.error(t->source(), tb.key(l),
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
                                           " is below " + kLimit[i - 1] + " = " +
                                           num(limits[i - 1]) +
                                           ": the limits must not decrease (io <= ls <= cp)");
          ok = false;
        }
      }
    }
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
