// The reader's tables of the I/O channels: inputs and outputs (read_tables.hpp).
#include "read_tables.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "record.hpp"  // tools/io: the rule of a scale factor

namespace ntn::modelc::compile {
namespace {

constexpr double kStandardGravity = 9.80665;  // m/s^2 per g (CGPM 1901)

const std::vector<std::string_view> kDirections3 = {"x", "y", "z"};
const std::vector<std::string_view> kReactionDirections = {"x", "y", "z", "rx", "ry", "rz"};
const std::vector<std::string_view> kComponents = {"N", "Vy", "Vz", "T", "My", "Mz"};

}  // namespace

// One [[inputs]] table: a ground acceleration (direction, units) or a nodal force (node,
// dof), its scale and accepted range.
void read_input(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p) {
  Input in;
  const std::vector<std::string_view> kinds = {"ground_acceleration", "nodal_force"};
  Table head(L, tt, path, {});
  auto name = read_id(L, head, "name");
  auto kind = head.choice("kind", Need::kRequired, kinds);
  if (!kind) return;
  const bool ground = *kind == 0;
  Table t(
      L, tt, path,
      ground ? std::vector<std::string_view>{"name", "kind", "direction", "units", "scale", "min",
                                             "max"}
             : std::vector<std::string_view>{"name", "kind", "node", "dof", "scale", "min", "max"});
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
}

// One [[outputs]] table: the kind and what it names (node, member end, drift nodes, hinge
// direction or reaction), and its limit alarm.
void read_output(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p) {
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
}

}  // namespace ntn::modelc::compile
