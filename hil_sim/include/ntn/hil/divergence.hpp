// Divergence check of the frame loop (DESIGN §8): a per-frame test on the
// kinetic energy, so that a model that went unstable (dt above the stable step) is caught a few
// steps after its response leaves what any stable run could reach, long before its numbers
// overflow to Inf / NaN. Everything here is outside step(); the per-frame part has no heap and
// no libm.
//
// The bound (hil_sim/README.md, "Divergence"). For a linear model with mass-proportional damping
// C = alpha M, alpha > 0, starting from rest, each mode i (M-normalized shape phi_i) obeys
// q'' + alpha q' + w_i^2 q = phi_i^T p(t). With |phi_i^T p(t)| <= Pi_i for all t, the impulse
// response gives |q'| <= (2 / alpha) (w / w_d) Pi_i and |w q| <= the same, so the mode's energy
// is at most 4 kappa Pi_i^2 / alpha^2, kappa = (w / w_d)^2 <= 2 while every mode has at most
// 1/sqrt(2) of critical damping (w_i >= alpha / sqrt(2)). Summed over the modes, with
// p(t) = sum_s p_s f_s(t), |f_s| <= F_s: sum_i Pi_i^2 <= (sum_s F_s |M^-1/2 p_s|)^2 =: P^2
// (Minkowski; constraints only shrink the projection). So E(t) <= 8 P^2 / alpha^2.
// For the sources: a ground acceleration along d with |a| <= A gives A sqrt(M_d) (M_d: mass
// of the unsupported DOFs along d); gravity |g_d| F_g sqrt(M_d) per direction; a nodal force or
// load of size F at DOF j gives F / sqrt(m_j).
// Central difference at dt <= 0.9 dt_stable answers a mode with a velocity at most
// 1 / cos(theta / 2) (theta = w_h dt <= 2 asin 0.9, so <= 2.3x, 5.3x in energy) above the
// continuous one. The limit takes a further margin: kKineticLimitFactor = 1000 >= 5.3 with
// room; since an unstable mode's energy grows by |lambda|^2 per step, a factor 10 in the limit
// costs only ln 10 / (2 ln|lambda|) steps of detection (0.6 steps at dt = 1.5 dt_stable).
//
// Where no such bound exists (no damping, damping that is not alpha M, hinges with curves or
// dashpots, an input channel without a finite range, a massless loaded DOF), the limit is +Inf
// and only the non-finite test remains: the state is then caught when it overflows.
#pragma once

#include <cmath>
#include <limits>

#include "ntn/kernel.hpp"

namespace ntn::hil {

inline constexpr double kKineticLimitFactor = 1000.0;

// Why a frame was declared diverged.
enum class DivergenceReason : std::uint8_t {
  kNone,
  kNonFinite,  // a velocity (step()) or the kinetic energy became NaN / Inf
  kEnergy,     // the kinetic energy passed the limit
};

inline const char* to_string(DivergenceReason r) {
  switch (r) {
    case DivergenceReason::kNone:
      return "none";
    case DivergenceReason::kNonFinite:
      return "non-finite state";
    case DivergenceReason::kEnergy:
      return "kinetic energy above the limit";
  }
  return "?";
}

// 1/2 sum_j m_j v_j^2 at v_{n+1/2} (J), DOFs in index order (a fixed summation order). NaN / Inf
// when a velocity is. No heap, no libm.
template <Sizes S>
double kinetic_energy(const Model<S>& m, const State<S>& s) {
  double t = 0;
  for (std::size_t j = 0; j < m.dofs(); ++j)
    t += m.mass[j] * s.v[j] * s.v[j];
  return 0.5 * t;
}

// The largest |value| a time function reaches (its points; the end values hold outside them).
template <Sizes S>
double time_function_peak(const Model<S>& m, int function) {
  if (function == kConstant) return 1.0;
  const TimeFunctionSpec& tf = m.time_functions[static_cast<std::size_t>(function)];
  double peak = tf.count <= 0 ? 1.0 : 0.0;
  for (int k = tf.first; k < tf.first + tf.count; ++k)
    peak = std::max(peak, std::abs(m.time_points[static_cast<std::size_t>(k)].value));
  return peak;
}

// E_max = 8 P^2 / alpha^2 (J): no stable run of the model from rest under inputs inside their
// ranges has more energy (see the top of this file), or +Inf where the argument does not apply.
template <Sizes S>
double response_energy_bound(const Model<S>& m) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Stiffness-proportional damping (beta K_el) overdamps the high modes: not the C = alpha M of
  // the argument.
  if (m.beta != 0) return kInf;
  // alpha: the same damping / mass ratio at every DOF that has mass.
  double alpha = -1;
  for (std::size_t j = 0; j < m.dofs(); ++j) {
    if (!(m.mass[j] > 0)) {
      if (m.damping[j] != 0) return kInf;
      continue;
    }
    const double a = m.damping[j] / m.mass[j];
    if (alpha < 0) alpha = a;
    if (!(std::abs(a - alpha) <= 1e-12 * alpha)) return kInf;
  }
  if (!(alpha > 0)) return kInf;
  for (const HingeData& h : m.hinges) {
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      if (h.dashpot[k] != 0 || h.curve_count[k] != 0) return kInf;
    }
  }
  // Mass of the unsupported DOFs per translation direction.
  std::array<double, 3> mass_dir{};
  for (std::size_t n = 0; n < m.sizes.nodes; ++n) {
    for (std::size_t d = 0; d < 3; ++d) {
      if ((m.fixed[n] >> d) & 1U) continue;
      mass_dir[d] += m.mass[kDofsPerNode * n + d];
    }
  }
  const auto at_dof = [&](int node, int dof, double force) {
    const double mj = m.mass[static_cast<std::size_t>(kDofsPerNode * node + dof)];
    if ((m.fixed[static_cast<std::size_t>(node)] >> dof) & 1U) return 0.0;  // a support takes it
    return force == 0 ? 0.0 : (mj > 0 ? std::abs(force) / std::sqrt(mj) : kInf);
  };
  double p = 0;
  const double fg = time_function_peak(m, m.gravity_function);
  for (std::size_t d = 0; d < 3; ++d)
    p += std::abs(m.gravity[d]) * fg * std::sqrt(mass_dir[d]);
  for (const LoadSpec& l : m.loads)
    p += at_dof(l.node, l.dof, l.value * time_function_peak(m, l.time_function));
  for (const InputSpec& in : m.inputs) {
    const double range =
        std::max(std::abs(in.min), std::abs(in.max)) * std::abs(in.scale * in.factor);
    if (!(range < 1e100)) return kInf;  // the default range (+-1e300) bounds nothing
    p += in.kind == InputKind::kGroundAcceleration
             ? range * std::sqrt(mass_dir[static_cast<std::size_t>(in.dof)])
             : at_dof(in.node, in.dof, range);
  }
  const double e = 8.0 * p * p / (alpha * alpha);
  return e < kInf ? e : kInf;
}

// The loop's per-frame limit on the kinetic energy: kKineticLimitFactor x the bound, or +Inf.
template <Sizes S>
double kinetic_energy_limit(const Model<S>& m) {
  return kKineticLimitFactor * response_energy_bound(m);
}

}  // namespace ntn::hil
