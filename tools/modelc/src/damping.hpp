// Rayleigh damping C = alpha M + beta K_el from a damping ratio at two circular frequencies
// ([model.damping] ratio with frequencies or modes, config/README.md): the one place the rule
// lives, for the reader (frequencies) and the compile stage set_damping_from_modes (modes).
#pragma once

#include <algorithm>
#include <cmath>

namespace ntn::modelc::compile {

// The largest mode number `modes` takes (a model's modal analysis computes that many modes).
inline constexpr long long kMaxDampingMode = 10000;

// Two frequencies that Rayleigh damping cannot tell apart: equal to 1e-9 relative (the two
// frequencies of a symmetric section's bending pair differ by the eigensolver's rounding only).
// With them the two conditions are one and the ratio is xi at that frequency alone, which is
// not what a file that names two frequencies means.
inline bool same_frequency(double a, double b) {
  return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b));
}

struct RayleighCoefficients {
  double alpha = 0;  // 1/s
  double beta = 0;   // s
  double sum = 0;    // omega_1 + omega_2, rad/s
  bool finite() const { return std::isfinite(alpha) && std::isfinite(beta) && std::isfinite(sum); }
};

// The mode of circular frequency omega has the damping ratio alpha / (2 omega) + beta omega / 2;
// it equals `ratio` at omega_1 and omega_2 (positive, different) for
//   alpha = 2 ratio omega_1 omega_2 / (omega_1 + omega_2),   beta = 2 ratio / (omega_1 + omega_2)
// (computed without the product omega_1 omega_2, which may overflow while alpha does not).
inline RayleighCoefficients rayleigh_coefficients(double ratio, double omega1, double omega2) {
  RayleighCoefficients c;
  c.sum = omega1 + omega2;
  c.alpha = 2.0 * ratio * (omega1 / c.sum) * omega2;
  c.beta = 2.0 * ratio / c.sum;
  return c;
}

}  // namespace ntn::modelc::compile
