#include "ntn/spectral/frf.hpp"

#include <algorithm>
#include <string>

#include "ntn/spectral/error.hpp"
#include "segments.hpp"

namespace ntn::spectral {

Frf frf_h1(Welch& welch, std::span<const double> input, std::span<const double> output) {
  if (input.size() != output.size())
    throw Error("input and output differ in length (" + std::to_string(input.size()) + " and " +
                std::to_string(output.size()) + " samples)");
  const Grid g = welch.grid(input.size());
  detail::check_finite(input, g.fs, "the input channel");
  detail::check_finite(output, g.fs, "the output channel");
  const std::size_t lines = g.lines();
  Frf f{g,
        {},
        {},
        std::vector<double>(lines, 0.0),
        std::vector<double>(lines, 0.0),
        std::vector<std::complex<double>>(lines, 0.0)};
  std::vector<std::complex<double>> xs(lines);
  std::vector<std::complex<double>> ys(lines);
  for (std::size_t m = 0; m < g.segments; ++m) {
    welch.segment_spectrum(input, m, xs);
    welch.segment_spectrum(output, m, ys);
    for (std::size_t k = 0; k < lines; ++k) {
      const std::complex<double> x = xs[k];
      const std::complex<double> y = ys[k];
      f.gxx[k] += x.real() * x.real() + x.imag() * x.imag();
      f.gyy[k] += y.real() * y.real() + y.imag() * y.imag();
      f.gxy[k] += std::complex<double>(x.real() * y.real() + x.imag() * y.imag(),
                                       x.real() * y.imag() - x.imag() * y.real());
    }
  }
  const double inv_k = 1 / static_cast<double>(g.segments);
  f.h.assign(lines, 0.0);
  f.coherence.assign(lines, 0.0);
  for (std::size_t k = 0; k < lines; ++k) {
    f.gxx[k] *= inv_k;
    f.gyy[k] *= inv_k;
    f.gxy[k] *= inv_k;
    if (f.gxx[k] > 0) f.h[k] = f.gxy[k] / f.gxx[k];
    const double d = f.gxx[k] * f.gyy[k];
    // |G_xy|^2 <= G_xx G_yy (Cauchy-Schwarz over the segments); min() removes rounding above 1.
    if (d > 0) f.coherence[k] = std::min(1.0, std::norm(f.gxy[k]) / d);
  }
  return f;
}

Frf frf_h1(std::span<const double> input, std::span<const double> output, double fs,
           const WelchOptions& options) {
  Welch w(fs, options);
  return frf_h1(w, input, output);
}

}  // namespace ntn::spectral
