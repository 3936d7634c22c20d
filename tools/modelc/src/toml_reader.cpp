#include "toml_reader.hpp"

#include <cstdio>

namespace ntn::modelc::compile {

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a floating-point number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    default:
      return "nothing";
  }
}

std::optional<IdAt> read_id(Reader& L, Table& t, std::string_view k, Need need) {
  auto s = t.string(k, need);
  if (!s) return std::nullopt;
  for (const char c : *s) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) {
      char code[8];
      std::snprintf(code, sizeof code, "0x%02X",
                    static_cast<unsigned>(static_cast<unsigned char>(c)));
      L.error(t.where(k), std::string("must not contain control characters (it has ") + code +
                              "): ids and names appear in messages, CSV headers, command lines "
                              "and the generated header");
      return std::nullopt;
    }
  }
  return IdAt{*s, t.where(k)};
}

std::optional<NodeRef> read_node_ref(Reader& L, const toml::node& n, const std::string& key) {
  if (n.is_integer()) {
    const auto id = L.integer(n, key, 0, kMaxNodeId);
    if (!id) return std::nullopt;
    NodeRef r;
    r.id = *id;
    return r;
  }
  const auto* tt = n.as_table();
  if (tt == nullptr) {
    L.error(n.source(), key,
            "expected a node id or a point inside a member ({ member = \"B1\", at = 0.5 } or "
            "{ member = \"B1\", at_m = 2.0 }), got " +
                type_name(n));
    return std::nullopt;
  }
  Table t(L, *tt, key, {"member", "at", "at_m"});
  t.check_unknown();
  bool ok = !std::any_of(tt->begin(), tt->end(), [](auto&& kv) {
    const std::string_view k = kv.first.str();
    return k != "member" && k != "at" && k != "at_m";
  });
  MemberPoint mp;
  auto member = read_id(L, t, "member");
  ok = ok && member.has_value();
  if (t.conflict("at", "at_m")) return std::nullopt;
  if (!t.has("at") && !t.has("at_m")) {
    L.error(tt->source(), key,
            "a point inside a member needs 'at' (a fraction of the length, 0 to 1) or 'at_m' "
            "(metres from the member's start)");
    return std::nullopt;
  }
  mp.in_metres = t.has("at_m");
  const std::string_view ak = mp.in_metres ? "at_m" : "at";
  const auto at = t.number(ak, Need::kRequired);
  if (at && mp.in_metres && *at < 0) {
    L.error(t.where(ak), "must be between 0 and the member's length (got " + num(*at) + " m)");
    ok = false;
  } else if (at && !mp.in_metres && !(*at >= 0 && *at <= 1)) {
    L.error(t.where(ak),
            "must be between 0 and 1 (a fraction of the member's length; got " + num(*at) + ")");
    ok = false;
  }
  if (!ok || !at) return std::nullopt;
  mp.member = *member;
  mp.at = *at;
  mp.at_at = t.where(ak);
  NodeRef r;
  r.point = mp;
  return r;
}

std::optional<NodeRef> read_node_ref(Reader& L, Table& t, std::string_view k, Need need) {
  const toml::node* n = t.get(k, need);
  return n ? read_node_ref(L, *n, t.key(k)) : std::nullopt;
}

// An array of [x, y] points whose x increases strictly (time-function and curve points): each
// bad entry and each x that does not come after the previous one is reported; `ok` turns false.
std::vector<std::array<double, 2>> increasing_pairs(Reader& L, const toml::array& a,
                                                    const std::string& key, const char* x,
                                                    const char* unit, const char* what, bool& ok) {
  std::vector<std::array<double, 2>> out;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string k = key + "[" + std::to_string(i) + "]";
    auto xy = L.array_of<double>(
        a[i], k, 2, [&L](const toml::node& e, const std::string& ek) { return L.number(e, ek); });
    if (!xy) {
      ok = false;
      continue;
    }
    if (!out.empty() && !((*xy)[0] > out.back()[0])) {
      L.error(a[i].source(), k,
              std::string(x) + " = " + num((*xy)[0]) + unit +
                  " does not come after the previous "
                  "point's " +
                  x + " = " + num(out.back()[0]) + unit + ": " + what + " must increase strictly");
      ok = false;
    }
    out.push_back({(*xy)[0], (*xy)[1]});
  }
  return out;
}

std::optional<std::vector<std::array<double, 2>>> read_points(Reader& L, Table& t,
                                                              std::size_t min_points,
                                                              const char* expected, const char* x,
                                                              const char* unit, const char* what) {
  const toml::node* pts = t.get("points", Need::kRequired);
  if (pts == nullptr) return std::nullopt;
  const std::string key = t.key("points");
  const auto* a = pts->as_array();
  if (a == nullptr || a->size() < min_points) {
    std::string got = type_name(*pts);
    if (a != nullptr && min_points == 1) {
      got = "an empty array";
    } else if (a != nullptr) {
      got = std::to_string(a->size()) + (a->size() == 1 ? " point" : " points");
    }
    L.error(pts->source(), key, std::string("expected an array of ") + expected + ", got " + got);
    return std::nullopt;
  }
  bool ok = true;
  std::vector<std::array<double, 2>> out = increasing_pairs(L, *a, key, x, unit, what, ok);
  if (!ok) return std::nullopt;
  return out;
}

}  // namespace ntn::modelc::compile
