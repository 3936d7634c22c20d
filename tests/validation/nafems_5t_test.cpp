// NAFEMS test 5T (NAFEMS R0016, "Selected Benchmarks for Forced Vibration", Maguire, Dawswell and
// Gould, 1989): deep simply supported beam, transient forced vibration under a suddenly applied
// uniform step load, with Rayleigh damping C = alpha M + beta K. As the benchmark gives it (and
// as vendors' verification manuals reproduce it, e.g. Altair OptiStruct OS-V 0330):
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
//
// Member (distributed) loads are not used: the uniform q is applied as its consistent nodal loads
// on the element nodes (each element its own member between nodes): q h at interior nodes,
// q h / 2 at the two end nodes, and the end moments -q h^2 / 12, +q h^2 / 12 (about z, from the
// fixed-end moments of the two end elements; the interior ones cancel). That is exactly the
// consistent load of the uniform q on these elements.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "ntn/kernel.hpp"
#include "support/builders.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"

namespace {

constexpr int kElements = 10, kMid = kElements / 2;
constexpr double kL = 10.0, kQ = 1e6;  // m, N/m
constexpr ntn::Sizes kS{.nodes = kElements + 1, .elements = kElements, .loads = kElements + 3};

ntn::ModelSpec<kS> spec;
ntn::Model<kS> model;
ntn::State<kS> state;
ntn::Scratch<kS> scratch;

TEST(Nafems5T, DeepSimplySupportedBeamStepLoadRayleighDamping) {
  constexpr ntn_test::Material kMat{200e9, 200e9 / 2.6, 8000.0};           // G = E / (2 (1 + 0.3))
  constexpr ntn_test::Section kSec = ntn_test::rectangle(2.0, 2.0, true);  // kappa = 5/6
  constexpr std::uint8_t kEndA = 0x0f;                                     // ux, uy, uz, rx
  constexpr std::uint8_t kEndB = 0x06;                                     // uy, uz
  spec = {};
  ntn_test::straight_beam(spec, kL, kMat, kSec, kEndA, kEndB);
  spec.settings.rotary_inertia = true;
  // The consistent nodal loads of the uniform q along y (see the top of the file).
  const double h = kL / kElements;
  for (int k = 0; k <= kElements; ++k) {
    const double f = (k == 0 || k == kElements) ? kQ * h / 2 : kQ * h;
    spec.loads[static_cast<std::size_t>(k)] = {k, ntn::kUy, f, ntn::kConstant};
  }
  spec.loads[kElements + 1] = {0, ntn::kRz, kQ * h * h / 12, ntn::kConstant};
  spec.loads[kElements + 2] = {kElements, ntn::kRz, -kQ * h * h / 12, ntn::kConstant};
  spec.settings.alpha = 5.36;
  spec.settings.beta = 7.46e-5;
  spec.settings.dt = 0.9 * ntn::stable_time_step(ntn::view(spec)).dt_stable;
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
  }
  state = {};
  ASSERT_EQ(ntn::start(model, state, scratch, {}), ntn::StepStatus::kOk);
  const std::size_t mid = ntn_test::dof(kMid, ntn::kUy);
  double peak = 0, t_peak = 0;
  const auto steps = static_cast<long>(0.025 / model.dt);  // past the first peak (~2 / 3 period)
  for (long n = 0; n < steps; ++n) {
    ASSERT_EQ(ntn::step(model, state, scratch, {}), ntn::StepStatus::kOk);
    const double u = state.u[mid];  // u_{n+1}
    if (u > peak) peak = u, t_peak = static_cast<double>(state.tick) * model.dt;
  }
  std::printf(
      "  NAFEMS 5T: dt = %.3e s (stable %.3e s); peak midspan deflection %.4f mm at %.2f ms "
      "(reference 1.043 mm at 11.7 ms): %+.2f %%, %+.2f %%\n",
      model.dt, model.stable.dt_stable, 1e3 * peak, 1e3 * t_peak, 100 * (peak / 1.043e-3 - 1),
      100 * (t_peak / 11.7e-3 - 1));
  EXPECT_NEAR(peak / 1.043e-3, 1.0, 0.02);
  EXPECT_NEAR(t_peak / 11.7e-3, 1.0, 0.02);
}

}  // namespace
