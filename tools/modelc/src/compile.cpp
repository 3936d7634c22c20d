// build(): the compile stages in order (compile.hpp lists them, what each makes and checks, and
// its file). The stages up to the channels each report every problem they find and go on with
// what is left; the checks after them run only while no error has been found, since each needs
// the results of the ones before it.
#include "compile.hpp"

#include <algorithm>
#include <utility>

#include "messages.hpp"

namespace ntn::modelc::compile {

// What the [model] table gives as it is.
void start_description(Compilation& comp, const std::string& file) {
  const SourceModel& p = comp.p;
  ModelDescription& d = comp.d;
  d.name = p.model.name;
  d.title = p.model.title;
  d.source_file = file;
  d.frame_rate = p.model.frame_rate;
  d.dt_auto = p.model.dt_auto;
  d.dt_requested = p.model.dt;
  d.damping_ratio = p.model.damping_ratio;
  d.damping_frequency = p.model.damping_frequency;
  d.damping_frequencies = p.model.damping_frequencies;
  d.damping_modes = p.model.damping_modes;
  Settings& s = d.settings;
  s.frame_period = 1.0 / p.model.frame_rate;
  s.alpha = p.model.alpha;
  s.beta = p.model.beta;
  s.damping_velocity = p.model.damping_velocity;
  s.gravity = p.model.gravity;
  s.rotary_inertia = p.model.rotary_inertia;
  s.allow_unstable = p.model.allow_unstable;
  s.hinge_method = p.model.hinge_method;
  s.clamp = p.model.clamp;
  d.penalty_stiffness_given = p.model.penalty_stiffness.has_value();
  d.penalty_rotational_stiffness_given = p.model.penalty_rotational_stiffness.has_value();
  d.limit_stiffness_given = p.model.limit_stiffness.has_value();
  d.limit_rotational_stiffness_given = p.model.limit_rotational_stiffness.has_value();
}

int Compilation::node_ref(long long id, const Where& at) {
  const auto it = ids.nodes.find(id);
  if (it != ids.nodes.end()) return it->second;
  L.error(at, "unknown node " + std::to_string(id));
  return -1;
}

int Compilation::node_of(const NodeRef& r, const Where& at) {
  if (!r.point) return node_ref(r.id, at);
  const auto it = points.find(&*r.point);
  if (it == points.end()) return -1;
  const auto mi = static_cast<std::size_t>(it->second.member);
  if (mi >= member_nodes.size()) return -1;
  const auto& along = member_nodes[mi];  // ascending t
  const auto at_or_after =
      std::lower_bound(along.begin(), along.end(), it->second.t - kSamePoint,
                       [](const std::pair<double, int>& tn, double t) { return tn.first < t; });
  if (at_or_after != along.end() && at_or_after->first <= it->second.t + kSamePoint)
    return at_or_after->second;
  return -1;  // the member was not meshed (its error was reported)
}

std::string NodeRef::text() const {
  if (!point) return std::to_string(id);
  return point->member.id + "@" + num(point->at) + (point->in_metres ? "m" : "");
}

int Compilation::ref(const std::map<std::string, int>& index, const IdAt& id,
                     const std::string& what) {
  const auto it = index.find(id.id);
  if (it != index.end()) return it->second;
  L.error(id.at, "unknown " + what + " '" + id.id + "'");
  return -1;
}

int Compilation::hinge_of(const IdAt& name) {
  const auto it = ids.hinges.find(name.id);
  if (it != ids.hinges.end()) return it->second >= 0 ? it->second : -1;
  L.error(name.at, "unknown hinge '" + name.id +
                       "' (hinges are named by their id, <member>.start and <member>.end for "
                       "releases, support.<node id> for supports with axes)");
  return -1;
}

void Compilation::refuse_hinge(const std::string& name) {
  ids.hinges.emplace(name, kRefusedHinge);
}

Where Compilation::node_at(int n) const {
  const auto i = static_cast<std::size_t>(n);
  if (i < p.nodes.size()) return p.nodes[i].at;
  return {};
}

std::optional<ModelDescription> compile_model(DiagnosticSink& sink, const SourceModel& p,
                                              const std::string& file) {
  Compilation comp(sink, p);
  // Pass 2: references, meshing, geometry; every problem reported.
  start_description(comp, file);
  resolve_ids(comp);
  collect_member_points(comp);
  mesh_members(comp);
  add_hinges(comp);
  add_supports(comp);
  hold_leaning_rotations(comp);
  add_point_masses(comp);
  check_corotational_hinges(comp);
  hold_out_of_plane(comp);
  add_loads(comp);
  add_member_loads(comp);
  add_channels(comp);
  add_initial_values(comp);
  if (sink.failed()) return std::nullopt;

  // Pass 3: rigid cycles (topology only), then mass from the kernel's lumped mass, curves
  // against the limit stiffness, effective mass, the static preload (before the damping: Rayleigh
  // damping from modes takes them about the preload, as modal analysis does), and the time step;
  // each check needs the ones before it.
  using Stage = void (*)(Compilation&);
  for (const Stage stage :
       {check_rigid_cycles, check_element_numbers, assemble_mass, check_nodes_have_mass,
        check_force_numbers, set_hinge_stiffness, check_curve_branches, check_kernel_accepts_hinges,
        check_effective_mass, check_hinge_spring_numbers, static_preload, set_damping_from_modes,
        choose_time_step}) {
    stage(comp);
    if (sink.failed()) return std::nullopt;
  }
  return std::move(comp.d);
}

}  // namespace ntn::modelc::compile
