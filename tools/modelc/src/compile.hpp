// The compile stages: SourceModel (the reader's, read_model.hpp) -> ModelDescription. Each stage
// reads what the ones before it made from a Compilation and reports through its sink;
// compile_model (compile.cpp) runs them in order and stops after the first stage of the checks
// that found an error, since each check needs the results of the ones before it.
//
//   stage                  file                 makes / checks
//   start_description      compile.cpp          name, title, settings as given
//   resolve_ids            resolve_ids.cpp      id -> index maps, duplicates; time functions and
//                                               curves concatenated; gravity_function
//   collect_member_points  member_points.cpp    points inside members given for node ids
//                                               (supports, loads, masses, outputs), checked
//   mesh_members           mesh_members.cpp     nodes, elements (orientation, divisions, a node
//                                               at each member point), the nodes of member-end
//                                               releases
//   add_hinges             hinges_supports.cpp  explicit hinges and member-end releases
//   add_supports           hinges_supports.cpp  supports (with axes: hinges to the ground)
//   add_point_masses       hinges_supports.cpp  point masses on their nodes (on an offset: a
//                                               node and a rigid eccentric hinge)
//   hold_out_of_plane      plane.cpp            [model] plane: out-of-plane DOFs held
//   add_loads              loads.cpp            nodal loads
//   add_member_loads       member_loads.cpp     distributed member loads as consistent nodal
//                                               forces and moments
//   add_channels           channels.cpp         inputs and outputs (units, drift heights)
//   add_initial_values     initial_state.cpp    [[initial.nodes]] u_0, v_0; [initial] gravity
//   --- checks: a stage runs only when no error was found before it ---
//   check_rigid_cycles     check_topology.cpp   cycles of rigid hinge directions
//   check_element_numbers  check_numbers.cpp    what the kernel derives from each element
//   assemble_mass          check_numbers.cpp    lumped mass, finite and normal
//   check_nodes_have_mass  check_mass.cpp       free DOFs without mass, loose nodes
//   check_force_numbers    check_numbers.cpp    gravity and loads as forces
//   set_hinge_stiffness    hinge_stiffness.cpp  penalty and limit stiffness (given or default)
//   check_curve_branches   hinge_stiffness.cpp  curves' rigid branches only at the ends
//   check_kernel_accepts_hinges  hinge_stiffness.cpp  ntn::make_hinge_data takes every hinge
//   check_effective_mass   check_mass.cpp       massless springs (errors), mechanisms (notes)
//   check_hinge_spring_numbers   check_numbers.cpp    k / m and c / m of hinge springs
//   set_damping_from_modes damping.cpp          [model.damping] modes: alpha, beta from the
//                                               model's own modes (modal analysis)
//   choose_time_step       time_step.cpp        stable step, dt, the frame rule
//   static_preload         initial_state.cpp    gravity = "static": K u = P, u_0 += u
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "diagnostic_sink.hpp"
#include "ntn/modelc/model_description.hpp"
#include "source_model.hpp"

namespace ntn::modelc::compile {

// Index by id of each kind of thing the file names (resolve_ids).
struct Ids {
  std::map<std::string, int> materials, sections, members, functions, curves;
  std::map<std::string, int> hinge_ids;  // explicit hinge id -> its index in SourceModel::hinges
  // Hinge name -> its index in ModelDescription::hinges, set only when the hinge is added
  // (add_hinge), so that no name leads to a hinge that was not built; kRefusedHinge for a hinge
  // refused with an error (hinge_of).
  std::map<std::string, int> hinges;
  std::map<long long, int> nodes;  // user node id -> node index
};

inline constexpr int kRefusedHinge = -2;

// A hinge made by a member-end release, waiting for the hinges stage (which adds explicit
// hinges first).
struct PendingHinge {
  HingeSpec spec;
  HingeInfo info;
  const Behaviours* dirs = nullptr;  // nullptr: behaviours already set (supports)
  Where at;                          // the key that made the hinge
};

// A point inside a member (MemberPoint), checked by collect_member_points: the member (index in
// SourceModel::members) and the point as a fraction of its length.
struct PointAt {
  int member = -1;
  double t = 0;
};

// Two fractions of a member's length closer than this are the same point (a member point on a
// division point or an end reuses that node).
inline constexpr double kSamePoint = 1e-9;

struct Compilation {
  Compilation(DiagnosticSink& sink, const SourceModel& source) : L(sink), p(source) {}

  DiagnosticSink& L;
  const SourceModel& p;
  ModelDescription d;

  Ids ids;
  std::vector<PendingHinge> releases;                   // mesh_members -> add_hinges
  std::vector<Where> hinge_at;                          // per hinge: the key that made it
  std::vector<std::array<Where, kDofsPerNode>> dir_at;  // per hinge and direction
  std::vector<Where> load_at;  // per kernel load: the [[loads]] table that made it
  std::vector<double> mass;    // lumped mass per DOF (assemble_mass)
  // Member points: each valid one (collect_member_points -> mesh_members, node_of); per member
  // of the file, its index in d.members (-1: not meshed, an error was reported) and its nodes
  // along it, (fraction of the length, node index) from start (0) to end (1), the joints at
  // the ends (not the nodes of releases).
  std::map<const MemberPoint*, PointAt> points;
  std::vector<int> member_index;
  std::vector<std::vector<std::pair<double, int>>> member_nodes;

  // The index of user node `id`, or -1 after an "unknown node" error at `at`.
  int node_ref(long long id, const Where& at);
  // The node index of a node reference: a user node (node_ref) or a member point (the node
  // mesh_members put there); -1 after an error (a point's errors were reported when collected).
  int node_of(const NodeRef& r, const Where& at);
  // The index of `id` in `index`, or -1 after an "unknown WHAT 'id'" error at the id.
  int ref(const std::map<std::string, int>& index, const IdAt& id, const std::string& what);
  // The index in d.hinges of the hinge named `name`; -1 after an "unknown hinge" error at it,
  // and -1 without one for a hinge that was refused (its error is the model's).
  int hinge_of(const IdAt& name);
  // A hinge that would be named `name` was refused with an error: a name that refers to it
  // (hinge_of) adds none.
  void refuse_hinge(const std::string& name);
  // The place of node n's id in the file (generated nodes: none, reported at 1:1).
  Where node_at(int n) const;
};

// The whole compiler after the reader: the stages below in order; nullopt when any found an
// error.
std::optional<ModelDescription> compile_model(DiagnosticSink& sink, const SourceModel& p,
                                              const std::string& file);

void start_description(Compilation& comp, const std::string& file);
void resolve_ids(Compilation& comp);
void collect_member_points(Compilation& comp);
void mesh_members(Compilation& comp);
void add_hinges(Compilation& comp);
void add_supports(Compilation& comp);
void hold_leaning_rotations(Compilation& comp);
void check_corotational_hinges(Compilation& comp);
void add_point_masses(Compilation& comp);
void hold_out_of_plane(Compilation& comp);
void add_loads(Compilation& comp);
void add_member_loads(Compilation& comp);
void add_channels(Compilation& comp);
void add_initial_values(Compilation& comp);

void check_rigid_cycles(Compilation& comp);
void check_element_numbers(Compilation& comp);
void assemble_mass(Compilation& comp);
void check_nodes_have_mass(Compilation& comp);
void check_force_numbers(Compilation& comp);
void set_hinge_stiffness(Compilation& comp);
void check_curve_branches(Compilation& comp);
void check_kernel_accepts_hinges(Compilation& comp);
void check_effective_mass(Compilation& comp);
void check_hinge_spring_numbers(Compilation& comp);
void set_damping_from_modes(Compilation& comp);
void choose_time_step(Compilation& comp);
void static_preload(Compilation& comp);

}  // namespace ntn::modelc::compile
