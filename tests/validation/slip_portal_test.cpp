// The sliding portal (config/portal_slip.toml) under 15 s of El Centro 1940 N-S: column
// bases on Coulomb friction (mu = 0.2 on their rigid normal), beam ends slip-critical
// (rigid_plastic at 35 kN m), gravity as a static preload. Truth no one here chose:
// - Coulomb's law at every step: each base's friction force at t_n is within mu max(0, -N) of
//   its normal force N at t_n (to 1e-12 of it, rounding), and equals it while the base slides;
//   a beam end's moment never exceeds its slip moment;
// - the discrete work-energy identity of the scheme (ntn::hil::EnergyBalance) with the slip
//   directions' forces counted: along the whole run it closes to 1e-10 of the largest input
//   energy (the rounding of the gravity terms, m g per step, which cancel in equilibrium);
// And the record makes both kinds of connection slide (the run's events).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string_view>

#include "el_centro_run.hpp"
#include "ntn/hil/energy.hpp"
#include "ntn/hil/yield_report.hpp"
#include "ntn/kernel.hpp"
#include "portal_slip_model.hpp"

namespace slip_portal_test {

namespace portal = ntn::models::portal_slip;
constexpr ntn::Sizes kS = portal::kSizes;

std::size_t channel(std::string_view name) {
  const auto it = std::find(portal::kOutputNames.begin(), portal::kOutputNames.end(), name);
  EXPECT_NE(it, portal::kOutputNames.end()) << name;
  return static_cast<std::size_t>(it - portal::kOutputNames.begin());
}

TEST(SlipPortal, BasesSlideByCoulombsLawAndTheEnergyBalanceCloses) {
  ntn_test::ElCentroRun<kS> run;
  ASSERT_TRUE(run.start(portal::kSpec));
  const auto& m = run.model;
  const auto& s = run.state;
  const auto& w = run.scratch;
  ntn::hil::EnergyBalance<kS> e;
  e.begin(*m, *s);
  const double mu = 0.2, slip_moment = 35e3;
  const std::size_t fl = channel("base_left_friction"), nl = channel("base_left_normal");
  const std::size_t fr = channel("base_right_friction"), nr = channel("base_right_normal");
  const std::size_t state = channel("base_left_state"), slide = channel("base_left_slide");
  const std::size_t work = channel("base_left_friction_work"), moment = channel("beam_start_My");
  const long steps = std::lround(15.0 / m->dt);
  double coulomb_worst = 0, at_limit_worst = 0, moment_peak = 0, worst = 0, path = 0;
  double last_slide = 0;
  long sliding = 0;
  for (long n = 0; n < steps; ++n) {
    ASSERT_EQ(run.step(n), ntn::StepStatus::kOk);
    e.after_step(*m, *s, *w);
    worst = std::fmax(worst, std::fabs(e.residual()));
    const auto& o = w->outputs;
    for (const auto& [f, nn] : {std::pair{fl, nl}, std::pair{fr, nr}}) {
      const double limit = mu * std::fmax(0.0, -o[nn]);
      coulomb_worst = std::fmax(coulomb_worst, (std::fabs(o[f]) - limit) / limit);
    }
    if (o[state] != 0) {  // sliding: the friction force is the limit
      ++sliding;
      const double limit = mu * std::fmax(0.0, -o[nl]);
      at_limit_worst = std::fmax(at_limit_worst, std::fabs(std::fabs(o[fl]) - limit) / limit);
    }
    path += std::fabs(o[slide] - last_slide);
    last_slide = o[slide];
    moment_peak = std::fmax(moment_peak, std::fabs(o[moment]));
  }
  std::printf(
      "  external %.6g J (largest %.6g J), internal %.6g J, kinetic %.4g J, damping "
      "%.6g J, residual %.3e J\n",
      e.external(), e.input_scale(), e.internal(), e.kinetic(), e.damping(), e.residual());
  const auto events = ntn::hil::yielded_directions(*m, *s);
  std::printf(
      "  15 s, %ld steps: %ld sliding at the left base (slide path %.4f m, now %.4f m), "
      "|F| - mu N <= %.1e of mu N, at the limit while sliding to %.1e; beam end |M| <= %.0f N m; "
      "friction work %.1f J; energy residual worst %.2e of the largest input; %zu connections "
      "slid\n",
      steps, sliding, path, last_slide, coulomb_worst, at_limit_worst, moment_peak,
      w->outputs[work], worst / e.input_scale(), events.size());
  EXPECT_LE(coulomb_worst, 1e-12);
  EXPECT_LE(at_limit_worst, 1e-12);
  EXPECT_LE(moment_peak, slip_moment);
  EXPECT_LE(worst, 1e-10 * e.input_scale());
  EXPECT_GT(sliding, 1000);      // El Centro's 0.35 g slides the bases (0.2 g)
  EXPECT_EQ(events.size(), 4U);  // both bases and both beam ends slid
  for (const auto& y : events) {
    EXPECT_GE(y.first_slip, 0.0);
    EXPECT_FALSE(y.failed);
  }
  EXPECT_GT(w->outputs[work], 0.0);  // friction work, f ds with f the limit: positive
}

}  // namespace slip_portal_test
