// What a monitor reads where connections stick, slide, stop and break: the channels that the
// constraint stages (the stops' clamp, the slip stage, the projection) act on, against truth that
// needs no simulation.
// - Every acceleration channel is the step's own a_n, (u_{n+1} - 2 u_n + u_{n-1}) / dt^2 of the
//   displacement channel, and every velocity channel (u_{n+1} - u_{n-1}) / (2 dt) (S 35-37), for
//   every hinge behaviour under every method that accepts it.
// - A block on a friction support under a ground motion: while it sticks its absolute
//   acceleration is the ground's a_g, while it slides +-mu g.
// - A block resting on a one-sided support (fixed_if on its own force, a stop): at rest, 0
//   relative acceleration and velocity from the first step on, and the stop carries its weight
//   (hinge_force and reaction), under every method.
// - Newmark's sliding block (a constant a_g > mu g from t = 0): the slide is the parabola
//   -(a_g - mu g) t^2 / 2 from the first step, which central difference follows exactly when the
//   start puts the friction force into a_0.
// The block: block_model.hpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "block_model.hpp"

namespace constraint_channels_test {

using namespace ntn_test::block;

// The largest misfit of the acceleration and velocity channels against the central differences
// of the displacement channel, relative to the tolerance: rounding of u (16 ulps of the largest
// |u|) over dt^2 and 2 dt, plus 1e-12 of the largest |a| and |v| or of g and g dt (the channels'
// own rounding).
double misfit(const std::vector<std::vector<double>>& rows, Channel u, Channel a, Channel v) {
  double u_max = 0, a_max = kG, v_max = kG * kDt;
  for (const auto& r : rows) {
    u_max = std::fmax(u_max, std::fabs(r[u]));
    a_max = std::fmax(a_max, std::fabs(r[a]));
    v_max = std::fmax(v_max, std::fabs(r[v]));
  }
  const double du = 16 * 2.220446049250313e-16 * u_max;
  const double tol_a = du / (kDt * kDt) + 1e-12 * a_max;
  const double tol_v = du / (2 * kDt) + 1e-12 * v_max;
  double worst = 0;
  for (std::size_t n = 1; n + 1 < rows.size(); ++n) {
    const double a2 = (rows[n + 1][u] - 2 * rows[n][u] + rows[n - 1][u]) / (kDt * kDt);
    const double v2 = (rows[n + 1][u] - rows[n - 1][u]) / (2 * kDt);
    worst = std::fmax(worst, std::fabs(rows[n][a] - a2) / tol_a);
    worst = std::fmax(worst, std::fabs(rows[n][v] - v2) / tol_v);
  }
  return worst;
}

TEST(ConstraintChannels, FrictionBlockReadsTheGroundWhileItSticksAndMuGWhileItSlides) {
  // Truth: sticking, the block moves with the ground (relative acceleration 0, absolute a_g);
  // sliding, the friction force mu m g is the only horizontal force on it (absolute +-mu g). The
  // sine of 4 m/s^2 at 1 Hz makes it stick about 800 of 20 000 steps and slide the rest.
  // Tolerance 1e-8 m/s^2: the relative acceleration's rounding, 16 ulps of u (0.14 m) over dt^2
  // (3e-8 at most), and the tether's 1e-10 N/m.
  Block b;
  b.ux = "{ friction = 0.2, normal = \"uz\" }";
  b.slip_state = true;
  auto rt = load(b);
  ASSERT_TRUE(rt);
  const auto rows = run(*rt, 20'000, sine);
  long stuck = 0, slid = 0;
  double worst_stick = 0, worst_slide = 0;
  for (std::size_t n = 1; n < rows.size(); ++n) {
    const double ag = sine(static_cast<double>(n) * kDt);
    // A step that stops a slide (0 after +-1) brings the slip rate to 0 within the step: its
    // acceleration lies between the two.
    if (rows[n][kSlip] == 0 && rows[n - 1][kSlip] == 0) {
      ++stuck;
      worst_stick = std::fmax(worst_stick, std::fabs(rows[n][kAbsAx] - ag));
    } else if (rows[n][kSlip] != 0) {
      ++slid;
      worst_slide = std::fmax(worst_slide, std::fabs(std::fabs(rows[n][kAbsAx]) - 0.2 * kG));
    }
  }
  EXPECT_GT(stuck, 500);
  EXPECT_GT(slid, 1000);
  EXPECT_LT(worst_stick, 1e-7);
  EXPECT_LT(worst_slide, 1e-7);
  EXPECT_LE(misfit(rows, kUx, kAx, kVx), 1.0);
  // The normal carries the weight (N < 0 presses) and the ground takes it.
  for (const auto& r : rows) {
    ASSERT_NEAR(r[kFz], -kMass * kG, 1e-9 * kMass * kG);
    ASSERT_NEAR(r[kRz], kMass * kG, 1e-9 * kMass * kG);
  }
}

TEST(ConstraintChannels, BlockOnAStopRestsAndTheStopCarriesItsWeight) {
  // Truth: at rest on its support. The stop's force is the clamp's; the reaction the ground's
  // force on the block. Tolerances: 1e-9 m/s^2 and 1e-12 m/s (rounding of u ~ 1e-19 m over dt^2
  // and dt), the force to 1e-9 relative. Every method clamps this stop (a curve's rigid branch).
  for (const char* method : {"ntn_exact", "penalty", "ntn_paper"}) {
    SCOPED_TRACE(method);
    Block b;
    b.method = method;
    b.ux = "\"free\"";
    b.uz = "{ fixed_if = \"negative\" }";
    b.ground_motion = false;
    auto rt = load(b);
    ASSERT_TRUE(rt);
    const auto rows = run(*rt, 5'000, [](double) { return 0.0; });
    const bool paper = std::string(method) == "ntn_paper";  // S 33 applies no force
    for (std::size_t n = 0; n < rows.size(); ++n) {
      ASSERT_NEAR(rows[n][kAz], 0.0, 1e-9) << "step " << n;
      ASSERT_NEAR(rows[n][kAbsAz], 0.0, 1e-9) << "step " << n;
      ASSERT_NEAR(rows[n][kVz], 0.0, 1e-12) << "step " << n;
      if (paper) continue;
      ASSERT_NEAR(rows[n][kFz], -kMass * kG, 1e-9 * kMass * kG) << "step " << n;
      ASSERT_NEAR(rows[n][kRz], kMass * kG, 1e-9 * kMass * kG) << "step " << n;
    }
  }
}

TEST(ConstraintChannels, NewmarksSlidingBlockFollowsTheParabolaFromTheFirstStep) {
  // Truth: under a constant a_g > mu g from t = 0 the block slides from rest with the relative
  // acceleration -(a_g - mu g): u = -(a_g - mu g) t^2 / 2, which central difference reproduces
  // exactly (the second difference of a parabola is exact) once a_0 has the friction force in
  // it. Tolerance 1e-10 of the slide at 1 s (rounding over 10^4 steps); a start without the
  // friction force in a_0 is off by (mu g) dt t / 2, 3e-5 of it.
  Block b;
  b.ux = "{ friction = 0.2, normal = \"uz\" }";
  b.slip_state = true;
  const double ag = 0.5 * kG, rel = -(ag - 0.2 * kG);
  auto rt = load(b, ag);
  ASSERT_TRUE(rt);
  const auto rows = run(*rt, 10'001, [&](double) { return ag; });
  const double slide = 0.5 * rel * 1.0;
  double worst = 0;
  for (std::size_t n = 0; n < rows.size(); ++n) {
    const double t = static_cast<double>(n) * kDt;
    worst = std::fmax(worst, std::fabs(rows[n][kUx] - 0.5 * rel * t * t));
    ASSERT_EQ(rows[n][kSlip], 1.0) << "step " << n;  // d = -u_x grows: the positive sense
    ASSERT_NEAR(rows[n][kAbsAx], 0.2 * kG, 1e-9) << "step " << n;
  }
  EXPECT_LT(worst, 1e-10 * std::fabs(slide));
}

// Each hinge behaviour (the base's ux) under each method that takes it: the acceleration and
// velocity channels are the central differences of the displacement channel (misfit()).
TEST(ConstraintChannels, EveryBehaviourReadsItsOwnCentralDifferences) {
  struct Case {
    const char* name;
    const char* ux;
    const char* extra;
    bool exact_only;  // refused by penalty and ntn_paper (the compiler's rule, config/README.md)
    bool not_paper;   // refused by ntn_paper
  };
  const char* stops = R"(
[[curves]]
id = "gap"
points = [[-0.0051, -1.0e10], [-0.005, 0.0], [0.005, 0.0], [0.0051, 1.0e10]]
)";
  const Case cases[] = {
      {"rigid", "\"rigid\"", "", false, false},
      {"free", "\"free\"", "", false, false},
      {"spring and dashpot", "{ linear = 1.0e5, dashpot = 1.0e3 }", "", false, false},
      {"curve with stops", "{ curve = \"gap\" }", stops, false, false},
      {"plastic", "{ plastic = 1.0e6, yield = 1.0e3 }", "", false, false},
      {"backbone",
       "{ backbone = [[0.002, 2.0e3], [0.01, 2.5e3], [0.01, 1.0e3], [0.05, 1.0e3]], rule = "
       "\"peak_oriented\" }",
       "", false, false},
      {"breaking spring", "{ linear = 1.0e6, failure = 2.0e3 }", "", false, false},
      {"rigid_plastic", "{ rigid_plastic = 2.0e3 }", "", false, true},
      {"rigid failure", "{ failure = 3.0e3 }", "", false, true},
      {"friction", "{ friction = 0.2, normal = \"uz\" }", "", true, true},
      {"fixed_if with a control", "{ fixed_if = \"negative\", control = \"uz\" }", "", true, true},
  };
  for (const Case& c : cases) {
    for (const char* method : {"ntn_exact", "penalty", "ntn_paper"}) {
      const std::string m = method;
      if ((c.exact_only && m != "ntn_exact") || (c.not_paper && m == "ntn_paper")) continue;
      SCOPED_TRACE(std::string(c.name) + " under " + m);
      Block b;
      b.method = m;
      b.ux = c.ux;
      b.extra = c.extra;
      auto rt = load(b);
      ASSERT_TRUE(rt);
      const auto rows = run(*rt, 20'000, sine);
      EXPECT_LE(misfit(rows, kUx, kAx, kVx), 1.0);
      EXPECT_LE(misfit(rows, kUz, kAz, kVz), 1.0);
      double worst = 0, scale = 0;  // the hinge's relative velocity: -vx (d = -u_1 on the ground)
      for (const auto& r : rows) {
        worst = std::fmax(worst, std::fabs(r[kHingeVx] + r[kVx]));
        scale = std::fmax(scale, std::fabs(r[kVx]));
      }
      EXPECT_LE(worst, 1e-12 * scale + 1e-300);
    }
  }
}

}  // namespace constraint_channels_test
