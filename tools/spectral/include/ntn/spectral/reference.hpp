// Reference implementations for tests and benchmarks: the same Welch estimate with the DFT
// summed directly, O(nfft^2) per segment, instead of FFTW.
#pragma once

#include <complex>
#include <cstddef>
#include <span>
#include <vector>

#include "ntn/spectral/spectrum.hpp"
#include "ntn/spectral/welch.hpp"

namespace ntn::spectral {

// X[k] = sum_n x[n] exp(-2 pi i k n / N), k = 0..N/2, summed in n order with the twiddle
// exp(-2 pi i ((k n) mod N) / N) from a table (so no large arguments to sin and cos).
std::vector<std::complex<double>> naive_dft(std::span<const double> x);

// welch_psd with naive_dft; the first `max_segments` segments only when it is not 0 (grid.segments
// says how many were used).
Spectrum welch_psd_naive(std::span<const double> x, double fs, const WelchOptions& options,
                         std::size_t max_segments = 0);

}  // namespace ntn::spectral
