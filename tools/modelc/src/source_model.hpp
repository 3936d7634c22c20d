// The model as the file describes it, with the place of every value that a later check may
// point at: what the reader (read_model.cpp) makes of the TOML text and the compile stages
// (compile.cpp) turn into a ModelDescription. Values here are read and range-checked one by one;
// nothing is resolved (ids are text, nodes user ids) and nothing is derived.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "diagnostic_sink.hpp"
#include "ntn/model_spec.hpp"

namespace ntn::modelc::compile {

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

// A point inside a member, given where a node id is accepted: { member = "B1", at = 0.5 } (a
// fraction of the length) or { member = "B1", at_m = 2.0 } (metres from the member's start). The
// mesher puts a node there (mesh_members); Compilation::node_of resolves it.
struct MemberPoint {
  IdAt member;
  double at = 0;           // as given: a fraction, or metres when in_metres
  bool in_metres = false;  // at_m
  Where at_at;             // the at / at_m value
};

// A node reference: a user node id or a point inside a member.
struct NodeRef {
  long long id = 0;
  std::optional<MemberPoint> point;
  // "12", or "B1 at 0.5" / "B1 at 2 m" for messages.
  std::string text() const;
};

struct UserNode {
  long long id = 0;
  Where at;
  double x = 0, y = 0, z = 0;
};

// One local direction of a hinge or release as the file gives it.
struct BehaviourIn {
  HingeBehaviour kind = HingeBehaviour::kRigid;
  double k = 0, c = 0;        // kLinear, kPlastic
  std::optional<IdAt> curve;  // kCurve
  HysteresisSpec law;         // kPlastic, kRigidPlastic: its law (friction: mu, normal)
  Where at;                   // the value that set it (for curve errors)
  Where normal_at;            // friction, fixed_if: its `normal` / `control` key (or the value)
  int stop = 0;     // fixed_if on its own force: -1 (+1) a stop against d < 0 (d > 0) at d = 0
  Where circle_at;  // friction: its `circle` key
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
  std::optional<Geometry> geometry;  // `geometry`; the model's default when not given
  // A leaning column's segment ([[leaning_columns]]): its area, no section (Geometry::kLeaning).
  std::optional<double> leaning_area;
  // start, end; held apart (a Release is six behaviours, over 2 KB): a member without
  // releases, the common case, costs two pointers
  std::array<std::shared_ptr<const Release>, 2> release;
};

// The section of a leaning column's member: its area alone, where its table gives it.
inline Section leaning_section(const Member& m) {
  Section s;
  s.id = m.id;
  s.A = m.leaning_area.value_or(0);
  s.A_at = m.nodes_at;
  return s;
}

struct Support {
  NodeRef node;
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
  IdAt frame_member;      // kMember: frame = { member } or axes = { member, roll }
  double frame_roll = 0;  // kMember: degrees about the member's local x (axes = { member, roll })
  std::array<double, 9> axes{};
  bool eccentric = false;
  Where eccentric_at;
  Behaviours dirs;
};

struct PointMass {
  NodeRef node;
  Where at;
  double mass = 0;
  std::array<double, 3> inertia{};  // about the mass centre (the node, or node + offset)
  std::optional<std::array<double, 3>> offset;  // m, global: the mass centre is node + offset
  Where offset_at;
};

struct TimeFunction {
  IdAt id;
  std::vector<TimePoint> points;
};

struct Load {
  NodeRef node;
  Where at;
  std::vector<std::pair<int, double>> components;  // (dof, value)
  std::optional<IdAt> function;
};

// A distributed load on a member ([[member_loads]]): per unit length along the member (not
// projected), q_start at `from` to q_end at `to`, linear in between (uniform: q_start = q_end).
struct MemberLoad {
  IdAt member;
  Where at;  // the member key
  std::array<double, 3> q_start{}, q_end{};
  bool member_axes = false;  // axes = "member": the components are in the member's local x, y, z
  double from = 0, to = 1;   // fractions of the length, or metres when in_metres
  bool in_metres = false;    // from_m / to_m
  Where from_at, to_at;      // the from / from_m and to / to_m values (the table when not given)
  std::optional<IdAt> function;
};

struct Input {
  IdAt name;
  InputKind kind = InputKind::kGroundAcceleration;
  long long node = 0;
  Where node_at;
  int dof = 0;
  double scale = 1, min = -1e300, max = 1e300;
  double factor = 1;  // a ground acceleration's `scale` (InputSpec::factor)
};

enum class OutKind { kNode, kElementForce, kDrift, kReaction, kHinge };

struct Output {
  IdAt name;
  OutKind kind = OutKind::kNode;
  OutputKind node_kind = OutputKind::kDisplacement;
  std::vector<NodeRef> nodes;  // node kinds: 1; drift: 2
  Where nodes_at;
  int dof = 0;  // DOF, direction or component
  Where dof_at;
  IdAt member;
  int end = 0;
  IdAt hinge;                              // kHinge
  double alarm = 0, alarm_hysteresis = 0;  // limit alarm on |value| (0: none), channel units
};

// A planar model ([model] plane): the plane its motion stays in.
enum class Plane { kNone, kXz, kXy, kYz };

struct ModelTable {
  std::string name, title;
  Plane plane = Plane::kNone;
  Where plane_at;
  bool dt_auto = true;
  double dt = 0;
  Where dt_at;
  double frame_rate = 1000;
  Where frame_rate_at;
  bool rotary_inertia = false, allow_unstable = false;
  std::array<double, 3> gravity{};
  Where gravity_at;
  std::optional<IdAt> gravity_function;
  double alpha = 0, beta = 0;  // [model.damping]: C = alpha M + beta K_el
  double damping_ratio = 0, damping_frequency = 0;
  std::array<double, 2> damping_frequencies{};  // Hz, `frequencies` (0: not given)
  std::array<int, 2> damping_modes{};           // 1-based, `modes` (0: not given)
  Where damping_modes_at;
  HingeMethod hinge_method = HingeMethod::kNtnExact;
  ClampRule clamp = ClampRule::kMomentum;
  DampingVelocity damping_velocity = DampingVelocity::kCentral;  // alpha M's and the dashpots'
  std::optional<double> penalty_stiffness, penalty_rotational_stiffness;
  std::optional<double> limit_stiffness, limit_rotational_stiffness;
  Where hinge_method_at;
  Geometry geometry = Geometry::kLinear;  // every member's unless it says otherwise
};

// [[initial.nodes]]: a node's initial displacement and velocity (global axes, DOF order; a
// three-number array gives the translations).
struct InitialNode {
  NodeRef node;
  Where at;
  std::array<double, kDofsPerNode> u{}, v{};
};

// [initial]: how the run starts. gravity = "static": from the static equilibrium under gravity
// and the constant loads (the preload); "sudden" (default): undeformed, gravity from t = 0.
struct InitialTable {
  bool gravity_static = false;
  Where gravity_at;
  std::vector<InitialNode> nodes;
};

struct SourceModel {
  ModelTable model;
  std::vector<Material> materials;
  std::vector<Section> sections;
  std::vector<UserNode> nodes;
  std::vector<Member> members;
  std::vector<Support> supports;
  std::vector<PointMass> point_masses;
  std::vector<TimeFunction> time_functions;
  std::vector<Load> loads;
  std::vector<MemberLoad> member_loads;
  std::vector<Input> inputs;
  std::vector<Output> outputs;
  std::vector<Curve> curves;
  std::vector<HingeIn> hinges;
  InitialTable initial;
};

}  // namespace ntn::modelc::compile
