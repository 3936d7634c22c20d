#include "ntn/modelc/emit_header.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string_view>

#include "ntn/laws/table.hpp"

namespace ntn::modelc {
namespace {

constexpr std::string_view kKeywords[] = {"alignas",       "alignof",     "and",
                                          "and_eq",        "asm",         "auto",
                                          "bitand",        "bitor",       "bool",
                                          "break",         "case",        "catch",
                                          "char",          "char8_t",     "char16_t",
                                          "char32_t",      "class",       "compl",
                                          "concept",       "const",       "consteval",
                                          "constexpr",     "constinit",   "const_cast",
                                          "continue",      "co_await",    "co_return",
                                          "co_yield",      "decltype",    "default",
                                          "delete",        "do",          "double",
                                          "dynamic_cast",  "else",        "enum",
                                          "explicit",      "export",      "extern",
                                          "false",         "float",       "for",
                                          "friend",        "goto",        "if",
                                          "inline",        "int",         "long",
                                          "mutable",       "namespace",   "new",
                                          "noexcept",      "not",         "not_eq",
                                          "nullptr",       "operator",    "or",
                                          "or_eq",         "private",     "protected",
                                          "public",        "register",    "reinterpret_cast",
                                          "requires",      "return",      "short",
                                          "signed",        "sizeof",      "static",
                                          "static_assert", "static_cast", "struct",
                                          "switch",        "template",    "this",
                                          "thread_local",  "throw",       "true",
                                          "try",           "typedef",     "typeid",
                                          "typename",      "union",       "unsigned",
                                          "using",         "virtual",     "void",
                                          "volatile",      "wchar_t",     "while",
                                          "xor",           "xor_eq"};

// A double literal that reads back to the same bits (%.17g) and is always a floating literal.
std::string lit(double v) {
  if (!std::isfinite(v)) throw std::invalid_argument("emit_header: non-finite number in model");
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  std::string s = buf;
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

std::string lit(int v) {
  return std::to_string(v);
}
std::string lit(std::size_t v) {
  return std::to_string(v);
}
// ", .geometry = ..." for an element whose geometry is not linear (a linear one keeps the
// default, so its header is what it was before the field existed).
std::string geometry_field(Geometry g) {
  switch (g) {
    case Geometry::kLinear:
      return "";
    case Geometry::kPDelta:
      return ", .geometry = ntn::Geometry::kPDelta";
    case Geometry::kLeaning:
      return ", .geometry = ntn::Geometry::kLeaning";
    case Geometry::kCorotational:
      return ", .geometry = ntn::Geometry::kCorotational";
  }
  return "";
}

std::string lit(bool v) {
  return v ? "true" : "false";
}

// Every string from the model file (or its path) reaches the header through str() or comment()
// only: nothing of it is ever written raw (a title with a newline once went raw into
// a // comment, and the next line of the title became C++).

// A C++ string literal (a std::string_view initializer); bytes outside printable ASCII as
// 3-digit octal escapes, which never take a following digit; '?' too, so that no trigraph can
// form. A string with a NUL byte becomes std::string_view{"...", N}: the plain literal would
// end at the NUL.
std::string str(std::string_view s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += ch;
    } else if (c >= 0x20 && c < 0x7F && c != '?') {  // '?' escaped: no trigraphs, ever
      out += ch;
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\%03o", static_cast<unsigned>(c));
      out += buf;
    }
  }
  out += '"';
  if (s.find('\0') != std::string_view::npos)
    out = "std::string_view{" + out + ", " + std::to_string(s.size()) + "}";
  return out;
}

// Text for a // comment: printable ASCII stays, every other byte and '%', '\\' and '?' become
// %XX (hex). So a comment never ends early (newline, CR, form feed...), never continues onto the
// next line (a backslash at its end splices the lines, even in a comment), and no trigraph (two
// question marks and a slash) can make a backslash. Lossless: %XX decodes back.
std::string comment(std::string_view s) {
  std::string out;
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c < 0x7F && c != '%' && c != '\\' && c != '?') {
      out += ch;
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "%%%02X", static_cast<unsigned>(c));
      out += buf;
    }
  }
  return out;
}

template <class T, std::size_t N>
std::string lits(const std::array<T, N>& a) {
  std::string s = "{{";
  for (std::size_t i = 0; i < N; ++i)
    s += (i ? ", " : "") + lit(a[i]);
  return s + "}}";
}

// {{ item, item, ... }} for a std::array of N items, or {} when N = 0.
template <class T, class F>
void array_init(std::string& out, const char* field, const std::vector<T>& items, F item) {
  out += "    .";
  out += field;
  if (items.empty()) {
    out += " = {},\n";
    return;
  }
  out += " = {{\n";
  for (const T& x : items) {
    out += "        ";
    out += item(x);
    out += ",\n";
  }
  out += "    }},\n";
}

std::string names(const std::vector<std::string>& v) {
  if (v.empty()) return "{}";
  std::string s = "{{";
  for (std::size_t i = 0; i < v.size(); ++i)
    s += (i ? ", " : "") + str(v[i]);
  return s + "}}";
}

std::string doubles(const std::vector<double>& v) {
  if (v.empty()) return "{}";
  std::string s = "{{";
  for (std::size_t i = 0; i < v.size(); ++i)
    s += (i ? ", " : "") + lit(v[i]);
  return s + "}}";
}

const char* input_kind(InputKind k) {
  switch (k) {
    case InputKind::kGroundAcceleration:
      return "ntn::InputKind::kGroundAcceleration";
    case InputKind::kNodalForce:
      return "ntn::InputKind::kNodalForce";
  }
  throw std::invalid_argument("emit_header: unknown input kind");
}

const char* output_kind(OutputKind k) {
  switch (k) {
    case OutputKind::kDisplacement:
      return "ntn::OutputKind::kDisplacement";
    case OutputKind::kVelocity:
      return "ntn::OutputKind::kVelocity";
    case OutputKind::kAcceleration:
      return "ntn::OutputKind::kAcceleration";
    case OutputKind::kElementForce:
      return "ntn::OutputKind::kElementForce";
    case OutputKind::kDrift:
      return "ntn::OutputKind::kDrift";
    case OutputKind::kReaction:
      return "ntn::OutputKind::kReaction";
    case OutputKind::kAbsoluteAcceleration:
      return "ntn::OutputKind::kAbsoluteAcceleration";
    case OutputKind::kHingeForce:
      return "ntn::OutputKind::kHingeForce";
    case OutputKind::kHingeDisplacement:
      return "ntn::OutputKind::kHingeDisplacement";
    case OutputKind::kHingePlastic:
      return "ntn::OutputKind::kHingePlastic";
    case OutputKind::kHingeDissipated:
      return "ntn::OutputKind::kHingeDissipated";
    case OutputKind::kHingeLevel:
      return "ntn::OutputKind::kHingeLevel";
    case OutputKind::kHingeVelocity:
      return "ntn::OutputKind::kHingeVelocity";
    case OutputKind::kHingeSlipState:
      return "ntn::OutputKind::kHingeSlipState";
  }
  throw std::invalid_argument("emit_header: unknown output kind");
}

const char* behaviour(HingeBehaviour b) {
  switch (b) {
    case HingeBehaviour::kRigid:
      return "ntn::HingeBehaviour::kRigid";
    case HingeBehaviour::kFree:
      return "ntn::HingeBehaviour::kFree";
    case HingeBehaviour::kLinear:
      return "ntn::HingeBehaviour::kLinear";
    case HingeBehaviour::kCurve:
      return "ntn::HingeBehaviour::kCurve";
    case HingeBehaviour::kPlastic:
      return "ntn::HingeBehaviour::kPlastic";
    case HingeBehaviour::kRigidPlastic:
      return "ntn::HingeBehaviour::kRigidPlastic";
  }
  throw std::invalid_argument("emit_header: unknown hinge behaviour");
}

const char* hinge_method(HingeMethod m) {
  switch (m) {
    case HingeMethod::kNtnExact:
      return "ntn::HingeMethod::kNtnExact";
    case HingeMethod::kNtnPaper:
      return "ntn::HingeMethod::kNtnPaper";
    case HingeMethod::kPenalty:
      return "ntn::HingeMethod::kPenalty";
  }
  throw std::invalid_argument("emit_header: unknown hinge method");
}

std::string hysteresis_rule(HysteresisRule r) {
  const std::string name = law_enum(r);  // the law table's (ntn/laws/table.hpp)
  if (name.empty()) throw std::invalid_argument("emit_header: unknown hysteresis rule");
  return "ntn::HysteresisRule::" + name;
}

const char* clamp_rule(ClampRule c) {
  switch (c) {
    case ClampRule::kMomentum:
      return "ntn::ClampRule::kMomentum";
    case ClampRule::kPaper:
      return "ntn::ClampRule::kPaper";
  }
  throw std::invalid_argument("emit_header: unknown clamp rule");
}

const char* damping_velocity(DampingVelocity v) {
  switch (v) {
    case DampingVelocity::kCentral:
      return "ntn::DampingVelocity::kCentral";
    case DampingVelocity::kLagged:
      return "ntn::DampingVelocity::kLagged";
  }
  throw std::invalid_argument("emit_header: unknown damping velocity");
}

std::string behaviours(const std::array<HingeBehaviour, kDofsPerNode>& a) {
  std::string s = "{{";
  for (std::size_t i = 0; i < a.size(); ++i)
    s += (i ? ", " : "") + std::string(behaviour(a[i]));
  return s + "}}";
}

}  // namespace

bool is_cpp_identifier(const std::string& s) {
  if (s.empty()) return false;
  const auto alpha = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
  };
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  if (!alpha(s[0])) return false;
  if (!std::all_of(s.begin(), s.end(), [&](char c) { return alpha(c) || digit(c); })) return false;
  // Reserved for the implementation: __x anywhere, _X at the start.
  if (s.find("__") != std::string::npos ||
      (s[0] == '_' && s.size() > 1 && s[1] >= 'A' && s[1] <= 'Z'))
    return false;
  return std::find(std::begin(kKeywords), std::end(kKeywords), s) == std::end(kKeywords);
}

std::string emit_header(const ModelDescription& m, const std::string& ns_name) {
  const std::string ns = ns_name.empty() ? m.name : ns_name;
  if (!is_cpp_identifier(ns)) {
    throw std::invalid_argument("emit_header: namespace name '" + ns + "' is not a C++ identifier");
  }
  const Sizes z = m.sizes();
  std::string o;
  o.reserve(400 * (m.elements.size() + m.nodes.size()) + 4096);
  o += "// Generated by ntn-modelc from " + comment(m.source_file) +
       ". Do not edit: change the model file.\n";
  o += "// Model '" + comment(m.name) + "'" + (m.title.empty() ? "" : ": " + comment(m.title)) +
       "\n";
  o += "#pragma once\n\n#include <array>\n#include <string_view>\n\n#include "
       "\"ntn/model_spec.hpp\"\n\n";
  o += "namespace ntn::models::" + ns + " {\n\n";
  o += "inline constexpr ntn::Sizes kSizes{.nodes = " + lit(z.nodes) +
       ", .elements = " + lit(z.elements) + ", .time_functions = " + lit(z.time_functions) +
       ", .time_points = " + lit(z.time_points) + ", .loads = " + lit(z.loads) +
       ", .inputs = " + lit(z.inputs) + ", .outputs = " + lit(z.outputs) +
       ", .hinges = " + lit(z.hinges) + ", .curves = " + lit(z.curves) +
       ", .curve_points = " + lit(z.curve_points) + ", .element_loads = " + lit(z.element_loads) +
       ", .hystereses = " + lit(z.hystereses) +
       (z.geometric == 0 ? "" : ", .geometric = " + lit(z.geometric)) +
       (z.corotational == 0 ? "" : ", .corotational = " + lit(z.corotational)) + "};\n\n";

  o += "inline constexpr ntn::ModelSpec<kSizes> kSpec{\n";
  array_init(o, "nodes", m.nodes, [](const NodeSpec& n) {
    return "{.x = " + lit(n.x) + ", .y = " + lit(n.y) + ", .z = " + lit(n.z) +
           ", .fixed = " + std::to_string(static_cast<unsigned>(n.fixed)) +
           ", .added = " + lits(n.added) +
           (n.u0 == std::array<double, kDofsPerNode>{} ? "" : ", .u0 = " + lits(n.u0)) +
           (n.v0 == std::array<double, kDofsPerNode>{} ? "" : ", .v0 = " + lits(n.v0)) + "}";
  });
  array_init(o, "elements", m.elements, [](const ElementSpec& e) {
    return "{.node_i = " + lit(e.node_i) + ", .node_j = " + lit(e.node_j) + ", .E = " + lit(e.E) +
           ", .G = " + lit(e.G) + ", .rho = " + lit(e.rho) + ", .A = " + lit(e.A) +
           ", .Iy = " + lit(e.Iy) + ", .Iz = " + lit(e.Iz) + ", .J = " + lit(e.J) +
           ", .shear_area_y = " + lit(e.shear_area_y) + ", .shear_area_z = " + lit(e.shear_area_z) +
           ", .ref_x = " + lit(e.ref_x) + ", .ref_y = " + lit(e.ref_y) +
           ", .ref_z = " + lit(e.ref_z) + ", .member = " + lit(e.member) +
           geometry_field(e.geometry) + "}";
  });
  array_init(o, "time_points", m.time_points, [](const TimePoint& p) {
    return "{.t = " + lit(p.t) + ", .value = " + lit(p.value) + "}";
  });
  array_init(o, "time_functions", m.time_functions, [](const TimeFunctionSpec& f) {
    return "{.first = " + lit(f.first) + ", .count = " + lit(f.count) + "}";
  });
  array_init(o, "loads", m.loads, [](const LoadSpec& l) {
    return "{.node = " + lit(l.node) + ", .dof = " + lit(l.dof) + ", .value = " + lit(l.value) +
           ", .time_function = " + lit(l.time_function) + "}";
  });
  array_init(o, "inputs", m.inputs, [](const InputSpec& i) {
    return "{.kind = " + std::string(input_kind(i.kind)) + ", .node = " + lit(i.node) +
           ", .dof = " + lit(i.dof) + ", .scale = " + lit(i.scale) + ", .min = " + lit(i.min) +
           ", .max = " + lit(i.max) + ", .factor = " + lit(i.factor) + "}";
  });
  array_init(o, "outputs", m.outputs, [](const OutputSpec& q) {
    return "{.kind = " + std::string(output_kind(q.kind)) + ", .node = " + lit(q.node) +
           ", .node2 = " + lit(q.node2) + ", .element = " + lit(q.element) +
           ", .end = " + lit(q.end) + ", .dof = " + lit(q.dof) + ", .scale = " + lit(q.scale) +
           ", .hinge = " + lit(q.hinge) + "}";
  });
  array_init(o, "hinges", m.hinges, [](const HingeSpec& h) {
    return "{.node1 = " + lit(h.node1) + ", .node2 = " + lit(h.node2) +
           ", .frame = " + lits(h.frame) + ", .eccentricity = " + lits(h.eccentricity) +
           ", .behaviour = " + behaviours(h.behaviour) + ", .stiffness = " + lits(h.stiffness) +
           ", .dashpot = " + lits(h.dashpot) + ", .curve = " + lits(h.curve) +
           ", .hysteresis = " + lits(h.hysteresis) + "}";
  });
  array_init(o, "curves", m.curves, [](const CurveSpec& c) {
    return "{.first = " + lit(c.first) + ", .count = " + lit(c.count) + "}";
  });
  array_init(o, "curve_points", m.curve_points, [](const CurvePoint& p) {
    return "{.d = " + lit(p.d) + ", .force = " + lit(p.force) + "}";
  });
  array_init(o, "element_loads", m.element_loads, [](const ElementLoadSpec& l) {
    return "{.element = " + lit(l.element) + ", .time_function = " + lit(l.time_function) +
           ", .local = " + lits(l.local) + "}";
  });
  array_init(o, "hystereses", m.hystereses, [](const HysteresisSpec& h) {
    std::string s = "{.yield_pos = " + lit(h.yield_pos) + ", .yield_neg = " + lit(h.yield_neg) +
                    ", .hardening = " + lit(h.hardening) + ", .limits = " + lits(h.limits);
    if (h.fixed_if != 0)
      return s + ", .normal = " + lit(h.normal) + ", .fixed_if = " + lit(h.fixed_if) + "}";
    if (h.normal >= 0)
      return s + ", .normal = " + lit(h.normal) + ", .mu = " + lit(h.mu) +
             ", .cohesion = " + lit(h.cohesion) + ", .circle = " + lit(h.circle) + "}";
    // The fields the law uses beyond the default law's: its rule, its envelope, its parameters.
    if (h.rule != HysteresisSpec{}.rule) s += ", .rule = " + hysteresis_rule(h.rule);
    const auto points = [](const std::array<CurvePoint, 4>& p) {
      std::string t = "{{";
      for (std::size_t i = 0; i < p.size(); ++i)
        t += (i ? ", " : "") + std::string("{.d = ") + lit(p[i].d) +
             ", .force = " + lit(p[i].force) + "}";
      return t + "}}";
    };
    if (law_has_envelope(h.rule))
      s += ",\n       .backbone_pos = " + points(h.backbone_pos) +
           ",\n       .backbone_neg = " + points(h.backbone_neg);
    if (h.parameters != LawParameters{}) s += ",\n       .parameters = " + lits(h.parameters);
    return s + "}";
  });
  const Settings& s = m.settings;
  o += "    .settings = {.dt = " + lit(s.dt) + ", .frame_period = " + lit(s.frame_period) +
       ", .alpha = " + lit(s.alpha) + ", .beta = " + lit(s.beta) +
       ", .damping_velocity = " + damping_velocity(s.damping_velocity) +
       ", .gravity = " + lits(s.gravity) + ", .gravity_function = " + lit(s.gravity_function) +
       ", .rotary_inertia = " + lit(s.rotary_inertia) +
       ", .allow_unstable = " + lit(s.allow_unstable) +
       ",\n                  .hinge_method = " + hinge_method(s.hinge_method) +
       ", .clamp = " + clamp_rule(s.clamp) + ", .penalty_stiffness = " + lit(s.penalty_stiffness) +
       ", .penalty_rotational_stiffness = " + lit(s.penalty_rotational_stiffness) +
       ", .limit_stiffness = " + lit(s.limit_stiffness) +
       ", .limit_rotational_stiffness = " + lit(s.limit_rotational_stiffness) + "},\n};\n\n";

  std::vector<std::string> member_names;
  for (const MemberInfo& mi : m.members)
    member_names.push_back(mi.name);
  o += "inline constexpr std::string_view kName = " + str(m.name) + ";\n";
  o += "inline constexpr std::string_view kTitle = " + str(m.title) + ";\n";
  o += "inline constexpr std::string_view kSourceFile = " + str(m.source_file) + ";\n";
  o += "inline constexpr bool kDtAuto = " + lit(m.dt_auto) + ";  // dt = \"auto\" in the file\n";
  o += "inline constexpr double kFrameRate = " + lit(m.frame_rate) + ";  // Hz\n";
  o += "inline constexpr std::array<std::string_view, kSizes.inputs> kInputNames" +
       names(m.input_names) + ";\n";
  o += "inline constexpr std::array<std::string_view, kSizes.outputs> kOutputNames" +
       names(m.output_names) + ";\n";
  o += "inline constexpr std::array<std::string_view, kSizes.outputs> kOutputUnits" +
       names(m.output_units) + ";\n";
  std::vector<double> limits, hysteresis;
  for (const OutputAlarm& a : m.output_alarms)
    limits.push_back(a.limit), hysteresis.push_back(a.hysteresis);
  o += "// Limit alarms per output ([[outputs]] alarm, alarm_hysteresis; channel units): on when\n"
       "// |value| > limit, off again when |value| < limit - hysteresis. Limit 0: no alarm.\n";
  o += "inline constexpr std::array<double, kSizes.outputs> kAlarmLimits" + doubles(limits) + ";\n";
  o += "inline constexpr std::array<double, kSizes.outputs> kAlarmHysteresis" +
       doubles(hysteresis) + ";\n";
  o += "inline constexpr std::array<std::string_view, " + std::to_string(member_names.size()) +
       "> kMemberNames" + names(member_names) + ";  // by ElementSpec::member\n";
  std::vector<std::string> hinge_names;
  for (const HingeInfo& h : m.hinge_info)
    hinge_names.push_back(h.name);
  o += "inline constexpr std::array<std::string_view, kSizes.hinges> kHingeNames" +
       names(hinge_names) + ";  // by hinge index\n";
  o += "// User node id per node; -1 for nodes made by meshing a member or at a released end.\n";
  o += "inline constexpr std::array<int, kSizes.nodes> kNodeIds{{";
  for (std::size_t i = 0; i < m.node_ids.size(); ++i) {
    o += (i ? (i % 20 == 0 ? ",\n    " : ", ") : "") + std::to_string(m.node_ids[i]);
  }
  o += "}};\n\n}  // namespace ntn::models::" + ns + "\n";
  return o;
}

}  // namespace ntn::modelc
