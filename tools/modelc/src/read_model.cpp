// The reader: model text -> SourceModel (pass 1 of the compiler). The size and nesting limits
// first (limits.cpp: toml++'s recursion must never see input that overflows it), then toml++,
// then every table: keys, types and values (unknown and missing keys, ranges, conflicts, hinge
// axes, curve and time-function points increasing). Each value is checked on its own here;
// references and everything derived are the compile stages' (compile.cpp).
#include "read_model.hpp"

#include <toml++/toml.h>
#include <numbers>

#include "damping.hpp"
#include "ntn/modelc/emit_header.hpp"
#include "ntn/modelc/limits.hpp"
#include "ntn/time_step.hpp"
#include "read_hinge_parts.hpp"
#include "record.hpp"  // tools/io: the rule of a scale factor
#include "roll.hpp"
#include "toml_reader.hpp"

namespace ntn::modelc::compile {
namespace {

constexpr double kStandardGravity = 9.80665;  // m/s^2 per g (CGPM 1901)

std::string roll_message(double deg) {
  return "must be within [-" + num(kMaxRollDegrees) + ", " + num(kMaxRollDegrees) +
         "] degrees, one turn either way (got " + num(deg) + ")";
}
constexpr long long kMaxDivisions = 1000000;

const std::vector<std::string_view> kDirections3 = {"x", "y", "z"};
const std::vector<std::string_view> kReactionDirections = {"x", "y", "z", "rx", "ry", "rz"};
const std::vector<std::string_view> kComponents = {"N", "Vy", "Vz", "T", "My", "Mz"};
const std::vector<std::string_view> kHingeMethods = {"ntn_exact", "ntn_paper", "penalty"};
const std::vector<std::string_view> kClampRules = {"momentum", "paper"};
const std::vector<std::string_view> kDampingVelocities = {"central", "lagged"};
const std::vector<std::string_view> kPlanes = {"xz", "xy", "yz"};

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
           "limit_rotational_stiffness", "plane"});
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
  if (auto pl = t.choice("plane", Need::kOptional, kPlanes)) m.plane = static_cast<Plane>(*pl + 1);
  m.plane_at = t.where("plane");
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

// One [[member_loads]] table: the member, q or q_start + q_end, axes, the part (from / to or
// from_m / to_m) and the time function. Ranges in metres need the member's length: checked by
// add_member_loads.
void read_member_load(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p) {
  Table t(L, tt, path,
          {"member", "q", "q_start", "q_end", "axes", "from", "to", "from_m", "to_m", "function"});
  t.check_unknown();
  MemberLoad ml;
  auto member = read_id(L, t, "member");
  bool ok = member.has_value();
  if (t.conflict("q", "q_start") || t.conflict("q", "q_end")) return;
  if (t.has("q")) {
    auto q = t.numbers("q", Need::kRequired, 3);
    if (q) ml.q_start = ml.q_end = {(*q)[0], (*q)[1], (*q)[2]};
    ok = ok && q;
  } else if (t.has("q_start") || t.has("q_end")) {
    const std::string hint = " (a linearly varying load needs both q_start and q_end)";
    std::optional<std::vector<double>> qs, qe;
    for (const std::string_view k : {"q_start", "q_end"}) {
      auto& q = k == "q_start" ? qs : qe;
      if (t.has(k)) {
        q = t.numbers(k, Need::kRequired, 3);
      } else {
        t.get(k, Need::kRequired, hint);
      }
    }
    if (qs) ml.q_start = {(*qs)[0], (*qs)[1], (*qs)[2]};
    if (qe) ml.q_end = {(*qe)[0], (*qe)[1], (*qe)[2]};
    ok = ok && qs && qe;
  } else {
    t.get("q", Need::kRequired, " (or q_start and q_end for a linearly varying load)");
    ok = false;
  }
  if (auto ax = t.choice("axes", Need::kOptional, {"global", "member"})) {
    ml.member_axes = *ax == 1;
  } else if (t.has("axes")) {
    ok = false;
  }
  // Fractions or metres, not both.
  for (const std::string_view f : {"from", "to"}) {
    for (const std::string_view m : {"from_m", "to_m"}) {
      if (t.conflict(f, m)) return;
    }
  }
  ml.in_metres = t.has("from_m") || t.has("to_m");
  const std::string_view kf = ml.in_metres ? "from_m" : "from";
  const std::string_view kt = ml.in_metres ? "to_m" : "to";
  ml.from_at = t.where(kf), ml.to_at = t.where(kt);
  const auto from = t.number(kf, Need::kOptional);
  const auto to = t.number(kt, Need::kOptional);
  ok = ok && (from || !t.has(kf)) && (to || !t.has(kt));
  if (from) ml.from = *from;
  if (to) ml.to = *to;
  if (ml.in_metres && !to) ml.to = -1;  // the member's end: set by add_member_loads
  if (from && !(ml.in_metres ? *from >= 0 : *from >= 0 && *from <= 1)) {
    L.error(ml.from_at, ml.in_metres
                            ? "must be between 0 and the member's length (got " + num(*from) + " m)"
                            : "must be between 0 and 1 (a fraction of the member's "
                              "length; got " +
                                  num(*from) + ")");
    ok = false;
  } else if (to && !(ml.in_metres ? *to >= 0 : *to >= 0 && *to <= 1)) {
    L.error(ml.to_at, ml.in_metres
                          ? "must be between 0 and the member's length (got " + num(*to) + " m)"
                          : "must be between 0 and 1 (a fraction of the member's "
                            "length; got " +
                                num(*to) + ")");
    ok = false;
  } else if (ok && (to || !ml.in_metres) && !(ml.from < ml.to)) {
    L.error(t.has(kt) ? ml.to_at : ml.from_at, std::string(kf) + " = " + num(ml.from) +
                                                   " must be less than " + std::string(kt) + " = " +
                                                   num(ml.to) + "");
    ok = false;
  }
  if (t.has("function")) {
    ml.function = read_id(L, t, "function");
    ok = ok && ml.function;
  }
  if (!ok) return;
  ml.member = *member;
  ml.at = t.where("member");
  p.member_loads.push_back(ml);
}

void read_tables(Reader& L, const toml::table& root, SourceModel& p) {
  {
    Table top(L, root, "",
              {"model", "materials", "sections", "nodes", "members", "supports", "point_masses",
               "time_functions", "loads", "member_loads", "inputs", "outputs", "curves", "hinges",
               "initial"});
    top.check_unknown();
  }
  read_model_table(L, root, p.model);

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
        if (auto release = read_release(L, *r, t.key(k)))
          m.release[e] = std::make_shared<const Release>(std::move(*release));
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
        if (r && !roll_in_range(*r)) {
          L.error(t.where("roll"), roll_message(*r));
          r.reset();
        }
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
    auto node = read_node_ref(L, t, "node", Need::kRequired);
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
    Table t(L, tt, path, {"node", "mass", "inertia", "offset"});
    t.check_unknown();
    auto node = read_node_ref(L, t, "node", Need::kRequired);
    auto mass = t.non_negative("mass", Need::kRequired);
    auto inertia = t.numbers("inertia", Need::kOptional, 3, true);
    auto offset = t.numbers("offset", Need::kOptional, 3);
    if (!node || !mass || (!inertia && t.has("inertia")) || (!offset && t.has("offset"))) return;
    PointMass pm{*node, t.where("node"), *mass, {}, std::nullopt, t.where("offset")};
    if (inertia) pm.inertia = {(*inertia)[0], (*inertia)[1], (*inertia)[2]};
    if (offset) pm.offset = std::array<double, 3>{(*offset)[0], (*offset)[1], (*offset)[2]};
    p.point_masses.push_back(pm);
  });

  for_each_table(L, root, "time_functions", [&](const toml::table& tt, const std::string& path) {
    Table t(L, tt, path, {"id", "points"});
    t.check_unknown();
    auto id = read_id(L, t, "id");
    const auto points =
        read_points(L, t, 1, "[t, value] points (at least one)", "t", " s", "times");
    if (!id || !points) return;
    TimeFunction f;
    for (const auto& [time, value] : *points)
      f.points.push_back({time, value});
    f.id = *id;
    p.time_functions.push_back(f);
  });

  for_each_table(L, root, "loads", [&](const toml::table& tt, const std::string& path) {
    Table t(L, tt, path, {"node", "dof", "value", "force", "function"});
    t.check_unknown();
    Load l;
    auto node = read_node_ref(L, t, "node", Need::kRequired);
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

  for_each_table(L, root, "member_loads", [&](const toml::table& tt, const std::string& path) {
    read_member_load(L, tt, path, p);
  });

  for_each_table(L, root, "inputs", [&](const toml::table& tt, const std::string& path) {
    Input in;
    const std::vector<std::string_view> kinds = {"ground_acceleration", "nodal_force"};
    Table head(L, tt, path, {});
    auto name = read_id(L, head, "name");
    auto kind = head.choice("kind", Need::kRequired, kinds);
    if (!kind) return;
    const bool ground = *kind == 0;
    Table t(L, tt, path,
            ground ? std::vector<std::string_view>{"name", "kind", "direction", "units", "scale",
                                                   "min", "max"}
                   : std::vector<std::string_view>{"name", "kind", "node", "dof", "scale", "min",
                                                   "max"});
    t.check_unknown();
    bool ok = name.has_value();
    if (ground) {
      in.kind = InputKind::kGroundAcceleration;
      auto dir = t.choice("direction", Need::kRequired, kDirections3);
      auto units = t.choice("units", Need::kOptional, {"m/s2", "g"});
      // `scale` multiplies the motion (InputSpec::factor): the raw values, their unit and range
      // stay those of the channel.
      auto factor = t.number("scale", Need::kOptional);
      if (factor && !io::scale_factor_valid(*factor)) {
        L.error(t.where("scale"),
                std::string("must be ") + io::kScaleFactorRule + " (got " + num(*factor) + ")");
        factor.reset();
      }
      if (dir) in.dof = *dir;
      in.scale = units.value_or(0) == 1 ? kStandardGravity : 1.0;
      if (factor) in.factor = *factor;
      ok = ok && dir && (units || !t.has("units")) && (factor || !t.has("scale"));
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
    const std::vector<std::string_view> kinds = {"displacement",
                                                 "velocity",
                                                 "acceleration",
                                                 "element_force",
                                                 "drift",
                                                 "reaction",
                                                 "absolute_acceleration",
                                                 "hinge_force",
                                                 "hinge_displacement",
                                                 "hinge_plastic_deformation",
                                                 "hinge_dissipated_energy",
                                                 "hinge_performance_level",
                                                 "hinge_velocity",
                                                 "hinge_slip_state"};
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
      auto node = read_node_ref(L, t, "node", Need::kRequired);
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
      std::optional<std::vector<NodeRef>> nodes;
      if (const toml::node* nn = t.get("nodes", Need::kRequired)) {
        nodes = L.array_of<NodeRef>(
            *nn, t.key("nodes"), 2,
            [&L](const toml::node& e, const std::string& ek) { return read_node_ref(L, e, ek); });
      }
      auto dir = t.choice("direction", Need::kRequired, {"x", "y"});
      if (nodes) o.nodes = *nodes, o.nodes_at = t.where("nodes");
      if (dir) o.dof = *dir;
      ok = ok && nodes && dir;
    } else if (*kind >= 7) {
      Table t(L, tt, path, {"name", "kind", "hinge", "direction", "alarm", "alarm_hysteresis"});
      t.check_unknown();
      o.kind = OutKind::kHinge;
      o.node_kind = *kind == 7    ? OutputKind::kHingeForce
                    : *kind == 8  ? OutputKind::kHingeDisplacement
                    : *kind == 9  ? OutputKind::kHingePlastic
                    : *kind == 10 ? OutputKind::kHingeDissipated
                    : *kind == 11 ? OutputKind::kHingeLevel
                    : *kind == 12 ? OutputKind::kHingeVelocity
                                  : OutputKind::kHingeSlipState;
      auto hinge = read_id(L, t, "hinge");
      auto dir = t.choice("direction", Need::kRequired, kDofNames);
      if (hinge) o.hinge = *hinge;
      if (dir) o.dof = *dir, o.dof_at = t.where("direction");
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
    const auto points =
        read_points(L, t, 2, "at least 2 [d, force] points", "d", "", "deformations");
    if (!id || !points) return;
    Curve c;
    for (const auto& [d, force] : *points)
      c.points.push_back({d, force});
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
      if (const auto* at = ax->as_table()) {
        // axes = { member = "id", roll = degrees }: the member's local axes turned by roll.
        const std::string akey = t.key("axes");
        Table fr(L, *at, akey, {"member", "roll"});
        fr.check_unknown();
        auto m = read_id(L, fr, "member");
        const toml::node* r = fr.get("roll", Need::kRequired,
                                     " (degrees about the member's local x; without a roll, "
                                     "give frame = { member = \"id\" })");
        auto roll = r != nullptr ? L.number(*r, fr.key("roll")) : std::nullopt;
        if (roll && !roll_in_range(*roll)) {
          L.error(fr.where("roll"), roll_message(*roll));
          roll.reset();
        }
        if (m && roll) {
          h.frame = FrameKind::kMember;
          h.frame_member = *m;
          h.frame_roll = *roll;
        }
        ok = ok && m && roll;
      } else if (!ax->is_array()) {
        L.error(ax->source(), t.key("axes"),
                "must be rows [[x], [y], [z]] or { member = \"id\", roll = degrees }, got " +
                    type_name(*ax));
        ok = false;
      } else {
        auto R = read_axes(L, *ax, t.key("axes"));
        if (R) {
          h.frame = FrameKind::kAxes;
          h.axes = *R;
        }
        ok = ok && R;
      }
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
