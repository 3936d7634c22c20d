// The model as the file describes it, with the place of every value that a later check may
// point at: what the reader (read_model.cpp) makes of the TOML text and the compile stages
// (compile.cpp) turn into a ModelDescription. Values here are read and range-checked one by one;
// nothing is resolved (ids are text, nodes user ids) and nothing is derived.
#pragma once

#include <array>
#include <cstdint>
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
  double alpha = 0, beta = 0;  // [model.damping]: C = alpha M + beta K_el
  double damping_ratio = 0, damping_frequency = 0;
  std::array<double, 2> damping_frequencies{};  // Hz, `frequencies` (0: not given)
  std::array<int, 2> damping_modes{};           // 1-based, `modes` (0: not given)
  Where damping_modes_at;
  HingeMethod hinge_method = HingeMethod::kNtnExact;
  ClampRule clamp = ClampRule::kMomentum;
  std::optional<double> penalty_stiffness, penalty_rotational_stiffness;
  std::optional<double> limit_stiffness, limit_rotational_stiffness;
  Where hinge_method_at;
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
  std::vector<Input> inputs;
  std::vector<Output> outputs;
  std::vector<Curve> curves;
  std::vector<HingeIn> hinges;
};

}  // namespace ntn::modelc::compile
