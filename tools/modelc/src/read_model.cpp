// The reader: model text -> SourceModel (pass 1 of the compiler). The size and nesting limits
// first (limits.cpp: toml++'s recursion must never see input that overflows it), then toml++,
// then every table: keys, types and values (unknown and missing keys, ranges, conflicts, hinge
// axes, curve and time-function points increasing). Each value is checked on its own here;
// references and everything derived are the compile stages' (compile.cpp). This file reads
// [model] and [initial] and runs the table readers (read_tables.hpp) in order.
#include "read_model.hpp"

#include <toml++/toml.h>
#include <numbers>

#include "damping.hpp"
#include "ntn/modelc/emit_header.hpp"
#include "ntn/modelc/limits.hpp"
#include "ntn/time_step.hpp"
#include "read_tables.hpp"
#include "toml_reader.hpp"

namespace ntn::modelc::compile {
namespace {

const std::vector<std::string_view> kHingeMethods = {"ntn_exact", "ntn_paper", "penalty"};
const std::vector<std::string_view> kClampRules = {"momentum", "paper"};
const std::vector<std::string_view> kDampingVelocities = {"central", "lagged"};
const std::vector<std::string_view> kPlanes = {"xz", "xy", "yz"};

// [model.damping]: alpha and beta as given, or a ratio at one frequency (mass-proportional),
// at two frequencies or at two of the model's modes (Rayleigh).
void read_damping_table(Reader& L, const toml::node* d, ModelTable& m) {
  const auto* dt = d->as_table();
  if (dt == nullptr) {
    L.error(d->source(), "model.damping",
            "expected a table ([model.damping]), got " + type_name(*d));
    return;
  }
  Table dmp(L, *dt, "model.damping",
            {"alpha", "beta", "ratio", "frequency", "frequencies", "modes"});
  dmp.check_unknown();
  // Every conflicting pair is reported (each checked before any return).
  const bool alpha_ratio = dmp.conflict("alpha", "ratio");
  const bool beta_ratio = dmp.conflict("beta", "ratio");
  if (alpha_ratio || beta_ratio) return;
  if (dmp.has("alpha") || dmp.has("beta")) {
    // C = alpha M + beta K_el as given.
    if (auto a = dmp.non_negative("alpha", Need::kOptional)) m.alpha = *a;
    if (auto b = dmp.non_negative("beta", Need::kOptional)) m.beta = *b;
    for (const char* k : {"frequency", "frequencies", "modes"}) {
      if (dmp.has(k)) L.error(dmp.where(k), "only applies with 'ratio'");
    }
    return;
  }
  const auto ratio = dmp.non_negative("ratio", Need::kRequired);
  const bool frequency_frequencies = dmp.conflict("frequency", "frequencies");
  const bool frequency_modes = dmp.conflict("frequency", "modes");
  const bool frequencies_modes = dmp.conflict("frequencies", "modes");
  if (frequency_frequencies || frequency_modes || frequencies_modes) return;
  if (dmp.has("frequencies")) {
    // Rayleigh damping with `ratio` at two frequencies: the ratio alpha / (2 omega) +
    // beta omega / 2 equals xi at omega_1 and omega_2 for alpha = 2 xi omega_1 omega_2 /
    // (omega_1 + omega_2), beta = 2 xi / (omega_1 + omega_2) (rayleigh_coefficients).
    const auto fs = dmp.numbers("frequencies", Need::kRequired, 2);
    if (!fs) return;
    const double f1 = (*fs)[0], f2 = (*fs)[1];
    if (!(f1 > 0) || !(f2 > 0)) {
      L.error(dmp.where("frequencies"), "must be positive (got [" + num(f1) + ", " + num(f2) +
                                            "] Hz): the ratio is set at two natural frequencies");
      return;
    }
    if (same_frequency(f1, f2)) {
      L.error(dmp.where("frequencies"),
              "the two frequencies are equal (" + num(f1) +
                  " Hz, to 1e-9): Rayleigh damping needs two different ones (one frequency: "
                  "'frequency', mass-proportional)");
      return;
    }
    if (!ratio) return;
    const RayleighCoefficients c =
        rayleigh_coefficients(*ratio, 2.0 * std::numbers::pi * f1, 2.0 * std::numbers::pi * f2);
    m.damping_ratio = *ratio, m.damping_frequencies = {f1, f2};
    if (!c.finite()) {
      L.error(dmp.where("frequencies"), "ratio = " + num(*ratio) + " at [" + num(f1) + ", " +
                                            num(f2) + "] Hz gives alpha = " + num(c.alpha) +
                                            " 1/s, beta = " + num(c.beta) +
                                            " s: beyond double (1.8e308); check the units");
      return;
    }
    m.alpha = c.alpha, m.beta = c.beta;
    return;
  }
  if (const toml::node* mn = dmp.get("modes", Need::kOptional)) {
    // Two of the model's own undamped modes (1-based): their frequencies come from the modal
    // analysis, in the compile stage set_damping_from_modes.
    const auto ids = L.array_of<long long>(
        *mn, dmp.key("modes"), 2,
        [&](const toml::node& e, const auto& k) { return L.integer(e, k, 1, kMaxDampingMode); });
    m.damping_modes_at = dmp.where("modes");
    if (!ids) return;
    if ((*ids)[0] == (*ids)[1]) {
      L.error(m.damping_modes_at, "the two modes are the same (" + std::to_string((*ids)[0]) +
                                      "): Rayleigh damping needs two different ones");
      return;
    }
    if (!ratio) return;
    m.damping_ratio = *ratio;
    m.damping_modes = {static_cast<int>((*ids)[0]), static_cast<int>((*ids)[1])};
    return;
  }
  // C = alpha M gives the fraction of critical damping alpha / (2 omega) in a mode of
  // circular frequency omega: alpha = 2 ratio (2 pi f) sets `ratio` at `frequency`.
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

void read_model_table(Reader& L, const toml::table& root, ModelTable& m) {
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
           "allow_unstable", "damping", "damping_velocity", "hinge_method", "clamp",
           "penalty_stiffness", "penalty_rotational_stiffness", "limit_stiffness",
           "limit_rotational_stiffness", "plane", "geometry"});
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
    m.dt_at = place(mt->source(), "model.dt");
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
  if (auto c = t.choice("damping_velocity", Need::kOptional, kDampingVelocities))
    m.damping_velocity = static_cast<DampingVelocity>(*c);
  if (auto g = t.choice("geometry", Need::kOptional, kGeometries)) m.geometry = kGeometryOf[*g];
  if (auto pl = t.choice("plane", Need::kOptional, kPlanes)) m.plane = static_cast<Plane>(*pl + 1);
  m.plane_at = t.where("plane");
  m.penalty_stiffness = t.positive("penalty_stiffness", Need::kOptional);
  m.penalty_rotational_stiffness = t.positive("penalty_rotational_stiffness", Need::kOptional);
  m.limit_stiffness = t.positive("limit_stiffness", Need::kOptional);
  m.limit_rotational_stiffness = t.positive("limit_rotational_stiffness", Need::kOptional);

  if (const toml::node* d = t.get("damping", Need::kOptional)) read_damping_table(L, d, m);
}

// [initial]: gravity = "sudden" | "static", and [[initial.nodes]] {node, u, v} (3 or 6 numbers).
void read_initial_table(Reader& L, const toml::table& root, InitialTable& init) {
  const toml::node* n = root.get("initial");
  if (n == nullptr) return;
  const auto* it = n->as_table();
  if (it == nullptr) {
    L.error(n->source(), "initial", "expected a table ([initial]), got " + type_name(*n));
    return;
  }
  Table t(L, *it, "initial", {"gravity", "nodes"});
  t.check_unknown();
  if (auto g = t.choice("gravity", Need::kOptional, {"sudden", "static"})) {
    init.gravity_static = *g == 1;
  }
  init.gravity_at = t.where("gravity");
  for_each_table(
      L, *it, "nodes",
      [&](const toml::table& tt, const std::string& path) {
        Table nt(L, tt, path, {"node", "u", "v"});
        nt.check_unknown();
        InitialNode in;
        auto node = read_node_ref(L, nt, "node", Need::kRequired);
        bool ok = node.has_value();
        // u and v: [x, y, z] translations, or all six DOFs [ux, uy, uz, rx, ry, rz].
        auto six = [&](std::string_view k, std::array<double, kDofsPerNode>& out) {
          const toml::node* a = nt.get(k, Need::kOptional);
          if (a == nullptr) return true;
          const auto* arr = a->as_array();
          if (arr != nullptr && arr->size() != 3 && arr->size() != 6) {
            L.error(a->source(), nt.key(k),
                    "expected 3 values (ux, uy, uz) or 6 (ux, uy, uz, rx, ry, rz), got " +
                        std::to_string(arr->size()));
            return false;
          }
          const std::size_t count = arr != nullptr && arr->size() == 3 ? 3 : 6;
          auto v = nt.numbers(k, Need::kOptional, count);
          if (!v) return false;
          for (std::size_t d = 0; d < count; ++d)
            out[d] = (*v)[d];
          return true;
        };
        ok = six("u", in.u) && ok;
        ok = six("v", in.v) && ok;
        if (!nt.has("u") && !nt.has("v")) {
          L.error(tt.source(), path,
                  "gives neither 'u' nor 'v' (the node's initial displacement "
                  "and velocity)");
          ok = false;
        }
        if (!ok) return;
        in.node = *node;
        in.at = nt.where("node");
        init.nodes.push_back(in);
      },
      "initial");
}

static_assert(static_cast<int>(HingeMethod::kNtnExact) == 0 &&
              static_cast<int>(HingeMethod::kNtnPaper) == 1 &&
              static_cast<int>(HingeMethod::kPenalty) == 2);  // the order of kHingeMethods
static_assert(static_cast<int>(Plane::kXz) == 1 && static_cast<int>(Plane::kXy) == 2 &&
              static_cast<int>(Plane::kYz) == 3);  // the order of kPlanes, after kNone
static_assert(static_cast<int>(ClampRule::kMomentum) == 0 &&
              static_cast<int>(ClampRule::kPaper) == 1);  // the order of kClampRules
static_assert(static_cast<int>(DampingVelocity::kCentral) == 0 &&
              static_cast<int>(DampingVelocity::kLagged) == 1);  // kDampingVelocities' order

// One reader per array of tables, in the order they are read (the order of the diagnostics):
// each reads one table of the array into the model (read_tables.hpp).
using TableReader = void (*)(Reader&, const toml::table&, const std::string&, SourceModel&);
constexpr std::pair<std::string_view, TableReader> kTableReaders[] = {
    {"materials", read_material},
    {"sections", read_section},
    {"nodes", read_node},
    {"members", read_member},
    {"leaning_columns", read_leaning_column},
    {"supports", read_support},
    {"point_masses", read_point_mass},
    {"time_functions", read_time_function},
    {"loads", read_load},
    {"member_loads", read_member_load},
    {"inputs", read_input},
    {"outputs", read_output},
    {"curves", read_curve},
    {"hinges", read_hinge}};

// The file's top-level keys: the tables a model file has.
void check_top_level_keys(Reader& L, const toml::table& root) {
  Table top(L, root, "",
            {"model", "materials", "sections", "nodes", "members", "leaning_columns", "supports",
             "point_masses", "time_functions", "loads", "member_loads", "inputs", "outputs",
             "curves", "hinges", "initial"});
  top.check_unknown();
}

void read_tables(Reader& L, const toml::table& root, SourceModel& p) {
  check_top_level_keys(L, root);
  read_model_table(L, root, p.model);
  for (const auto& [name, read] : kTableReaders) {
    for_each_table(L, root, name,
                   [&](const toml::table& tt, const std::string& path) { read(L, tt, path, p); });
  }
  read_initial_table(L, root, p.initial);
}

}  // namespace

std::optional<SourceModel> read_model_text(DiagnosticSink& sink, std::string_view text,
                                           const std::string& file) {
  // Size and nesting first: the parser's recursion must never see input that overflows it.
  if (auto limit = check_model_text_limits(text, file)) {
    sink.add(std::move(*limit));
    return std::nullopt;
  }
  Reader L(sink);
  toml::table root;
  try {
    root = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    L.error(e.source(), "", "TOML syntax: " + std::string(e.description()));
    return std::nullopt;
  }
  SourceModel p;
  read_tables(L, root, p);
  if (sink.failed()) return std::nullopt;
  return p;
}

}  // namespace ntn::modelc::compile
