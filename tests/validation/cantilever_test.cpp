// Cantilever validation: static tip deflection by damped dynamic relaxation, the first
// three bending frequencies of the kernel's own mass and stiffness, the time-stepping response
// at the first frequency, and the dynamic amplification of a suddenly applied load. All against
// Euler-Bernoulli closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "ntn/kernel.hpp"
#include "support/assemble.hpp"
#include "support/builders.hpp"
#include "support/closed_forms.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"
#include "support/relaxation.hpp"
#include "support/zero_crossings.hpp"

namespace cantilever_test {

using ntn_test::dof;
constexpr double kPi = 3.14159265358979323846;

// Steel cantilever, L = 2 m, 20 elements, solid 50 x 20 mm rectangle: A = 1e-3 m^2,
// Iy = 3.33e-8 m^4 (bending in x-z, deflection uz), Iz = 2.08e-7 m^4 (x-y, deflection uy).
constexpr double kLength = 2.0;
constexpr ntn_test::Section kSection = ntn_test::rectangle(0.05, 0.02);
constexpr ntn_test::Material kMat = ntn_test::kSteel;
constexpr int kElements = 20;
constexpr int kTip = kElements;
constexpr ntn::Sizes kS{.nodes = kElements + 1, .elements = kElements, .loads = 1};

ntn::ModelSpec<kS> spec;
ntn::Model<kS> model;
ntn::State<kS> state;
ntn::Scratch<kS> scratch;

// Builds the cantilever (node 0 clamped) with a tip load P in DOF `load_dof`, damping alpha and
// dt = 0.9 dt_stable; returns the init status.
ntn::InitStatus build(int load_dof, double P, double alpha) {
  spec = {};
  ntn_test::straight_beam(spec, kLength, kMat, kSection);
  spec.loads[0] = {kTip, load_dof, P, ntn::kConstant};
  spec.settings.alpha = alpha;
  const ntn::StableStepReport r = ntn::stable_time_step(ntn::view(spec));
  spec.settings.dt = 0.9 * r.dt_stable;
  const ntn_test::EigenNoMalloc guard;
  return ntn_test::init_model(spec, model);
}

// Euler-Bernoulli cantilever: omega_i = (beta_i L)^2 sqrt(E I / (rho A)) / L^2.
double omega_closed_form(int i, double I) {
  const double b = ntn_test::cantilever_beta_l(i);
  return b * b / (kLength * kLength) * std::sqrt(kMat.E * I / (kMat.rho * kSection.A));
}

TEST(Cantilever, BetaRootsMatchTheIssue) {
  // The Newton refinement must stay on the issue's roots (to their 5 digits).
  EXPECT_NEAR(ntn_test::cantilever_beta_l(0), 1.8751, 5e-5);
  EXPECT_NEAR(ntn_test::cantilever_beta_l(1), 4.6941, 5e-5);
  EXPECT_NEAR(ntn_test::cantilever_beta_l(2), 7.8548, 5e-5);
}

// Static tip deflection PL^3 / (3 E I) by dynamic relaxation in both bending planes. Cubic
// Hermite elements reproduce the Euler-Bernoulli solution of a point-loaded beam exactly at the
// nodes, so the only error is the relaxation's: converged to 1e-10 in residual and motion, the
// deflection should be right to ~1e-9. Tolerance 0.5 %.
TEST(Cantilever, StaticTipDeflectionByDynamicRelaxation) {
  struct Case {
    int dof, other;
    double I;
  };
  for (const Case c :
       {Case{ntn::kUz, ntn::kUy, kSection.Iy}, Case{ntn::kUy, ntn::kUz, kSection.Iz}}) {
    const double P = 100.0;  // N
    // Mass-proportional damping at critical for mode 1 of this plane: alpha = 2 omega_1.
    ASSERT_TRUE(build(c.dof, P, 2.0 * omega_closed_form(0, c.I)).ok());
    state = {};
    ntn_test::RelaxationResult r;
    {
      const ntn_test::EigenNoMalloc guard;
      r = ntn_test::relax(model, state, scratch, 1e-10, 2'000'000);
    }
    ASSERT_TRUE(r.converged) << "residual " << r.residual << " motion " << r.motion;
    const double expected = P * kLength * kLength * kLength / (3.0 * kMat.E * c.I);
    const double tip = state.u[dof(kTip, c.dof)];
    const double err = std::abs(tip / expected - 1.0);
    std::printf("  load in dof %d: %lld steps, tip %.9e m, PL^3/3EI %.9e m, error %.2e\n", c.dof,
                static_cast<long long>(r.steps), tip, expected, err);
    EXPECT_LT(err, 5e-3);
    // The other plane is not loaded and not coupled (principal axes along y and z).
    EXPECT_EQ(state.u[dof(kTip, c.other)], 0.0);
    // Tip rotation PL^2 / (2 E I): about -y for +uz, about +z for +uy. Same tolerance.
    const double rot =
        c.dof == ntn::kUz ? -state.u[dof(kTip, ntn::kRy)] : state.u[dof(kTip, ntn::kRz)];
    EXPECT_NEAR(rot / (P * kLength * kLength / (2.0 * kMat.E * c.I)), 1.0, 5e-3);
  }
}

// Modal analysis of a cantilever of N elements with the kernel's lumped (HRZ) mass and
// stiffness: relative errors of the first three bending frequencies of each plane against
// Euler-Bernoulli, plane x-z (uz, Iy) in [0..2], plane x-y (uy, Iz) in [3..5].
template <int N>
std::array<double, 6> frequency_errors() {
  constexpr ntn::Sizes S{.nodes = N + 1, .elements = N};
  static ntn::ModelSpec<S> sp;
  sp = {};
  ntn_test::straight_beam(sp, kLength, kMat, kSection);
  const ntn_test::Modes m = ntn_test::modes(ntn::view(sp));
  const std::vector<Eigen::Index> z = ntn_test::modes_in(m, {ntn::kUz, ntn::kRy});
  const std::vector<Eigen::Index> y = ntn_test::modes_in(m, {ntn::kUy, ntn::kRz});
  std::array<double, 6> err{};
  if (z.size() < 3 || y.size() < 3) return {1, 1, 1, 1, 1, 1};
  for (std::size_t i = 0; i < 3; ++i) {
    err[i] = m.omega(z[i]) / omega_closed_form(static_cast<int>(i), kSection.Iy) - 1.0;
    err[i + 3] = m.omega(y[i]) / omega_closed_form(static_cast<int>(i), kSection.Iz) - 1.0;
    std::printf("  N = %d, mode %zu: error %+.4e (x-z plane), %+.4e (x-y plane)\n", N, i + 1,
                err[i], err[i + 3]);
  }
  return err;
}

// First three bending frequencies of the 20-element cantilever from the kernel's own lumped mass
// and stiffness (the modal analysis uses the kernel's element functions; the time-stepping test
// below confirms it is the model step() integrates), against Euler-Bernoulli.
//
// Measured: -0.129 %, -0.499 %, -0.892 % in both planes (the error is relative, so it does not
// depend on I). Modes 1 and 2 meet the issue's 0.5 %. Mode 3 does NOT, and cannot with a lumped
// mass at this mesh: the HRZ rotational mass rho A l^3 / 78 (DESIGN §4) is implemented exactly
// (beam_test checks it against the consistent mass it is derived from), the error converges at
// second order (next test), and a diagonal mass with zero rotational inertia would still give
// -0.65 %, a consistent mass +0.002 %. So mode 3 is held to 1 % here, a deliberate, reported
// deviation from the issue's figure; the issue's 0.5 % is met for all three modes at 40 elements.
TEST(Cantilever, FirstThreeBendingFrequencies) {
  const std::array<double, 6> e = frequency_errors<kElements>();
  for (std::size_t i = 0; i < 6; ++i) {
    const bool mode3 = i % 3 == 2;
    EXPECT_LT(std::abs(e[i]), mode3 ? 1e-2 : 5e-3) << "mode " << i % 3 + 1;
    EXPECT_LT(e[i], 0.0) << "a lumped mass underestimates these frequencies";
  }
}

// The lumped-mass frequency error is a discretization error of order h^2: halving the element
// length divides it by 4 (tolerance 2.5 % on that ratio; the h^4 term changes it by ~0.5 %
// at mode 3). Then Richardson extrapolation (4 e_40 - e_20) / 3 removes the h^2 term and must
// land on the closed form to within the h^4 remainder, ~1e-4 at these meshes (tolerance 2e-4).
// A wrong mass or stiffness term would converge to a wrong limit or at a wrong rate. At 40
// elements all three modes meet the issue's 0.5 %.
TEST(Cantilever, FrequencyErrorIsSecondOrderInTheMesh) {
  const std::array<double, 6> e20 = frequency_errors<20>();
  const std::array<double, 6> e40 = frequency_errors<40>();
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_NEAR(e20[i] / e40[i], 4.0, 0.1) << "mode " << i % 3 + 1;
    const double extrapolated = (4.0 * e40[i] - e20[i]) / 3.0;
    std::printf("  mode %zu: Richardson-extrapolated error %+.2e\n", i % 3 + 1, extrapolated);
    EXPECT_LT(std::abs(extrapolated), 2e-4) << "mode " << i % 3 + 1;
    EXPECT_LT(std::abs(e40[i]), 5e-3) << "mode " << i % 3 + 1;
  }
}

// Free vibration in the kernel, started from the first mode shape of each plane (from the modal
// analysis above). Each plane then carries a single discrete mode, which central difference
// advances with the exact phase omega_h dt per step, omega_h = (2/dt) asin(omega dt / 2)
// (STYLE, "Numerics to remember"). The period is measured from linearly interpolated zero
// crossings of the tip displacement over many cycles, which resolves frequency to ~1e-11
// (measured 3e-12). The test asks the measurement to sit ten times closer to omega_h than the
// shift omega_h / omega - 1 = (omega dt)^2 / 24 + ... (3e-9 and 2e-8 in the two planes here), so
// it sees omega_h, not omega. The result is also held to 0.5 %
// of the Euler-Bernoulli closed form.
TEST(Cantilever, TimeSteppingOscillatesAtTheFirstFrequency) {
  ASSERT_TRUE(build(ntn::kUz, 0.0, 0.0).ok());
  const ntn_test::Modes m = ntn_test::modes(ntn::view(spec));
  const Eigen::Index mz = ntn_test::modes_in(m, {ntn::kUz, ntn::kRy}).front();
  const Eigen::Index my = ntn_test::modes_in(m, {ntn::kUy, ntn::kRz}).front();
  state = {};
  const double sz = 1e-3 / m.shapes(static_cast<Eigen::Index>(dof(kTip, ntn::kUz)), mz);
  const double sy = 1e-3 / m.shapes(static_cast<Eigen::Index>(dof(kTip, ntn::kUy)), my);
  for (Eigen::Index j = 0; j < m.shapes.rows(); ++j) {
    state.u[static_cast<std::size_t>(j)] = sz * m.shapes(j, mz) + sy * m.shapes(j, my);
  }
  const double dt = model.dt;
  const double period_z = 2 * kPi / m.omega(mz);
  const auto steps = static_cast<long>(10.5 * period_z / dt);  // ten periods of the slower plane

  ntn_test::ZeroCrossings cz(state.u[dof(kTip, ntn::kUz)]), cy(state.u[dof(kTip, ntn::kUy)]);
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_EQ(ntn::start(model, state, scratch, {}), ntn::StepStatus::kOk);
    for (long n = 0; n < steps; ++n) {
      ASSERT_EQ(ntn::step(model, state, scratch, {}), ntn::StepStatus::kOk);
      const double t = static_cast<double>(state.tick) * dt;
      cz.add(state.u[dof(kTip, ntn::kUz)], t, dt);
      cy.add(state.u[dof(kTip, ntn::kUy)], t, dt);
    }
  }
  struct Check {
    const char* name;
    const ntn_test::ZeroCrossings& c;
    double omega, I;
  };
  for (const Check& k :
       {Check{"uz", cz, m.omega(mz), kSection.Iy}, Check{"uy", cy, m.omega(my), kSection.Iz}}) {
    ASSERT_GE(k.c.count(), 20);
    const double omega_h = 2.0 / dt * std::asin(k.omega * dt / 2.0);
    const double measured = k.c.omega();
    std::printf(
        "  %s: %d crossings, measured %.12f rad/s, omega_h %.12f, omega %.12f "
        "(meas/omega_h - 1 = %.2e, omega_h/omega - 1 = %.2e, vs Euler-Bernoulli %+.3e)\n",
        k.name, k.c.count(), measured, omega_h, k.omega, measured / omega_h - 1.0,
        omega_h / k.omega - 1.0, measured / omega_closed_form(0, k.I) - 1.0);
    EXPECT_LT(std::abs(measured / omega_h - 1.0), 0.1 * (omega_h / k.omega - 1.0));
    EXPECT_NEAR(measured / omega_closed_form(0, k.I), 1.0, 5e-3);
  }
}

// Suddenly applied constant load, undamped. For any linear undamped system started at rest, the
// response at the loaded tip is u(t) = sum_i c_i (1 - cos omega_i t) with c_i = P phi_i(tip)^2 /
// omega_i^2 > 0 and sum_i c_i = delta_static; central difference keeps this form with omega_h,i
// (the start v_-1/2 = -dt/2 a_0 makes u_n symmetric about n = 0). So the peak lies between
// 2 c_1 and 2 delta_static, and equals 2 x static only for a single mode. A heavy tip mass on a
// light cantilever makes the first mode carry almost all of the static tip deflection; the test
// computes that share c_1 / delta from the modal analysis and requires it above 0.99, which
// bounds the peak within 1 % of 2 x static. Tolerance 2 %. The static deflection is
// the closed form P L^3 / (3 E I) (cubic elements are exact for it).
TEST(Cantilever, SuddenlyAppliedLoadPeaksAtTwiceTheStaticDeflection) {
  constexpr int kN = 10;
  constexpr ntn::Sizes S{.nodes = kN + 1, .elements = kN, .loads = 1};
  static ntn::ModelSpec<S> sp;
  static ntn::Model<S> mo;
  static ntn::State<S> st;
  static ntn::Scratch<S> sc;
  const double P = 1000.0, tip_mass = 200.0;  // N; kg, 12.7 x the beam's 15.7 kg
  sp = {};
  ntn_test::straight_beam(sp, kLength, kMat, kSection);
  sp.nodes[kN].added = {tip_mass, tip_mass, tip_mass, 0, 0, 0};
  sp.loads[0] = {kN, ntn::kUy, P, ntn::kConstant};  // constant from t = 0: a step load
  sp.settings.dt = 0.9 * ntn::stable_time_step(ntn::view(sp)).dt_stable;

  const ntn_test::Modes m = ntn_test::modes(ntn::view(sp));
  const auto tip = static_cast<Eigen::Index>(dof(kN, ntn::kUy));
  const Eigen::Index first = ntn_test::modes_in(m, {ntn::kUy, ntn::kRz}).front();
  double delta = 0;
  for (Eigen::Index i = 0; i < m.omega.size(); ++i) {
    delta += P * m.shapes(tip, i) * m.shapes(tip, i) / (m.omega(i) * m.omega(i));
  }
  const double c1 =
      P * m.shapes(tip, first) * m.shapes(tip, first) / (m.omega(first) * m.omega(first));
  const double static_closed = P * kLength * kLength * kLength / (3.0 * kMat.E * kSection.Iz);
  EXPECT_NEAR(delta / static_closed, 1.0, 1e-9);  // modal sum = exact static deflection
  ASSERT_GT(c1 / delta, 0.99) << "not single-mode dominated: the 2 % bound does not follow";

  double peak = 0;
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(sp, mo).ok());
    st = {};
    ASSERT_EQ(ntn::start(mo, st, sc, {}), ntn::StepStatus::kOk);
    const double t_end = 1.5 * 2 * kPi / m.omega(first);  // past the first peak at T1 / 2
    while (static_cast<double>(st.tick) * mo.dt < t_end) {
      ASSERT_EQ(ntn::step(mo, st, sc, {}), ntn::StepStatus::kOk);
      peak = std::max(peak, st.u[dof(kN, ntn::kUy)]);
    }
  }
  std::printf("  mode-1 share of the static tip deflection %.5f, peak / static %.5f\n", c1 / delta,
              peak / static_closed);
  EXPECT_NEAR(peak / (2.0 * static_closed), 1.0, 0.02);
  EXPECT_LE(peak, 2.0 * static_closed * (1 + 1e-9));  // the upper bound above, to rounding
}

}  // namespace cantilever_test
