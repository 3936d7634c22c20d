// Welch's averaged, modified periodogram (Welch 1967): one-sided PSD in units^2/Hz (density
// scaling), cross-spectral densities and the cross-spectral matrix of several channels.
//
// With segments x_m[n] (n = 0..L-1) detrended and multiplied by the window w,
// X_m[k] = sum_n w[n] x_m[n] exp(-2 pi i k n / nfft), U = sum_n w[n]^2, K segments:
//
//   G_xy[k] = c_k / (fs U K) * sum_m conj(X_m[k]) Y_m[k],  c_k = 1 at k = 0 and k = nfft/2 (nfft
//   even), 2 otherwise;  G_xx = G_xy with y = x.
//
// So sum_k G_xx[k] df = (1/K) sum_m sum_n (w x_m)^2 / U (Parseval): the PSD integrates to the
// mean square of the detrended record (Bendat & Piersol, "Random Data", ch. 11).
#pragma once

#include <complex>
#include <cstddef>
#include <span>
#include <vector>

#include "ntn/spectral/fft.hpp"
#include "ntn/spectral/spectrum.hpp"
#include "ntn/spectral/window.hpp"

namespace ntn::spectral {

// Per segment, before the window: nothing, the mean, or the least-squares line removed.
enum class Detrend : std::uint8_t { kNone, kMean, kLinear };

struct WelchOptions {
  std::size_t segment = 0;   // samples per segment; 0: ceil(fs / resolution_hz)
  double resolution_hz = 0;  // the line spacing asked for when segment = 0
  double overlap = 0.5;      // fraction of a segment shared with the next, in [0, 1)
  std::size_t nfft = 0;      // DFT length >= segment (zero padding); 0: the segment
  Window window = Window::kHann;
  Detrend detrend = Detrend::kMean;
  Planner planner = Planner::kEstimate;
};

// Segments: starts 0, s, 2s, ... with s = segment - floor(overlap * segment), as many as fit
// whole; samples after the last whole segment are not used.
//
// A Welch object owns the window, one FFTW plan of size nfft and its buffers: make it once per
// (fs, options) and call it for every channel. Not for concurrent use (see fft.hpp).
// Every call checks its input and throws Error: a non-finite sample (index and time), channels of
// unequal length, or a record shorter than one segment ("too short for the requested
// resolution", with the duration needed).
class Welch {
 public:
  // Throws Error on fs <= 0, no segment length, segment < 2, nfft < segment, overlap outside
  // [0, 1).
  Welch(double fs, const WelchOptions& options);

  const WelchOptions& options() const { return options_; }
  const std::vector<double>& window() const { return window_; }
  // The grid for a record of `samples`; throws Error when it is shorter than one segment.
  Grid grid(std::size_t samples) const;

  Spectrum psd(std::span<const double> x);
  std::vector<Spectrum> psd(std::span<const std::vector<double>> channels);
  CrossSpectrum csd(std::span<const double> x, std::span<const double> y);
  CrossSpectralMatrix matrix(std::span<const std::vector<double>> channels);

  // The scaled one-sided DFT of segment m of x (detrended, windowed), for the FRF and tests:
  // out[k] = sqrt(c_k / (fs U)) X_m[k], so conj(out_x) out_y summed over m, divided by K, is
  // G_xy.
  void segment_spectrum(std::span<const double> x, std::size_t m,
                        std::span<std::complex<double>> out);

 private:
  Spectrum psd_of_finite(std::span<const double> x);

  double fs_;
  WelchOptions options_;
  std::vector<double> window_;
  double u_ = 0;          // sum of w^2
  double enbw_bins_ = 0;  // of the window
  RealFft fft_;
};

Spectrum welch_psd(std::span<const double> x, double fs, const WelchOptions& options = {});
CrossSpectrum cross_spectral_density(std::span<const double> x, std::span<const double> y,
                                     double fs, const WelchOptions& options = {});
CrossSpectralMatrix cross_spectral_matrix(std::span<const std::vector<double>> channels, double fs,
                                          const WelchOptions& options = {});

}  // namespace ntn::spectral
