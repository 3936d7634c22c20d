// Stage choose_time_step: the kernel's stable step for the model's hinge method (an error when it
// is zero or not finite, at the hinge direction or member that sets it), dt ("auto" or the given
// dt, at most the stable step unless allow_unstable) and the frame rule (whole substeps per
// frame, at most ntn::kMaxSubsteps).
#include "compile.hpp"

#include <cmath>

#include "messages.hpp"
#include "ntn/hinge.hpp"
#include "ntn/hinge_methods.hpp"
#include "ntn/time_step.hpp"

namespace ntn::modelc::compile {

// Time step (DESIGN §6, kernel/README.md "Stable time step"): the element eigenvalue bound and
// the node-by-node bound of the hinge springs, with damping, for the model's hinge method.
void choose_time_step(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const SourceModel& p = comp.p;
  ModelDescription& d = comp.d;
  Settings& s = comp.d.settings;
  const std::vector<double>& mass = comp.mass;
  d.stable = stable_time_step(d.view(), mass);
  // A plastic hinge direction stands for a connection that is rigid until it yields, so its
  // elastic k is often chosen far stiffer than needed; when it sets the step well below the
  // elements' own (half or less), say so at the direction (a note: the model runs). Without
  // elements there is no such step to compare with (an oscillator on its hinge).
  if (const StableStepReport& st = d.stable; !d.elements.empty() && st.governing_hinge >= 0 &&
                                             st.dt_stable > 0 &&
                                             st.dt_stable <= 0.5 * st.dt_elements) {
    const auto h = static_cast<std::size_t>(st.governing_hinge);
    const auto k = static_cast<std::size_t>(st.hinge_direction);
    if (d.hinges[h].behaviour[k] == HingeBehaviour::kPlastic) {
      L.note(
          comp.dir_at[h][k],
          "the elastic stiffness of this plastic direction (k = " + num(d.hinges[h].stiffness[k]) +
              (k < 3 ? " N/m" : " N m/rad") + ") sets the stable step " + num(st.dt_stable) +
              " s, " + num(st.dt_elements / st.dt_stable) + " x below the elements' own " +
              num(st.dt_elements) +
              " s: a smaller k, still well above the stiffness of the members it joins, runs "
              "faster with the same plastic behaviour");
    }
  }
  auto governing = [&](const StableStepReport& r) { return d.describe_stable_step(r); };
  if (!(d.stable.dt_stable > 0) || !std::isfinite(d.stable.dt_stable)) {
    // Where it showed: the hinge direction's value, or the governing element's member.
    const StableStepReport& st = d.stable;
    Where at = p.model.dt_at;
    if (st.governing_hinge >= 0) {
      at = comp.dir_at[static_cast<std::size_t>(st.governing_hinge)]
                      [static_cast<std::size_t>(st.hinge_direction)];
    } else if (st.governing_element >= 0) {
      at = p.members[static_cast<std::size_t>(
                         d.element_member[static_cast<std::size_t>(st.governing_element)])]
               .nodes_at;
    }
    // The values there: the spring's k and c, or the element's E, rho and A.
    std::string values;
    if (st.governing_hinge >= 0) {
      const auto h = static_cast<std::size_t>(st.governing_hinge);
      const auto k = static_cast<std::size_t>(st.hinge_direction);
      HingeData hd;
      if (make_hinge_data(d.hinges[h], s, d.nodes.size(), d.curves, d.curve_points, hd)) {
        values = " (k = " + num(hd.stiffness[k]) + (k < 3 ? " N/m" : " N m/rad") +
                 ", dashpot c = " + num(hd.dashpot[k]) + (k < 3 ? " N s/m)" : " N m s/rad)");
      }
    } else if (st.governing_element >= 0) {
      const ElementSpec& e = d.elements[static_cast<std::size_t>(st.governing_element)];
      values =
          " (E = " + num(e.E) + " Pa, rho = " + num(e.rho) + " kg/m^3, A = " + num(e.A) + " m^2)";
    }
    L.error(at, "the stable step is zero (set by " + governing(st) + values + "): " +
                    (st.issue == StepIssue::kMassless
                         ? std::string("a spring acts on a DOF without mass")
                         : std::string("an intermediate result of the stable-step bound is "
                                       "beyond double there (stiffness, damping or mass too "
                                       "large or too small by hundreds of orders of magnitude)")));
    return;
  }
  if (d.dt_auto) {
    s.dt = auto_time_step(d.stable.dt_stable, s.frame_period);
  } else {
    s.dt = d.dt_requested;
    if (s.dt > d.stable.dt_stable && !s.allow_unstable) {
      L.error(p.model.dt_at, "dt = " + num(s.dt) + " s is above the stable step " +
                                 num(d.stable.dt_stable) + " s set by " + governing(d.stable) +
                                 "; use dt = \"auto\" or a smaller dt");
    }
  }
  // The frame rule (ntn::frame_substeps, kernel/README.md "Frames and substeps"): the same test
  // the real-time loop makes, so that a model that passes here runs there.
  const Substeps n = frame_substeps(s.dt, s.frame_period);
  const std::string frame =
      " the frame period " + num(s.frame_period) + " s (frame_rate = " + num(d.frame_rate) + " Hz)";
  const std::string stable_by =
      "the stable step is " + num(d.stable.dt_stable) + " s, set by " + governing(d.stable);
  switch (n.error) {
    case SubstepError::kNone:
      break;
    case SubstepError::kTooMany:
      if (d.dt_auto) {
        L.error(p.model.dt_at,
                "dt = \"auto\" needs " + num(auto_substeps(d.stable.dt_stable, s.frame_period)) +
                    " substeps in" + frame + ", more than the limit " +
                    std::to_string(kMaxSubsteps) + " (ntn::kMaxSubsteps): " + stable_by +
                    ". No machine runs such a model; check the units and the geometry there "
                    "(nodes almost coincident?), or lower frame_rate");
      } else {
        L.error(p.model.dt_at, "dt = " + num(s.dt) + " s gives " + num(n.ratio) + " substeps in" +
                                   frame + ", more than the limit " + std::to_string(kMaxSubsteps) +
                                   " (ntn::kMaxSubsteps)");
      }
      break;
    case SubstepError::kNotWhole:
      L.error(p.model.dt_at, "dt = " + num(s.dt) + " s does not divide" + frame +
                                 " into a whole number of substeps (period / dt = " + num(n.ratio) +
                                 "); use dt = \"auto\" or the period / N");
      break;
    case SubstepError::kLongerThanFrame:
      L.error(p.model.dt_at, "dt = " + num(s.dt) + " s is longer than" + frame +
                                 ": a frame needs at least one step; use dt = \"auto\", or "
                                 "lower frame_rate");
      break;
    case SubstepError::kBadTimeStep:
    case SubstepError::kBadPeriod:
      L.error(p.model.dt_at, "dt = " + num(s.dt) + " s and" + frame + ": " + to_string(n.error));
      break;
  }
}

}  // namespace ntn::modelc::compile
