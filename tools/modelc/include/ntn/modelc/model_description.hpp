// A validated model at run-time sizes: everything a ntn::ModelSpec holds, plus the names the
// model file gave (nodes, members, channels) so that tools can report in the user's terms.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "ntn/model_spec.hpp"
#include "ntn/time_step.hpp"

namespace ntn::modelc {

inline constexpr int kGeneratedNode = -1;  // node_ids entry of a node made by meshing a member

struct MemberInfo {
  std::string name;
  std::string material;
  std::string section;
  int first_element = 0;        // elements [first_element, first_element + element_count)
  int element_count = 0;        // divisions, plus one per member point between division points
  int start_node = 0;           // node index of the member's first end
  int end_node = 0;             // node index of the member's second end
  int first_interior_node = 0;  // generated nodes [first, first + count), start to end
  int interior_node_count = 0;  // = element_count - 1
  // Member-end releases: the node made at that end (after the interior nodes) and its hinge
  // (node 1 = that node, node 2 = start_node / end_node), or -1 without a release.
  int start_release_node = -1;
  int end_release_node = -1;
  int start_hinge = -1;
  int end_hinge = -1;
};

// A point inside a member that the file gave for a node ({ member, at } / { member, at_m }):
// where it is and the node it became (one entry per distinct point).
struct MemberPointInfo {
  int member = 0;      // index in members
  double at = 0;       // fraction of the length
  int node = 0;        // node index
  bool split = false;  // true: a new node split an element; false: an end or division point
};

// A distributed member load ([[member_loads]]) and the check of its consistent nodal loads.
struct MemberLoadInfo {
  int member = 0;                 // index in members
  std::array<double, 3> total{};  // N, the integral of q over the loaded part, global x, y, z
  std::array<double, 3> nodal{};  // N, the sum of the nodal forces it produced, global
  int first_load = 0;             // its nodal loads: loads [first_load, first_load + count)
  int load_count = 0;
};

// A limit alarm on an output channel ([[outputs]] alarm, alarm_hysteresis), in the channel's
// units: on when |value| > limit, off again when |value| < limit - hysteresis. limit 0: none.
struct OutputAlarm {
  double limit = 0;
  double hysteresis = 0;
};

// Where a hinge came from. Hinges are ordered: explicit [[hinges]] in file order, then
// member-end releases (member order, start before end), then supports with axes (file order),
// then point masses on an offset (file order: node 1 the node, node 2 the mass centre).
enum class HingeOrigin : std::uint8_t { kExplicit, kRelease, kSupport, kPointMass };

struct HingeInfo {
  // The id, "<member>.start" / "<member>.end", "support.<node id>" or "point mass at node <id>
  // (offset)" (" (offset 2)", ... for more than one on a node).
  std::string name;
  HingeOrigin origin = HingeOrigin::kExplicit;
  int member = -1;  // kRelease: member index
  int end = 0;      // kRelease: 0 start, 1 end
};

// DOFs with no effective mass and no stiffness (a mechanism, DESIGN §7.1): not an error; the
// kernel holds them at zero. Bits as NodeSpec::fixed, in global axes.
struct Mechanism {
  int node = 0;
  std::uint8_t dofs = 0;
};

struct ModelDescription {
  std::string name;  // C++ identifier
  std::string title;
  std::string source_file;  // as given to load_model

  std::vector<NodeSpec> nodes;
  std::vector<ElementSpec> elements;
  std::vector<TimePoint> time_points;
  std::vector<TimeFunctionSpec> time_functions;
  std::vector<LoadSpec> loads;
  std::vector<InputSpec> inputs;
  std::vector<OutputSpec> outputs;
  std::vector<HingeSpec> hinges;
  std::vector<CurveSpec> curves;
  std::vector<CurvePoint> curve_points;
  std::vector<ElementLoadSpec> element_loads;  // the member loads' parts, element by element
  std::vector<HysteresisSpec> hystereses;      // the plastic hinge directions' laws, by slot
  Settings settings;

  std::vector<int> node_ids;  // user id per node index, kGeneratedNode for mesh nodes
  std::vector<MemberInfo> members;
  std::vector<int> element_member;  // member index per element (= ElementSpec::member)
  std::vector<std::string> time_function_ids;
  std::vector<std::string> input_names;
  std::vector<std::string> output_names;
  std::vector<std::string> output_units;       // "m", "m/s", "m/s2", "rad", "N", "N m", "-", ...
  std::vector<OutputAlarm> output_alarms;      // per output
  std::vector<HingeInfo> hinge_info;           // per hinge
  std::vector<std::string> curve_ids;          // per curve
  std::vector<Mechanism> mechanisms;           // ascending node index
  std::vector<MemberPointInfo> member_points;  // member by member, start to end
  std::vector<MemberLoadInfo> member_loads;    // file order
  // Which hinge stiffnesses the file gave (false: the compiler's default, config/README.md).
  bool penalty_stiffness_given = false;
  bool penalty_rotational_stiffness_given = false;
  bool limit_stiffness_given = false;
  bool limit_rotational_stiffness_given = false;

  // [model] plane: "xz", "xy", "yz" (empty: a 3D model), the DOFs it holds on every node, and how
  // (config/README.md): support bits set, hinge directions made rigid.
  std::string plane;
  std::string plane_held_names;  // "uy, rx, rz", ...
  int plane_held_dofs = 0;
  int plane_rigid_directions = 0;

  bool dt_auto = true;           // dt = "auto" in the file
  double dt_requested = 0;       // s, the number given when !dt_auto
  double frame_rate = 1000;      // Hz; settings.frame_period = 1 / frame_rate
  double damping_ratio = 0;      // [model.damping] ratio as given (0 when alpha was given)
  double damping_frequency = 0;  // Hz, [model.damping] frequency as given (0 likewise)
  // Hz, the two frequencies of Rayleigh damping: `frequencies` as given, or the frequencies of
  // `modes` (damping_modes, 1-based) from the modal analysis; 0 otherwise.
  std::array<double, 2> damping_frequencies{};
  std::array<int, 2> damping_modes{};
  StableStepReport stable;  // the kernel's stable step report for this model (its method)

  // [initial] (NodeSpec::u0, v0 hold the result): the static preload under gravity and the
  // constant loads, and the nodes given initial values.
  struct Preload {
    bool on = false;                 // gravity = "static"
    int loads = 0;                   // constant nodal loads in it (besides gravity)
    double max_displacement = 0;     // m, the largest translation of the preload
    int max_node = -1;               // where
    int max_dof = 0;                 // and along which axis (0..2)
    double relative_residual = 0;    // of the static solve
    std::vector<std::string> notes;  // how curves were linearized, loads left out
  } preload;
  int initial_nodes = 0;  // [[initial.nodes]] given

  Sizes sizes() const;
  SpecView view() const;

  // "member C1, element 3 of 4 (model element 17)"; element is a model element index.
  std::string describe_element(int element) const;
  // "node 12" for a user node, "node 2 of member C1 (model node 40)" for a generated one.
  std::string describe_node(int node) const;
  // "hinge H1", "member-end release B1.start", "support with axes support.3".
  std::string describe_hinge(int hinge) const;
  // What sets a stable step `r` of this model: "hinge H1, direction ry (the spring with ...)",
  // "member C1, element 3 of 4 (model element 17)", or without elements the damping alpha, or
  // nothing.
  std::string describe_stable_step(const StableStepReport& r) const;
  // Counts of hinges by origin.
  int hinge_count(HingeOrigin origin) const;
};

}  // namespace ntn::modelc
