// NAFEMS test 5T (NAFEMS R0016, "Selected Benchmarks for Forced Vibration", Maguire, Dawswell and
// Gould, 1989), written as a model file (nafems_5t.toml: [[member_loads]] for the uniform load,
// [model.damping] alpha and beta, a member point for the midspan channel): deep simply supported
// beam, transient forced vibration under a suddenly applied uniform step load, with Rayleigh
// damping C = alpha M + beta K. As the benchmark gives it (and as vendors' verification manuals
// reproduce it, e.g. Altair OptiStruct OS-V 0330):
//   L = 10 m, square section 2 m x 2 m, shear deformable (Timoshenko, with rotary inertia),
//   E = 200 GPa, nu = 0.3, rho = 8000 kg/m^3;
//   end A: ux, uy, uz and rx held; end B: uy and uz held;
//   q = 1e6 N/m along y, applied at t = 0 and held;
//   Rayleigh damping alpha = 5.36 1/s, beta = 7.46e-5 s (2 % of critical at the first mode,
//   42.65 Hz: 5.36 / (2 omega_1) + 7.46e-5 omega_1 / 2 = 0.01 + 0.01);
//   10 elements (the benchmark's mesh).
// Reference: peak midspan deflection 1.043 mm at t = 11.7 ms (static deflection 0.538 mm).
// Tolerance 2 % in the peak and 2 % in its time (the issue's): the reference is Timoshenko beam
// theory; the kernel's 10 elements with lumped (HRZ) mass shift the first frequency by a fraction
// of a percent, and the peak comes almost entirely from mode 1 (static x (1 + exp(-pi xi))).
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

#include "nafems_5t_model.hpp"
#include "ntn/kernel.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"

namespace nafems_5t_test {

namespace nafems = ntn::models::nafems_5t;
constexpr ntn::Sizes kS = nafems::kSizes;

TEST(Nafems5T, DeepSimplySupportedBeamStepLoadRayleighDamping) {
  const auto model = std::make_unique<ntn::Model<kS>>();
  const auto state = std::make_unique<ntn::State<kS>>();
  const auto scratch = std::make_unique<ntn::Scratch<kS>>();
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(nafems::kSpec, *model).ok());
  }
  ASSERT_EQ(nafems::kSpec.settings.alpha, 5.36);
  ASSERT_EQ(nafems::kSpec.settings.beta, 7.46e-5);
  ntn::initial_state(*model, *state);
  ASSERT_EQ(ntn::start(*model, *state, *scratch, {}), ntn::StepStatus::kOk);
  double peak = 0, t_peak = 0;
  const auto steps = static_cast<long>(0.025 / model->dt);  // past the first peak (~2/3 period)
  for (long n = 0; n < steps; ++n) {
    ASSERT_EQ(ntn::step(*model, *state, *scratch, {}), ntn::StepStatus::kOk);
    const double u = scratch->outputs[0];  // mid_uy at t_n
    if (u > peak) peak = u, t_peak = scratch->time;
  }
  std::printf(
      "  NAFEMS 5T: dt = %.3e s (stable %.3e s); peak midspan deflection %.4f mm at %.2f ms "
      "(reference 1.043 mm at 11.7 ms): %+.2f %%, %+.2f %%\n",
      model->dt, model->stable.dt_stable, 1e3 * peak, 1e3 * t_peak, 100 * (peak / 1.043e-3 - 1),
      100 * (t_peak / 11.7e-3 - 1));
  EXPECT_NEAR(peak / 1.043e-3, 1.0, 0.02);
  EXPECT_NEAR(t_peak / 11.7e-3, 1.0, 0.02);
}

}  // namespace nafems_5t_test
