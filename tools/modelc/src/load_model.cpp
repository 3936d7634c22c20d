// Model file (TOML) -> ModelDescription. Three passes, each collecting every problem it can:
//   1. read every table, check keys, types and values (unknown/missing keys, ranges, duplicates,
//      hinge axes orthonormal and right-handed, curve points increasing);
//   2. resolve references, mesh the members, make the nodes and hinges of member-end releases
//      and supports with axes, check geometry (zero length, orientation, hinge nodes coincident
//      unless eccentric, no eccentricity with ntn_paper);
//   3. rigid cycles of hinges; physics with the kernel's own functions: lumped mass, the
//      penalty and limit stiffness defaults, curves against the limit stiffness, effective mass
//      with the hinge constraints (mechanisms are notes, massless springs errors), and the
//      stable time step (dt = "auto", or a given dt above the stable step).
// A pass runs only when the ones before it found nothing: its checks need their results.
#include "ntn/modelc/load_model.hpp"

#include <toml++/toml.h>
#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <unordered_map>
#include <utility>

#include "ntn/beam.hpp"
#include "ntn/hinge.hpp"
#include "ntn/model.hpp"
#include "ntn/modelc/emit_header.hpp"
#include "ntn/modelc/hinge_checks.hpp"
#include "ntn/modelc/limits.hpp"
#include "ntn/time_step.hpp"

namespace ntn::modelc {
namespace {

constexpr double kStandardGravity = 9.80665;  // m/s^2 per g (CGPM 1901)
constexpr long long kMaxDivisions = 1000000;
constexpr long long kMaxNodeId = INT_MAX;

const std::vector<std::string_view> kDofNames = {"ux", "uy", "uz", "rx", "ry", "rz"};
const std::vector<std::string_view> kDirections3 = {"x", "y", "z"};
const std::vector<std::string_view> kReactionDirections = {"x", "y", "z", "rx", "ry", "rz"};
const std::vector<std::string_view> kComponents = {"N", "Vy", "Vz", "T", "My", "Mz"};
const std::vector<std::string_view> kHingeMethods = {"ntn_exact", "ntn_paper", "penalty"};
const std::vector<std::string_view> kClampRules = {"momentum", "paper"};
constexpr double kCoincident = 1e-9;    // m: hinge nodes closer than this coincide
constexpr double kPenaltyFactor = 1e4;  // default penalty stiffness / largest element stiffness

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string quoted_list(const std::vector<std::string_view>& items) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) s += ", ";
    s += '"';  // appended piecewise: GCC 12 -Wrestrict misfires on "\"" + string + "\""
    s += items[i];
    s += '"';
  }
  return s;
}

std::string plain_list(const std::vector<std::string_view>& items) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) s += ", ";
    s += std::string(items[i]);
  }
  return s;
}

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

int line_of(const toml::source_region& r) {
  return static_cast<int>(r.begin.line);
}

// A place in the file and the key it belongs to, kept for checks made after reading.
struct Where {
  toml::source_region region;
  std::string key;
};

// The diagnostics sink: every error and note goes through add(), which keeps the first
// kShownPerKind of each kind (severity and key with the array indices taken out: every
// "nodes[i].id" error is one kind) and counts the rest; take_errors() / take_notes() end each
// capped kind with one summary note. A million unconnected nodes give 50 errors and one line
// "999950 more ...", not 238 MB.
constexpr std::size_t kShownPerKind = 50;

std::string kind_key(const std::string& key) {
  std::string k;
  for (std::size_t i = 0; i < key.size(); ++i) {
    k += key[i];
    if (key[i] != '[') continue;
    std::size_t j = i + 1;
    while (j < key.size() && key[j] >= '0' && key[j] <= '9')
      ++j;
    if (j > i + 1 && j < key.size() && key[j] == ']') i = j - 1;
  }
  return k;
}

class Loader {
 public:
  explicit Loader(std::string file) : file_(std::move(file)) {}

  void error(const toml::source_region& r, const std::string& key, std::string message) {
    add({file_, std::max(1, static_cast<int>(r.begin.line)),
         std::max(1, static_cast<int>(r.begin.column)), key, std::move(message)});
  }
  void error(const Where& w, std::string message) { error(w.region, w.key, std::move(message)); }
  void error_at_start(const std::string& key, std::string message) {
    add({file_, 1, 1, key, std::move(message)});
  }
  void note(const Where& w, std::string message) {
    add({file_, std::max(1, static_cast<int>(w.region.begin.line)),
         std::max(1, static_cast<int>(w.region.begin.column)), w.key, std::move(message),
         Severity::kNote});
  }
  std::vector<Diagnostic> take_notes() { return take(notes_, Severity::kNote); }
  bool failed() const { return error_count_ > 0; }
  std::size_t error_count() const { return error_count_; }
  std::vector<Diagnostic> take_errors() { return take(errors_, Severity::kError); }

  // --- values (n is the value node, key its full path) ---
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
  struct Kind {
    std::size_t shown = 0, hidden = 0;
    Diagnostic first_hidden;
  };
  void add(Diagnostic d) {
    const bool is_error = d.severity == Severity::kError;
    if (is_error) ++error_count_;
    Kind& k = kinds_[std::string(is_error ? "e" : "n") + kind_key(d.key)];
    if (k.shown < kShownPerKind) {
      ++k.shown;
      (is_error ? errors_ : notes_).push_back(std::move(d));
    } else if (k.hidden++ == 0) {
      k.first_hidden = std::move(d);
    }
  }
  // Sorted by place, each capped kind summarized at its first diagnostic left out.
  std::vector<Diagnostic> take(std::vector<Diagnostic>& v, Severity severity) {
    for (const auto& [name, k] : kinds_) {
      if (k.hidden == 0 || k.first_hidden.severity != severity) continue;
      const std::string what = severity == Severity::kError ? " error" : " note";
      v.push_back({file_, k.first_hidden.line, k.first_hidden.column, kind_key(k.first_hidden.key),
                   "... and " + std::to_string(k.hidden) + " more" + what +
                       (k.hidden == 1 ? "" : "s") +
                       " of this kind (this key, any index), the first of them here: only the "
                       "first " +
                       std::to_string(kShownPerKind) + " of each kind are listed",
                   Severity::kNote});
    }
    std::stable_sort(v.begin(), v.end(), [](const Diagnostic& a, const Diagnostic& b) {
      return a.line != b.line ? a.line < b.line : a.column < b.column;
    });
    return std::move(v);
  }

  std::string file_;
  std::vector<Diagnostic> errors_;
  std::vector<Diagnostic> notes_;
  std::map<std::string, Kind> kinds_;
  std::size_t error_count_ = 0;
};

enum class Need { kRequired, kOptional };

// One TOML table being read: the keys it may hold, and typed access to them.
class Table {
 public:
  Table(Loader& L, const toml::table& t, std::string path, std::vector<std::string_view> allowed)
      : L_(L), t_(t), path_(std::move(path)), allowed_(std::move(allowed)) {}

  std::string key(std::string_view k) const {
    return path_.empty() ? std::string(k) : path_ + "." + std::string(k);
  }
  const toml::table& raw() const { return t_; }
  Where where(std::string_view k) const {
    const toml::node* n = t_.get(k);
    return {n != nullptr ? n->source() : t_.source(), key(k)};
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
  Loader& L_;
  const toml::table& t_;
  std::string path_;
  std::vector<std::string_view> allowed_;
};

// --- what pass 1 reads ---

struct IdAt {
  std::string id;
  Where at;  // the id's value
};

struct Material {
  IdAt id;
  double E = 0, G = 0, rho = 0;
  Where E_at, G_at, rho_at;  // G_at: E's place when G comes from nu (G = E / (2 (1 + nu)))
};

struct Section {
  IdAt id;
  double A = 0, Iy = 0, Iz = 0, J = 0, shear_y = 0, shear_z = 0;
  Where A_at, Iy_at, Iz_at, J_at, shear_at;
};

struct UserNode {
  long long id = 0;
  Where at;
  double x = 0, y = 0, z = 0;
};

// One local direction of a hinge or release as the file gives it.
struct BehaviourIn {
  HingeBehaviour kind = HingeBehaviour::kRigid;
  double k = 0, c = 0;        // kLinear
  std::optional<IdAt> curve;  // kCurve
  Where at;                   // the value that set it (for curve errors)
};
using Behaviours = std::array<BehaviourIn, kDofsPerNode>;

struct Release {
  Behaviours dirs;
  Where at;  // the release_start / release_end value
};

struct Member {
  IdAt id;
  std::vector<long long> nodes;
  Where nodes_at;
  IdAt material, section;
  int divisions = 1;
  std::optional<std::array<double, 3>> orientation;
  Where orientation_at;
  double roll_deg = 0;
  std::optional<Release> release[2];  // start, end
};

struct Support {
  long long node = 0;
  Where at;
  std::uint8_t fixed = 0;
  std::optional<std::array<double, 9>> axes;  // a support with its own frame: a ground hinge
  Where axes_at;
};

struct Curve {
  IdAt id;
  std::vector<CurvePoint> points;
  Where points_at;
};

enum class FrameKind { kGlobal, kMember, kAxes };

struct HingeIn {
  IdAt id;
  long long node1 = 0;
  std::optional<long long> node2;  // none: the ground
  Where nodes_at;
  FrameKind frame = FrameKind::kGlobal;
  IdAt frame_member;
  std::array<double, 9> axes{};
  bool eccentric = false;
  Where eccentric_at;
  Behaviours dirs;
};

struct PointMass {
  long long node = 0;
  Where at;
  double mass = 0;
  std::array<double, 3> inertia{};
};

struct TimeFunction {
  IdAt id;
  std::vector<TimePoint> points;
};

// An array of [x, y] points whose x increases strictly (time-function and curve points): each
// bad entry and each x that does not come after the previous one is reported; `ok` turns false.
std::vector<std::array<double, 2>> increasing_pairs(Loader& L, const toml::array& a,
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

struct Load {
  long long node = 0;
  Where at;
  std::vector<std::pair<int, double>> components;  // (dof, value)
  std::optional<IdAt> function;
};

struct Input {
  IdAt name;
  InputKind kind = InputKind::kGroundAcceleration;
  long long node = 0;
  Where node_at;
  int dof = 0;
  double scale = 1, min = -1e300, max = 1e300;
};

enum class OutKind { kNode, kElementForce, kDrift, kReaction, kHinge };

struct Output {
  IdAt name;
  OutKind kind = OutKind::kNode;
  OutputKind node_kind = OutputKind::kDisplacement;
  std::vector<long long> nodes;  // node kinds: 1; drift: 2
  Where nodes_at;
  int dof = 0;  // DOF, direction or component
  Where dof_at;
  IdAt member;
  int end = 0;
  IdAt hinge;                              // kHinge
  double alarm = 0, alarm_hysteresis = 0;  // limit alarm on |value| (0: none), channel units
};

struct ModelTable {
  std::string name, title;
  bool dt_auto = true;
  double dt = 0;
  Where dt_at;
  double frame_rate = 1000;
  Where frame_rate_at;
  bool rotary_inertia = false, allow_unstable = false;
  std::array<double, 3> gravity{};
  Where gravity_at;
  std::optional<IdAt> gravity_function;
  double alpha = 0;
  double damping_ratio = 0, damping_frequency = 0;
  HingeMethod hinge_method = HingeMethod::kNtnExact;
  ClampRule clamp = ClampRule::kMomentum;
  std::optional<double> penalty_stiffness, penalty_rotational_stiffness;
  std::optional<double> limit_stiffness, limit_rotational_stiffness;
  Where hinge_method_at;
};

struct Parsed {
  ModelTable model;
  std::vector<Material> materials;
  std::vector<Section> sections;
  std::vector<UserNode> nodes;
  std::vector<Member> members;
  std::vector<Support> supports;
  std::vector<PointMass> point_masses;
  std::vector<TimeFunction> time_functions;
  std::vector<Load> loads;
  std::vector<Input> inputs;
  std::vector<Output> outputs;
  std::vector<Curve> curves;
  std::vector<HingeIn> hinges;
};

// An id or channel name: any text but control characters (bytes below 0x20 and 0x7F: newline,
// tab, NUL, ...). Ids name things in diagnostics (one a line), CSV headers, command lines
// (--input NAME=FILE) and the generated header.
std::optional<IdAt> read_id(Loader& L, Table& t, std::string_view k, Need need = Need::kRequired) {
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

// Calls f(table, path) for each table of the array of tables `name` at the root.
template <class F>
void for_each_table(Loader& L, const toml::table& root, std::string_view name, F f) {
  const toml::node* n = root.get(name);
  if (n == nullptr) return;
  const auto* a = n->as_array();
  if (a == nullptr) {
    L.error(n->source(), std::string(name),
            "expected an array of tables ([[" + std::string(name) + "]]), got " + type_name(*n));
    return;
  }
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = (*a)[i];
    const std::string path = std::string(name) + "[" + std::to_string(i) + "]";
    if (const auto* t = e.as_table()) {
      f(*t, path);
    } else {
      L.error(e.source(), path, "expected a table, got " + type_name(e));
    }
  }
}

void read_model(Loader& L, const toml::table& root, ModelTable& m) {
  const toml::node* n = root.get("model");
  if (n == nullptr) {
    L.error_at_start("model", "missing required table [model]");
    return;
  }
  const auto* mt = n->as_table();
  if (mt == nullptr) {
    L.error(n->source(), "model", "expected a table ([model]), got " + type_name(*n));
    return;
  }
  Table t(L, *mt, "model",
          {"name", "title", "dt", "frame_rate", "rotary_inertia", "gravity", "gravity_function",
           "allow_unstable", "damping", "hinge_method", "clamp", "penalty_stiffness",
           "penalty_rotational_stiffness", "limit_stiffness", "limit_rotational_stiffness"});
  t.check_unknown();
  if (auto name = t.string("name", Need::kRequired)) {
    if (is_cpp_identifier(*name)) {
      m.name = *name;
    } else {
      L.error(t.where("name"),
              "must be a C++ identifier (letters, digits and _, not starting with a digit, not a "
              "keyword), got \"" +
                  *name + "\"");
    }
  }
  if (auto title = t.string("title", Need::kOptional)) m.title = *title;
  if (const toml::node* dt = t.get("dt", Need::kOptional)) {
    m.dt_at = t.where("dt");
    if (const auto* s = dt->as_string()) {
      if (s->get() == "auto") {
        m.dt_auto = true;
      } else {
        L.error(m.dt_at, "must be \"auto\" or a number of seconds (got \"" + s->get() + "\")");
      }
    } else if (auto v = L.positive(*dt, t.key("dt"))) {
      m.dt_auto = false;
      m.dt = *v;
    }
  } else {
    m.dt_at = {mt->source(), "model.dt"};
  }
  m.frame_rate_at = t.where("frame_rate");
  if (auto f = t.positive("frame_rate", Need::kOptional)) {
    // The kernel's frame rule (ntn::frame_substeps): a period of 1 us to 1000 s.
    if (!(1.0 / *f >= kMinFramePeriod && 1.0 / *f <= kMaxFramePeriod)) {
      L.error(m.frame_rate_at, "must be between " + num(1.0 / kMaxFramePeriod) + " and " +
                                   num(1.0 / kMinFramePeriod) + " Hz (got " + num(*f) +
                                   " Hz): the frame period 1 / frame_rate must be 1 us to 1000 s "
                                   "(the real-time loop counts whole nanoseconds)");
    } else {
      m.frame_rate = *f;
    }
  }
  if (auto b = t.boolean("rotary_inertia", Need::kOptional)) m.rotary_inertia = *b;
  if (auto b = t.boolean("allow_unstable", Need::kOptional)) m.allow_unstable = *b;
  if (auto g = t.numbers("gravity", Need::kOptional, 3)) m.gravity = {(*g)[0], (*g)[1], (*g)[2]};
  m.gravity_at = t.where("gravity");
  m.gravity_function = read_id(L, t, "gravity_function", Need::kOptional);
  if (auto hm = t.choice("hinge_method", Need::kOptional, kHingeMethods)) {
    m.hinge_method = static_cast<HingeMethod>(*hm);
  }
  m.hinge_method_at = t.where("hinge_method");
  if (auto c = t.choice("clamp", Need::kOptional, kClampRules))
    m.clamp = static_cast<ClampRule>(*c);
  m.penalty_stiffness = t.positive("penalty_stiffness", Need::kOptional);
  m.penalty_rotational_stiffness = t.positive("penalty_rotational_stiffness", Need::kOptional);
  m.limit_stiffness = t.positive("limit_stiffness", Need::kOptional);
  m.limit_rotational_stiffness = t.positive("limit_rotational_stiffness", Need::kOptional);

  if (const toml::node* d = t.get("damping", Need::kOptional)) {
    const auto* dt = d->as_table();
    if (dt == nullptr) {
      L.error(d->source(), "model.damping",
              "expected a table ([model.damping]), got " + type_name(*d));
      return;
    }
    Table dmp(L, *dt, "model.damping", {"alpha", "ratio", "frequency"});
    dmp.check_unknown();
    if (dmp.conflict("alpha", "ratio")) return;
    if (dmp.has("alpha")) {
      if (auto a = dmp.non_negative("alpha", Need::kRequired)) m.alpha = *a;
      if (dmp.has("frequency")) L.error(dmp.where("frequency"), "only applies with 'ratio'");
    } else {
      // C = alpha M gives the fraction of critical damping alpha / (2 omega) in a mode of
      // circular frequency omega: alpha = 2 ratio (2 pi f) sets `ratio` at `frequency`.
      const auto ratio = dmp.non_negative("ratio", Need::kRequired);
      const auto f = dmp.positive("frequency", Need::kRequired);
      if (ratio && f) {
        m.alpha = 2.0 * *ratio * (2.0 * std::numbers::pi * *f);
        m.damping_ratio = *ratio, m.damping_frequency = *f;
        if (!std::isfinite(m.alpha)) {
          const bool blame_ratio = std::abs(std::log10(*ratio)) >= std::abs(std::log10(*f));
          L.error(dmp.where(blame_ratio ? "ratio" : "frequency"),
                  "ratio = " + num(*ratio) + " at frequency = " + num(*f) +
                      " Hz gives alpha = 2 ratio (2 pi frequency) beyond the largest double "
                      "(1.8e308)");
        }
      }
    }
  }
}

static_assert(static_cast<int>(HingeMethod::kNtnExact) == 0 &&
              static_cast<int>(HingeMethod::kNtnPaper) == 1 &&
              static_cast<int>(HingeMethod::kPenalty) == 2);  // the order of kHingeMethods
static_assert(static_cast<int>(ClampRule::kMomentum) == 0 &&
              static_cast<int>(ClampRule::kPaper) == 1);  // the order of kClampRules

// One hinge direction: "rigid", "free", { linear = k, dashpot = c } or { curve = "id" }.
std::optional<BehaviourIn> read_behaviour(Loader& L, const toml::node& n, const std::string& key) {
  BehaviourIn b;
  b.at = {n.source(), key};
  const std::string what =
      "must be \"rigid\", \"free\", { linear = k, dashpot = c } or { curve = \"id\" }";
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
  Table tb(L, *t, key, {"linear", "dashpot", "curve"});
  tb.check_unknown();
  if (tb.conflict("linear", "curve")) return std::nullopt;
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
std::optional<Release> read_release(Loader& L, const toml::node& n, const std::string& key) {
  Release r;
  r.at = {n.source(), key};
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
        r.dirs[static_cast<std::size_t>(*d)].at = {(*a)[i].source(), ik};
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
std::optional<std::array<double, 9>> read_axes(Loader& L, const toml::node& n,
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

void read_tables(Loader& L, const toml::table& root, Parsed& p) {
  {
    Table top(L, root, "",
              {"model", "materials", "sections", "nodes", "members", "supports", "point_masses",
               "time_functions", "loads", "inputs", "outputs", "curves", "hinges"});
    top.check_unknown();
  }
  read_model(L, root, p.model);

  for_each_table(L, root, "materials", [&](const toml::table& tt, const std::string& path) {
    Table t(L, tt, path, {"id", "E", "G", "nu", "rho"});
    t.check_unknown();
    Material m;
    auto id = read_id(L, t, "id");
    auto E = t.positive("E", Need::kRequired);
    auto rho = t.positive("rho", Need::kRequired);
    std::optional<double> G;
    if (!t.conflict("G", "nu")) {
      if (t.has("nu")) {
        if (auto nu = t.number("nu", Need::kRequired)) {
          if (!(*nu > -1.0 && *nu < 0.5)) {
            L.error(t.where("nu"),
                    "must be greater than -1 and less than 0.5 (got " + num(*nu) + ")");
          } else if (E) {
            G = *E / (2.0 * (1.0 + *nu));  // isotropic elasticity
          }
        }
      } else {
        G = t.positive("G", Need::kRequired);
      }
    }
    if (!id || !E || !rho || !G) return;
    m.id = *id, m.E = *E, m.G = *G, m.rho = *rho;
    m.E_at = t.where("E"), m.rho_at = t.where("rho");
    m.G_at = t.where(t.has("nu") ? "E" : "G");  // G = E / (2 (1 + nu)) follows E
    p.materials.push_back(m);
  });

  for_each_table(L, root, "sections", [&](const toml::table& tt, const std::string& path) {
    Table t(L, tt, path, {"id", "A", "Iy", "Iz", "J", "shear", "kappa_y", "kappa_z"});
    t.check_unknown();
    Section s;
    auto id = read_id(L, t, "id");
    auto A = t.positive("A", Need::kRequired);
    auto Iy = t.positive("Iy", Need::kRequired);
    auto Iz = t.positive("Iz", Need::kRequired);
    auto J = t.positive("J", Need::kRequired);
    auto shear = t.choice("shear", Need::kOptional, {"euler_bernoulli", "timoshenko"});
    double ky = 5.0 / 6.0, kz = 5.0 / 6.0;  // shear coefficient of a rectangle
    bool ok = id && A && Iy && Iz && J && (shear || !t.has("shear"));
    if (shear.value_or(0) == 1) {
      auto y = t.positive("kappa_y", Need::kOptional);
      auto z = t.positive("kappa_z", Need::kOptional);
      if (y) ky = *y;
      if (z) kz = *z;
      ok = ok && (y || !t.has("kappa_y")) && (z || !t.has("kappa_z"));
    } else {
      for (std::string_view k : {"kappa_y", "kappa_z"}) {
        if (t.has(k)) {
          L.error(t.where(k), "only applies with shear = \"timoshenko\"");
          ok = false;
        }
      }
    }
    if (!ok) return;
    s.id = *id, s.A = *A, s.Iy = *Iy, s.Iz = *Iz, s.J = *J;
    s.A_at = t.where("A"), s.Iy_at = t.where("Iy"), s.Iz_at = t.where("Iz"), s.J_at = t.where("J");
    s.shear_at = t.where("shear");
    if (shear.value_or(0) == 1) s.shear_y = ky * *A, s.shear_z = kz * *A;
    p.sections.push_back(s);
  });

  for_each_table(L, root, "nodes", [&](const toml::table& tt, const std::string& path) {
    Table t(L, tt, path, {"id", "xyz"});
    t.check_unknown();
    auto id = t.integer("id", Need::kRequired, 0, kMaxNodeId);
    auto xyz = t.numbers("xyz", Need::kRequired, 3);
    if (!id || !xyz) return;
    p.nodes.push_back({*id, t.where("id"), (*xyz)[0], (*xyz)[1], (*xyz)[2]});
  });

  for_each_table(L, root, "members", [&](const toml::table& tt, const std::string& path) {
    Table t(L, tt, path,
            {"id", "nodes", "material", "section", "divisions", "orientation", "roll",
             "release_start", "release_end"});
    t.check_unknown();
    Member m;
    for (std::size_t e = 0; e < 2; ++e) {
      const std::string_view k = e == 0 ? "release_start" : "release_end";
      if (const toml::node* r = t.get(k, Need::kOptional)) {
        m.release[e] = read_release(L, *r, t.key(k));
      }
    }
    auto id = read_id(L, t, "id");
    auto nodes = t.node_ids("nodes", Need::kRequired, 2);
    auto mat = read_id(L, t, "material");
    auto sec = read_id(L, t, "section");
    auto div = t.integer("divisions", Need::kOptional, 1, kMaxDivisions);
    bool ok = id && nodes && mat && sec && (div || !t.has("divisions"));
    if (!t.conflict("orientation", "roll")) {
      if (t.has("orientation")) {
        auto o = t.numbers("orientation", Need::kRequired, 3);
        if (o) {
          m.orientation = std::array<double, 3>{(*o)[0], (*o)[1], (*o)[2]};
        } else {
          ok = false;
        }
        m.orientation_at = t.where("orientation");
      } else if (t.has("roll")) {
        auto r = t.number("roll", Need::kRequired);
        if (r) {
          m.roll_deg = *r;
        } else {
          ok = false;
        }
      }
    } else {
      ok = false;
    }
    if (!ok) return;
    m.id = *id, m.nodes = *nodes, m.nodes_at = t.where("nodes"), m.material = *mat;
    m.section = *sec, m.divisions = static_cast<int>(div.value_or(1));
    p.members.push_back(m);
  });

  for_each_table(L, root, "supports", [&](const toml::table& tt, const std::string& path) {
    Table t(L, tt, path, {"node", "fix", "axes"});
    t.check_unknown();
    auto node = t.integer("node", Need::kRequired, 0, kMaxNodeId);
    std::optional<std::array<double, 9>> axes;
    if (const toml::node* ax = t.get("axes", Need::kOptional)) {
      axes = read_axes(L, *ax, t.key("axes"));
      if (!axes) return;
    }
    const toml::node* fix = t.get("fix", Need::kRequired);
    std::optional<std::uint8_t> bits;
    if (fix != nullptr) {
      const std::string msg =
          "must be \"all\", \"pinned\" or an array of DOF names (" + quoted_list(kDofNames) + ")";
      if (const auto* s = fix->as_string()) {
        if (s->get() == "all") {
          bits = 0x3F;
        } else if (s->get() == "pinned") {
          bits = 0x07;  // translations held, rotations free
        } else {
          L.error(fix->source(), t.key("fix"), msg + ", got \"" + s->get() + "\"");
        }
      } else if (const auto* a = fix->as_array(); a != nullptr && !a->empty()) {
        std::uint8_t b = 0;
        bool ok = true;
        for (std::size_t i = 0; i < a->size(); ++i) {
          auto d = L.choice((*a)[i], t.key("fix") + "[" + std::to_string(i) + "]", kDofNames);
          if (d) {
            b = static_cast<std::uint8_t>(b | (1U << *d));
          } else {
            ok = false;
          }
        }
        if (ok) bits = b;
      } else {
        L.error(fix->source(), t.key("fix"),
                msg + ", got " + (fix->is_array() ? "an empty array" : type_name(*fix)));
      }
    }
    if (!node || !bits) return;
    p.supports.push_back({*node, t.where("node"), *bits, axes, t.where("axes")});
  });

  for_each_table(L, root, "point_masses", [&](const toml::table& tt, const std::string& path) {
    Table t(L, tt, path, {"node", "mass", "inertia"});
    t.check_unknown();
    auto node = t.integer("node", Need::kRequired, 0, kMaxNodeId);
    auto mass = t.non_negative("mass", Need::kRequired);
    auto inertia = t.numbers("inertia", Need::kOptional, 3, true);
    if (!node || !mass || (!inertia && t.has("inertia"))) return;
    PointMass pm{*node, t.where("node"), *mass, {}};
    if (inertia) pm.inertia = {(*inertia)[0], (*inertia)[1], (*inertia)[2]};
    p.point_masses.push_back(pm);
  });

  for_each_table(L, root, "time_functions", [&](const toml::table& tt, const std::string& path) {
    Table t(L, tt, path, {"id", "points"});
    t.check_unknown();
    auto id = read_id(L, t, "id");
    const toml::node* pts = t.get("points", Need::kRequired);
    if (pts == nullptr) return;
    const std::string pkey = t.key("points");
    const auto* a = pts->as_array();
    if (a == nullptr || a->empty()) {
      L.error(pts->source(), pkey,
              "expected an array of [t, value] points (at least one), got " +
                  (a ? std::string("an empty array") : type_name(*pts)));
      return;
    }
    TimeFunction f;
    bool ok = true;
    for (const auto& [time, value] : increasing_pairs(L, *a, pkey, "t", " s", "times", ok))
      f.points.push_back({time, value});
    if (!id || !ok) return;
    f.id = *id;
    p.time_functions.push_back(f);
  });

  for_each_table(L, root, "loads", [&](const toml::table& tt, const std::string& path) {
    Table t(L, tt, path, {"node", "dof", "value", "force", "function"});
    t.check_unknown();
    Load l;
    auto node = t.integer("node", Need::kRequired, 0, kMaxNodeId);
    bool ok = node.has_value();
    if (t.conflict("dof", "force") || t.conflict("value", "force")) return;
    if (t.has("force")) {
      auto f = t.numbers("force", Need::kRequired, 6);
      if (f) {
        for (int d = 0; d < kDofsPerNode; ++d) {
          const double v = (*f)[static_cast<std::size_t>(d)];
          if (v != 0.0) l.components.emplace_back(d, v);
        }
      }
      ok = ok && f;
    } else {
      const std::string hint = " (or give force = [Fx, Fy, Fz, Mx, My, Mz])";
      const toml::node* dn = t.get("dof", Need::kRequired, hint);
      std::optional<int> dof;
      if (dn != nullptr) dof = L.choice(*dn, t.key("dof"), kDofNames);
      auto v = t.number("value", Need::kRequired);
      if (dof && v) l.components.emplace_back(*dof, *v);
      ok = ok && dof && v;
    }
    if (t.has("function")) {
      l.function = read_id(L, t, "function");
      ok = ok && l.function;
    }
    if (!ok) return;
    l.node = *node, l.at = t.where("node");
    p.loads.push_back(l);
  });

  for_each_table(L, root, "inputs", [&](const toml::table& tt, const std::string& path) {
    Input in;
    const std::vector<std::string_view> kinds = {"ground_acceleration", "nodal_force"};
    Table head(L, tt, path, {});
    auto name = read_id(L, head, "name");
    auto kind = head.choice("kind", Need::kRequired, kinds);
    if (!kind) return;
    const bool ground = *kind == 0;
    Table t(
        L, tt, path,
        ground
            ? std::vector<std::string_view>{"name", "kind", "direction", "units", "min", "max"}
            : std::vector<std::string_view>{"name", "kind", "node", "dof", "scale", "min", "max"});
    t.check_unknown();
    bool ok = name.has_value();
    if (ground) {
      in.kind = InputKind::kGroundAcceleration;
      auto dir = t.choice("direction", Need::kRequired, kDirections3);
      auto units = t.choice("units", Need::kOptional, {"m/s2", "g"});
      if (dir) in.dof = *dir;
      in.scale = units.value_or(0) == 1 ? kStandardGravity : 1.0;
      ok = ok && dir && (units || !t.has("units"));
    } else {
      in.kind = InputKind::kNodalForce;
      auto node = t.integer("node", Need::kRequired, 0, kMaxNodeId);
      auto dof = t.choice("dof", Need::kRequired, kDofNames);
      auto scale = t.number("scale", Need::kOptional);
      if (node) in.node = *node, in.node_at = t.where("node");
      if (dof) in.dof = *dof;
      if (scale) in.scale = *scale;
      ok = ok && node && dof && (scale || !t.has("scale"));
    }
    auto lo = t.number("min", Need::kOptional);
    auto hi = t.number("max", Need::kOptional);
    if (lo) in.min = *lo;
    if (hi) in.max = *hi;
    ok = ok && (lo || !t.has("min")) && (hi || !t.has("max"));
    if (lo && hi && !(*lo < *hi)) {
      L.error(t.where("min"), "min = " + num(*lo) + " must be less than max = " + num(*hi));
      ok = false;
    }
    if (!ok) return;
    in.name = *name;
    p.inputs.push_back(in);
  });

  for_each_table(L, root, "outputs", [&](const toml::table& tt, const std::string& path) {
    Output o;
    const std::vector<std::string_view> kinds = {
        "displacement",          "velocity",    "acceleration",
        "element_force",         "drift",       "reaction",
        "absolute_acceleration", "hinge_force", "hinge_displacement"};
    Table head(L, tt, path, {});
    auto name = read_id(L, head, "name");
    auto kind = head.choice("kind", Need::kRequired, kinds);
    if (!kind) return;
    bool ok = name.has_value();
    if (*kind <= 2 || *kind == 6) {
      Table t(L, tt, path, {"name", "kind", "node", "dof", "alarm", "alarm_hysteresis"});
      t.check_unknown();
      o.kind = OutKind::kNode;
      o.node_kind = *kind == 0   ? OutputKind::kDisplacement
                    : *kind == 1 ? OutputKind::kVelocity
                    : *kind == 2 ? OutputKind::kAcceleration
                                 : OutputKind::kAbsoluteAcceleration;
      auto node = t.integer("node", Need::kRequired, 0, kMaxNodeId);
      auto dof = t.choice("dof", Need::kRequired, kDofNames);
      if (node) o.nodes = {*node}, o.nodes_at = t.where("node");
      if (dof) o.dof = *dof;
      ok = ok && node && dof;
    } else if (*kind == 3) {
      Table t(L, tt, path,
              {"name", "kind", "member", "end", "component", "alarm", "alarm_hysteresis"});
      t.check_unknown();
      o.kind = OutKind::kElementForce;
      auto member = read_id(L, t, "member");
      auto end = t.choice("end", Need::kRequired, {"start", "end"});
      auto comp = t.choice("component", Need::kRequired, kComponents);
      if (member) o.member = *member;
      if (end) o.end = *end;
      if (comp) o.dof = *comp;
      ok = ok && member && end && comp;
    } else if (*kind == 4) {
      Table t(L, tt, path, {"name", "kind", "nodes", "direction", "alarm", "alarm_hysteresis"});
      t.check_unknown();
      o.kind = OutKind::kDrift;
      auto nodes = t.node_ids("nodes", Need::kRequired, 2);
      auto dir = t.choice("direction", Need::kRequired, {"x", "y"});
      if (nodes) o.nodes = *nodes, o.nodes_at = t.where("nodes");
      if (dir) o.dof = *dir;
      ok = ok && nodes && dir;
    } else if (*kind >= 7) {
      Table t(L, tt, path, {"name", "kind", "hinge", "direction", "alarm", "alarm_hysteresis"});
      t.check_unknown();
      o.kind = OutKind::kHinge;
      o.node_kind = *kind == 7 ? OutputKind::kHingeForce : OutputKind::kHingeDisplacement;
      auto hinge = read_id(L, t, "hinge");
      auto dir = t.choice("direction", Need::kRequired, kDofNames);
      if (hinge) o.hinge = *hinge;
      if (dir) o.dof = *dir;
      ok = ok && hinge && dir;
    } else {
      Table t(L, tt, path, {"name", "kind", "direction", "alarm", "alarm_hysteresis"});
      t.check_unknown();
      o.kind = OutKind::kReaction;
      auto dir = t.choice("direction", Need::kRequired, kReactionDirections);
      if (dir) o.dof = *dir, o.dof_at = t.where("direction");
      ok = ok && dir;
    }
    // Limit alarm, in the channel's units: on when |value| > alarm, off again below
    // alarm - alarm_hysteresis (ntn-hil-<model>).
    Table a(L, tt, path, {});
    const auto alarm = a.positive("alarm", Need::kOptional);
    const auto hysteresis = a.non_negative("alarm_hysteresis", Need::kOptional);
    ok = ok && (alarm || !a.has("alarm")) && (hysteresis || !a.has("alarm_hysteresis"));
    if (hysteresis && !a.has("alarm")) {
      L.error(a.where("alarm_hysteresis"),
              "alarm_hysteresis needs an alarm: give alarm = LIMIT in this output");
      ok = false;
    } else if (alarm && hysteresis && !(*hysteresis < *alarm)) {
      L.error(a.where("alarm_hysteresis"), "alarm_hysteresis = " + num(*hysteresis) +
                                               " must be less than alarm = " + num(*alarm) +
                                               " (the alarm goes off below alarm - hysteresis)");
      ok = false;
    }
    if (!ok) return;
    o.name = *name;
    o.alarm = alarm.value_or(0.0);
    o.alarm_hysteresis = hysteresis.value_or(0.0);
    p.outputs.push_back(o);
  });

  for_each_table(L, root, "curves", [&](const toml::table& tt, const std::string& path) {
    Table t(L, tt, path, {"id", "points"});
    t.check_unknown();
    auto id = read_id(L, t, "id");
    const toml::node* pts = t.get("points", Need::kRequired);
    if (pts == nullptr) return;
    const std::string pkey = t.key("points");
    const auto* a = pts->as_array();
    if (a == nullptr || a->size() < 2) {
      L.error(pts->source(), pkey,
              "expected an array of at least 2 [d, force] points, got " +
                  (a ? std::to_string(a->size()) + (a->size() == 1 ? " point" : " points")
                     : type_name(*pts)));
      return;
    }
    Curve c;
    bool ok = true;
    for (const auto& [d, force] : increasing_pairs(L, *a, pkey, "d", "", "deformations", ok))
      c.points.push_back({d, force});
    if (!id || !ok) return;
    c.id = *id;
    c.points_at = t.where("points");
    p.curves.push_back(c);
  });

  for_each_table(L, root, "hinges", [&](const toml::table& tt, const std::string& path) {
    Table t(L, tt, path,
            {"id", "nodes", "frame", "axes", "eccentric", "ux", "uy", "uz", "rx", "ry", "rz"});
    t.check_unknown();
    HingeIn h;
    auto id = read_id(L, t, "id");
    bool ok = id.has_value();
    if (const toml::node* nn = t.get("nodes", Need::kRequired)) {
      const std::string nkey = t.key("nodes");
      h.nodes_at = t.where("nodes");
      const auto* a = nn->as_array();
      if (a == nullptr || a->size() != 2) {
        L.error(nn->source(), nkey,
                "expected [node 1, node 2] (node 2 may be \"ground\"), got " +
                    (a ? std::to_string(a->size()) + (a->size() == 1 ? " value" : " values")
                       : type_name(*nn)));
        ok = false;
      } else {
        auto n1 = L.integer((*a)[0], nkey + "[0]", 0, kMaxNodeId);
        if (n1) h.node1 = *n1;
        ok = ok && n1;
        const toml::node& second = (*a)[1];
        if (const auto* s = second.as_string()) {
          if (s->get() != "ground") {
            L.error(second.source(), nkey + "[1]",
                    "must be a node id or \"ground\" (got \"" + s->get() + "\")");
            ok = false;
          }
        } else {
          auto n2 = L.integer(second, nkey + "[1]", 0, kMaxNodeId);
          if (n2) h.node2 = *n2;
          ok = ok && n2;
        }
      }
    } else {
      ok = false;
    }
    if (t.conflict("frame", "axes")) {
      ok = false;
    } else if (const toml::node* f = t.get("frame", Need::kOptional)) {
      const std::string fkey = t.key("frame");
      const std::string what = "must be \"global\" or { member = \"id\" } (or give axes)";
      if (const auto* s = f->as_string()) {
        if (s->get() != "global") {
          L.error(f->source(), fkey, what + ", got \"" + s->get() + "\"");
          ok = false;
        }
      } else if (const auto* ft = f->as_table()) {
        Table fr(L, *ft, fkey, {"member"});
        fr.check_unknown();
        auto m = read_id(L, fr, "member");
        if (m) {
          h.frame = FrameKind::kMember;
          h.frame_member = *m;
        }
        ok = ok && m;
      } else {
        L.error(f->source(), fkey, what + ", got " + type_name(*f));
        ok = false;
      }
    } else if (const toml::node* ax = t.get("axes", Need::kOptional)) {
      auto R = read_axes(L, *ax, t.key("axes"));
      if (R) {
        h.frame = FrameKind::kAxes;
        h.axes = *R;
      }
      ok = ok && R;
    }
    if (auto e = t.boolean("eccentric", Need::kOptional)) h.eccentric = *e;
    h.eccentric_at = t.where("eccentric");
    for (std::size_t d = 0; d < kDofNames.size(); ++d) {
      h.dirs[d].at = t.where("nodes");
      const toml::node* v = t.get(kDofNames[d], Need::kOptional);
      if (v == nullptr) continue;
      auto b = read_behaviour(L, *v, t.key(kDofNames[d]));
      if (b) {
        h.dirs[d] = *b;
      } else {
        ok = false;
      }
    }
    if (!ok) return;
    h.id = *id;
    p.hinges.push_back(h);
  });
}

// Index by id; reports every repeat at the repeated id, naming the line of the first.
template <class T, class GetId>
std::map<std::string, int> index_by_id(Loader& L, const std::vector<T>& items, GetId get,
                                       const std::string& what) {
  std::map<std::string, int> index;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const IdAt& id = get(items[i]);
    const auto [it, inserted] = index.emplace(id.id, static_cast<int>(i));
    if (!inserted) {
      const IdAt& first = get(items[static_cast<std::size_t>(it->second)]);
      L.error(id.at, "duplicate " + what + " '" + id.id + "' (first defined at line " +
                         std::to_string(line_of(first.at.region)) + ")");
    }
  }
  return index;
}

// --- Numbers beyond double (issue 12, item 9) ---
//
// Every input number is finite, but what the kernel derives from them (E A / l, 12 E I / l^3,
// rho A l / 2, k / m, ...) can still overflow to inf or underflow to zero or a subnormal, and
// then fail far from its cause ("a spring acts on a DOF without mass" for E = 1e308). A derived
// quantity is checked as the kernel computes it, and refused naming the input that drives it
// out of range the most: the factor with the largest power x log10(value), towards overflow or
// underflow.
struct Factor {
  std::string name;  // "E", "A", "l"
  double value = 0;
  int power = 1;
  Where at;
  std::string unit;
};

// True when v is finite (and, with `normal`, at least the smallest normal double).
bool check_derived(Loader& L, double v, const std::string& what, const std::vector<Factor>& f,
                   bool normal) {
  const bool over = !std::isfinite(v);
  const bool under = normal && !over && !(std::abs(v) >= std::numeric_limits<double>::min());
  if (!over && !under) return true;
  std::size_t blame = 0;
  double worst = -std::numeric_limits<double>::infinity();
  std::string all;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double c = f[i].power * std::log10(std::abs(f[i].value)) * (under ? -1.0 : 1.0);
    if (c > worst) worst = c, blame = i;
    all += (i > 0 ? ", " : "") + f[i].name + " = " + num(f[i].value) + f[i].unit;
  }
  const Factor& b = f[blame];
  L.error(b.at, b.name + " = " + num(b.value) + b.unit +
                    (over ? " gives a non-finite " + what + " (" + all +
                                "): beyond the largest double, 1.8e308"
                          : " is too small: it gives a zero or subnormal " + what + " (" + all +
                                "), below the smallest normal double 2.2e-308"));
  return false;
}

// Pass 2 and 3: references, meshing, geometry, mass, time step.
std::optional<ModelDescription> build(Loader& L, const Parsed& p, const std::string& file) {
  ModelDescription d;
  d.name = p.model.name;
  d.title = p.model.title;
  d.source_file = file;
  d.frame_rate = p.model.frame_rate;
  d.dt_auto = p.model.dt_auto;
  d.dt_requested = p.model.dt;
  d.damping_ratio = p.model.damping_ratio;
  d.damping_frequency = p.model.damping_frequency;
  Settings& s = d.settings;
  s.frame_period = 1.0 / p.model.frame_rate;
  s.alpha = p.model.alpha;
  s.gravity = p.model.gravity;
  s.rotary_inertia = p.model.rotary_inertia;
  s.allow_unstable = p.model.allow_unstable;
  s.hinge_method = p.model.hinge_method;
  s.clamp = p.model.clamp;
  d.penalty_stiffness_given = p.model.penalty_stiffness.has_value();
  d.penalty_rotational_stiffness_given = p.model.penalty_rotational_stiffness.has_value();
  d.limit_stiffness_given = p.model.limit_stiffness.has_value();
  d.limit_rotational_stiffness_given = p.model.limit_rotational_stiffness.has_value();

  const auto materials = index_by_id(
      L, p.materials, [](const Material& m) -> const IdAt& { return m.id; }, "material id");
  const auto sections = index_by_id(
      L, p.sections, [](const Section& x) -> const IdAt& { return x.id; }, "section id");
  const auto members = index_by_id(
      L, p.members, [](const Member& x) -> const IdAt& { return x.id; }, "member id");
  const auto functions = index_by_id(
      L, p.time_functions, [](const TimeFunction& x) -> const IdAt& { return x.id; },
      "time function id");
  index_by_id(
      L, p.inputs, [](const Input& x) -> const IdAt& { return x.name; }, "input name");
  index_by_id(
      L, p.outputs, [](const Output& x) -> const IdAt& { return x.name; }, "output name");
  const auto curve_index = index_by_id(
      L, p.curves, [](const Curve& x) -> const IdAt& { return x.id; }, "curve id");
  std::map<std::string, int> hinge_index = index_by_id(
      L, p.hinges, [](const HingeIn& x) -> const IdAt& { return x.id; }, "hinge id");
  std::map<long long, int> node_index;
  for (std::size_t i = 0; i < p.nodes.size(); ++i) {
    const UserNode& n = p.nodes[i];
    const auto [it, inserted] = node_index.emplace(n.id, static_cast<int>(i));
    if (!inserted) {
      L.error(n.at,
              "duplicate node id " + std::to_string(n.id) + " (first defined at line " +
                  std::to_string(line_of(p.nodes[static_cast<std::size_t>(it->second)].at.region)) +
                  ")");
    }
  }

  auto node_ref = [&](long long id, const Where& at) -> int {
    const auto it = node_index.find(id);
    if (it != node_index.end()) return it->second;
    L.error(at, "unknown node " + std::to_string(id));
    return -1;
  };
  auto ref = [&](const std::map<std::string, int>& index, const IdAt& id,
                 const std::string& what) -> int {
    const auto it = index.find(id.id);
    if (it != index.end()) return it->second;
    L.error(id.at, "unknown " + what + " '" + id.id + "'");
    return -1;
  };

  // Time functions, concatenated.
  for (const TimeFunction& f : p.time_functions) {
    d.time_functions.push_back(
        {static_cast<int>(d.time_points.size()), static_cast<int>(f.points.size())});
    d.time_points.insert(d.time_points.end(), f.points.begin(), f.points.end());
    d.time_function_ids.push_back(f.id.id);
  }
  if (p.model.gravity_function) {
    s.gravity_function = ref(functions, *p.model.gravity_function, "time function");
  }

  // Force-deformation curves, concatenated like time functions.
  for (const Curve& c : p.curves) {
    d.curves.push_back(
        {static_cast<int>(d.curve_points.size()), static_cast<int>(c.points.size())});
    d.curve_points.insert(d.curve_points.end(), c.points.begin(), c.points.end());
    d.curve_ids.push_back(c.id.id);
  }

  // Hinges are collected with where they came from (for later errors), and added in order:
  // explicit, member-end releases, supports with axes.
  struct PendingHinge {
    HingeSpec spec;
    HingeInfo info;
    const Behaviours* dirs = nullptr;  // nullptr: behaviours already set (supports)
    Where at;                          // the key that made the hinge
  };
  std::vector<PendingHinge> releases;

  // User nodes first, in file order; generated nodes follow, member by member.
  for (const UserNode& n : p.nodes) {
    NodeSpec ns;
    ns.x = n.x, ns.y = n.y, ns.z = n.z;
    d.nodes.push_back(ns);
    d.node_ids.push_back(static_cast<int>(n.id));
  }

  if (p.members.empty()) {
    L.error_at_start("members",
                     "the model has no members, so it has no mass and nothing to integrate");
  }

  for (std::size_t mi = 0; mi < p.members.size(); ++mi) {
    const Member& m = p.members[mi];
    const int a = node_ref(m.nodes[0], m.nodes_at);
    const int b = node_ref(m.nodes[1], m.nodes_at);
    const int mat = ref(materials, m.material, "material");
    const int sec = ref(sections, m.section, "section");
    if (a < 0 || b < 0 || mat < 0 || sec < 0) continue;
    const Material& ma = p.materials[static_cast<std::size_t>(mat)];
    const Section& se = p.sections[static_cast<std::size_t>(sec)];
    const NodeSpec na = d.nodes[static_cast<std::size_t>(a)];
    const NodeSpec nb = d.nodes[static_cast<std::size_t>(b)];

    ElementSpec e;
    e.E = ma.E, e.G = ma.G, e.rho = ma.rho;
    e.A = se.A, e.Iy = se.Iy, e.Iz = se.Iz, e.J = se.J;
    e.shear_area_y = se.shear_y, e.shear_area_z = se.shear_z;
    e.member = static_cast<int>(mi);

    // Orientation vector (DESIGN §3): given, or the default reference turned by `roll`.
    const double dx = nb.x - na.x, dy = nb.y - na.y, dz = nb.z - na.z;
    const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (m.orientation) {
      e.ref_x = (*m.orientation)[0], e.ref_y = (*m.orientation)[1], e.ref_z = (*m.orientation)[2];
    } else if (len > 0) {
      const double ex[3] = {dx / len, dy / len, dz / len};
      // Vertical members (axis within 1e-3 rad of global Z) take global X as the reference,
      // all others global Z.
      const bool vertical = std::sqrt(ex[0] * ex[0] + ex[1] * ex[1]) < 1e-3;
      const double r0[3] = {vertical ? 1.0 : 0.0, 0.0, vertical ? 0.0 : 1.0};
      const double along = r0[0] * ex[0] + r0[1] * ex[1] + r0[2] * ex[2];
      double ez[3] = {r0[0] - along * ex[0], r0[1] - along * ex[1], r0[2] - along * ex[2]};
      const double zn = std::sqrt(ez[0] * ez[0] + ez[1] * ez[1] + ez[2] * ez[2]);
      for (double& c : ez)
        c /= zn;
      const double ey[3] = {ez[1] * ex[2] - ez[2] * ex[1], ez[2] * ex[0] - ez[0] * ex[2],
                            ez[0] * ex[1] - ez[1] * ex[0]};  // y = z x x
      // Right-handed turn by `roll` about local x: z' = cos(roll) z - sin(roll) y.
      const double th = m.roll_deg * std::numbers::pi / 180.0;
      const double c = m.roll_deg == 0.0 ? 1.0 : std::cos(th);
      const double sn = m.roll_deg == 0.0 ? 0.0 : std::sin(th);
      e.ref_x = c * ez[0] - sn * ey[0];
      e.ref_y = c * ez[1] - sn * ey[1];
      e.ref_z = c * ez[2] - sn * ey[2];
    }

    // Whole-member geometry with the kernel's own check.
    e.node_i = a, e.node_j = b;
    const BeamGeometry g = beam_geometry(na, nb, e);
    if (g.check == ElementCheck::kZeroLength) {
      L.error(m.nodes_at, "member " + m.id.id + " has zero length: nodes " +
                              std::to_string(m.nodes[0]) + " and " + std::to_string(m.nodes[1]) +
                              " are both at (" + num(na.x) + ", " + num(na.y) + ", " + num(na.z) +
                              ")");
      continue;
    }
    if (g.check == ElementCheck::kOrientationParallel) {
      L.error(m.orientation_at, "orientation (" + num(e.ref_x) + ", " + num(e.ref_y) + ", " +
                                    num(e.ref_z) + ") is parallel to the axis of member " +
                                    m.id.id);
      continue;
    }

    // Mesh: divisions equal elements, interior nodes at x_a + (k / N)(x_b - x_a).
    MemberInfo info;
    info.name = m.id.id;
    info.material = ma.id.id;
    info.section = se.id.id;
    info.first_element = static_cast<int>(d.elements.size());
    info.element_count = m.divisions;
    info.start_node = a;
    info.end_node = b;
    info.first_interior_node = static_cast<int>(d.nodes.size());
    info.interior_node_count = m.divisions - 1;
    int prev = a;
    for (int k = 1; k <= m.divisions; ++k) {
      int next = b;
      if (k < m.divisions) {
        const double t = static_cast<double>(k) / static_cast<double>(m.divisions);
        NodeSpec n;
        n.x = na.x + t * dx, n.y = na.y + t * dy, n.z = na.z + t * dz;
        next = static_cast<int>(d.nodes.size());
        d.nodes.push_back(n);
        d.node_ids.push_back(kGeneratedNode);
      }
      ElementSpec el = e;
      el.node_i = prev, el.node_j = next;
      d.elements.push_back(el);
      d.element_member.push_back(static_cast<int>(mi));
      prev = next;
    }
    // Member-end releases: a node at the end, coincident with the joint, takes the end element;
    // a hinge in the member's local axes (the end element's rotation) joins it to the joint.
    for (int end = 0; end < 2; ++end) {
      if (!m.release[end]) continue;
      const int joint = end == 0 ? a : b;
      const int el_index =
          end == 0 ? info.first_element : info.first_element + info.element_count - 1;
      NodeSpec rn;
      rn.x = d.nodes[static_cast<std::size_t>(joint)].x;
      rn.y = d.nodes[static_cast<std::size_t>(joint)].y;
      rn.z = d.nodes[static_cast<std::size_t>(joint)].z;
      const int rnode = static_cast<int>(d.nodes.size());
      d.nodes.push_back(rn);
      d.node_ids.push_back(kGeneratedNode);
      ElementSpec& el = d.elements[static_cast<std::size_t>(el_index)];
      (end == 0 ? el.node_i : el.node_j) = rnode;
      PendingHinge ph;
      ph.spec.node1 = rnode;
      ph.spec.node2 = joint;
      ph.spec.frame = beam_geometry(d.nodes[static_cast<std::size_t>(el.node_i)],
                                    d.nodes[static_cast<std::size_t>(el.node_j)], el)
                          .rotation;
      ph.info = {m.id.id + (end == 0 ? ".start" : ".end"), HingeOrigin::kRelease,
                 static_cast<int>(d.members.size()), end};
      ph.dirs = &m.release[end]->dirs;
      ph.at = m.release[end]->at;
      releases.push_back(ph);
      (end == 0 ? info.start_release_node : info.end_release_node) = rnode;
    }
    d.members.push_back(info);
  }

  // Hinges. Directions: a curve reference resolves to its index.
  std::vector<Where> hinge_at;                          // per hinge: the key that made it
  std::vector<std::array<Where, kDofsPerNode>> dir_at;  // per hinge and direction
  auto set_dirs = [&](HingeSpec& hs, const Behaviours& dirs) {
    bool ok = true;
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      const BehaviourIn& b = dirs[k];
      hs.behaviour[k] = b.kind;
      if (b.kind == HingeBehaviour::kLinear) hs.stiffness[k] = b.k, hs.dashpot[k] = b.c;
      if (b.kind == HingeBehaviour::kCurve) {
        hs.curve[k] = ref(curve_index, *b.curve, "curve");
        ok = ok && hs.curve[k] >= 0;
      }
    }
    return ok;
  };
  auto add_hinge = [&](const HingeSpec& hs, const HingeInfo& info, const Where& at,
                       const Behaviours* dirs) {
    if (info.origin != HingeOrigin::kExplicit) {
      const auto [it, inserted] = hinge_index.emplace(info.name, static_cast<int>(d.hinges.size()));
      if (!inserted && it->second < static_cast<int>(p.hinges.size())) {
        L.error(p.hinges[static_cast<std::size_t>(it->second)].id.at,
                "hinge id '" + info.name + "' is also the name of the " +
                    (info.origin == HingeOrigin::kRelease ? "member-end release"
                                                          : "support with axes") +
                    " at " + at.key + ": choose another id");
      }
    }
    std::array<Where, kDofsPerNode> w;
    for (std::size_t k = 0; k < kDofsPerNode; ++k)
      w[k] = dirs != nullptr ? (*dirs)[k].at : at;
    d.hinges.push_back(hs);
    d.hinge_info.push_back(info);
    hinge_at.push_back(at);
    dir_at.push_back(w);
  };

  for (const HingeIn& h : p.hinges) {
    HingeSpec hs;
    bool ok = true;
    hs.node1 = node_ref(h.node1, h.nodes_at);
    hs.node2 = h.node2 ? node_ref(*h.node2, h.nodes_at) : kGround;
    ok = hs.node1 >= 0 && (hs.node2 >= 0 || !h.node2);
    if (ok && hs.node1 == hs.node2) {
      L.error(h.nodes_at,
              "a hinge joins two different nodes; both are node " + std::to_string(h.node1));
      ok = false;
    }
    if (h.frame == FrameKind::kAxes) {
      hs.frame = h.axes;
    } else if (h.frame == FrameKind::kMember) {
      if (ref(members, h.frame_member, "member") < 0) {
        ok = false;
      } else {
        // Geometry errors leave a member without elements (already reported).
        const auto it = std::find_if(d.members.begin(), d.members.end(), [&](const MemberInfo& mi) {
          return mi.name == h.frame_member.id;
        });
        if (it == d.members.end()) {
          ok = false;
        } else {
          const ElementSpec& el = d.elements[static_cast<std::size_t>(it->first_element)];
          hs.frame = beam_geometry(d.nodes[static_cast<std::size_t>(el.node_i)],
                                   d.nodes[static_cast<std::size_t>(el.node_j)], el)
                         .rotation;
        }
      }
    }
    if (ok && hs.node2 == kGround && h.eccentric) {
      L.error(h.eccentric_at,
              "a hinge to the ground cannot be eccentric (the ground has no position): leave out "
              "eccentric");
      ok = false;
    } else if (ok && hs.node2 != kGround) {
      const NodeSpec& n1 = d.nodes[static_cast<std::size_t>(hs.node1)];
      const NodeSpec& n2 = d.nodes[static_cast<std::size_t>(hs.node2)];
      const std::array<double, 3> e{n2.x - n1.x, n2.y - n1.y, n2.z - n1.z};
      const double dist = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
      if (!h.eccentric && dist > kCoincident) {
        L.error(h.nodes_at, "nodes " + std::to_string(h.node1) + " and " +
                                std::to_string(*h.node2) + " do not coincide (they are " +
                                num(dist) +
                                " m apart): set eccentric = true for an eccentric hinge (e = x2 - "
                                "x1), or give the nodes the same position");
        ok = false;
      } else if (h.eccentric) {
        hs.eccentricity = e;
        if (dist > 0 && s.hinge_method == HingeMethod::kNtnPaper) {
          L.error(h.eccentric_at, "an eccentric hinge (e = (" + num(e[0]) + ", " + num(e[1]) +
                                      ", " + num(e[2]) +
                                      ") m) needs hinge_method = \"ntn_exact\" or \"penalty\": "
                                      "the seed's algorithm (\"ntn_paper\", S 17-37) has no "
                                      "eccentricity");
          ok = false;
        }
      }
    }
    ok = set_dirs(hs, h.dirs) && ok;
    if (!ok) continue;
    add_hinge(hs, {h.id.id, HingeOrigin::kExplicit, -1, 0}, h.nodes_at, &h.dirs);
  }
  for (PendingHinge& ph : releases) {
    if (!set_dirs(ph.spec, *ph.dirs)) continue;
    MemberInfo& mi = d.members[static_cast<std::size_t>(ph.info.member)];
    (ph.info.end == 0 ? mi.start_hinge : mi.end_hinge) = static_cast<int>(d.hinges.size());
    add_hinge(ph.spec, ph.info, ph.at, ph.dirs);
  }

  // Supports.
  std::map<int, int> support_of;  // node -> support index
  for (std::size_t i = 0; i < p.supports.size(); ++i) {
    const Support& sp = p.supports[i];
    const int n = node_ref(sp.node, sp.at);
    if (n < 0) continue;
    const auto [it, inserted] = support_of.emplace(n, static_cast<int>(i));
    if (!inserted) {
      L.error(sp.at, "node " + std::to_string(sp.node) + " already has a support (line " +
                         std::to_string(
                             line_of(p.supports[static_cast<std::size_t>(it->second)].at.region)) +
                         ")");
      continue;
    }
    if (sp.axes) {
      // A support with its own frame is a hinge to the ground: rigid in the fixed local
      // directions, free in the others (DESIGN §7.1); the node's own support bits stay 0.
      HingeSpec hs;
      hs.node1 = n;
      hs.node2 = kGround;
      hs.frame = *sp.axes;
      for (std::size_t k = 0; k < kDofsPerNode; ++k) {
        hs.behaviour[k] = ((sp.fixed >> k) & 1U) ? HingeBehaviour::kRigid : HingeBehaviour::kFree;
      }
      add_hinge(hs, {"support." + std::to_string(sp.node), HingeOrigin::kSupport, -1, 0},
                sp.axes_at, nullptr);
      continue;
    }
    d.nodes[static_cast<std::size_t>(n)].fixed = sp.fixed;
  }

  // Point masses add up on their node.
  for (const PointMass& pm : p.point_masses) {
    const int n = node_ref(pm.node, pm.at);
    if (n < 0) continue;
    auto& added = d.nodes[static_cast<std::size_t>(n)].added;
    for (std::size_t k = 0; k < 3; ++k) {
      added[k] += pm.mass;
      added[3 + k] += pm.inertia[k];
    }
  }

  std::vector<Where> load_at;  // per kernel load: the [[loads]] table that made it
  for (const Load& l : p.loads) {
    const int n = node_ref(l.node, l.at);
    int f = kConstant;
    if (l.function) f = ref(functions, *l.function, "time function");
    if (n < 0 || (l.function && f < 0)) continue;
    for (const auto& [dof, value] : l.components) {
      d.loads.push_back({n, dof, value, f});
      load_at.push_back(l.at);
    }
  }

  for (const Input& in : p.inputs) {
    InputSpec is;
    is.kind = in.kind, is.dof = in.dof, is.scale = in.scale, is.min = in.min, is.max = in.max;
    if (in.kind == InputKind::kNodalForce) {
      is.node = node_ref(in.node, in.node_at);
      if (is.node < 0) continue;
    }
    d.inputs.push_back(is);
    d.input_names.push_back(in.name.id);
  }

  const char* const rot_units[3] = {"rad", "rad/s", "rad/s2"};
  const char* const trans_units[3] = {"m", "m/s", "m/s2"};
  for (const Output& o : p.outputs) {
    OutputSpec os;
    std::string units;
    os.dof = o.dof;
    switch (o.kind) {
      case OutKind::kNode: {
        os.kind = o.node_kind;
        os.node = node_ref(o.nodes[0], o.nodes_at);
        if (os.node < 0) continue;
        const std::size_t k = o.node_kind == OutputKind::kAbsoluteAcceleration
                                  ? 2
                                  : static_cast<std::size_t>(o.node_kind);
        units = o.dof < 3 ? trans_units[k] : rot_units[k];
        break;
      }
      case OutKind::kElementForce: {
        os.kind = OutputKind::kElementForce;
        const int m = ref(members, o.member, "member");
        if (m < 0) continue;
        // Geometry errors leave a member without elements; nothing to point at then.
        const auto it = std::find_if(d.members.begin(), d.members.end(),
                                     [&](const MemberInfo& mi) { return mi.name == o.member.id; });
        if (it == d.members.end()) continue;
        os.end = o.end;
        os.element = o.end == 0 ? it->first_element : it->first_element + it->element_count - 1;
        units = o.dof < 3 ? "N" : "N m";
        break;
      }
      case OutKind::kDrift: {
        os.kind = OutputKind::kDrift;
        os.node = node_ref(o.nodes[0], o.nodes_at);
        os.node2 = node_ref(o.nodes[1], o.nodes_at);
        if (os.node < 0 || os.node2 < 0) continue;
        const double z0 = d.nodes[static_cast<std::size_t>(os.node)].z;
        const double z1 = d.nodes[static_cast<std::size_t>(os.node2)].z;
        const double h = z1 - z0;
        if (h == 0.0) {
          L.error(o.nodes_at, "drift height is zero: nodes " + std::to_string(o.nodes[0]) +
                                  " and " + std::to_string(o.nodes[1]) +
                                  " are both at z = " + num(z0) + " m");
          continue;
        }
        if (h < 0.0) {
          L.error(o.nodes_at, "the upper node " + std::to_string(o.nodes[1]) + " (z = " + num(z1) +
                                  " m) is below the lower node " + std::to_string(o.nodes[0]) +
                                  " (z = " + num(z0) + " m)");
          continue;
        }
        os.scale = 1.0 / h;  // drift ratio = relative displacement / storey height
        units = "-";
        break;
      }
      case OutKind::kHinge: {
        os.kind = o.node_kind;
        const auto it = hinge_index.find(o.hinge.id);
        if (it == hinge_index.end()) {
          L.error(o.hinge.at, "unknown hinge '" + o.hinge.id +
                                  "' (hinges are named by their id, <member>.start and "
                                  "<member>.end for releases, support.<node id> for supports "
                                  "with axes)");
          continue;
        }
        os.hinge = it->second;
        if (o.node_kind == OutputKind::kHingeForce) {
          units = o.dof < 3 ? "N" : "N m";
        } else {
          units = o.dof < 3 ? "m" : "rad";
        }
        break;
      }
      case OutKind::kReaction: {
        os.kind = OutputKind::kReaction;
        const bool held = std::any_of(d.nodes.begin(), d.nodes.end(), [&](const NodeSpec& n) {
          return ((n.fixed >> o.dof) & 1U) != 0;
        });
        if (!held) {
          L.error(o.dof_at, "no support holds DOF " +
                                std::string(kDofNames[static_cast<std::size_t>(o.dof)]) +
                                ", so this reaction is always zero");
          continue;
        }
        units = o.dof < 3 ? "N" : "N m";
        break;
      }
    }
    d.outputs.push_back(os);
    d.output_names.push_back(o.name.id);
    d.output_units.push_back(units);
    d.output_alarms.push_back({o.alarm, o.alarm_hysteresis});
  }

  if (L.failed()) return std::nullopt;

  // Pass 3: rigid cycles (topology only), then mass from the kernel's lumped mass, curves
  // against the limit stiffness, effective mass, and the time step.
  auto node_name = [&](int n) { return n == kGround ? std::string("ground") : d.describe_node(n); };
  for (const RigidCycle& c : rigid_cycles(d.view())) {
    std::string path;
    for (int n : c.nodes)
      path += node_name(n) + " - ";
    path += node_name(c.nodes.front());
    L.error(hinge_at[static_cast<std::size_t>(c.hinge)],
            d.describe_hinge(c.hinge) + " closes a cycle of rigid connections: " + path +
                ". A node can hang from one chain of rigid hinge directions only, and a "
                "supported node counts as joined to the ground: make a direction of one of "
                "these hinges free or a spring, or leave one out");
  }
  if (L.failed()) return std::nullopt;

  // What the kernel derives from each element, checked before anything uses it: length,
  // stiffness terms, end masses, the element's highest frequency (one error per member).
  for (std::size_t mi = 0; mi < p.members.size(); ++mi) {
    const Member& m = p.members[mi];
    const MemberInfo& info = d.members[mi];
    const Material& ma = p.materials[static_cast<std::size_t>(materials.at(m.material.id))];
    const Section& se = p.sections[static_cast<std::size_t>(sections.at(m.section.id))];
    const std::string of = " of member " + m.id.id;
    for (int k = 0; k < info.element_count; ++k) {
      const ElementSpec& e = d.elements[static_cast<std::size_t>(info.first_element + k)];
      const NodeSpec& na = d.nodes[static_cast<std::size_t>(e.node_i)];
      const NodeSpec& nb = d.nodes[static_cast<std::size_t>(e.node_j)];
      const BeamGeometry g = beam_geometry(na, nb, e);
      const double l = g.length;
      if (!std::isfinite(l)) {
        L.error(m.nodes_at, "the length of member " + m.id.id +
                                " is beyond the largest double (1.8e308 m): its nodes' "
                                "coordinates are too far apart");
        break;
      }
      const Factor E{"E", e.E, 1, ma.E_at, " Pa"}, G{"G", e.G, 1, ma.G_at, " Pa"};
      const Factor rho{"rho", e.rho, 1, ma.rho_at, " kg/m^3"}, A{"A", e.A, 1, se.A_at, " m^2"};
      const Factor Iy{"Iy", e.Iy, 1, se.Iy_at, " m^4"}, Iz{"Iz", e.Iz, 1, se.Iz_at, " m^4"};
      const Factor J{"J", e.J, 1, se.J_at, " m^4"};
      auto len = [&](int power) {
        return Factor{"l", l, power, m.nodes_at, " m (element length)"};
      };
      auto inv = [](Factor f) {
        f.power = -f.power;
        return f;
      };
      const BeamStiffness ks = beam_stiffness(e, l);
      bool ok =
          check_derived(L, ks.axial, "axial stiffness E A / l" + of, {E, A, len(-1)}, false) &&
          check_derived(L, ks.torsion, "torsional stiffness G J / l" + of, {G, J, len(-1)}, false);
      for (int plane = 0; ok && plane < 2; ++plane) {
        const auto& t = plane == 0 ? ks.xy : ks.xz;
        const Factor& I = plane == 0 ? Iz : Iy;
        const double shear = plane == 0 ? e.shear_area_y : e.shear_area_z;
        std::vector<Factor> f{E, I, len(-3)};
        if (shear > 0)
          f.push_back(inv(G)), f.push_back(inv(Factor{"kappa A", shear, 1, se.shear_at, " m^2"}));
        double worst = 0;
        for (double v : t)
          worst = std::isfinite(v) ? std::max(worst, std::abs(v)) : v;
        ok = check_derived(L, worst, "bending stiffness 12 E " + I.name + " / (l^3 (1 + Phi))" + of,
                           f, false);
      }
      if (!ok) break;
      const auto me = beam_end_mass(e, g, d.settings.rotary_inertia);
      ok = check_derived(L, me[0], "end mass rho A l / 2" + of, {rho, A, len(1)}, true);
      for (std::size_t c = 3; ok && c < 6; ++c) {
        Factor I{"Iy + Iz", e.Iy + e.Iz, 1, se.Iy_at, " m^4"};
        ok =
            check_derived(L, me[c], "rotational end mass rho (Iy + Iz) l / 2 + rho A l^3 / 78" + of,
                          {rho, A, I, len(1)}, true);
      }
      if (!ok) break;
      const double w = element_omega_max(e, na, nb, d.settings.rotary_inertia);
      if (!check_derived(
              L, w, "highest frequency sqrt(lambda_max(M^-1 K)) (about sqrt(E / rho) / l)" + of,
              {E, inv(rho), len(-1)}, true))
        break;
    }
  }
  if (L.failed()) return std::nullopt;

  std::vector<double> mass(static_cast<std::size_t>(kDofsPerNode) * d.nodes.size());
  assemble_lumped_mass(d.view(), mass);
  // Point masses add up with the elements' masses on a node: the sum must stay finite, and be
  // 0 (no mass) or a normal number (1 / m finite).
  for (std::size_t i = 0; i < d.nodes.size(); ++i) {
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      const double m = mass[i * kDofsPerNode + k];
      if (m == 0 || (m >= std::numeric_limits<double>::min() && std::isfinite(m))) continue;
      L.error(i < p.nodes.size() ? p.nodes[i].at : Where{toml::source_region{}, ""},
              "the lumped mass of " + d.describe_node(static_cast<int>(i)) + " in " +
                  std::string(kDofNames[k]) + " (its members' masses and point masses added up) " +
                  (std::isfinite(m) ? "is " + num(m) +
                                          " kg, subnormal: too small to be a mass (give 0 or at "
                                          "least 2.2e-308)"
                                    : std::string("is beyond the largest double, 1.8e308")));
      break;
    }
  }
  if (L.failed()) return std::nullopt;

  std::vector<bool> hinged(d.nodes.size(), false), connected(d.nodes.size(), false);
  for (const HingeSpec& h : d.hinges) {
    hinged[static_cast<std::size_t>(h.node1)] = true;
    if (h.node2 != kGround) hinged[static_cast<std::size_t>(h.node2)] = true;
  }
  for (const ElementSpec& e : d.elements)
    connected[static_cast<std::size_t>(e.node_i)] = connected[static_cast<std::size_t>(e.node_j)] =
        true;
  for (std::size_t i = 0; i < d.nodes.size(); ++i)
    connected[i] = connected[i] || hinged[i];
  // A given node that no member or hinge connects, at the same place (to kCoincident) as
  // another node: most likely a typo for that node. Cells of kCoincident hold the nodes; the
  // 27 cells around one hold every node within kCoincident of it.
  struct CellHash {
    std::size_t operator()(const std::array<double, 3>& c) const {
      std::size_t h = 0;
      for (double v : c)
        h = h * 1000003U ^ std::hash<double>{}(v);
      return h;
    }
  };
  std::unordered_map<std::array<double, 3>, std::vector<int>, CellHash> cells;
  auto cell_of = [](const NodeSpec& n) {
    return std::array<double, 3>{std::floor(n.x / kCoincident), std::floor(n.y / kCoincident),
                                 std::floor(n.z / kCoincident)};
  };
  bool any_loose = false;
  for (std::size_t i = 0; i < p.nodes.size(); ++i)
    any_loose = any_loose || !connected[i];
  if (any_loose) {
    for (std::size_t i = 0; i < d.nodes.size(); ++i)
      cells[cell_of(d.nodes[i])].push_back(static_cast<int>(i));
  }
  auto twin_of = [&](std::size_t i) -> int {  // the first other node within kCoincident, or -1
    const NodeSpec& n = d.nodes[i];
    const auto c = cell_of(n);
    int best = -1;
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == cells.end()) continue;
          for (int j : it->second) {
            if (j == static_cast<int>(i)) continue;
            const NodeSpec& o = d.nodes[static_cast<std::size_t>(j)];
            const double ex = o.x - n.x, ey = o.y - n.y, ez = o.z - n.z;
            if (std::sqrt(ex * ex + ey * ey + ez * ez) <= kCoincident && (best < 0 || j < best))
              best = j;
          }
        }
      }
    }
    return best;
  };
  // A node no hinge touches gets its mass from elements and point masses only; generated
  // nodes always have elements.
  for (std::size_t i = 0; i < p.nodes.size(); ++i) {
    const int twin = connected[i] ? -1 : twin_of(i);
    const std::string same_place =
        twin < 0 ? ""
                 : " It is connected to no member or hinge, at the same place as " +
                       d.describe_node(twin) + " (within 1e-9 m): did you mean that node?";
    if (hinged[i]) continue;
    std::string missing;
    for (int k = 0; k < kDofsPerNode; ++k) {
      const bool held = ((d.nodes[i].fixed >> k) & 1U) != 0;
      if (!held && !(mass[i * kDofsPerNode + static_cast<std::size_t>(k)] > 0)) {
        missing +=
            (missing.empty() ? "" : ", ") + std::string(kDofNames[static_cast<std::size_t>(k)]);
      }
    }
    if (!missing.empty()) {
      L.error(p.nodes[i].at, "node " + std::to_string(p.nodes[i].id) +
                                 " has no mass in its free DOFs " + missing +
                                 ": connect it to a member, give it a point mass (with inertia "
                                 "for rotations) or support those DOFs." +
                                 same_place);
    } else if (twin >= 0) {
      L.note(p.nodes[i].at, "node " + std::to_string(p.nodes[i].id) +
                                " moves on its own (its point mass or support only)." + same_place);
    }
  }
  if (L.failed()) return std::nullopt;

  // Gravity and nodal loads as forces: M g f(t) and value f(t) must be finite (f: the largest
  // |value| of the time function scaling them, 1 without).
  auto function_peak = [&](int f) {
    double peak = 1;
    if (f < 0) return peak;
    const TimeFunctionSpec& tf = d.time_functions[static_cast<std::size_t>(f)];
    peak = 0;
    for (int k = 0; k < tf.count; ++k)
      peak = std::max(peak, std::abs(d.time_points[static_cast<std::size_t>(tf.first + k)].value));
    return peak;
  };
  const double g_peak = function_peak(s.gravity_function);
  const double g_max =
      std::max({std::abs(s.gravity[0]), std::abs(s.gravity[1]), std::abs(s.gravity[2])});
  if (g_max > 0) {
    const double m_max = *std::max_element(mass.begin(), mass.end());
    std::vector<Factor> f{{"|gravity|", g_max, 1, p.model.gravity_at, " m/s^2"},
                          {"the largest nodal mass", m_max, 1, p.model.gravity_at, " kg"}};
    if (s.gravity_function >= 0)
      f.push_back({"the largest |value| of gravity_function", g_peak, 1, p.model.gravity_at, ""});
    (void)check_derived(L, g_max * m_max * g_peak, "gravity force M g", f, false);
  }
  for (std::size_t i = 0; i < d.loads.size(); ++i) {
    const LoadSpec& l = d.loads[i];
    (void)check_derived(L, l.value * function_peak(l.time_function),
                        "load (value times the largest |value| of its time function)",
                        {{"value", l.value, 1, load_at[i], " N (or N m)"},
                         {"the largest |value| of its time function",
                          function_peak(l.time_function), 1, load_at[i], ""}},
                        false);
  }
  if (L.failed()) return std::nullopt;

  // Penalty and limit stiffness: given, or kPenaltyFactor x the stiffest element term (axial
  // EA/l; bending 4EI/l with the larger I). The limit default does not follow a given penalty
  // stiffness, so that which curve segments are rigid never depends on the method.
  double axial = 0, bending = 0;
  std::size_t axial_at = 0, bending_at = 0;  // their elements
  for (std::size_t ei = 0; ei < d.elements.size(); ++ei) {
    const ElementSpec& e = d.elements[ei];
    const double l = beam_geometry(d.nodes[static_cast<std::size_t>(e.node_i)],
                                   d.nodes[static_cast<std::size_t>(e.node_j)], e)
                         .length;
    if (e.E * e.A / l > axial) axial = e.E * e.A / l, axial_at = ei;
    if (4.0 * e.E * std::max(e.Iy, e.Iz) / l > bending)
      bending = 4.0 * e.E * std::max(e.Iy, e.Iz) / l, bending_at = ei;
  }
  // The defaults must be numbers too (they go into the header even without hinges).
  for (int rotational = 0; rotational < 2; ++rotational) {
    const bool given = rotational == 0 ? p.model.penalty_stiffness && p.model.limit_stiffness
                                       : p.model.penalty_rotational_stiffness &&
                                             p.model.limit_rotational_stiffness;
    const double v = kPenaltyFactor * (rotational == 0 ? axial : bending);
    const std::size_t ei = rotational == 0 ? axial_at : bending_at;
    const Member& m = p.members[static_cast<std::size_t>(d.element_member[ei])];
    const Material& ma = p.materials[static_cast<std::size_t>(materials.at(m.material.id))];
    if (!given && !std::isfinite(v)) {
      L.error(ma.E_at,
              "E = " + num(d.elements[ei].E) + " Pa in member " + m.id.id + " gives a default " +
                  (rotational == 0 ? "penalty and limit stiffness 1e4 E A / l"
                                   : "rotational penalty and limit stiffness 1e4 x 4 E I / l") +
                  " beyond the largest double (1.8e308): give model." +
                  (rotational == 0 ? "penalty_stiffness and model.limit_stiffness"
                                   : "penalty_rotational_stiffness and "
                                     "model.limit_rotational_stiffness"));
    }
  }
  if (L.failed()) return std::nullopt;
  s.penalty_stiffness = p.model.penalty_stiffness.value_or(kPenaltyFactor * axial);
  s.penalty_rotational_stiffness =
      p.model.penalty_rotational_stiffness.value_or(kPenaltyFactor * bending);
  s.limit_stiffness = p.model.limit_stiffness.value_or(kPenaltyFactor * axial);
  s.limit_rotational_stiffness =
      p.model.limit_rotational_stiffness.value_or(kPenaltyFactor * bending);

  // Curves in use: a spring part (segments softer than the limit stiffness) that contains
  // d = 0, where every run starts, with rigid branches (slope >= limit) only at the ends.
  for (std::size_t hi = 0; hi < d.hinges.size(); ++hi) {
    const HingeSpec& h = d.hinges[hi];
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      if (h.behaviour[k] != HingeBehaviour::kCurve) continue;
      const int ci = h.curve[k];
      const CurveSpec& cs = d.curves[static_cast<std::size_t>(ci)];
      const double k_lim = k < 3 ? s.limit_stiffness : s.limit_rotational_stiffness;
      const std::string units = k < 3 ? " N/m" : " N m/rad";
      const std::string name = "curve '" + d.curve_ids[static_cast<std::size_t>(ci)] + "'";
      const Where& at = dir_at[hi][k];
      // The kernel's split (ntn::curve_branches), with the reason by segment.
      const CurveBranches br = curve_branches(d.curve_points, cs, k_lim);
      const int inner = br.inner;
      if (br.first < 0) {
        L.error(at, name + " has no segment softer than the limit stiffness " + num(k_lim) + units +
                        ": all of it is a rigid branch. A direction without play is \"rigid\"; "
                        "for a spring or a gap, add softer segments or raise the limit stiffness");
        continue;
      }
      if (inner >= 0) {
        L.error(at, name + " has a rigid segment (points " + std::to_string(inner) + " to " +
                        std::to_string(inner + 1) + ", slope at least the limit stiffness " +
                        num(k_lim) + units +
                        ") between softer ones: rigid branches may only end a curve");
        continue;
      }
      const double lower = br.lower, upper = br.upper;
      if (lower > 0 || upper < 0) {
        auto end = [](double v) { return v <= -1e300 ? "-inf" : v >= 1e300 ? "+inf" : num(v); };
        L.error(at, name + " has its spring part from d = " + end(lower) + " to " + end(upper) +
                        ", which does not contain d = 0 where every run starts: a hinge cannot "
                        "start on a rigid branch");
      }
    }
  }
  if (L.failed()) return std::nullopt;

  // The kernel must accept every hinge as the compiler built it (same rules, one place to look
  // when they part).
  for (std::size_t hi = 0; hi < d.hinges.size(); ++hi) {
    HingeData hd;
    if (!make_hinge_data(d.hinges[hi], s, static_cast<int>(d.nodes.size()), d.curves,
                         d.curve_points, hd)) {
      L.error(hinge_at[hi], "internal error: the kernel refuses " +
                                d.describe_hinge(static_cast<int>(hi)) +
                                " (ntn::make_hinge_data); please report this model");
    }
  }
  if (L.failed()) return std::nullopt;

  // Effective mass with the hinge constraints (config/README.md, "Mass and mechanisms").
  auto node_at = [&](int n) -> Where {
    const auto i = static_cast<std::size_t>(n);
    if (i < p.nodes.size()) return p.nodes[i].at;
    return {toml::source_region{}, ""};
  };
  auto dof_list = [](std::uint8_t bits) {
    std::string out;
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      if (((bits >> k) & 1U) == 0) continue;
      out += (out.empty() ? "" : ", ") + std::string(kDofNames[k]);
    }
    return out;
  };
  const MassCheck mc = hinge_mass_check(d.view(), mass);
  for (const MassProblem& mp : mc.springs) {
    std::string msg = d.describe_node(mp.node) + " has no effective mass in " + dof_list(mp.dofs) +
                      " (global axes), but a hinge spring, dashpot or curve acts there: an "
                      "explicit step cannot integrate a massless spring (its frequency is "
                      "infinite). Give the node a point mass (with inertia for rotations), or make "
                      "those hinge directions rigid or free";
    if (mp.penalty) {
      msg +=
          ". With hinge_method = \"penalty\" a rigid direction is a stiff spring: penalty "
          "needs mass on both nodes; give the joint a point mass or use ntn_exact";
    }
    L.error(node_at(mp.node), msg);
  }
  if (L.failed()) return std::nullopt;
  d.mechanisms = mc.mechanisms;
  for (const Mechanism& m : d.mechanisms) {
    L.note(node_at(m.node), d.describe_node(m.node) +
                                " has no effective mass and no stiffness in " + dof_list(m.dofs) +
                                " (global axes): a mechanism (DESIGN §7.1); the kernel holds "
                                "these DOFs at zero");
  }

  // Hinge springs against the masses they join: k w and c w (w = b^T M^-1 b = n1 + n2 of the
  // kernel's scaled_spring_direction) are the spring's own frequency^2 and damping rate, the
  // seeds of its stable-step terms: beyond double, there is no step to compute.
  for (std::size_t hi = 0; hi < d.hinges.size(); ++hi) {
    HingeData hd;
    if (!make_hinge_data(d.hinges[hi], s, static_cast<int>(d.nodes.size()), d.curves,
                         d.curve_points, hd))
      continue;
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      if (!((hd.springs >> k) & 1U)) continue;
      double s1[6], s2[6], n1 = 0, n2 = 0;
      if (!scaled_spring_direction(hd, k, d.nodes, mass, s1, s2, n1, n2)) continue;  // massless
      const double w = n1 + n2;
      const std::string of = " of " + d.describe_hinge(static_cast<int>(hi)) + ", direction " +
                             std::string(kDofNames[k]);
      const HingeBehaviour b = d.hinges[hi].behaviour[k];
      const std::string unit = k < 3 ? " N/m" : " N m/rad";
      const Factor inv_mass{"1/m1 + 1/m2 (along the direction)", w, 1, dir_at[hi][k], " 1/kg"};
      const Factor stiff{b == HingeBehaviour::kRigid   ? "the penalty stiffness"
                         : b == HingeBehaviour::kCurve ? "the curve's steepest soft slope"
                                                       : "linear",
                         hd.stiffness[k], 1, dir_at[hi][k], unit};
      if (!check_derived(L, hd.stiffness[k] * w, "frequency^2 k (1/m1 + 1/m2)" + of,
                         {stiff, inv_mass}, false))
        continue;
      (void)check_derived(
          L, hd.dashpot[k] * w, "damping rate c (1/m1 + 1/m2)" + of,
          {{"dashpot", hd.dashpot[k], 1, dir_at[hi][k], k < 3 ? " N s/m" : " N m s/rad"}, inv_mass},
          false);
    }
  }
  if (L.failed()) return std::nullopt;

  // Time step (DESIGN §6, kernel/README.md "Stable time step"): the element eigenvalue bound and
  // the node-by-node bound of the hinge springs, with damping, for the model's hinge method.
  d.stable = stable_time_step(d.view(), mass);
  auto governing = [&](const StableStepReport& r) {
    if (r.governing_hinge >= 0) {
      return d.describe_hinge(r.governing_hinge) + ", direction " +
             std::string(kDofNames[static_cast<std::size_t>(r.hinge_direction)]) +
             " (the spring with the largest share of the governing node's bound)";
    }
    return d.describe_element(r.governing_element);
  };
  if (!(d.stable.dt_stable > 0) || !std::isfinite(d.stable.dt_stable)) {
    // Where it showed: the hinge direction's value, or the governing element's member.
    const StableStepReport& st = d.stable;
    Where at = p.model.dt_at;
    if (st.governing_hinge >= 0) {
      at = dir_at[static_cast<std::size_t>(st.governing_hinge)]
                 [static_cast<std::size_t>(st.hinge_direction)];
    } else if (st.governing_element >= 0) {
      at = p.members[static_cast<std::size_t>(
                         d.element_member[static_cast<std::size_t>(st.governing_element)])]
               .nodes_at;
    }
    // The values there: the spring's k and c, or the element's E, rho and A.
    std::string values;
    if (st.governing_hinge >= 0) {
      const auto h = static_cast<std::size_t>(st.governing_hinge);
      const auto k = static_cast<std::size_t>(st.hinge_direction);
      HingeData hd;
      if (make_hinge_data(d.hinges[h], s, static_cast<int>(d.nodes.size()), d.curves,
                          d.curve_points, hd)) {
        values = " (k = " + num(hd.stiffness[k]) + (k < 3 ? " N/m" : " N m/rad") +
                 ", dashpot c = " + num(hd.dashpot[k]) + (k < 3 ? " N s/m)" : " N m s/rad)");
      }
    } else if (st.governing_element >= 0) {
      const ElementSpec& e = d.elements[static_cast<std::size_t>(st.governing_element)];
      values =
          " (E = " + num(e.E) + " Pa, rho = " + num(e.rho) + " kg/m^3, A = " + num(e.A) + " m^2)";
    }
    L.error(at, "the stable step is zero (set by " + governing(st) + values + "): " +
                    (st.issue == StepIssue::kMassless
                         ? std::string("a spring acts on a DOF without mass")
                         : std::string("an intermediate result of the stable-step bound is "
                                       "beyond double there (stiffness, damping or mass too "
                                       "large or too small by hundreds of orders of magnitude)")));
    return std::nullopt;
  }
  if (d.dt_auto) {
    s.dt = auto_time_step(d.stable.dt_stable, s.frame_period);
  } else {
    s.dt = d.dt_requested;
    if (s.dt > d.stable.dt_stable && !s.allow_unstable) {
      L.error(p.model.dt_at, "dt = " + num(s.dt) + " s is above the stable step " +
                                 num(d.stable.dt_stable) + " s set by " + governing(d.stable) +
                                 "; use dt = \"auto\" or a smaller dt");
    }
  }
  // The frame rule (ntn::frame_substeps, kernel/README.md "Frames and substeps"): the same test
  // the real-time loop makes, so that a model that passes here runs there.
  const Substeps n = frame_substeps(s.dt, s.frame_period);
  const std::string frame =
      " the frame period " + num(s.frame_period) + " s (frame_rate = " + num(d.frame_rate) + " Hz)";
  const std::string stable_by =
      "the stable step is " + num(d.stable.dt_stable) + " s, set by " + governing(d.stable);
  switch (n.error) {
    case SubstepError::kNone:
      break;
    case SubstepError::kTooMany:
      if (d.dt_auto) {
        L.error(p.model.dt_at,
                "dt = \"auto\" needs " + num(auto_substeps(d.stable.dt_stable, s.frame_period)) +
                    " substeps in" + frame + ", more than the limit " +
                    std::to_string(kMaxSubsteps) + " (ntn::kMaxSubsteps): " + stable_by +
                    ". No machine runs such a model; check the units and the geometry there "
                    "(nodes almost coincident?), or lower frame_rate");
      } else {
        L.error(p.model.dt_at, "dt = " + num(s.dt) + " s gives " + num(n.ratio) + " substeps in" +
                                   frame + ", more than the limit " + std::to_string(kMaxSubsteps) +
                                   " (ntn::kMaxSubsteps)");
      }
      break;
    case SubstepError::kNotWhole:
      L.error(p.model.dt_at, "dt = " + num(s.dt) + " s does not divide" + frame +
                                 " into a whole number of substeps (period / dt = " + num(n.ratio) +
                                 "); use dt = \"auto\" or the period / N");
      break;
    case SubstepError::kLongerThanFrame:
      L.error(p.model.dt_at, "dt = " + num(s.dt) + " s is longer than" + frame +
                                 ": a frame needs at least one step; use dt = \"auto\", or "
                                 "lower frame_rate");
      break;
    case SubstepError::kBadTimeStep:
    case SubstepError::kBadPeriod:
      L.error(p.model.dt_at, "dt = " + num(s.dt) + " s and" + frame + ": " + to_string(n.error));
      break;
  }
  if (L.failed()) return std::nullopt;
  return d;
}

LoadResult load_parsed(Loader& L, const toml::table& root, const std::string& file) {
  Parsed p;
  read_tables(L, root, p);
  LoadResult r;
  if (!L.failed()) r.model = build(L, p, file);
  r.error_count = L.error_count();
  r.errors = L.take_errors();
  if (!r.errors.empty()) {
    r.model.reset();
  } else {
    r.notes = L.take_notes();
  }
  return r;
}

LoadResult load_text(std::string_view text, const std::string& file) {
  Loader L(file);
  // Size and nesting first: the parser's recursion must never see input that overflows it.
  if (auto limit = check_model_text_limits(text, file)) {
    LoadResult r;
    r.errors.push_back(std::move(*limit));
    r.error_count = 1;
    return r;
  }
  try {
    const toml::table root = toml::parse(text, file);
    return load_parsed(L, root, file);
  } catch (const toml::parse_error& e) {
    L.error(e.source(), "", "TOML syntax: " + std::string(e.description()));
  } catch (const std::exception& e) {
    L.error_at_start("", std::string("internal error: ") + e.what());
  }
  LoadResult r;
  r.error_count = L.error_count();
  r.errors = L.take_errors();
  return r;
}

}  // namespace

LoadResult load_model(const std::string& path) {
  auto unreadable = [&](const std::string& why) {
    LoadResult r;
    r.unreadable = true;
    r.errors.push_back({path, 1, 1, "", "cannot read the model file: " + why});
    r.error_count = 1;
    return r;
  };
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return unreadable("it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return unreadable(std::filesystem::exists(path, ec) ? "permission denied"
                                                        : "no such file (or a path through a "
                                                          "file that is not a directory)");
  }
  // At most one byte more than the limit: a huge file is refused without reading it all.
  std::string text;
  char buf[1 << 16];
  while (text.size() <= kMaxModelFileBytes && in.read(buf, sizeof buf).gcount() > 0)
    text.append(buf, static_cast<std::size_t>(in.gcount()));
  if (in.bad()) return unreadable("read error");
  return load_text(text, path);
}

LoadResult load_model_from_string(std::string_view toml_text, const std::string& source_name) {
  return load_text(toml_text, source_name);
}

}  // namespace ntn::modelc
