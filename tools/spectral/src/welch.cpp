#include "ntn/spectral/welch.hpp"

#include <algorithm>
#include <cmath>

#include "segments.hpp"

namespace ntn::spectral {

namespace {

double sum_of_squares(const std::vector<double>& w) {
  double s = 0;
  for (double v : w)
    s += v * v;
  return s;
}

std::string channel_name(std::size_t c) {
  return "channel " + std::to_string(c);
}

}  // namespace

Spectrum CrossSpectralMatrix::auto_spectrum(std::size_t i) const {
  if (i >= channels) throw Error("auto_spectrum: no channel " + std::to_string(i));
  Spectrum s{grid, Scale::kPower, std::vector<double>(grid.lines())};
  for (std::size_t k = 0; k < s.values.size(); ++k)
    s.values[k] = values[k * channels * channels + i * channels + i].real();
  return s;
}

Welch::Welch(double fs, const WelchOptions& options)
    : fs_(fs),
      options_(detail::resolve(fs, options)),
      window_(make_window(options_.window, options_.segment)),
      u_(sum_of_squares(window_)),
      enbw_bins_(window_properties(window_).enbw_bins),
      fft_(options_.nfft, options_.planner) {}

Grid Welch::grid(std::size_t samples) const {
  return detail::make_grid(fs_, options_, enbw_bins_, samples);
}

Spectrum Welch::psd(std::span<const double> x) {
  detail::check_finite(x, fs_, "the channel");
  return psd_of_finite(x);
}

Spectrum Welch::psd_of_finite(std::span<const double> x) {
  const Grid g = grid(x.size());
  std::vector<double> acc(g.lines(), 0.0);
  for (std::size_t m = 0; m < g.segments; ++m) {
    detail::prepare_segment(x, m, g, options_.detrend, window_, fft_.input());
    fft_.execute();
    const std::span<const std::complex<double>> X = fft_.output();
    for (std::size_t k = 0; k < acc.size(); ++k)
      acc[k] += X[k].real() * X[k].real() + X[k].imag() * X[k].imag();
  }
  const double scale = 1 / (fs_ * u_ * static_cast<double>(g.segments));
  for (std::size_t k = 0; k < acc.size(); ++k)
    acc[k] *= detail::one_sided_weight(k, g.nfft) * scale;
  return {g, Scale::kPower, std::move(acc)};
}

std::vector<Spectrum> Welch::psd(std::span<const std::vector<double>> channels) {
  std::vector<Spectrum> out;
  out.reserve(channels.size());
  for (std::size_t c = 0; c < channels.size(); ++c) {
    detail::check_finite(channels[c], fs_, channel_name(c));
    out.push_back(psd_of_finite(channels[c]));
  }
  return out;
}

CrossSpectrum Welch::csd(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size())
    throw Error("the two channels differ in length (" + std::to_string(x.size()) + " and " +
                std::to_string(y.size()) + " samples)");
  detail::check_finite(x, fs_, "the first channel");
  detail::check_finite(y, fs_, "the second channel");
  const Grid g = grid(x.size());
  std::vector<std::complex<double>> xs(g.lines());
  std::vector<std::complex<double>> acc(g.lines(), 0.0);
  for (std::size_t m = 0; m < g.segments; ++m) {
    detail::prepare_segment(x, m, g, options_.detrend, window_, fft_.input());
    fft_.execute();
    std::copy(fft_.output().begin(), fft_.output().end(), xs.begin());
    detail::prepare_segment(y, m, g, options_.detrend, window_, fft_.input());
    fft_.execute();
    const std::span<const std::complex<double>> Y = fft_.output();
    for (std::size_t k = 0; k < acc.size(); ++k) {
      // conj(X) Y written out: no library call for NaN/inf recovery in the inner loop.
      acc[k] += std::complex<double>(xs[k].real() * Y[k].real() + xs[k].imag() * Y[k].imag(),
                                     xs[k].real() * Y[k].imag() - xs[k].imag() * Y[k].real());
    }
  }
  const double scale = 1 / (fs_ * u_ * static_cast<double>(g.segments));
  for (std::size_t k = 0; k < acc.size(); ++k)
    acc[k] *= detail::one_sided_weight(k, g.nfft) * scale;
  return {g, std::move(acc)};
}

CrossSpectralMatrix Welch::matrix(std::span<const std::vector<double>> channels) {
  const std::size_t n = channels.size();
  if (n == 0) throw Error("a cross-spectral matrix needs at least one channel");
  for (std::size_t c = 0; c < n; ++c) {
    if (channels[c].size() != channels[0].size())
      throw Error("channel " + std::to_string(c) + " has " + std::to_string(channels[c].size()) +
                  " samples, channel 0 has " + std::to_string(channels[0].size()));
    detail::check_finite(channels[c], fs_, channel_name(c));
  }
  const Grid g = grid(channels[0].size());
  const std::size_t lines = g.lines();
  std::vector<std::complex<double>> spec(n * lines);  // this segment's X_c[k] at c lines + k
  std::vector<std::complex<double>> acc(lines * n * n, 0.0);
  for (std::size_t m = 0; m < g.segments; ++m) {
    for (std::size_t c = 0; c < n; ++c) {
      detail::prepare_segment(channels[c], m, g, options_.detrend, window_, fft_.input());
      fft_.execute();
      std::copy(fft_.output().begin(), fft_.output().end(),
                spec.begin() + static_cast<std::ptrdiff_t>(c * lines));
    }
    // Upper triangle (i <= j) of conj(X_i) X_j; the lower one is its conjugate.
    for (std::size_t k = 0; k < lines; ++k) {
      std::complex<double>* gk = acc.data() + k * n * n;
      for (std::size_t j = 0; j < n; ++j) {
        const std::complex<double> xj = spec[j * lines + k];
        for (std::size_t i = 0; i <= j; ++i) {
          const std::complex<double> xi = spec[i * lines + k];
          gk[j * n + i] += std::complex<double>(xi.real() * xj.real() + xi.imag() * xj.imag(),
                                                xi.real() * xj.imag() - xi.imag() * xj.real());
        }
      }
    }
  }
  const double scale = 1 / (fs_ * u_ * static_cast<double>(g.segments));
  for (std::size_t k = 0; k < lines; ++k) {
    std::complex<double>* gk = acc.data() + k * n * n;
    const double s = detail::one_sided_weight(k, g.nfft) * scale;
    for (std::size_t j = 0; j < n; ++j) {
      for (std::size_t i = 0; i <= j; ++i) {
        gk[j * n + i] *= s;
        gk[i * n + j] = std::conj(gk[j * n + i]);
      }
    }
  }
  return {g, n, std::move(acc)};
}

void Welch::segment_spectrum(std::span<const double> x, std::size_t m,
                             std::span<std::complex<double>> out) {
  const Grid g = grid(x.size());
  if (m >= g.segments)
    throw Error("segment " + std::to_string(m) + " of " + std::to_string(g.segments));
  if (out.size() < g.lines()) throw Error("segment_spectrum: output shorter than the lines");
  detail::prepare_segment(x, m, g, options_.detrend, window_, fft_.input());
  fft_.execute();
  const std::span<const std::complex<double>> X = fft_.output();
  for (std::size_t k = 0; k < g.lines(); ++k)
    out[k] = X[k] * std::sqrt(detail::one_sided_weight(k, g.nfft) / (fs_ * u_));
}

Spectrum welch_psd(std::span<const double> x, double fs, const WelchOptions& options) {
  Welch w(fs, options);
  return w.psd(x);
}

CrossSpectrum cross_spectral_density(std::span<const double> x, std::span<const double> y,
                                     double fs, const WelchOptions& options) {
  Welch w(fs, options);
  return w.csd(x, y);
}

CrossSpectralMatrix cross_spectral_matrix(std::span<const std::vector<double>> channels, double fs,
                                          const WelchOptions& options) {
  Welch w(fs, options);
  return w.matrix(channels);
}

}  // namespace ntn::spectral
