// The energy books by mechanism (ntn::hil::EnergyBalance::accounts, hil_sim/include/ntn/hil/
// energy.hpp) on the block of block_model.hpp, each account against its closed form or a sum
// taken from the output channels, and the books closing to 1e-10 of the input in every case:
// - a block dropped onto a stop: the impact takes m g h (the perfectly plastic clamp);
// - a block on a spring and dashpot in free vibration: the viscous account is the dashpot's
//   integral of c v^2 dt, and the exact damped oscillator's loss;
// - a degrading backbone driven past E: once it has no strength left, the hysteretic account is
//   all the work done on it (the drops' released energy included);
// - a friction block: the friction account is mu N times the slide's path;
// - a breaking spring (a bolt): the fracture account is the energy it held, F^2 / (2 k).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "block_model.hpp"

namespace energy_books_test {

using namespace ntn_test::block;

// The books close: external = the sum of the accounts + a residual of rounding (1e-10 of the
// largest input, or of `scale` where the input is an initial state's energy: a few ulps per step
// over 10^4 - 10^5 steps).
void expect_closed(const ntn::hil::EnergyAccounts& a, double scale = 0) {
  std::printf(
      "  external %.9g J = kinetic %.4g + elastic %.6g + viscous %.6g + hysteretic %.6g + "
      "friction %.6g + impacts %.6g + fracture %.6g; residual %.2e of the input\n",
      a.external, a.kinetic, a.elastic, a.viscous, a.hysteretic, a.friction, a.impacts, a.fracture,
      a.relative_residual());
  if (scale == 0) {
    EXPECT_GT(a.input_scale, 0.0);
    scale = a.input_scale;
  }
  EXPECT_LE(std::fabs(a.residual), 1e-10 * scale);
}

TEST(EnergyBooks, ABlockDroppedOnAStopLosesMghInTheImpact) {
  // Truth: released 5 cm above its support at rest, the block lands and stays (the momentum
  // clamp stops it: a perfectly plastic impact). Gravity's work is m g h, all of it taken by the
  // impact. Tolerance 1e-6 of m g h: the start's half-step kinetic energy 1/2 m (g dt/2)^2 = 1.2e-4
  // J (2.4e-7 of it) is in the kinetic account.
  Block b;
  b.ux = "\"free\"";
  b.uz = "{ fixed_if = \"negative\" }";
  b.ground_motion = false;
  b.initial = "\n[[initial.nodes]]\nnode = 1\nu = [0.0, 0.0, 0.05]\n";
  auto rt = load(b);
  ASSERT_TRUE(rt);
  Books books;
  const auto rows = run(
      *rt, 10'000, [](double) { return 0.0; }, &books);
  const auto a = books.accounts(rt->model(), rt->state());
  expect_closed(a);
  const double mgh = kMass * kG * 0.05;
  EXPECT_NEAR(rows.back()[kUz], 0.0, 1e-12);  // on its support
  EXPECT_NEAR(a.external, mgh, 1e-6 * mgh);   // and gravity's work over the start's half step
  EXPECT_NEAR(a.impacts, mgh, 1e-6 * mgh);
}

TEST(EnergyBooks, ADashpotDissipatesTheIntegralOfCV2) {
  // Truth: m x'' + c x' + k x = 0 from x(0) = x0 at rest (m = 1000 kg, k = 1e5 N/m, c = 2e3 N s/m:
  // 10 % of critical), the loss after T = 1 s: 1/2 k x0^2 - (1/2 k x^2 + 1/2 m x'^2) at T, and the
  // integral of c v^2 dt over the velocity channel. Tolerances: 1e-3 of the loss, the lagged
  // damping force's first-order error (zeta w dt = 1e-4) and the channel sum's, with margin.
  Block b;
  b.ux = "{ linear = 1.0e5, dashpot = 2.0e3 }";
  b.ground_motion = false;
  b.initial = "\n[[initial.nodes]]\nnode = 1\nu = [0.01, 0.0, 0.0]\n";
  auto rt = load(b);
  ASSERT_TRUE(rt);
  Books books;
  const long steps = 10'000;
  const auto rows = run(
      *rt, steps, [](double) { return 0.0; }, &books);
  const auto a = books.accounts(rt->model(), rt->state());
  const double m = kMass, k = 1e5, c = 2e3, x0 = 0.01;
  expect_closed(a, 0.5 * k * x0 * x0);  // no external work: the input is the spring's energy
  const double wn = std::sqrt(k / m), zeta = c / (2 * std::sqrt(k * m));
  const double wd = wn * std::sqrt(1 - zeta * zeta), T = static_cast<double>(steps) * kDt;
  const double e = std::exp(-zeta * wn * T);
  const double x = x0 * e * (std::cos(wd * T) + zeta * wn / wd * std::sin(wd * T));
  const double v = -x0 * e * wn * wn / wd * std::sin(wd * T);
  const double loss = 0.5 * k * x0 * x0 - (0.5 * k * x * x + 0.5 * m * v * v);
  double integral = 0;
  for (const auto& r : rows)
    integral += c * r[kVx] * r[kVx] * kDt;
  EXPECT_NEAR(a.viscous, loss, 1e-3 * loss);
  EXPECT_NEAR(a.viscous, integral, 1e-3 * loss);
  EXPECT_NEAR(a.hysteretic + a.friction + a.impacts + a.fracture, 0.0, 1e-12 * loss);
}

TEST(EnergyBooks, ABackboneDrivenPastItsEndDissipatesAllTheWorkDoneOnIt) {
  // Truth: a peak-oriented backbone (B 2 kN at 2 mm, C 2.5 kN at 1 cm, D 1 kN, E at 3 cm) under a
  // 4 m/s^2 sine is driven past E and has no strength left; what it stored is then zero, so the
  // hysteretic account is the whole work done on it, sum f_n (d_{n+1} - d_{n-1}) / 2 over its
  // force and displacement channels (the same products: 1e-9 of it).
  Block b;
  b.ux =
      "{ backbone = [[0.002, 2.0e3], [0.01, 2.5e3], [0.01, 1.0e3], [0.03, 1.0e3]], rule = "
      "\"peak_oriented\" }";
  auto rt = load(b);
  ASSERT_TRUE(rt);
  Books books;
  const auto rows = run(*rt, 30'000, sine, &books);
  const auto a = books.accounts(rt->model(), rt->state());
  expect_closed(a);
  double work = 0;  // the first and last steps' forces are 0 (at rest; broken)
  for (std::size_t n = 1; n + 1 < rows.size(); ++n)
    work += rows[n][kFx] * 0.5 * (rows[n + 1][kHingeDx] - rows[n - 1][kHingeDx]);
  ASSERT_EQ(rows.back()[kFx], 0.0) << "the backbone still has strength";
  EXPECT_GT(a.hysteretic, 10.0);
  EXPECT_NEAR(a.hysteretic, work, 1e-9 * a.hysteretic);
}

TEST(EnergyBooks, FrictionIsMuNTimesThePath) {
  // Truth: a sliding block's friction force is mu N = mu m g, so the friction work is mu N times
  // the path of the slide, taken from the hinge displacement channel over the steps it slides:
  // sum |d_{n+1} - d_{n-1}| / 2 (the books weigh each force by that increment). Tolerance 1e-3
  // of it: the steps that start and stop a slide weigh a force below mu N.
  Block b;
  b.ux = "{ friction = 0.2, normal = \"uz\" }";
  b.slip_state = true;
  auto rt = load(b);
  ASSERT_TRUE(rt);
  Books books;
  const auto rows = run(*rt, 20'000, sine, &books);
  const auto a = books.accounts(rt->model(), rt->state());
  expect_closed(a);
  double path = 0;
  for (std::size_t n = 1; n + 1 < rows.size(); ++n) {
    if (rows[n][kSlip] != 0) path += 0.5 * std::fabs(rows[n + 1][kHingeDx] - rows[n - 1][kHingeDx]);
  }
  const double expected = 0.2 * kMass * kG * path;
  EXPECT_GT(path, 0.1);
  EXPECT_NEAR(a.friction, expected, 1e-3 * expected);
}

TEST(EnergyBooks, ABreakingBoltReleasesWhatItHeld) {
  // Truth: a spring k = 1e6 N/m that breaks when its force first passes F = 2 kN held F^2 / (2 k)
  // = 2 J then, and after it nothing: the fracture account. Tolerance 1e-2: the force passes F
  // by one step's growth (about 1 % at the 4 m/s^2 sine's slope).
  Block b;
  b.ux = "{ linear = 1.0e6, failure = 2.0e3 }";
  auto rt = load(b);
  ASSERT_TRUE(rt);
  Books books;
  const auto rows = run(*rt, 20'000, sine, &books);
  const auto a = books.accounts(rt->model(), rt->state());
  expect_closed(a);
  ASSERT_EQ(rows.back()[kFx], 0.0) << "the bolt did not break";
  const double held = 2e3 * 2e3 / (2 * 1e6);
  EXPECT_NEAR(a.fracture, held, 1e-2 * held);
  EXPECT_NEAR(a.hysteretic, 0.0, 1e-12);
}

}  // namespace energy_books_test
