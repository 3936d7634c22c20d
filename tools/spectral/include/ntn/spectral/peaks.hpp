// Peaks of a spectrum with sub-line frequency interpolation, and damping by half-power bandwidth.
//
// Interpolation: a parabola fitted by least squares to the logarithms of the values on the lines
// k-h..k+h around a local maximum k, h the mean of the numbers of lines above half power (v[k]/2,
// or v[k]/sqrt(2) for an amplitude spectrum) on its two sides, at least 1 (for h = 1, the
// parabola through the three values). Its vertex gives the frequency; the value there comes from
// the same fit over the lines within 1 dB (0.8 in power), which reads a Lorentzian's top within
// 0.3 % where the half-power band would read it 3 % low. It works on any positive spectrum
// (averaged PSD, singular value spectrum, amplitude), where estimators that need the complex DFT
// (Jacobsen, Quinn) cannot be used; it is exact for a Gaussian-shaped peak.
// - A tone is a few lines wide (h = 1): the bias is at most 0.017 line (Hann, Hamming), 0.007
//   (Blackman), 0.15 (flat-top), 0.17 (rectangular) (tests/spectral/tone_test.cpp), so the
//   relative frequency error is below 0.1 % for a Hann peak from line 17 on.
// - A damped mode is a Lorentzian B_r = 2 zeta f_n wide, B_r/df lines. Three lines of an averaged
//   PSD curve too little for their random error when B_r spans many lines; the fit over the
//   whole half-power band averages that error down (about 3x for 10 lines), and its bias for a
//   Lorentzian stays below 0.06 line (tone_test.cpp) for any width.
//
// Half power: from the interpolated peak value P, the first crossings of P/2 (P/sqrt(2) for an
// amplitude spectrum) on each side, interpolated linearly between lines, give f1 < f2, and
// zeta = (f2 - f1) / (2 f_peak). The window's resolution bandwidth B_e (grid.enbw_hz) widens a
// mode's half-power bandwidth B_r = 2 zeta f_n: for Hann, by about 0.85 (B_e/B_r)^2 relative
// (Be/Br = 0.1: +0.9 %, 0.25: +5 %, 0.5: +19 %, 1: +57 %). HalfPower::resolution_ratio reports
// B_e / B_r; keep it below about 0.25 (a longer segment) for a damping within 5 %. Random error
// (few averages) and neighbouring modes closer than a few bandwidths bias it further.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "ntn/spectral/spectrum.hpp"

namespace ntn::spectral {

struct PeakOptions {
  double f_min = 0;                                        // band, Hz
  double f_max = std::numeric_limits<double>::infinity();  // Hz
  double relative_threshold = 0;  // keep peaks >= this x the largest value in the band
  double min_prominence = 1;      // keep peaks >= this x the higher of their two bases
  std::size_t max_peaks = 0;      // 0: all; else the largest ones (still in frequency order)
};

struct Peak {
  std::size_t line = 0;   // the local maximum
  double frequency = 0;   // interpolated, Hz
  double value = 0;       // interpolated peak value, in the spectrum's units
  double prominence = 0;  // value / the higher of the lowest values between it and a higher
                          // value (or the band edge) on either side; >= 1
};

// Local maxima (v[k-1] < v[k] >= v[k+1], lines 1..lines-2, inside the band) that pass the
// threshold and the prominence, in frequency order. Throws Error on an empty band or f_min >
// f_max.
std::vector<Peak> find_peaks(const Spectrum& spectrum, const PeakOptions& options = {});

// The interpolated peak at line k (1 <= k <= lines-2); the line itself when the values around
// it are not positive or do not curve down.
Peak interpolate_peak(const Spectrum& spectrum, std::size_t k);

struct HalfPower {
  double f_low = 0;             // Hz
  double f_high = 0;            // Hz
  double damping = 0;           // zeta, fraction of critical
  double resolution_ratio = 0;  // B_e / (f_high - f_low)
};

// Empty when a crossing is not found before the spectrum ends or rises above the peak line's
// value (a higher neighbour overlaps), or the spectrum has no value at the peak.
std::optional<HalfPower> half_power(const Spectrum& spectrum, const Peak& peak);

}  // namespace ntn::spectral
