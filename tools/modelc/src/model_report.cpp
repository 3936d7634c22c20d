#include "ntn/modelc/model_report.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "ntn/beam.hpp"
#include "ntn/model.hpp"
#include "ntn/modelc/model_bytes.hpp"

namespace ntn::modelc {
namespace {

std::string f(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

std::string bytes(std::size_t b) {
  std::string s = std::to_string(b) + " B";
  if (b >= 1024 * 1024) {
    s += " (" + f("%.2f", static_cast<double>(b) / (1024.0 * 1024.0)) + " MiB)";
  } else if (b >= 1024) {
    s += " (" + f("%.1f", static_cast<double>(b) / 1024.0) + " KiB)";
  }
  return s;
}

}  // namespace

MassTotals mass_totals(const ModelDescription& m) {
  MassTotals t;
  std::vector<double> mass(static_cast<std::size_t>(kDofsPerNode) * m.nodes.size());
  assemble_lumped_mass(m.view(), mass);
  for (std::size_t n = 0; n < m.nodes.size(); ++n) {
    for (std::size_t d = 0; d < kDofsPerNode; ++d) {
      const double v = mass[n * kDofsPerNode + d];
      t.all[d] += v;
      if (((m.nodes[n].fixed >> d) & 1U) == 0) {
        t.free[d] += v;
        ++t.free_dofs;
      }
    }
    t.point_masses += m.nodes[n].added[0];
  }
  for (const ElementSpec& e : m.elements) {
    const BeamGeometry g = beam_geometry(m.nodes[static_cast<std::size_t>(e.node_i)],
                                         m.nodes[static_cast<std::size_t>(e.node_j)], e);
    t.elements += e.rho * e.A * g.length;
  }
  return t;
}

std::string info_text(const ModelDescription& m) {
  const Sizes z = m.sizes();
  const MassTotals mt = mass_totals(m);
  const Settings& s = m.settings;
  std::string o;
  auto line = [&o](const char* head, const std::string& text) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%-13s", head);
    o += buf + text + "\n";
  };

  int given = 0;
  for (int id : m.node_ids)
    given += id != kGeneratedNode ? 1 : 0;
  line("model", m.name + (m.title.empty() ? "" : ": " + m.title));
  line("file", m.source_file);
  line("nodes", std::to_string(z.nodes) + " (" + std::to_string(given) + " given, " +
                    std::to_string(z.nodes - given) + " from meshing members)");
  line("elements",
       std::to_string(z.elements) + " in " + std::to_string(m.members.size()) + " members");
  line("DOFs", std::to_string(kDofsPerNode * z.nodes) + " (" + std::to_string(mt.free_dofs) +
                   " free, " + std::to_string(kDofsPerNode * z.nodes - mt.free_dofs) +
                   " supported)");
  line("loads", std::to_string(z.loads) + " nodal loads, " + std::to_string(z.time_functions) +
                    " time functions (" + std::to_string(z.time_points) + " points)");
  line("channels", std::to_string(z.inputs) + " inputs, " + std::to_string(z.outputs) + " outputs");
  line("mass", "translational, all nodes: x " + f("%.1f", mt.all[0]) + " kg, y " +
                   f("%.1f", mt.all[1]) + " kg, z " + f("%.1f", mt.all[2]) + " kg");
  line("", "  = elements (sum rho A l) " + f("%.1f", mt.elements) + " kg + point masses " +
               f("%.1f", mt.point_masses) + " kg");
  line("", "on free DOFs: x " + f("%.1f", mt.free[0]) + " kg, y " + f("%.1f", mt.free[1]) +
               " kg, z " + f("%.1f", mt.free[2]) + " kg");
  line("", "rotational (sum of lumped): rx " + f("%.4g", mt.all[3]) + ", ry " +
               f("%.4g", mt.all[4]) + ", rz " + f("%.4g", mt.all[5]) + " kg m^2");
  if (s.alpha > 0) {
    // Fraction of critical damping of C = alpha M in a mode at f: alpha / (4 pi f).
    const double at = m.damping_frequency > 0 ? m.damping_frequency : 1.0;
    line("damping", "C = alpha M, alpha = " + f("%.6g", s.alpha) +
                        " 1/s: " + f("%.3g", 100.0 * s.alpha / (4.0 * std::numbers::pi * at)) +
                        " % at " + f("%g", at) + " Hz, " +
                        f("%.3g", 100.0 * s.alpha / (4.0 * std::numbers::pi * 10.0 * at)) +
                        " % at " + f("%g", 10.0 * at) + " Hz");
  } else {
    line("damping", "none");
  }
  if (s.gravity[0] != 0 || s.gravity[1] != 0 || s.gravity[2] != 0) {
    line("gravity", "(" + f("%g", s.gravity[0]) + ", " + f("%g", s.gravity[1]) + ", " +
                        f("%g", s.gravity[2]) + ") m/s^2");
  }

  const StableStepReport& st = m.stable;
  const double substeps = s.frame_period / s.dt;
  const bool whole = std::abs(substeps - std::round(substeps)) <= 1e-9 * substeps;
  line("dt", f("%.6g", s.dt) + " s, " +
                 (m.dt_auto ? std::string("auto (0.9 x stable, rounded down to fill a frame)")
                            : std::string("as given")) +
                 ", dt / dt_stable = " + f("%.4f", s.dt / st.dt_stable));
  line("stable dt", f("%.6g", st.dt_stable) +
                        " s (element eigenvalue bound with damping, "
                        "omega_max = " +
                        f("%.6g", st.omega_max) + " rad/s, f_max = " +
                        f("%.6g", st.omega_max / (2.0 * std::numbers::pi)) + " Hz)");
  line("", "set by " + m.describe_element(st.governing_element));
  line("CFL (seed)",
       f("%.6g", st.dt_cfl) + " s = l / sqrt(E / rho) at " + m.describe_element(st.cfl_element));
  line("substeps", (whole ? std::to_string(std::llround(substeps))
                          : f("%.6g", substeps) + " (not a whole number)") +
                       " per frame of " + f("%g", s.frame_period * 1e3) + " ms (" +
                       f("%g", m.frame_rate) + " Hz)");

  const MemoryFootprint mem = memory_footprint(z);
  line("memory", "Model " + std::to_string(mem.model) + " B + State " + std::to_string(mem.state) +
                     " B + Scratch " + std::to_string(mem.scratch) + " B = " + bytes(mem.total));
  const std::size_t rest = mem.total - mem.per_element * static_cast<std::size_t>(z.elements) -
                           mem.per_node * static_cast<std::size_t>(z.nodes);
  line("", "per element " + std::to_string(mem.per_element) + " B (ntn::BeamData) x " +
               std::to_string(z.elements) + " = " +
               std::to_string(mem.per_element * static_cast<std::size_t>(z.elements)) + " B");
  line("", "per node " + std::to_string(mem.per_node) +
               " B (6 DOFs x 8 double arrays + fixed + support list) x " + std::to_string(z.nodes) +
               " = " + std::to_string(mem.per_node * static_cast<std::size_t>(z.nodes)) + " B");
  line("",
       "rest " + std::to_string(rest) + " B (loads, channels, time functions, scalars, padding)");
  return o;
}

}  // namespace ntn::modelc
