// Damped modes: frequency within 0.1 % and damping by half-power within 10 % (the issue's
// tolerances), for a free decay of two modes and for an oscillator under white noise.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "ntn/spectral/amplitude.hpp"
#include "ntn/spectral/peaks.hpp"
#include "ntn/spectral/welch.hpp"
#include "signals.hpp"

namespace ntn::spectral {
namespace damping_test {

// x(t) = sum_j a_j exp(-zeta_j w_j t) cos(w_dj t + phi_j), two modes (2 Hz 1 %, 7.3 Hz 2 %),
// 100 Hz for 200 s: both have decayed below exp(-25) by the end, so the rectangular window
// truncates nothing and the DFT samples the decay's exact transform, whose squared magnitude
// near w_dj is the Lorentzian 1 / ((w - w_dj)^2 + (zeta w)^2): peak at f_dj, half-power
// half-width zeta w_j, so (f2 - f1) / (2 f_peak) = zeta / sqrt(1 - zeta^2). Lines are 0.005 Hz,
// the half-power bandwidths 8 and 58 lines.
// Tolerances: frequency 0.1 % (issue) against f_dj (f_nj differs by 0.005 % and 0.02 %);
// damping 10 % (issue) against zeta_j. Measured: 0.007 % and 0.005 %, 0.03 % and 0.7 %.
TEST(Damping, FreeDecayOfTwoModes) {
  const double fs = 100;
  const std::size_t n = 20000;
  struct Mode {
    double f, zeta, a, phi;
  };
  const std::vector<Mode> modes{{2.0, 0.01, 1.0, 0.3}, {7.3, 0.02, 0.6, -1.1}};
  std::vector<double> x(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / fs;
    for (const Mode& m : modes) {
      const double w = 2 * std::numbers::pi * m.f;
      const double wd = w * std::sqrt(1 - m.zeta * m.zeta);
      x[i] += m.a * std::exp(-m.zeta * w * t) * std::cos(wd * t + m.phi);
    }
  }
  const Spectrum a =
      amplitude_spectrum(x, fs, {.window = Window::kRectangular, .detrend = Detrend::kNone});
  const auto peaks = find_peaks(a, {.f_max = 20, .min_prominence = 3});
  ASSERT_EQ(peaks.size(), 2u);
  for (std::size_t j = 0; j < 2; ++j) {
    const double fd = modes[j].f * std::sqrt(1 - modes[j].zeta * modes[j].zeta);
    EXPECT_NEAR(peaks[j].frequency, fd, 1e-3 * fd) << "mode " << j;
    const auto hp = half_power(a, peaks[j]);
    ASSERT_TRUE(hp.has_value());
    EXPECT_NEAR(hp->damping, modes[j].zeta, 0.1 * modes[j].zeta) << "mode " << j;
    EXPECT_LT(hp->resolution_ratio, 0.2);
  }
}

// An oscillator (5 Hz, 2 %) under white noise, simulated exactly (signals.hpp, zero-order hold)
// at 20 Hz for 2^22 samples (58 h); Welch, Hann, 2048-sample segments, 50 % overlap: 4095
// averages. Choices: lines of 0.0098 Hz make B_e / B_r = 0.0146 / 0.2 = 0.07, a half-power bias
// of +0.5 % (peaks.hpp); 4095 averages leave a random error of about 1.6 % per line, which moves
// each half-power crossing by about 0.2 line and the damping by about 2 % (1 sigma).
// Truth: the peak of the exact discrete |H|^2 (golden-section search on signals.hpp's transfer
// function; it sits 0.04 % below f_n, at f_n sqrt(1 - 2 zeta^2) for the continuous oscillator)
// and zeta. Tolerances: 0.1 % and 10 % (issue), 5 sigma of the random error for the damping.
TEST(Damping, OscillatorUnderWhiteNoise) {
  const double fs = 20;
  const test::Sdof sdof(5.0, 0.02, 1 / fs);
  const auto x = sdof.displacement(test::white_noise(std::size_t{1} << 22, 1.0, 21));
  WelchOptions o;
  o.segment = 2048;
  const Spectrum p = welch_psd(x, fs, o);
  const auto peaks = find_peaks(p, {.relative_threshold = 0.1, .min_prominence = 10});
  ASSERT_EQ(peaks.size(), 1u);
  const double f_peak = sdof.peak_frequency(4.5, 5.5);
  EXPECT_NEAR(peaks[0].frequency, f_peak, 1e-3 * f_peak);
  const auto hp = half_power(p, peaks[0]);
  ASSERT_TRUE(hp.has_value());
  EXPECT_NEAR(hp->damping, 0.02, 0.1 * 0.02);
  EXPECT_NEAR(hp->resolution_ratio, p.grid.enbw_hz / (2 * 0.02 * 5.0), 0.01);
}

// The resolution bias peaks.hpp states, seen: the same oscillator with segments so short that
// B_e / B_r = 1.1; the result is too wide and says so (resolution_ratio, computed from the
// widened band, > 0.6). Truth: the Lorentzian convolved with the Hann power kernel has a
// half-power band 1.66 times the true one (numerical convolution, as for peaks.hpp's table).
// Tolerance: 1.5 to 1.85 times zeta: at 2.2 lines per half-power band the linear interpolation
// of the crossings and the peak fit add about +5 % to 1.66 (1.73 to 1.76 over 8 noise seeds).
TEST(Damping, ShortSegmentsOverestimateTheDamping) {
  const double fs = 20;
  const test::Sdof sdof(5.0, 0.02, 1 / fs);
  const auto x = sdof.displacement(test::white_noise(std::size_t{1} << 20, 1.0, 22));
  WelchOptions o;
  o.segment = 136;  // B_e = 1.5 x 20 / 136 = 0.22 Hz, B_r = 0.2 Hz
  const Spectrum p = welch_psd(x, fs, o);
  const auto peaks = find_peaks(p, {.relative_threshold = 0.1, .min_prominence = 10});
  ASSERT_EQ(peaks.size(), 1u);
  const auto hp = half_power(p, peaks[0]);
  ASSERT_TRUE(hp.has_value());
  EXPECT_GT(hp->damping, 1.5 * 0.02);
  EXPECT_LT(hp->damping, 1.85 * 0.02);
  EXPECT_GT(hp->resolution_ratio, 0.6);
}

}  // namespace damping_test
}  // namespace ntn::spectral
