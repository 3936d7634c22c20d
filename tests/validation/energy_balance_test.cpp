// The energy balance of a yielding frame under a real record: the demo portal with
// plastic hinges at its column bases and beam ends (config/portal_plastic.toml) under gravity
// (static preload) and 15 s of El Centro 1940 N-S. The discrete work-energy identity of the scheme
// (ntn::hil::EnergyBalance, hil_sim/include/ntn/hil/energy.hpp): kinetic energy now minus at the
// start = external work (base excitation, gravity) - internal work (elements, beta K, hinges,
// plastic directions) - mass-proportional damping. Each step's terms are the products the step
// itself made, so the balance holds to rounding: a few ulp per step of the largest terms,
// accumulated over ~5.4e5 steps, stays below 1e-10 of the input energy (the largest |external
// work| reached). It fails when a force enters the accelerations but not F_n or P_n (or the
// reverse), a damping term is left out, or the update does not follow the equations.
// The frame yields: the hysteretic share (the plastic directions' plastic work) is reported.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "el_centro_run.hpp"
#include "frame3d_model.hpp"
#include "ntn/hil/energy.hpp"
#include "ntn/kernel.hpp"
#include "portal_plastic_model.hpp"
#include "portal_slip_model.hpp"

namespace energy_balance_test {

namespace portal = ntn::models::portal_plastic;
constexpr ntn::Sizes kS = portal::kSizes;

// A demo model under the whole El Centro record (31.2 s): the books by mechanism close to 1e-10
// of the input, and the mechanisms the model has take their share.
template <ntn::Sizes S>
ntn::hil::EnergyAccounts books_under_el_centro(const ntn::ModelSpec<S>& spec) {
  ntn_test::ElCentroRun<S> run;
  EXPECT_TRUE(run.start(spec));
  ntn::hil::EnergyBalance<S> e;
  e.reserve(run.model->dofs());
  e.begin(*run.model, *run.state);
  const long steps = std::lround(31.18 / run.model->dt);
  for (long n = 0; n < steps; ++n) {
    EXPECT_EQ(run.step(n), ntn::StepStatus::kOk);
    e.after_step(*run.model, *run.state, *run.scratch);
  }
  const ntn::hil::EnergyAccounts a = e.accounts(*run.model, *run.state);
  std::printf(
      "  %ld steps: external %.6g J = kinetic %.4g + elastic %.6g + viscous %.6g + hysteretic "
      "%.6g + friction %.6g + impacts %.6g + fracture %.6g; residual %.2e of the input\n",
      steps, a.external, a.kinetic, a.elastic, a.viscous, a.hysteretic, a.friction, a.impacts,
      a.fracture, a.relative_residual());
  EXPECT_LE(a.relative_residual(), 1e-10);
  return a;
}

TEST(EnergyBooks, TheDemoModelsCloseUnderElCentro) {
  const auto frame = books_under_el_centro(ntn::models::frame3d::kSpec);  // elastic, Rayleigh
  EXPECT_GT(frame.viscous, 0.5 * frame.external);
  EXPECT_EQ(frame.hysteretic + frame.friction + frame.impacts + frame.fracture, 0.0);
  const auto plastic = books_under_el_centro(portal::kSpec);  // plastic hinges yield
  EXPECT_GT(plastic.hysteretic, 0.1 * plastic.external);
  const auto slip = books_under_el_centro(ntn::models::portal_slip::kSpec);  // bases slide
  EXPECT_GT(slip.friction, 0.1 * slip.external);
}

TEST(EnergyBalance, YieldingPortalUnderElCentroClosesToRounding) {
  ntn_test::ElCentroRun<kS> run;
  ASSERT_TRUE(run.start(portal::kSpec));
  const auto& m = run.model;
  const auto& s = run.state;
  const auto& w = run.scratch;
  ntn::hil::EnergyBalance<kS> e;
  e.begin(*m, *s);
  const long steps = std::lround(15.0 / m->dt);
  double worst = 0;  // the largest |residual| / input scale along the run
  for (long n = 0; n < steps; ++n) {
    ASSERT_EQ(run.step(n), ntn::StepStatus::kOk);
    e.after_step(*m, *s, *w);
    if (e.input_scale() > 0) worst = std::fmax(worst, std::fabs(e.residual()) / e.input_scale());
  }
  const double hyst = ntn::hil::hysteretic_energy(*s);
  std::printf(
      "  15 s, %ld steps: external work %.6g J (largest |W_ext| %.6g J), kinetic %.4g J, "
      "internal work %.6g J (of it hysteretic %.6g J, %.1f %%), damping %.6g J; "
      "residual %.3e J, worst along the run %.2e of the input\n",
      steps, e.external(), e.input_scale(), e.kinetic(), e.internal(), hyst,
      100 * hyst / e.internal(), e.damping(), e.residual(), worst);
  EXPECT_LE(worst, 1e-10);
  EXPECT_GT(hyst, 0.0);  // it yielded
  int yielded = 0;
  for (double p : s->plastic_peak)
    yielded += p > 0 ? 1 : 0;
  std::printf("  plastic directions that yielded: %d of %zu\n", yielded, kS.hystereses);
}

}  // namespace energy_balance_test
