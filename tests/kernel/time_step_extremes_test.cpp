// The stable step and the substep rule at the extremes of double
// (kernel/include/ntn/time_step.hpp): the damped formula without cancellation or overflow, hinge
// springs and dashpots of 1e300 and more never dropped from the bound, elements beyond double
// refused (step 0, issue kNonFinite, the element named), and frame_substeps, the one rule for N.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "ntn/kernel.hpp"
#include "ntn/modal/assembly.hpp"
#include "support/builders.hpp"
#include "support/hinges.hpp"

namespace time_step_extremes_test {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// For xi = alpha / (2 omega) >> 1 the step 2 / (omega (sqrt(1 + xi^2) + xi)) tends to 2 / alpha
// with relative error 1 / (4 xi^2) (expand the root): at xi >= 1e4 below 2.5e-9, so the test
// allows 1e-8. The old form (2/omega)(sqrt(1 + xi^2) - xi) gave 0 from xi ~ 1e8 (cancellation)
// and inf once xi^2 overflowed (alpha = 1e308: "stable dt inf").
TEST(DampedStableStepExtremes, HeavyDampingTendsToTwoOverAlphaWithoutCancellation) {
  const double omega = 1e3;
  for (double xi : {1e4, 1e8, 1e12, 1e100, 1e150, 1e151, 1e200, 1e300}) {
    const double alpha = 2 * xi * omega;
    if (!std::isfinite(alpha)) continue;
    const double dt = ntn::damped_stable_step(omega, alpha);
    EXPECT_GT(dt, 0.0) << "xi " << xi;
    EXPECT_NEAR(dt * alpha / 2, 1.0, 1e-8) << "xi " << xi;
  }
  // alpha = 1e308 with frequencies from 1e-3 to 1e150 rad/s: 2 / alpha, finite, never inf.
  for (double w : {1e-3, 1.0, 1e3, 1e150}) {
    const double dt = ntn::damped_stable_step(w, 1e308);
    EXPECT_TRUE(std::isfinite(dt)) << "omega " << w;
    EXPECT_NEAR(dt / 2e-308, 1.0, 1e-6) << "omega " << w;  // 2e-308 is subnormal: 1e-6
  }
}

// Moderate damping: the new form equals the textbook one to rounding (a few ulps; 1e-14).
TEST(DampedStableStepExtremes, EqualsTheTextbookFormWhereThatOneIsAccurate) {
  for (double omega : {1.0, 1e4, 1e7}) {
    for (double xi : {0.0, 1e-3, 0.05, 0.5, 1.0, 3.0}) {
      const double textbook = 2.0 / omega * (std::sqrt(1.0 + xi * xi) - xi);
      EXPECT_NEAR(ntn::damped_stable_step(omega, 2 * xi * omega) / textbook, 1.0, 1e-14);
    }
  }
  EXPECT_EQ(ntn::damped_stable_step(kInf, 1.0), 0.0);
  EXPECT_EQ(ntn::damped_stable_step(kNaN, 1.0), 0.0);
  EXPECT_EQ(ntn::damped_stable_step(1.0, kNaN), 0.0);
}

// The clamped-clamped beam of hinge_time_step_test cut at midspan by a hinge that is rigid
// except ry, where it has a linear spring k and a dashpot c.
constexpr int kN = 8, kMid = 4, kExtra = 9;
constexpr ntn::Sizes kS{.nodes = kN + 2, .elements = kN, .hinges = 1};
ntn::ModelSpec<kS> spec;

void build(double k, double c) {
  spec = {};
  ntn_test::split_beam(spec, 4.0, ntn_test::kSteel, ntn_test::rectangle(0.1, 0.15), kMid, kExtra,
                       ntn_test::kFixedAll, ntn_test::kFixedAll);
  auto b = ntn_test::released(0);
  b[ntn::kRy] = ntn::HingeBehaviour::kLinear;
  spec.hinges[0] = ntn_test::hinge(kExtra, kMid, ntn_test::kIdentity3, b);
  spec.hinges[0].stiffness[ntn::kRy] = k;
  spec.hinges[0].dashpot[ntn::kRy] = c;
}

// w = b^T M^-1 b of the ry spring: 1 / m_ry at each node (rigid directions add no mass here).
double spring_w() {
  const std::vector<double> mass = ntn::modal::lumped_mass(ntn::view(spec));
  return 1.0 / mass[ntn::kDofsPerNode * kExtra + ntn::kRy] +
         1.0 / mass[ntn::kDofsPerNode * kMid + ntn::kRy];
}

// A stiffer spring never gives a longer step, up to k = 1e308 (where k w overflows: the step
// is 0, issue kNonFinite, naming the hinge and ry). Before the fix a spring of 1e308 gave NaN
// weights and was left out: the step stayed the elements' own.
TEST(HingeStepExtremes, HugeSpringIsNeverDropped) {
  build(0, 0);
  const ntn::StableStepReport none = ntn_test::hinged_stable_step(spec);
  ASSERT_GT(none.dt_stable, 0.0);
  double previous = none.dt_stable;
  for (double k : {1e6, 1e12, 1e50, 1e150, 1e250, 1e300}) {
    build(k, 0);
    const ntn::StableStepReport r = ntn_test::hinged_stable_step(spec);
    EXPECT_LE(r.dt_stable, previous) << "k " << k;
    // Two-node oscillator bound (kernel/README.md): never above 2 / sqrt(k w).
    EXPECT_LE(r.dt_stable, 2.0 / std::sqrt(k * spring_w()) * (1 + 1e-12)) << "k " << k;
    EXPECT_GT(r.dt_stable, 0.0) << "k " << k;
    EXPECT_EQ(r.issue, ntn::StepIssue::kNone);
    previous = r.dt_stable;
  }
  build(1e308, 0);
  const ntn::StableStepReport r = ntn_test::hinged_stable_step(spec);
  EXPECT_EQ(r.dt_stable, 0.0);
  EXPECT_EQ(r.issue, ntn::StepIssue::kNonFinite);
  EXPECT_EQ(r.governing_hinge, 0);
  EXPECT_EQ(r.hinge_direction, ntn::kRy);
}

// A dashpot c: dt^2 omega^2 + 2 dt eta < 4 with eta >= c w at one of the hinge's nodes gives
// dt < 2 / (c w); and the node-by-node bound keeps at least half of it for one isolated hinge
// (g <= 2 at either node). Before the fix c = 1e300 made xi^2 overflow and the node's step inf:
// the dashpot was dropped and the step stayed the elements' own (about 1e-5 s).
TEST(HingeStepExtremes, HugeDashpotSetsTheStep) {
  for (double c : {1e3, 1e100, 1e300}) {
    build(0, c);
    const ntn::StableStepReport r = ntn_test::hinged_stable_step(spec);
    const double bound = 2.0 / (c * spring_w());
    EXPECT_TRUE(std::isfinite(r.dt_stable)) << "c " << c;
    if (c < 1e10) continue;  // a small dashpot does not govern
    EXPECT_LE(r.dt_stable, bound * (1 + 1e-12)) << "c " << c;
    EXPECT_GE(r.dt_stable, 0.25 * bound) << "c " << c;
    EXPECT_EQ(r.governing_hinge, 0) << "c " << c;
  }
}

// Damping alpha = 1e308 (C = alpha M): the step is 2 / alpha, finite; it was "stable dt inf".
TEST(StableStepExtremes, HugeMassProportionalDampingGivesAFiniteStep) {
  build(0, 0);
  spec.settings.alpha = 1e308;
  spec.settings.damping_velocity = ntn::DampingVelocity::kLagged;  // alpha in the bound
  const ntn::StableStepReport r = ntn_test::hinged_stable_step(spec);
  EXPECT_TRUE(std::isfinite(r.dt_stable));
  EXPECT_GT(r.dt_stable, 0.0);
  EXPECT_NEAR(r.dt_stable / 2e-308, 1.0, 1e-6);
}

// An element whose stiffness overflows (E = 1e308: 12 E I overflows) has no finite frequency:
// the step is 0 with that element named, not the other elements' step (it was dropped: its
// eigen solve failed and counted as omega = 0).
TEST(StableStepExtremes, ElementBeyondDoubleIsRefusedNotDropped) {
  build(0, 0);
  spec.elements[2].E = 1e308;
  const ntn::StableStepReport r = ntn::stable_time_step(ntn::view(spec));
  EXPECT_EQ(r.dt_stable, 0.0);
  EXPECT_EQ(r.issue, ntn::StepIssue::kNonFinite);
  EXPECT_EQ(r.governing_element, 2);
  EXPECT_EQ(ntn_test::hinged_stable_step(spec).issue, ntn::StepIssue::kNonFinite);
}

// ---- frame_substeps: N = period / dt, whole, 1..kMaxSubsteps ----------------------------------

TEST(FrameSubsteps, WholeDivisionsAreCounted) {
  const double p = 1e-3;
  for (long long n : {1LL, 2LL, 9LL, 1000LL, 123457LL, ntn::kMaxSubsteps}) {
    const ntn::Substeps s = ntn::frame_substeps(p / static_cast<double>(n), p);
    EXPECT_TRUE(s.ok()) << n << ": " << ntn::to_string(s.error);
    EXPECT_EQ(s.count, n);
  }
  // Within the tolerance 1e-9 of the period: accepted; beyond it: not whole.
  EXPECT_EQ(ntn::frame_substeps(p / 7 * (1 + 5e-10), p).count, 7);
  EXPECT_EQ(ntn::frame_substeps(p / 7 * (1 + 2e-9), p).error, ntn::SubstepError::kNotWhole);
  EXPECT_EQ(ntn::frame_substeps(3e-4, p).error, ntn::SubstepError::kNotWhole);
  EXPECT_EQ(ntn::frame_substeps(p * (1 + 1e-12), p).count, 1);
}

// Regression: dt = 1e-300 claimed "1 per 1 ms frame", nodes 1e-12 m apart gave 2.2e10
// substeps and `info` printed -9223372036854775808. Each is a named error now.
TEST(FrameSubsteps, AbsurdStepsAndPeriodsAreRefused) {
  const double p = 1e-3;
  EXPECT_EQ(ntn::frame_substeps(1e-300, p).error, ntn::SubstepError::kTooMany);
  EXPECT_EQ(ntn::frame_substeps(9.3e-30, p).error, ntn::SubstepError::kTooMany);
  EXPECT_EQ(ntn::frame_substeps(p / 2.2e10, p).error, ntn::SubstepError::kTooMany);
  EXPECT_EQ(ntn::frame_substeps(p / static_cast<double>(ntn::kMaxSubsteps + 1), p).error,
            ntn::SubstepError::kTooMany);
  EXPECT_EQ(ntn::frame_substeps(2e-3, p).error, ntn::SubstepError::kLongerThanFrame);
  for (double dt : {0.0, -1e-4, kInf, -kInf, kNaN})
    EXPECT_EQ(ntn::frame_substeps(dt, p).error, ntn::SubstepError::kBadTimeStep) << dt;
  // frame_rate = 1e-300 is a period of 1e300 s; 1e300 Hz one of 1e-300 s.
  for (double period : {1e300, 1e-300, 0.0, -1e-3, kInf, kNaN, 0.99e-6, 1000.1})
    EXPECT_EQ(ntn::frame_substeps(1e-4, period).error, ntn::SubstepError::kBadPeriod) << period;
  EXPECT_TRUE(ntn::frame_substeps(1e-6, 1e-6).ok());
  EXPECT_TRUE(ntn::frame_substeps(1e-3, 1e3).ok());
  EXPECT_FALSE(ntn::frame_substeps(1e-300, p).ok());
  EXPECT_EQ(ntn::frame_substeps(1e-300, p).count, 0);
}

// dt = "auto" always satisfies the rule when it needs at most kMaxSubsteps steps.
TEST(FrameSubsteps, AutoStepsPassTheRule) {
  for (double period : {1e-6, 1e-3, 1.0 / 3.0, 0.1, 1e3}) {
    for (double dt_stable : {1e-9, 1.234e-7, 3.3e-6, 2e-4, 5e-2, 7.0}) {
      const double dt = ntn::auto_time_step(dt_stable, period);
      const double n = std::ceil(period / (0.9 * dt_stable));
      const ntn::Substeps s = ntn::frame_substeps(dt, period);
      if (n > static_cast<double>(ntn::kMaxSubsteps)) {
        EXPECT_EQ(s.error, ntn::SubstepError::kTooMany) << period << " " << dt_stable;
      } else {
        EXPECT_TRUE(s.ok()) << period << " " << dt_stable << ": " << ntn::to_string(s.error);
        EXPECT_EQ(s.count, static_cast<long long>(std::max(1.0, n)));
      }
    }
  }
}

}  // namespace time_step_extremes_test
