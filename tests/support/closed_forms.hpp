// Closed forms the tests hold the kernel and the tools to (no project code: the truth nobody here
// chose, written once).
#pragma once

#include <cmath>

namespace ntn_test {

// beta_i L, i = 0, 1, 2: the first roots of cos(x) cosh(x) = -1 (Euler-Bernoulli cantilever,
// omega_i = (beta_i L)^2 sqrt(E I / (rho A)) / L^2), by Newton from 1.8751, 4.6941, 7.8548.
inline double cantilever_beta_l(int i) {
  const double start[3] = {1.8751, 4.6941, 7.8548};
  double x = start[i];
  for (int k = 0; k < 20; ++k) {
    const double g = std::cos(x) * std::cosh(x) + 1.0;
    const double dg = -std::sin(x) * std::cosh(x) + std::cos(x) * std::sinh(x);
    x -= g / dg;
  }
  return x;
}

}  // namespace ntn_test
