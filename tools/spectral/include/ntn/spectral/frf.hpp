// Frequency response function by the H1 estimator and the ordinary coherence (Bendat & Piersol,
// "Random Data", ch. 9):
//
//   H1 = G_xy / G_xx,   gamma^2 = |G_xy|^2 / (G_xx G_yy),
//
// x the input channel, y the output, Welch averages of the same segments. H1 is unbiased by noise
// on the output; with uncorrelated output noise n, gamma^2 = |H|^2 G_xx / (|H|^2 G_xx + G_nn).
// With one segment gamma^2 = 1 identically: coherence needs averaging.
#pragma once

#include <complex>
#include <span>
#include <vector>

#include "ntn/spectral/spectrum.hpp"
#include "ntn/spectral/welch.hpp"

namespace ntn::spectral {

struct Frf {
  Grid grid;
  std::vector<std::complex<double>> h;  // H1, output units / input units; 0 where G_xx = 0
  std::vector<double> coherence;        // gamma^2 in [0, 1]; 0 where G_xx G_yy = 0
  std::vector<double> gxx, gyy;         // auto-spectra, units^2/Hz
  std::vector<std::complex<double>> gxy;
};

Frf frf_h1(Welch& welch, std::span<const double> input, std::span<const double> output);
Frf frf_h1(std::span<const double> input, std::span<const double> output, double fs,
           const WelchOptions& options = {});

}  // namespace ntn::spectral
