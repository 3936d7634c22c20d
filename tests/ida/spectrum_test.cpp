// Intensity measures: the pseudo-spectral acceleration of the Nigam-Jennings recurrence
// against an independent fine-step Newmark integration of the same oscillator under the shipped
// records, and against the closed-form step response; the peak ground acceleration.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "ntn/ida/spectrum.hpp"
#include "record.hpp"

namespace ntn::ida {
namespace spectrum_test {

const std::string kRecords = NTN_RECORDS_DIR;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Sa of the oscillator by Newmark's average acceleration (gamma 1/2, beta 1/4) with `substeps`
// steps per sample interval, ag linear between the samples, max |u| at the sample instants: the
// same input and the same instants as pseudo_spectral_acceleration, by another method.
double newmark_sa(const std::vector<double>& ag, double dt, double period, double zeta,
                  int substeps) {
  const double omega = 2 * std::numbers::pi / period;
  const double stiffness = omega * omega;
  const double damping = 2 * zeta * omega;
  const double h = dt / substeps;
  double u = 0;
  double v = 0;
  double a = -ag[0];  // at rest: u'' = -ag
  double peak = 0;
  for (std::size_t k = 1; k < ag.size(); ++k) {
    for (int s = 1; s <= substeps; ++s) {
      const double fraction = static_cast<double>(s) / substeps;
      const double ag_now = ag[k - 1] + (ag[k] - ag[k - 1]) * fraction;
      const double u_predicted = u + h * v + 0.25 * h * h * a;
      const double v_predicted = v + 0.5 * h * a;
      a = (-ag_now - damping * v_predicted - stiffness * u_predicted) /
          (1 + 0.5 * h * damping + 0.25 * h * h * stiffness);
      u = u_predicted + 0.25 * h * h * a;
      v = v_predicted + 0.5 * h * a;
    }
    peak = std::max(peak, std::abs(u));
  }
  return stiffness * peak;
}

io::Record read_record(const std::string& name) {
  const io::ReadResult r = io::read_at2(kRecords + "/" + name);
  if (!r.record) {
    ADD_FAILURE() << (r.error ? r.error->format() : name + ": no record");
    return {};
  }
  return *r.record;
}

// Newmark with 200 steps per sample (h = 1e-4 s) lengthens the period by (omega h)^2 / 12: 8e-7
// at T = 0.2 s, less at the longer periods; its phase error builds up only over the oscillator's
// memory (1 / (zeta omega), a few periods at 5 %), so it is far below the tolerance, 0.1 % (the
// issue's). Measured: 2.2e-6 at T = 0.2 s, 3e-7 or less at the others, each falling 4 times
// when Newmark's step is halved (it is Newmark's error).
void expect_matches_newmark(const std::string& name, double period) {
  const io::Record record = read_record(name);
  ASSERT_GT(record.values.size(), 1000u) << name;
  const double zeta = 0.05;
  const double sa = pseudo_spectral_acceleration(record.values, record.dt, period, zeta);
  const double reference = newmark_sa(record.values, record.dt, period, zeta, 200);
  std::printf("  %s T = %.1f s: Sa = %.6f g, Newmark %.6f g, relative difference %.2e\n",
              name.c_str(), period, sa, reference, std::abs(sa / reference - 1));
  EXPECT_GT(reference, 0.05) << name << " T = " << period;  // a response, not two zeros
  EXPECT_NEAR(sa, reference, 1e-3 * reference) << name << " T = " << period;
}

TEST(PseudoSpectralAcceleration, ElCentroMatchesFineStepNewmark) {
  for (const double period : {0.2, 0.5, 1.0, 2.0}) {
    expect_matches_newmark("elCentro.AT2", period);
  }
}

TEST(PseudoSpectralAcceleration, ArletaMatchesFineStepNewmark) {
  expect_matches_newmark("ARL360.AT2", 0.5);
}

// ag = a0 from t = 0: u(t) = -(a0 / omega^2) (1 - exp(-zeta omega t) (cos(wd t) +
// zeta omega / wd sin(wd t))), whose largest |u| is the first overshoot at t = pi / wd:
// Sa = a0 (1 + exp(-zeta pi / sqrt(1 - zeta^2))), 2 a0 undamped. dt puts that instant on a
// sample (pi / wd = steps_to_peak dt; a sample within rounding of the peak misses it by the
// square of that offset); the record runs on to a full damped period. Cases: omega dt from pi
// (the direct phi formulas) down to 3e-5 (their Taylor series; the textbook B coefficients would
// be 5e-8 off there).
// Tolerance 1e-10 relative: the recurrence is exact up to rounding, which accumulates over up to
// 2e5 steps; measured 6e-13 or less.
TEST(PseudoSpectralAcceleration, StepResponseClosedForm) {
  struct Case {
    double period;
    double zeta;
    int steps_to_peak;
  };
  const double a0 = 0.3;
  for (const Case c :
       {Case{1.0, 0, 50}, Case{0.2, 0, 1}, Case{0.2, 0, 2}, Case{0.5, 0, 5}, Case{20.0, 0, 100000},
        Case{1.0, 0.05, 50}, Case{0.3, 0.2, 3}, Case{10.0, 0.05, 50000}}) {
    const double omega = 2 * std::numbers::pi / c.period;
    const double omega_d = omega * std::sqrt(1 - c.zeta * c.zeta);
    const double dt = std::numbers::pi / omega_d / c.steps_to_peak;
    const std::vector<double> ag(static_cast<std::size_t>(2 * c.steps_to_peak + 1), a0);
    const double expected =
        a0 * (1 + std::exp(-c.zeta * std::numbers::pi / std::sqrt(1 - c.zeta * c.zeta)));
    const double sa = pseudo_spectral_acceleration(ag, dt, c.period, c.zeta);
    std::printf("  step T = %g s zeta = %g omega dt = %.1e: relative error %.1e\n", c.period,
                c.zeta, omega * dt, std::abs(sa / expected - 1));
    EXPECT_NEAR(sa, expected, 1e-10 * expected)
        << "T = " << c.period << " zeta = " << c.zeta << " dt = " << dt;
  }
}

TEST(PseudoSpectralAcceleration, RecordOfZerosGivesZero) {
  const std::vector<double> zeros(1000, 0.0);
  EXPECT_EQ(pseudo_spectral_acceleration(zeros, 0.01, 0.5, 0.05), 0.0);
}

// At rest at t = 0: a record of one sample has only that instant, u = 0 there.
TEST(PseudoSpectralAcceleration, ShortRecords) {
  const std::vector<double> one{0.4};
  EXPECT_EQ(pseudo_spectral_acceleration(one, 0.01, 0.5, 0.05), 0.0);
  EXPECT_EQ(pseudo_spectral_acceleration({}, 0.01, 0.5, 0.05), 0.0);
}

TEST(PseudoSpectralAcceleration, BadArgumentsGiveNaN) {
  const std::vector<double> ag{0.0, 0.1, -0.2, 0.05};
  const double inf = std::numeric_limits<double>::infinity();
  ASSERT_TRUE(std::isfinite(pseudo_spectral_acceleration(ag, 0.01, 0.5, 0.05)));  // the control
  EXPECT_TRUE(std::isnan(pseudo_spectral_acceleration(ag, 0.01, 0.0, 0.05)));
  EXPECT_TRUE(std::isnan(pseudo_spectral_acceleration(ag, 0.01, -1.0, 0.05)));
  EXPECT_TRUE(std::isnan(pseudo_spectral_acceleration(ag, 0.01, inf, 0.05)));
  EXPECT_TRUE(std::isnan(pseudo_spectral_acceleration(ag, 0.01, kNaN, 0.05)));
  EXPECT_TRUE(std::isnan(pseudo_spectral_acceleration(ag, 0.01, 0.5, -0.01)));
  EXPECT_TRUE(std::isnan(pseudo_spectral_acceleration(ag, 0.01, 0.5, 1.0)));
  EXPECT_TRUE(std::isnan(pseudo_spectral_acceleration(ag, 0.01, 0.5, kNaN)));
  EXPECT_TRUE(std::isnan(pseudo_spectral_acceleration(ag, 0.0, 0.5, 0.05)));
  EXPECT_TRUE(std::isnan(pseudo_spectral_acceleration(ag, -0.01, 0.5, 0.05)));
  EXPECT_TRUE(std::isnan(pseudo_spectral_acceleration(ag, kNaN, 0.5, 0.05)));
  const std::vector<double> with_nan{0.0, 0.1, kNaN, 0.05};
  EXPECT_TRUE(std::isnan(pseudo_spectral_acceleration(with_nan, 0.01, 0.5, 0.05)));
}

TEST(PeakGroundAcceleration, LargestMagnitude) {
  const std::vector<double> ag{0.0, 0.12, -0.35, 0.2, -0.01};
  EXPECT_EQ(peak_ground_acceleration(ag), 0.35);
  EXPECT_EQ(peak_ground_acceleration({}), 0.0);
  const std::vector<double> with_nan{0.1, kNaN, 0.2};
  EXPECT_TRUE(std::isnan(peak_ground_acceleration(with_nan)));
}

}  // namespace spectrum_test
}  // namespace ntn::ida
