// Shared by the FFTW and the naive Welch paths: option checks, segmentation, detrending and
// windowing, input checks, one-sided line weights. Private to the library.
#pragma once

#include <cmath>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "ntn/spectral/error.hpp"
#include "ntn/spectral/spectrum.hpp"
#include "ntn/spectral/welch.hpp"

namespace ntn::spectral::detail {

// Checks fs and the options; returns them with segment and nfft resolved.
WelchOptions resolve(double fs, const WelchOptions& options);

// The grid of `samples` with resolved options; throws Error when the record is too short.
Grid make_grid(double fs, const WelchOptions& resolved, double enbw_bins, std::size_t samples);

// Throws Error naming the first non-finite sample (index, time, channel when given).
void check_finite(std::span<const double> x, double fs, const std::string& what);

// Samples between segment starts: segment - floor(overlap segment), at least 1.
std::size_t segment_step(const WelchOptions& resolved);

// Writes segment m of x (from m grid.step, grid.segment samples), detrended and windowed, to
// out[0..segment) and zeros to the rest of out.
void prepare_segment(std::span<const double> x, std::size_t m, const Grid& grid, Detrend kind,
                     const std::vector<double>& window, std::span<double> out);

// Removes the mean or the least-squares line from y in place.
void detrend(std::span<double> y, Detrend kind);

// c_k: 1 at DC and at nfft/2 when nfft is even, 2 elsewhere (one-sided folding).
inline double one_sided_weight(std::size_t k, std::size_t nfft) {
  return (k == 0 || 2 * k == nfft) ? 1.0 : 2.0;
}

}  // namespace ntn::spectral::detail
