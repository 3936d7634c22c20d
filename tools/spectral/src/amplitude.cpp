#include "ntn/spectral/amplitude.hpp"

#include <cmath>
#include <string>

#include "ntn/spectral/error.hpp"
#include "segments.hpp"

namespace ntn::spectral {

Spectrum amplitude_spectrum(std::span<const double> x, double fs, const AmplitudeOptions& options) {
  if (!(fs > 0) || !std::isfinite(fs)) throw Error("the sample rate must be positive");
  if (x.size() < 2) throw Error("an amplitude spectrum needs at least 2 samples");
  detail::check_finite(x, fs, "the channel");
  const std::size_t nfft = options.nfft == 0 ? x.size() : options.nfft;
  if (nfft < x.size())
    throw Error("nfft (" + std::to_string(nfft) + ") is shorter than the record (" +
                std::to_string(x.size()) + " samples)");

  const std::vector<double> w = make_window(options.window, x.size());
  double sum_w = 0;
  for (double v : w)
    sum_w += v;
  Grid g;
  g.fs = fs;
  g.nfft = nfft;
  g.segment = x.size();
  g.step = x.size();
  g.segments = 1;
  g.window = options.window;
  g.enbw_hz = window_properties(w).enbw_bins * fs / static_cast<double>(x.size());

  RealFft fft(nfft, options.planner);
  detail::prepare_segment(x, 0, g, options.detrend, w, fft.input());
  fft.execute();
  std::vector<double> a(g.lines());
  for (std::size_t k = 0; k < a.size(); ++k)
    a[k] = detail::one_sided_weight(k, nfft) * std::abs(fft.output()[k]) / sum_w;
  return {g, Scale::kAmplitude, std::move(a)};
}

}  // namespace ntn::spectral
