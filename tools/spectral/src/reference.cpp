#include "ntn/spectral/reference.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "segments.hpp"

namespace ntn::spectral {

std::vector<std::complex<double>> naive_dft(std::span<const double> x) {
  const std::size_t n = x.size();
  std::vector<std::complex<double>> twiddle(n);
  for (std::size_t m = 0; m < n; ++m) {
    const double a = 2 * std::numbers::pi * static_cast<double>(m) / static_cast<double>(n);
    twiddle[m] = {std::cos(a), -std::sin(a)};
  }
  std::vector<std::complex<double>> out(n / 2 + 1);
  for (std::size_t k = 0; k < out.size(); ++k) {
    double re = 0;
    double im = 0;
    std::size_t idx = 0;  // (k j) mod n
    for (std::size_t j = 0; j < n; ++j) {
      re += x[j] * twiddle[idx].real();
      im += x[j] * twiddle[idx].imag();
      idx += k;
      if (idx >= n) idx -= n;
    }
    out[k] = {re, im};
  }
  return out;
}

Spectrum welch_psd_naive(std::span<const double> x, double fs, const WelchOptions& options,
                         std::size_t max_segments) {
  const WelchOptions r = detail::resolve(fs, options);
  const std::vector<double> w = make_window(r.window, r.segment);
  double u = 0;
  for (double v : w)
    u += v * v;
  detail::check_finite(x, fs, "the channel");
  Grid g = detail::make_grid(fs, r, window_properties(w).enbw_bins, x.size());
  if (max_segments != 0) g.segments = std::min(g.segments, max_segments);
  std::vector<double> seg(g.nfft);
  std::vector<double> acc(g.lines(), 0.0);
  for (std::size_t m = 0; m < g.segments; ++m) {
    detail::prepare_segment(x, m, g, r.detrend, w, seg);
    const std::vector<std::complex<double>> X = naive_dft(seg);
    for (std::size_t k = 0; k < acc.size(); ++k)
      acc[k] += X[k].real() * X[k].real() + X[k].imag() * X[k].imag();
  }
  const double scale = 1 / (fs * u * static_cast<double>(g.segments));
  for (std::size_t k = 0; k < acc.size(); ++k)
    acc[k] *= detail::one_sided_weight(k, g.nfft) * scale;
  return {g, Scale::kPower, std::move(acc)};
}

}  // namespace ntn::spectral
