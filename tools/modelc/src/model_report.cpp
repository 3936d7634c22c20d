#include "ntn/modelc/model_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "ntn/beam.hpp"
#include "ntn/element_order.hpp"
#include "ntn/element_pass.hpp"
#include "ntn/geometry.hpp"
#include "ntn/init.hpp"
#include "ntn/modal/assembly.hpp"
#include "ntn/modal/modal.hpp"
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

const char* const kDofName[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};

const char* method_name(HingeMethod h) {
  switch (h) {
    case HingeMethod::kNtnExact:
      return "ntn_exact (constraint forest, DESIGN 7.1)";
    case HingeMethod::kNtnPaper:
      return "ntn_paper (the seed's S 17-37)";
    case HingeMethod::kPenalty:
      return "penalty (rigid directions as stiff springs)";
  }
  return "?";
}

// The kernel's element order of the model (ntn::element_order): its blocks of one orientation,
// and the elements it takes in another place than the file's.
std::string order_line(const ModelDescription& m) {
  const std::size_t n = m.elements.size();
  std::vector<OrderElement> el(n);
  std::vector<std::int32_t> order(n);
  spec_element_order(m.view(), el, order);
  std::size_t moved = 0, uniform = 0;
  const std::size_t blocks = beam_blocks(n);
  for (std::size_t k = 0; k < n; ++k)
    moved += order[k] != static_cast<std::int32_t>(k) ? 1 : 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    bool same = true;
    for (std::size_t k = b * kBeamLanes + 1; k < std::min(n, (b + 1) * kBeamLanes); ++k)
      same = same && el[static_cast<std::size_t>(order[k])].axes ==
                         el[static_cast<std::size_t>(order[b * kBeamLanes])].axes;
    uniform += same ? 1 : 0;
  }
  // The blocks as init() fills them: how many distinct stiffness entries they share.
  std::vector<BeamBlock> blk(blocks);
  std::vector<BeamRotations> rot(blocks);
  std::vector<BeamStiffnessBlock> stiff(blocks);
  std::vector<std::int32_t> slot(n);
  const std::size_t entries =
      fill_beam_blocks(m.view(), order, blk.data(), rot.data(), stiff.data(), slot.data());
  return std::to_string(blocks) + " blocks of " + std::to_string(kBeamLanes) + ", " +
         std::to_string(uniform) + " of one orientation, " + std::to_string(entries) +
         " distinct stiffness blocks; " + std::to_string(moved) + " of " + std::to_string(n) +
         " elements away from their place in the file (kernel/README, the model's element order)";
}

}  // namespace

StableStepReport stable_step_with(const ModelDescription& m, HingeMethod method) {
  if (method == m.settings.hinge_method) return m.stable;  // the compiler's, computed once
  SpecView v = m.view();
  v.settings.hinge_method = method;
  return stable_time_step(v, modal::lumped_mass(v));
}

MassTotals mass_totals(const ModelDescription& m) {
  MassTotals t;
  const std::vector<double> mass = modal::lumped_mass(m.view());
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

namespace {

// The text of `ntn-model info`: one line per call, its head in a column of 13.
struct InfoText {
  std::string o;
  void line(const char* head, const std::string& text) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%-13s", head);
    o += buf + text + "\n";
  }
};

// The model, its nodes (given and meshed), the plane, elements, element order, DOFs, loads.
void size_lines(InfoText& out, const ModelDescription& m, const Sizes& z, const MassTotals& mt) {
  std::size_t given = 0;
  for (int id : m.node_ids)
    given += id != kGeneratedNode ? 1U : 0U;
  out.line("model", m.name + (m.title.empty() ? "" : ": " + m.title));
  out.line("file", m.source_file);
  out.line("nodes", std::to_string(z.nodes) + " (" + std::to_string(given) + " given, " +
                        std::to_string(z.nodes - given) + " from meshing members)");
  if (!m.plane.empty()) {
    out.line("plane", m.plane + ": " + m.plane_held_names +
                          " held on every node: " + std::to_string(m.plane_held_dofs) +
                          " DOFs held as supports, " + std::to_string(m.plane_rigid_directions) +
                          " hinge directions made rigid (config/README.md, plane)");
  }
  out.line("elements",
           std::to_string(z.elements) + " in " + std::to_string(m.members.size()) + " members");
  out.line("order", order_line(m));
  out.line("DOFs",
           std::to_string(kDofsPerNode * z.nodes) + " (" + std::to_string(mt.free_dofs) +
               " free, " +
               std::to_string(kDofsPerNode * z.nodes - static_cast<std::size_t>(mt.free_dofs)) +
               " supported)");
  out.line("loads", std::to_string(z.loads) + " nodal loads, " + std::to_string(z.time_functions) +
                        " time functions (" + std::to_string(z.time_points) + " points)");
}

// The check of the consistent loads: their forces add up to the load's total.
void member_load_lines(InfoText& out, const ModelDescription& m) {
  for (const MemberLoadInfo& ml : m.member_loads) {
    auto vec = [](const std::array<double, 3>& v) {
      return "(" + f("%.9g", v[0]) + ", " + f("%.9g", v[1]) + ", " + f("%.9g", v[2]) + ") N";
    };
    const std::array<double, 3> diff{ml.nodal[0] - ml.total[0], ml.nodal[1] - ml.total[1],
                                     ml.nodal[2] - ml.total[2]};
    out.line(&ml == &m.member_loads.front() ? "member loads" : "",
             "member " + m.members[static_cast<std::size_t>(ml.member)].name + ": total " +
                 vec(ml.total) + ", sum of its " + std::to_string(ml.load_count) + " nodal loads " +
                 vec(ml.nodal) + ", difference " +
                 f("%.3g", std::sqrt(diff[0] * diff[0] + diff[1] * diff[1] + diff[2] * diff[2])) +
                 " N");
  }
}

// The nodes placed along members, new or existing.
void member_point_lines(InfoText& out, const ModelDescription& m) {
  for (const MemberPointInfo& mp : m.member_points) {
    const MemberInfo& mi = m.members[static_cast<std::size_t>(mp.member)];
    const NodeSpec& a = m.nodes[static_cast<std::size_t>(mi.start_node)];
    const NodeSpec& b = m.nodes[static_cast<std::size_t>(mi.end_node)];
    const double len = std::hypot(b.x - a.x, b.y - a.y, b.z - a.z);
    out.line(&mp == &m.member_points.front() ? "points" : "",
             "member " + mi.name + " at " + f("%.9g", mp.at) + " (" + f("%.9g", mp.at * len) +
                 " m): " + m.describe_node(mp.node) +
                 (mp.split ? ", a new node splitting an element" : ", an existing node"));
  }
}

// The channel counts and each output's alarm.
void channel_lines(InfoText& out, const ModelDescription& m, const Sizes& z) {
  out.line("channels",
           std::to_string(z.inputs) + " inputs, " + std::to_string(z.outputs) + " outputs");
  for (std::size_t c = 0; c < m.output_alarms.size(); ++c) {
    const OutputAlarm& a = m.output_alarms[c];
    if (a.limit <= 0) continue;
    const std::string unit = m.output_units[c] == "-" ? "" : " " + m.output_units[c];
    out.line("alarm", "|" + m.output_names[c] + "| > " + f("%g", a.limit) + unit + ", off below " +
                          f("%g", a.limit - a.hysteresis) + unit);
  }
}

// The lumped mass: translational (all nodes, its parts, free DOFs) and rotational.
void mass_lines(InfoText& out, const MassTotals& mt) {
  out.line("mass", "translational, all nodes: x " + f("%.6g", mt.all[0]) + " kg, y " +
                       f("%.6g", mt.all[1]) + " kg, z " + f("%.6g", mt.all[2]) + " kg");
  out.line("", "  = elements (sum rho A l) " + f("%.6g", mt.elements) + " kg + point masses " +
                   f("%.6g", mt.point_masses) + " kg");
  out.line("", "on free DOFs: x " + f("%.6g", mt.free[0]) + " kg, y " + f("%.6g", mt.free[1]) +
                   " kg, z " + f("%.6g", mt.free[2]) + " kg");
  out.line("", "rotational (sum of lumped): rx " + f("%.4g", mt.all[3]) + ", ry " +
                   f("%.4g", mt.all[4]) + ", rz " + f("%.4g", mt.all[5]) + " kg m^2");
}

// Rayleigh damping and its fraction of critical at two frequencies.
void damping_line(InfoText& out, const ModelDescription& m) {
  const Settings& s = m.settings;
  if (!(s.alpha > 0 || s.beta > 0)) {
    out.line("damping", "none");
    return;
  }
  // Fraction of critical damping of C = alpha M + beta K_el in a mode at f (omega = 2 pi f):
  // alpha / (2 omega) + beta omega / 2 (ntn-model modes gives it for each mode).
  const auto ratio = [&s](double hz) {
    const double w = 2.0 * std::numbers::pi * hz;
    return s.alpha / (2.0 * w) + s.beta * w / 2.0;
  };
  std::vector<double> at;
  if (m.damping_frequencies[0] > 0) {
    at = {m.damping_frequencies[0], m.damping_frequencies[1]};
  } else {
    const double f0 = m.damping_frequency > 0 ? m.damping_frequency : 1.0;
    at = {f0, 10.0 * f0};
  }
  std::string text = s.beta > 0 ? "C = alpha M + beta K_el, alpha = " + f("%.6g", s.alpha) +
                                      " 1/s, beta = " + f("%.6g", s.beta) + " s:"
                                : "C = alpha M, alpha = " + f("%.6g", s.alpha) + " 1/s:";
  for (std::size_t k = 0; k < at.size(); ++k) {
    text += std::string(k ? "," : "") + " " + f("%.3g", 100.0 * ratio(at[k])) + " % at " +
            f("%g", at[k]) + " Hz";
  }
  if (m.damping_modes[0] > 0) {
    text += " (modes " + std::to_string(m.damping_modes[0]) + " and " +
            std::to_string(m.damping_modes[1]) + ")";
  }
  out.line("damping", text);
}

// Gravity, the static preload under it and the initial conditions.
void gravity_initial_lines(InfoText& out, const ModelDescription& m) {
  const Settings& s = m.settings;
  if (s.gravity[0] != 0 || s.gravity[1] != 0 || s.gravity[2] != 0) {
    out.line("gravity",
             "(" + f("%g", s.gravity[0]) + ", " + f("%g", s.gravity[1]) + ", " +
                 f("%g", s.gravity[2]) + ") m/s^2" +
                 (m.preload.on ? ", static preload (the run starts at rest in equilibrium)"
                               : ", applied at t = 0 (sudden)"));
  }
  if (m.preload.on) {
    static const char* const kAxis[3] = {"x", "y", "z"};
    out.line("initial",
             "static preload under gravity and " + std::to_string(m.preload.loads) +
                 " constant nodal loads: largest displacement " +
                 f("%.6g", m.preload.max_displacement) + " m" +
                 (m.preload.max_node >= 0 ? " along " + std::string(kAxis[m.preload.max_dof]) +
                                                " at " + m.describe_node(m.preload.max_node)
                                          : std::string()) +
                 " (relative residual " + f("%.2g", m.preload.relative_residual) + ")");
    for (const std::string& note : m.preload.notes)
      out.line("", note);
  }
  if (m.initial_nodes > 0) {
    out.line("initial", std::to_string(m.initial_nodes) +
                            " nodes with initial displacements or velocities ([[initial.nodes]])");
  }
}

// The hinge counts by origin and the curves.
void hinge_count_line(InfoText& out, const ModelDescription& m, const Sizes& z) {
  out.line("hinges",
           std::to_string(z.hinges) + ": " + std::to_string(m.hinge_count(HingeOrigin::kExplicit)) +
               " explicit, " + std::to_string(m.hinge_count(HingeOrigin::kRelease)) +
               " member-end releases, " + std::to_string(m.hinge_count(HingeOrigin::kSupport)) +
               " supports with axes" +
               (m.hinge_count(HingeOrigin::kPointMass) > 0
                    ? ", " + std::to_string(m.hinge_count(HingeOrigin::kPointMass)) +
                          " rigid offsets of point masses"
                    : std::string()) +
               "; " + std::to_string(z.curves) + " curves (" + std::to_string(z.curve_points) +
               " points)");
}

// The hysteretic directions: their kinds, yield range and performance limits.
void plastic_line(InfoText& out, const ModelDescription& m) {
  if (m.hystereses.empty()) return;
  // Each slot's kind: from its law, and rigid-plastic or not from its direction.
  std::vector<bool> rigid(m.hystereses.size(), false);
  for (const HingeSpec& h : m.hinges) {
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      if (h.behaviour[k] == HingeBehaviour::kRigidPlastic)
        rigid[static_cast<std::size_t>(h.hysteresis[k])] = true;
    }
  }
  double lo = 1e300, hi = 0;
  int limits = 0;
  // The kinds: the laws of spring directions in the law table's order, then the
  // rigid-plastic ones.
  std::vector<std::string> kind_names;
  each_law([&kind_names](auto l) { kind_names.emplace_back(decltype(l)::kSummary); });
  const std::size_t laws = kind_names.size();
  for (const char* n : {"rigid_plastic", "friction", "fixed_if", "rigid failure"})
    kind_names.emplace_back(n);
  std::vector<int> count(kind_names.size(), 0);
  for (std::size_t i = 0; i < m.hystereses.size(); ++i) {
    const HysteresisSpec& h = m.hystereses[i];
    if (h.yield_pos > 0) {
      lo = std::min({lo, h.yield_pos, h.yield_neg});
      hi = std::max({hi, h.yield_pos, h.yield_neg});
    }
    limits += h.limits[0] > 0 ? 1 : 0;
    const std::size_t kind = !rigid[i]            ? static_cast<std::size_t>(law_index(h.rule))
                             : law_breaks(h.rule) ? laws + 3
                             : h.fixed_if != 0    ? laws + 2
                             : h.normal >= 0      ? laws + 1
                                                  : laws;
    ++count[kind];
  }
  std::string kinds;
  for (std::size_t k = 0; k < count.size(); ++k) {
    if (count[k] > 0)
      kinds += (kinds.empty() ? "" : ", ") + std::to_string(count[k]) + " " + kind_names[k];
  }
  out.line("plastic",
           std::to_string(m.hystereses.size()) + " hysteretic directions (" + kinds + ")" +
               (hi > 0 ? ", yield " + f("%.4g", lo) +
                             (hi > lo ? " to " + f("%.4g", hi) : std::string()) + " N or N m"
                       : std::string()) +
               ", " + std::to_string(limits) +
               " with IO/LS/CP limits; at their elastic stiffness in the stable step "
               "and the modes (rigid-plastic ones: rigid)");
}

// The hinge method, the clamp and the penalty and limit stiffnesses.
void method_lines(InfoText& out, const ModelDescription& m, const Sizes& z) {
  const Settings& s = m.settings;
  out.line("method", std::string(method_name(s.hinge_method)) + ", clamp " +
                         (s.clamp == ClampRule::kMomentum ? "momentum" : "paper (S 33)"));
  const bool members = z.elements > 0;  // without them no default (0)
  const char* def = members ? " (default: 1e4 x largest EA/l)" : " (no members: no default)";
  const char* def_rot = members ? " (default: 1e4 x largest 4EI/l)" : " (no members: no default)";
  out.line("", "penalty k " + f("%.4g", s.penalty_stiffness) + " N/m" +
                   (m.penalty_stiffness_given ? "" : def) + ", " +
                   f("%.4g", s.penalty_rotational_stiffness) + " N m/rad" +
                   (m.penalty_rotational_stiffness_given ? "" : def_rot));
  out.line("", "limit k " + f("%.4g", s.limit_stiffness) + " N/m" +
                   (m.limit_stiffness_given ? "" : def) + ", " +
                   f("%.4g", s.limit_rotational_stiffness) + " N m/rad" +
                   (m.limit_rotational_stiffness_given ? "" : def_rot));
}

// The time step, as given or chosen, and the stable step that bounds it.
void time_step_lines(InfoText& out, const ModelDescription& m, const Sizes& z) {
  const Settings& s = m.settings;
  const StableStepReport& st = m.stable;
  const bool bounded = st.dt_stable < 1e300;  // 1e300: no element, hinge spring or damping
  out.line("dt", f("%.6g", s.dt) + " s, " +
                     (m.dt_auto ? std::string("auto (0.9 x stable, rounded down to fill a frame)")
                                : std::string("as given")) +
                     (bounded ? ", dt / dt_stable = " + f("%.4g", s.dt / st.dt_stable)
                              : std::string(", the frame period")));
  if (bounded) {
    out.line("stable dt", f("%.6g", st.dt_stable) +
                              " s (element eigenvalue bound and hinge springs, with damping, "
                              "omega_max = " +
                              f("%.6g", st.omega_max) + " rad/s, f_max = " +
                              f("%.6g", st.omega_max / (2.0 * std::numbers::pi)) + " Hz" +
                              (z.elements > 0 ? ")" : ": no elements)"));
  } else {
    out.line("stable dt", "none: nothing bounds it (no element, hinge spring or damping)");
  }
  if (bounded) out.line("", "set by " + m.describe_stable_step(st));
}

// The lowest frequency (Hz) of a model's modal analysis, 0 when it has none or fails.
double lowest_frequency(const SpecView& v, bool geometric = true) {
  modal::ModalOptions o;
  o.modes = 1;
  o.geometric = geometric;
  const modal::ModalResult r = modal::modal_analysis(v, o);
  return r.ok() && r.frequency.size() > 0 ? r.frequency(0) : 0.0;
}

// Second-order geometry (geometry.hpp): how many elements, the stable step's bound on their
// axial force and chord rotation at the step the run takes (the smallest Q_max, as a share of the
// element's E A), and the lowest frequency about the preload with and without the geometric
// stiffness of its axial forces.
void geometry_lines(InfoText& out, const ModelDescription& m, const Sizes& z) {
  if (z.geometric == 0 && z.corotational == 0) return;
  std::size_t leaning = 0;
  double share = 1e300;
  int governing = -1;
  const SpecView v = m.view();
  for (std::size_t i = 0; i < m.elements.size(); ++i) {
    const ElementSpec& e = m.elements[i];
    if (e.geometry == Geometry::kLinear) continue;
    leaning += e.geometry == Geometry::kLeaning ? 1U : 0U;
    const NodeSpec& a = m.nodes[static_cast<std::size_t>(e.node_i)];
    const NodeSpec& b = m.nodes[static_cast<std::size_t>(e.node_j)];
    const BeamGeometry g = beam_geometry(a, b, e);
    const double q = geometric_force_limit(element_omega_max(e, a, b, m.settings.rotary_inertia),
                                           e.rho, e.A, g.length, m.stable.dt_stable, m.settings.dt);
    if (q / (e.E * e.A) < share) share = q / (e.E * e.A), governing = static_cast<int>(i);
  }
  out.line("geometry", std::to_string(z.geometric - leaning) + " p_delta element(s), " +
                           std::to_string(leaning) + " leaning column(s), " +
                           std::to_string(z.corotational) + " corotational, " +
                           std::to_string(z.elements - z.geometric - z.corotational) + " linear");
  out.line("", "the stable dt is without axial forces (compression only lowers the frequencies)");
  out.line("",
           "it holds while N+ + k l (phi + phi^2) <= Q_max in every element (tension, chord "
           "rotation phi; a corotational element's chord turns freely: phi = 0); past it the "
           "step counts and flags it");
  if (z.corotational > 0) {
    out.line("",
             "corotational: rotary inertia made isotropic at their nodes; preload and modes "
             "about it with the p_delta tangent (the same at small displacements)");
  }
  out.line("", "smallest Q_max = " + f("%.3g", share) + " E A, " + m.describe_element(governing));
  const double f_geo = lowest_frequency(v), f_lin = lowest_frequency(v, false);
  if (f_geo > 0 && f_lin > 0) {
    out.line("", "lowest frequency " + f("%.6g", f_geo) + " Hz about the preload with P-Delta, " +
                     f("%.6g", f_lin) + " Hz without (" + f("%+.3g", 100 * (f_geo / f_lin - 1)) +
                     " %)");
  }
}

// Whether a rigid direction has no penalty stiffness: a model without elements has no default
// (0), and penalty cannot make its rigid directions springs unless the file gives it.
bool lacks_penalty_stiffness(const ModelDescription& m) {
  bool no_penalty_k = false;
  for (const HingeSpec& h : m.hinges) {
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      no_penalty_k = no_penalty_k || ((h.behaviour[k] == HingeBehaviour::kRigid ||
                                       h.behaviour[k] == HingeBehaviour::kRigidPlastic) &&
                                      !(penalty_stiffness(m.settings, k) > 0));
    }
  }
  return no_penalty_k;
}

// The same model's stable step with each method (the NTN / penalty ratio).
void method_step_lines(InfoText& out, const ModelDescription& m) {
  const StableStepReport exact = stable_step_with(m, HingeMethod::kNtnExact);
  const StableStepReport pen = stable_step_with(m, HingeMethod::kPenalty);
  out.line("ntn_exact dt", f("%.6g", exact.dt_stable) + " s (rigid directions add no stiffness)");
  if (lacks_penalty_stiffness(m)) {
    out.line("penalty dt",
             "none: no penalty stiffness (the default is 1e4 x the stiffest element, "
             "and there is none; give model.penalty_stiffness and "
             "penalty_rotational_stiffness)");
  } else if (pen.dt_stable > 0) {
    std::string by = pen.governing_hinge >= 0 ? m.describe_hinge(pen.governing_hinge) +
                                                    ", direction " + kDofName[pen.hinge_direction]
                                              : m.describe_element(pen.governing_element);
    out.line("penalty dt", f("%.6g", pen.dt_stable) + " s (rigid directions as springs of the " +
                               "penalty k), set by " + by);
    out.line("", "ntn_exact / penalty = " + f("%.4g", exact.dt_stable / pen.dt_stable));
  } else {
    out.line("penalty dt",
             "0 s: a penalty spring acts on a DOF without mass (penalty needs mass "
             "on both nodes); ntn_exact / penalty = inf");
  }
}

// The seed's CFL step and the substeps per frame (the kernel's frame rule; a loaded model
// passes it, the compiler refuses the others).
void frame_lines(InfoText& out, const ModelDescription& m) {
  const Settings& s = m.settings;
  const StableStepReport& st = m.stable;
  const Substeps substeps = frame_substeps(s.dt, s.frame_period);
  out.line("CFL (seed)", st.cfl_element < 0 ? std::string("none (no elements)")
                                            : f("%.6g", st.dt_cfl) + " s = l / sqrt(E / rho) at " +
                                                  m.describe_element(st.cfl_element));
  out.line("substeps",
           (substeps.ok() ? std::to_string(substeps.count)
                          : f("%.6g", substeps.ratio) + " (" + to_string(substeps.error) + ")") +
               " per frame of " + f("%g", s.frame_period * 1e3) + " ms (" + f("%g", m.frame_rate) +
               " Hz)");
}

// The memory of Model, State and Scratch, and its parts per element, node and hinge.
void memory_lines(InfoText& out, const Sizes& z) {
  const MemoryFootprint mem = memory_footprint(z);
  out.line("memory", "Model " + std::to_string(mem.model) + " B + State " +
                         std::to_string(mem.state) + " B + Scratch " + std::to_string(mem.scratch) +
                         " B = " + bytes(mem.total));
  const std::size_t hinge_nodes = z.hinges > 0 ? z.nodes : 0;
  const std::size_t hinge_bytes = mem.per_hinge * z.hinges +
                                  mem.per_node_with_hinges * hinge_nodes +
                                  mem.per_curve_point * z.curve_points;
  const std::size_t rest =
      mem.total - mem.per_element * z.elements - mem.per_node * z.nodes - hinge_bytes;
  out.line("", "per element " + std::to_string(mem.per_element) +
                   " B (ntn::BeamBlock and ntn::BeamRotations / 4) x " +
                   std::to_string(z.elements) + " = " +
                   std::to_string(mem.per_element * z.elements) + " B");
  out.line("", "per node " + std::to_string(mem.per_node) +
                   " B (6 DOFs x 9 double arrays + fixed + support list) x " +
                   std::to_string(z.nodes) + " = " + std::to_string(mem.per_node * z.nodes) + " B");
  if (z.hinges > 0) {
    out.line("", "per hinge " + std::to_string(mem.per_hinge) +
                     " B (ntn::HingeData + forest edge, root, mass, index) x " +
                     std::to_string(z.hinges) + " + per node " +
                     std::to_string(mem.per_node_with_hinges) +
                     " B (tree, held, residual scale, coupled force) x " + std::to_string(z.nodes) +
                     " + curve points " + std::to_string(mem.per_curve_point * z.curve_points) +
                     " B = " + std::to_string(hinge_bytes) + " B");
  }
  out.line("", "rest " + std::to_string(rest) +
                   " B (loads, channels, time functions, scalars, padding)");
}

// The DOFs without effective mass or stiffness, held at zero.
void mechanism_lines(InfoText& out, const ModelDescription& m) {
  for (const Mechanism& mech : m.mechanisms) {
    std::string dofs;
    for (int d = 0; d < kDofsPerNode; ++d) {
      if ((mech.dofs >> d) & 1U) dofs += (dofs.empty() ? "" : ", ") + std::string(kDofName[d]);
    }
    out.line(&mech == &m.mechanisms.front() ? "mechanisms" : "",
             m.describe_node(mech.node) + ": " + dofs +
                 " (no effective mass, no stiffness: held at zero)");
  }
}

}  // namespace

std::string info_text(const ModelDescription& m) {
  const Sizes z = m.sizes();
  const MassTotals mt = mass_totals(m);
  InfoText out;
  size_lines(out, m, z, mt);
  member_load_lines(out, m);
  member_point_lines(out, m);
  channel_lines(out, m, z);
  mass_lines(out, mt);
  damping_line(out, m);
  gravity_initial_lines(out, m);
  if (z.hinges > 0) {
    hinge_count_line(out, m, z);
    plastic_line(out, m);
    method_lines(out, m, z);
  }
  time_step_lines(out, m, z);
  geometry_lines(out, m, z);
  if (z.hinges > 0) method_step_lines(out, m);
  frame_lines(out, m);
  memory_lines(out, z);
  mechanism_lines(out, m);
  return out.o;
}

}  // namespace ntn::modelc
