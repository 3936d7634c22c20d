// Reading TOML values with the compiler's messages: typed access to a value or a table's keys
// (number, positive, integer, choice, fixed-length arrays, ...), each problem reported at the
// value's place through the DiagnosticSink. The reader (read_model.cpp) is built on these.
#pragma once

#include <toml++/toml.h>
#include <algorithm>
#include <climits>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "diagnostic_sink.hpp"
#include "messages.hpp"
#include "source_model.hpp"

namespace ntn::modelc::compile {

inline constexpr long long kMaxNodeId = INT_MAX;

// "an integer", "a table", ... for "expected X, got Y".
std::string type_name(const toml::node& n);

// The place of a TOML node, for a Where.
inline Where place(const toml::source_region& r, std::string key) {
  return {static_cast<int>(r.begin.line), static_cast<int>(r.begin.column), std::move(key)};
}

// Values: checks one TOML value and reports what is wrong with it (n is the value node, key its
// full path). Errors go to the sink.
class Reader {
 public:
  explicit Reader(DiagnosticSink& sink) : sink_(sink) {}

  void error(const toml::source_region& r, const std::string& key, std::string message) {
    sink_.error(place(r, key), std::move(message));
  }
  void error(const Where& w, std::string message) { sink_.error(w, std::move(message)); }
  void error_at_start(const std::string& key, std::string message) {
    sink_.error_at_start(key, std::move(message));
  }

  std::optional<double> number(const toml::node& n, const std::string& key) {
    double v = 0;
    if (const auto* f = n.as_floating_point()) {
      v = f->get();
    } else if (const auto* i = n.as_integer()) {
      v = static_cast<double>(i->get());
    } else {
      error(n.source(), key, "expected a number, got " + type_name(n));
      return std::nullopt;
    }
    if (!std::isfinite(v)) {
      error(n.source(), key, "must be a finite number");
      return std::nullopt;
    }
    return v;
  }
  std::optional<double> positive(const toml::node& n, const std::string& key) {
    const auto v = number(n, key);
    if (v && !(*v > 0)) {
      error(n.source(), key, "must be positive (got " + num(*v) + ")");
      return std::nullopt;
    }
    return v;
  }
  std::optional<double> non_negative(const toml::node& n, const std::string& key) {
    const auto v = number(n, key);
    if (v && *v < 0) {
      error(n.source(), key, "must not be negative (got " + num(*v) + ")");
      return std::nullopt;
    }
    return v;
  }
  std::optional<long long> integer(const toml::node& n, const std::string& key, long long lo,
                                   long long hi) {
    const auto* i = n.as_integer();
    if (i == nullptr) {
      error(n.source(), key, "expected an integer, got " + type_name(n));
      return std::nullopt;
    }
    const long long v = i->get();
    if (v < lo) {
      error(n.source(), key,
            "must be at least " + std::to_string(lo) + " (got " + std::to_string(v) + ")");
      return std::nullopt;
    }
    if (v > hi) {
      error(n.source(), key,
            "must be at most " + std::to_string(hi) + " (got " + std::to_string(v) + ")");
      return std::nullopt;
    }
    return v;
  }
  std::optional<std::string> string(const toml::node& n, const std::string& key) {
    const auto* s = n.as_string();
    if (s == nullptr) {
      error(n.source(), key, "expected a string, got " + type_name(n));
      return std::nullopt;
    }
    return s->get();
  }
  std::optional<int> choice(const toml::node& n, const std::string& key,
                            const std::vector<std::string_view>& options) {
    const auto s = string(n, key);
    if (!s) return std::nullopt;
    for (std::size_t i = 0; i < options.size(); ++i) {
      if (*s == options[i]) return static_cast<int>(i);
    }
    error(n.source(), key, "must be one of " + quoted_list(options) + " (got \"" + *s + "\")");
    return std::nullopt;
  }
  // A fixed-length array; each item read by `item(node, key)`.
  template <class T, class F>
  std::optional<std::vector<T>> array_of(const toml::node& n, const std::string& key,
                                         std::size_t count, F item) {
    const auto* a = n.as_array();
    if (a == nullptr) {
      error(n.source(), key,
            "expected an array of " + std::to_string(count) + " values, got " + type_name(n));
      return std::nullopt;
    }
    if (a->size() != count) {
      error(n.source(), key,
            "expected " + std::to_string(count) + " values, got " + std::to_string(a->size()));
      return std::nullopt;
    }
    std::vector<T> out;
    bool ok = true;
    for (std::size_t i = 0; i < count; ++i) {
      const auto v = item((*a)[i], key + "[" + std::to_string(i) + "]");
      if (v) {
        out.push_back(*v);
      } else {
        ok = false;
      }
    }
    if (!ok) return std::nullopt;
    return out;
  }

 private:
  DiagnosticSink& sink_;
};

enum class Need { kRequired, kOptional };

// One TOML table being read: the keys it may hold, and typed access to them.
class Table {
 public:
  Table(Reader& L, const toml::table& t, std::string path, std::vector<std::string_view> allowed)
      : L_(L), t_(t), path_(std::move(path)), allowed_(std::move(allowed)) {}

  std::string key(std::string_view k) const {
    return path_.empty() ? std::string(k) : path_ + "." + std::string(k);
  }
  const toml::table& raw() const { return t_; }
  Where where(std::string_view k) const {
    const toml::node* n = t_.get(k);
    return place(n != nullptr ? n->source() : t_.source(), key(k));
  }
  bool has(std::string_view k) const { return t_.get(k) != nullptr; }

  const toml::node* get(std::string_view k, Need need, std::string_view hint = {}) {
    const toml::node* n = t_.get(k);
    if (n == nullptr && need == Need::kRequired) {
      L_.error(t_.source(), key(k),
               "missing required key '" + std::string(k) + "'" + std::string(hint));
    }
    return n;
  }
  std::optional<double> number(std::string_view k, Need need) {
    const toml::node* n = get(k, need);
    return n ? L_.number(*n, key(k)) : std::nullopt;
  }
  std::optional<double> positive(std::string_view k, Need need) {
    const toml::node* n = get(k, need);
    return n ? L_.positive(*n, key(k)) : std::nullopt;
  }
  std::optional<double> non_negative(std::string_view k, Need need) {
    const toml::node* n = get(k, need);
    return n ? L_.non_negative(*n, key(k)) : std::nullopt;
  }
  std::optional<long long> integer(std::string_view k, Need need, long long lo, long long hi) {
    const toml::node* n = get(k, need);
    return n ? L_.integer(*n, key(k), lo, hi) : std::nullopt;
  }
  std::optional<std::string> string(std::string_view k, Need need) {
    const toml::node* n = get(k, need);
    return n ? L_.string(*n, key(k)) : std::nullopt;
  }
  std::optional<bool> boolean(std::string_view k, Need need) {
    const toml::node* n = get(k, need);
    if (n == nullptr) return std::nullopt;
    if (const auto* b = n->as_boolean()) return b->get();
    L_.error(n->source(), key(k), "expected a boolean, got " + type_name(*n));
    return std::nullopt;
  }
  std::optional<int> choice(std::string_view k, Need need,
                            const std::vector<std::string_view>& options) {
    const toml::node* n = get(k, need);
    return n ? L_.choice(*n, key(k), options) : std::nullopt;
  }
  // Fixed-length array of numbers; sign: 0 any finite, 1 non-negative.
  std::optional<std::vector<double>> numbers(std::string_view k, Need need, std::size_t count,
                                             bool non_negative = false) {
    const toml::node* n = get(k, need);
    if (n == nullptr) return std::nullopt;
    return L_.array_of<double>(*n, key(k), count,
                               [this, non_negative](const toml::node& e, const std::string& ek) {
                                 return non_negative ? L_.non_negative(e, ek) : L_.number(e, ek);
                               });
  }
  std::optional<std::vector<long long>> node_ids(std::string_view k, Need need, std::size_t count) {
    const toml::node* n = get(k, need);
    if (n == nullptr) return std::nullopt;
    return L_.array_of<long long>(*n, key(k), count,
                                  [this](const toml::node& e, const std::string& ek) {
                                    return L_.integer(e, ek, 0, kMaxNodeId);
                                  });
  }
  // "cannot be given together with" for two keys that exclude each other; true if both given.
  bool conflict(std::string_view a, std::string_view b) {
    const toml::node* na = t_.get(a);
    const toml::node* nb = t_.get(b);
    if (na == nullptr || nb == nullptr) return false;
    const bool b_later = nb->source().begin > na->source().begin;
    const toml::node* later = b_later ? nb : na;
    L_.error(later->source(), key(b_later ? b : a),
             "cannot be given together with '" + std::string(b_later ? a : b) + "'");
    return true;
  }
  void check_unknown() {
    for (auto&& [k, v] : t_) {
      (void)v;
      if (std::find(allowed_.begin(), allowed_.end(), k.str()) == allowed_.end()) {
        L_.error(k.source(), key(k.str()),
                 "unknown key '" + std::string(k.str()) +
                     "' (this table takes: " + plain_list(allowed_) + ")");
      }
    }
  }

 private:
  Reader& L_;
  const toml::table& t_;
  std::string path_;
  std::vector<std::string_view> allowed_;
};

// An id or channel name: any text but control characters (bytes below 0x20 and 0x7F: newline,
// tab, NUL, ...). Ids name things in diagnostics (one a line), CSV headers, command lines
// (--input NAME=FILE) and the generated header.
std::optional<IdAt> read_id(Reader& L, Table& t, std::string_view k, Need need = Need::kRequired);

// A node reference (source_model.hpp NodeRef) at value n of key `key`: a node id (0 to
// kMaxNodeId) or a member point { member = "B1", at = 0.5 } / { member = "B1", at_m = 2.0 }
// (at in [0, 1], at_m >= 0: its upper bound, the member's length, is the compiler's check).
std::optional<NodeRef> read_node_ref(Reader& L, const toml::node& n, const std::string& key);
// The same for key k of table t.
std::optional<NodeRef> read_node_ref(Reader& L, Table& t, std::string_view k, Need need);

// Calls f(table, path) for each table of the array of tables `name` in `root` (the file's root,
// or the table at `parent`, e.g. "initial" for [[initial.nodes]]).
template <class F>
void for_each_table(Reader& L, const toml::table& root, std::string_view name, F f,
                    std::string_view parent = {}) {
  const toml::node* n = root.get(name);
  if (n == nullptr) return;
  const std::string full =
      parent.empty() ? std::string(name) : std::string(parent) + "." + std::string(name);
  const auto* a = n->as_array();
  if (a == nullptr) {
    L.error(n->source(), full,
            "expected an array of tables ([[" + full + "]]), got " + type_name(*n));
    return;
  }
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = (*a)[i];
    const std::string path = full + "[" + std::to_string(i) + "]";
    if (const auto* t = e.as_table()) {
      f(*t, path);
    } else {
      L.error(e.source(), path, "expected a table, got " + type_name(e));
    }
  }
}

// An array of [x, y] points whose x increases strictly (time-function and curve points): each
// bad entry and each x that does not come after the previous one is reported; `ok` turns false.
std::vector<std::array<double, 2>> increasing_pairs(Reader& L, const toml::array& a,
                                                    const std::string& key, const char* x,
                                                    const char* unit, const char* what, bool& ok);

// The `points` of an "id + points" table (time functions, curves): at least `min_points` pairs
// [x, y] with x increasing (increasing_pairs). nullopt, reported, when `points` is missing, not an
// array or too short ("expected an array of <expected>, got " an empty array, or the count when
// more than one point is needed), or when a point is bad.
std::optional<std::vector<std::array<double, 2>>> read_points(Reader& L, Table& t,
                                                              std::size_t min_points,
                                                              const char* expected, const char* x,
                                                              const char* unit, const char* what);

}  // namespace ntn::modelc::compile
