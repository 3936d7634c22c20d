// Stages set_hinge_stiffness (penalty and limit stiffness: given, or 1e4 x the stiffest element
// term), check_curve_branches (a curve in use: a spring part around d = 0, rigid branches only at
// its ends) and check_kernel_accepts_hinges (ntn::make_hinge_data takes every hinge as built).
#include "compile.hpp"

#include <algorithm>
#include <cmath>

#include "messages.hpp"
#include "ntn/beam.hpp"
#include "ntn/hinge.hpp"
#include "ntn/hinge_methods.hpp"

namespace ntn::modelc::compile {
namespace {

constexpr double kPenaltyFactor = 1e4;  // default penalty stiffness / largest element stiffness

}  // namespace

void set_hinge_stiffness(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const SourceModel& p = comp.p;
  ModelDescription& d = comp.d;
  Settings& s = comp.d.settings;
  // Penalty and limit stiffness: given, or kPenaltyFactor x the stiffest element term (axial
  // EA/l; bending 4EI/l with the larger I). The limit default does not follow a given penalty
  // stiffness, so that which curve segments are rigid never depends on the method.
  double axial = 0, bending = 0;
  std::size_t axial_at = 0, bending_at = 0;  // their elements
  for (std::size_t ei = 0; ei < d.elements.size(); ++ei) {
    const ElementSpec& e = d.elements[ei];
    const double l = beam_geometry(d.nodes[static_cast<std::size_t>(e.node_i)],
                                   d.nodes[static_cast<std::size_t>(e.node_j)], e)
                         .length;
    if (e.E * e.A / l > axial) axial = e.E * e.A / l, axial_at = ei;
    if (4.0 * e.E * std::max(e.Iy, e.Iz) / l > bending)
      bending = 4.0 * e.E * std::max(e.Iy, e.Iz) / l, bending_at = ei;
  }
  // Without elements there is no default (0: no penalty spring, and no curve segment is a
  // rigid branch, branch_slope_limit); penalty then needs the stiffness of each kind of
  // direction it makes a spring of.
  if (d.elements.empty() && s.hinge_method == HingeMethod::kPenalty) {
    bool needs[2] = {false, false};
    for (const HingeSpec& h : d.hinges) {
      for (std::size_t k = 0; k < kDofsPerNode; ++k) {
        if (h.behaviour[k] == HingeBehaviour::kRigid ||
            h.behaviour[k] == HingeBehaviour::kRigidPlastic)
          needs[k / 3] = true;
      }
    }
    const bool given[2] = {p.model.penalty_stiffness.has_value(),
                           p.model.penalty_rotational_stiffness.has_value()};
    if ((needs[0] && !given[0]) || (needs[1] && !given[1])) {
      L.error(p.model.hinge_method_at,
              std::string("hinge_method = \"penalty\" in a model without members needs ") +
                  (needs[0] && !given[0] && needs[1] && !given[1]
                       ? "model.penalty_stiffness and model.penalty_rotational_stiffness"
                   : needs[0] && !given[0] ? "model.penalty_stiffness"
                                           : "model.penalty_rotational_stiffness") +
                  " for its rigid hinge directions: the default is 1e4 x the stiffest element");
      return;
    }
  }
  // The defaults must be numbers too (they go into the header even without hinges).
  for (int rotational = 0; rotational < 2 && !d.elements.empty(); ++rotational) {
    const bool given = rotational == 0 ? p.model.penalty_stiffness && p.model.limit_stiffness
                                       : p.model.penalty_rotational_stiffness &&
                                             p.model.limit_rotational_stiffness;
    const double v = kPenaltyFactor * (rotational == 0 ? axial : bending);
    const std::size_t ei = rotational == 0 ? axial_at : bending_at;
    const Member& m = p.members[static_cast<std::size_t>(d.element_member[ei])];
    const Material& ma =
        p.materials[static_cast<std::size_t>(comp.ids.materials.at(m.material.id))];
    if (!given && !std::isfinite(v)) {
      L.error(ma.E_at,
              "E = " + num(d.elements[ei].E) + " Pa in member " + m.id.id + " gives a default " +
                  (rotational == 0 ? "penalty and limit stiffness 1e4 E A / l"
                                   : "rotational penalty and limit stiffness 1e4 x 4 E I / l") +
                  " beyond the largest double (1.8e308): give model." +
                  (rotational == 0 ? "penalty_stiffness and model.limit_stiffness"
                                   : "penalty_rotational_stiffness and "
                                     "model.limit_rotational_stiffness"));
    }
  }
  if (L.failed()) return;
  s.penalty_stiffness = p.model.penalty_stiffness.value_or(kPenaltyFactor * axial);
  s.penalty_rotational_stiffness =
      p.model.penalty_rotational_stiffness.value_or(kPenaltyFactor * bending);
  s.limit_stiffness = p.model.limit_stiffness.value_or(kPenaltyFactor * axial);
  s.limit_rotational_stiffness =
      p.model.limit_rotational_stiffness.value_or(kPenaltyFactor * bending);
}

// Curves in use: a spring part (segments softer than the limit stiffness) that contains
// d = 0, where every run starts, with rigid branches (slope >= limit) only at the ends.
void check_curve_branches(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const ModelDescription& d = comp.d;
  const Settings& s = comp.d.settings;
  for (std::size_t hi = 0; hi < d.hinges.size(); ++hi) {
    const HingeSpec& h = d.hinges[hi];
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      if (h.behaviour[k] != HingeBehaviour::kCurve) continue;
      const int ci = h.curve[k];
      const CurveSpec& cs = d.curves[static_cast<std::size_t>(ci)];
      const double k_lim = branch_slope_limit(s, k);
      const std::string units = k < 3 ? " N/m" : " N m/rad";
      const std::string name = "curve '" + d.curve_ids[static_cast<std::size_t>(ci)] + "'";
      const Where& at = comp.dir_at[hi][k];
      // The kernel's split (ntn::curve_branches), with the reason by segment.
      const CurveBranches br = curve_branches(d.curve_points, cs, k_lim);
      const int inner = br.inner;
      if (br.first < 0) {
        L.error(at, name + " has no segment softer than the limit stiffness " + num(k_lim) + units +
                        ": all of it is a rigid branch. A direction without play is \"rigid\"; "
                        "for a spring or a gap, add softer segments or raise the limit stiffness");
        continue;
      }
      if (inner >= 0) {
        L.error(at, name + " has a rigid segment (points " + std::to_string(inner) + " to " +
                        std::to_string(inner + 1) + ", slope at least the limit stiffness " +
                        num(k_lim) + units +
                        ") between softer ones: rigid branches may only end a curve");
        continue;
      }
      const double lower = br.lower, upper = br.upper;
      if (lower > 0 || upper < 0) {
        auto end = [](double v) { return v <= -1e300 ? "-inf" : v >= 1e300 ? "+inf" : num(v); };
        L.error(at, name + " has its spring part from d = " + end(lower) + " to " + end(upper) +
                        ", which does not contain d = 0 where every run starts: a hinge cannot "
                        "start on a rigid branch");
      }
    }
  }
}

// The kernel must accept every hinge as the compiler built it (same rules, one place to look
// when they part).
void check_kernel_accepts_hinges(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const ModelDescription& d = comp.d;
  const Settings& s = comp.d.settings;
  for (std::size_t hi = 0; hi < d.hinges.size(); ++hi) {
    HingeData hd;
    if (!make_hinge_data(d.hinges[hi], s, d.nodes.size(), d.curves, d.curve_points, hd)) {
      L.error(comp.hinge_at[hi], "internal error: the kernel refuses " +
                                     d.describe_hinge(static_cast<int>(hi)) +
                                     " (ntn::make_hinge_data); please report this model");
    }
  }
}

}  // namespace ntn::modelc::compile
