// Amplitude spectrum of a whole record by one DFT, scaled so a sinusoid a cos(2 pi f t + phi) on
// a line reads a (amplitude-correct, "peak" scaling):
//
//   A[k] = c_k |X[k]| / sum(w),  c_k = 1 at k = 0 and k = nfft/2 (nfft even), 2 otherwise.
//
// Between lines a tone reads less, by window_response(w, delta) (down to 1 - scalloping_loss at
// half a line): use the flat-top window for amplitudes, Hann or Blackman for frequencies.
#pragma once

#include <cstddef>
#include <span>

#include "ntn/spectral/fft.hpp"
#include "ntn/spectral/spectrum.hpp"
#include "ntn/spectral/welch.hpp"
#include "ntn/spectral/window.hpp"

namespace ntn::spectral {

struct AmplitudeOptions {
  Window window = Window::kHann;
  Detrend detrend = Detrend::kMean;
  std::size_t nfft = 0;  // >= the record (zero padding); 0: the record length
  Planner planner = Planner::kEstimate;
};

// Throws Error on fs <= 0, fewer than 2 samples, a non-finite sample, nfft < samples.
Spectrum amplitude_spectrum(std::span<const double> x, double fs,
                            const AmplitudeOptions& options = {});

}  // namespace ntn::spectral
