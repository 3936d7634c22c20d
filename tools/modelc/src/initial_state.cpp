// The run's initial state (config/README.md "[initial]"): stage add_initial_values writes the
// [[initial.nodes]] displacements and velocities into NodeSpec::u0, v0 and checks that
// gravity = "static" has a constant gravity; stage static_preload, the last check, solves the
// kernel's own K once for gravity and the constant nodal loads (ntn::modal::static_solution) and
// adds that displacement to u0: the run starts in static equilibrium, at rest.
#include <cmath>

#include "compile.hpp"
#include "messages.hpp"
#include "ntn/loads.hpp"
#include "ntn/modal/modal.hpp"

namespace ntn::modelc::compile {

void add_initial_values(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const SourceModel& p = comp.p;
  ModelDescription& d = comp.d;
  d.preload.on = p.initial.gravity_static;
  if (p.initial.gravity_static && p.model.gravity_function) {
    L.error(p.initial.gravity_at,
            "gravity = \"static\" holds gravity constant from the static preload on, but "
            "model.gravity_function '" +
                p.model.gravity_function->id +
                "' varies it: remove gravity_function, or use gravity = \"sudden\"");
  }
  for (const InitialNode& in : p.initial.nodes) {
    const int n = comp.node_of(in.node, in.at);
    if (n < 0) continue;
    NodeSpec& ns = d.nodes[static_cast<std::size_t>(n)];
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      if (((ns.fixed >> k) & 1U) && (in.u[k] != 0.0 || in.v[k] != 0.0)) {
        L.error(in.at, "node " + in.node.text() + ": " + std::string(kDofNames[k]) +
                           " is held by a support, so its initial displacement and velocity "
                           "are 0 (got u = " +
                           num(in.u[k]) + ", v = " + num(in.v[k]) + ")");
      }
      ns.u0[k] += in.u[k];
      ns.v0[k] += in.v[k];
    }
    ++d.initial_nodes;
  }
}

void static_preload(Compilation& comp) {
  ModelDescription& d = comp.d;
  if (!d.preload.on) return;
  const Settings& s = d.settings;
  // P as the kernel's step forms it at t = 0 (integrator.hpp apply_loads): M g on translations
  // with the lumped mass, plus the nodal loads without a time function. Loads with one start at
  // their value at t = 0, applied suddenly (said in a note when it is not zero).
  std::vector<double> P(comp.mass.size(), 0.0);
  for (std::size_t j = 0; j < P.size(); ++j) {
    const std::size_t k = j % kDofsPerNode;
    if (k < 3) P[j] = comp.mass[j] * s.gravity[k];
  }
  d.preload.loads = 0;
  int sudden = 0;
  for (const LoadSpec& l : d.loads) {
    if (l.time_function == kConstant) {
      P[static_cast<std::size_t>(kDofsPerNode * l.node + l.dof)] += l.value;
      ++d.preload.loads;
    } else if (load_factor(d.time_points, d.time_functions, l.time_function, 0.0) != 0.0) {
      ++sudden;
    }
  }
  if (sudden > 0) {
    d.preload.notes.push_back(std::to_string(sudden) +
                              " load(s) with a time function not zero at t = 0 are not in the "
                              "preload: they act suddenly at t = 0");
  }
  const modal::StaticResult r = modal::static_solution(d.view(), P);
  if (!r.ok()) {
    comp.L.error(comp.p.initial.gravity_at,
                 "gravity = \"static\": no static equilibrium under gravity and the constant "
                 "loads: " +
                     r.error);
    return;
  }
  for (const std::string& note : r.notes)
    d.preload.notes.push_back(note);
  d.preload.relative_residual = r.relative_residual;
  for (std::size_t n = 0; n < d.nodes.size(); ++n) {
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      const double u = r.u[kDofsPerNode * n + k];
      d.nodes[n].u0[k] += u;
      if (k < 3 && std::abs(u) > d.preload.max_displacement) {
        d.preload.max_displacement = std::abs(u);
        d.preload.max_node = static_cast<int>(n);
        d.preload.max_dof = static_cast<int>(k);
      }
    }
  }
}

}  // namespace ntn::modelc::compile
