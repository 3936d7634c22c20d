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
