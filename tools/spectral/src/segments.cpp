#include "segments.hpp"

#include <algorithm>
#include <cstdio>

namespace ntn::spectral::detail {

namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

}  // namespace

WelchOptions resolve(double fs, const WelchOptions& options) {
  if (!(fs > 0) || !std::isfinite(fs))
    throw Error("the sample rate must be positive, got " + num(fs));
  WelchOptions r = options;
  if (r.segment == 0) {
    if (!(r.resolution_hz > 0) || !std::isfinite(r.resolution_hz))
      throw Error("give a segment length or a resolution (Hz) for the spectrum");
    if (!(fs / r.resolution_hz <= 1e9))
      throw Error("a resolution of " + num(r.resolution_hz) + " Hz at " + num(fs) +
                  " Hz needs more than 10^9 samples per segment");
    r.segment = static_cast<std::size_t>(std::ceil(fs / r.resolution_hz));
  }
  if (r.segment < 2) throw Error("a segment needs at least 2 samples");
  if (!(r.overlap >= 0 && r.overlap < 1))
    throw Error("overlap must be in [0, 1), got " + num(r.overlap));
  if (r.nfft == 0) r.nfft = r.segment;
  if (r.nfft < r.segment)
    throw Error("nfft (" + std::to_string(r.nfft) + ") is shorter than the segment (" +
                std::to_string(r.segment) + ")");
  return r;
}

Grid make_grid(double fs, const WelchOptions& resolved, double enbw_bins, std::size_t samples) {
  if (samples < resolved.segment) {
    throw Error("the record is too short for the requested resolution: " + std::to_string(samples) +
                " samples (" + num(static_cast<double>(samples) / fs) + " s at " + num(fs) +
                " Hz), but one segment of " + std::to_string(resolved.segment) + " samples (" +
                num(static_cast<double>(resolved.segment) / fs) + " s) is needed for " +
                num(fs / static_cast<double>(resolved.segment)) + " Hz resolution");
  }
  Grid g;
  g.fs = fs;
  g.nfft = resolved.nfft;
  g.segment = resolved.segment;
  g.step = segment_step(resolved);
  g.segments = (samples - g.segment) / g.step + 1;
  g.window = resolved.window;
  g.enbw_hz = enbw_bins * fs / static_cast<double>(g.segment);
  return g;
}

void check_finite(std::span<const double> x, double fs, const std::string& what) {
  for (std::size_t n = 0; n < x.size(); ++n) {
    if (!std::isfinite(x[n])) {
      throw Error((what.empty() ? std::string("the data") : what) + " has " +
                  (std::isnan(x[n]) ? "a NaN" : "an infinite value") + " at sample " +
                  std::to_string(n) + " (t = " + num(static_cast<double>(n) / fs) +
                  " s from the start); a spectrum needs finite data");
    }
  }
}

void detrend(std::span<double> y, Detrend kind) {
  if (kind == Detrend::kNone || y.empty()) return;
  const double l = static_cast<double>(y.size());
  double mean = 0;
  for (double v : y)
    mean += v;
  mean /= l;
  if (kind == Detrend::kMean) {
    for (double& v : y)
      v -= mean;
    return;
  }
  // Least-squares line about the centre c = (L-1)/2: slope = sum (n-c) y / sum (n-c)^2.
  const double c = 0.5 * (l - 1);
  double sty = 0;
  for (std::size_t n = 0; n < y.size(); ++n)
    sty += (static_cast<double>(n) - c) * y[n];
  const double stt = l * (l * l - 1) / 12;
  const double slope = stt > 0 ? sty / stt : 0.0;
  for (std::size_t n = 0; n < y.size(); ++n)
    y[n] -= mean + slope * (static_cast<double>(n) - c);
}

std::size_t segment_step(const WelchOptions& resolved) {
  const auto shared = static_cast<std::size_t>(
      std::floor(resolved.overlap * static_cast<double>(resolved.segment)));
  return std::max<std::size_t>(1, resolved.segment - shared);
}

void prepare_segment(std::span<const double> x, std::size_t m, const Grid& grid, Detrend kind,
                     const std::vector<double>& window, std::span<double> out) {
  const std::size_t l = grid.segment;
  std::copy_n(x.begin() + static_cast<std::ptrdiff_t>(m * grid.step), l, out.begin());
  detrend(out.first(l), kind);
  for (std::size_t n = 0; n < l; ++n)
    out[n] *= window[n];
  std::fill(out.begin() + static_cast<std::ptrdiff_t>(l), out.end(), 0.0);
}

}  // namespace ntn::spectral::detail
