// One-sided spectra on the DFT lines f_k = k fs / nfft, k = 0..nfft/2, and how they were made.
#pragma once

#include <complex>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "ntn/spectral/window.hpp"

namespace ntn::spectral {

// The lines of a spectrum and the averaging behind it.
struct Grid {
  double fs = 0;             // sample rate, Hz
  std::size_t nfft = 0;      // DFT length (segment plus zero padding)
  std::size_t segment = 0;   // samples per segment
  std::size_t step = 0;      // samples between segment starts
  std::size_t segments = 0;  // segments averaged
  Window window = Window::kHann;
  double enbw_hz = 0;  // equivalent noise bandwidth of one line, Hz (B_e)

  std::size_t lines() const { return nfft / 2 + 1; }
  double df() const { return fs / static_cast<double>(nfft); }  // line spacing, Hz
  double frequency(std::size_t k) const { return static_cast<double>(k) * df(); }  // Hz
};

// kPower: a PSD (units^2/Hz) or another power-like quantity (singular values of a spectral
// matrix); half power is value / 2. kAmplitude: peak amplitude in signal units; half power is
// value / sqrt(2).
enum class Scale : std::uint8_t { kPower, kAmplitude };

struct Spectrum {
  Grid grid;
  Scale scale = Scale::kPower;
  std::vector<double> values;  // one per line
};

// G_xy(f_k), one per line (Welch CSD; G_xy = (2 / (fs U K)) sum conj(X) Y).
struct CrossSpectrum {
  Grid grid;
  std::vector<std::complex<double>> values;
};

// The cross-spectral matrix G(f_k) of n channels: entry (i, j) is G_{x_i x_j}; Hermitian.
struct CrossSpectralMatrix {
  Grid grid;
  std::size_t channels = 0;
  std::vector<std::complex<double>> values;  // line k: n x n column-major from k n^2

  Eigen::Map<const Eigen::MatrixXcd> at(std::size_t k) const {
    const auto n = static_cast<Eigen::Index>(channels);
    return {values.data() + k * channels * channels, n, n};
  }
  Spectrum auto_spectrum(std::size_t i) const;  // G_{x_i x_i}, real
};

}  // namespace ntn::spectral
