#include "ntn/spectral/significance.hpp"

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <vector>

#include "ntn/spectral/window.hpp"

namespace ntn::spectral {

double welch_dof(const Grid& g) {
  const std::size_t K = g.segments;
  if (K <= 1 || g.segment == 0) return 2;
  const std::vector<double> w = make_window(g.window, g.segment);
  double w2 = 0;
  for (const double v : w)
    w2 += v * v;
  double sum = 0;  // sum_j (K - j) rho_j^2, j = 1 .. K - 1, while the segments overlap
  for (std::size_t j = 1; j < K && j * g.step < g.segment; ++j) {
    double r = 0;
    for (std::size_t n = 0; n + j * g.step < g.segment; ++n)
      r += w[n] * w[n + j * g.step];
    const double rho = r / w2;
    sum += static_cast<double>(K - j) * rho * rho;
  }
  const double k = static_cast<double>(K);
  return 2 * k * k / (k + 2 * sum);
}

double local_floor(const Spectrum& s, std::size_t k, std::size_t exclude) {
  const double df = s.grid.df(), f = static_cast<double>(k) * df;
  std::vector<double> v;
  for (std::size_t i = 1; i < s.values.size(); ++i) {
    const double fi = static_cast<double>(i) * df;
    if (fi < f / 1.5 || fi > 1.5 * f) continue;
    if ((i > k ? i - k : k - i) <= exclude) continue;
    v.push_back(s.values[i]);
  }
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double noise_threshold(double dof, double lines, double false_alarm) {
  const boost::math::chi_squared chi(dof);
  // P(max of M lines <= t) = F(t)^M = 1 - false_alarm.
  const double p = std::pow(1 - false_alarm, 1 / std::max(1.0, lines));
  return boost::math::quantile(chi, p) / boost::math::median(chi);
}

}  // namespace ntn::spectral
