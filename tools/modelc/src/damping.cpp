// Stage set_damping_from_modes: [model.damping] ratio with modes = [i, j] sets Rayleigh damping
// (damping.hpp) at the model's own undamped modes i and j, as `ntn-model modes` computes and
// numbers them (ntn::modal::modal_analysis on the finished model: supports and rigid hinge
// directions tied, linear hinge directions as springs). Errors at `modes`: the analysis fails,
// a mode beyond the ones the model has, a mode of zero frequency, two modes of equal frequency,
// coefficients beyond double.
#include <algorithm>
#include <numbers>
#include <string>

#include "compile.hpp"
#include "damping.hpp"
#include "messages.hpp"
#include "ntn/modal/modal.hpp"

namespace ntn::modelc::compile {

void set_damping_from_modes(Compilation& comp) {
  const ModelTable& m = comp.p.model;
  if (m.damping_modes[0] <= 0) return;
  DiagnosticSink& L = comp.L;
  const Where& at = m.damping_modes_at;
  const int i = m.damping_modes[0], j = m.damping_modes[1];
  modal::ModalOptions o;
  o.modes = std::max(i, j);
  const modal::ModalResult r = modal::modal_analysis(comp.d.view(), o);
  if (!r.ok()) {
    L.error(at, "the modal analysis for the damping failed: " + r.error);
    return;
  }
  if (r.modes() < o.modes) {
    L.error(at, "mode " + std::to_string(o.modes) + " asked for, but the model has " +
                    std::to_string(r.modes()) + " mode" + (r.modes() == 1 ? "" : "s") +
                    " (ntn-model modes lists them)");
    return;
  }
  const double w1 = r.omega(i - 1), w2 = r.omega(j - 1);
  // Zero frequency: a rigid-body motion, whose eigenvalue is 0 to the solver's rounding (below
  // 1e-6 of the highest frequency computed).
  const double top = r.omega(r.modes() - 1);
  for (const int k : {i, j}) {
    if (!(r.omega(k - 1) > 1e-6 * top) || !(r.omega(k - 1) > 0)) {
      L.error(at, "mode " + std::to_string(k) +
                      " has zero frequency (a rigid-body motion): no damping ratio can be set "
                      "there");
      return;
    }
  }
  if (same_frequency(w1, w2)) {
    L.error(at, "modes " + std::to_string(i) + " and " + std::to_string(j) +
                    " have the same frequency (" + num(r.frequency(i - 1)) +
                    " Hz, to 1e-9): Rayleigh damping needs two different frequencies");
    return;
  }
  const RayleighCoefficients c = rayleigh_coefficients(m.damping_ratio, w1, w2);
  if (!c.finite()) {
    L.error(at, "ratio = " + num(m.damping_ratio) + " at modes " + std::to_string(i) + " and " +
                    std::to_string(j) + " gives alpha = " + num(c.alpha) +
                    " 1/s, beta = " + num(c.beta) + " s: beyond double (1.8e308)");
    return;
  }
  comp.d.settings.alpha = c.alpha;
  comp.d.settings.beta = c.beta;
  comp.d.damping_frequencies = {r.frequency(i - 1), r.frequency(j - 1)};
}

}  // namespace ntn::modelc::compile
