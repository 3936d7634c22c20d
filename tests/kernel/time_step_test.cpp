// Stable time step (kernel/include/ntn/time_step.hpp, DESIGN §6): the element eigenvalue bound
// against closed forms, the damped formula against the amplification matrix of the update
// (DESIGN §5), the report and dt = "auto", and the tightness of the bound: a free single element
// is stable at 0.99 x the reported step and blows up at 1.05 x, with C = alpha M + beta K too.
#include <gtest/gtest.h>

#include <ostream>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "ntn/kernel.hpp"
#include "support/builders.hpp"
#include "support/hinges.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"

namespace time_step_test {

using ntn_test::Vec3;

ntn::NodeSpec node_at(double x, double y, double z) {
  ntn::NodeSpec n;
  n.x = x, n.y = y, n.z = z;
  return n;
}

const ntn_test::Section kSlender = ntn_test::circle(0.01);              // l / r = 200 at 1 m
const ntn_test::Section kStocky = ntn_test::rectangle(0.1, 0.2, true);  // l / h = 0.5 at 0.1 m

// A free-free two-node bar with lumped masses rho A l / 2 has omega^2 = 2 k / (m/2) = 4 E / (rho
// l^2): omega = 2 c / l, so dt_stable = l / c, the seed's CFL estimate (S 9-10). For a slender
// element the axial mode is the highest, so element_omega_max must equal 2 c / l (rounding of a
// 12x12 eigen solve, 1e-12). For any element it can only be larger.
TEST(ElementOmegaMax, SlenderElementIsGovernedByTheAxialMode) {
  const ntn::ElementSpec e = ntn_test::element(0, 1, ntn_test::kSteel, kSlender, {0, 0, 1});
  const double l = 1.0, c = std::sqrt(e.E / e.rho);
  const double w = ntn::element_omega_max(e, node_at(0, 0, 0), node_at(l, 0, 0), false);
  EXPECT_NEAR(w / (2 * c / l), 1.0, 1e-12);
  // Orientation does not change an element's spectrum.
  const double w2 = ntn::element_omega_max(e, node_at(1, 1, 1),
                                           node_at(1 + l / 3, 1 + 2 * l / 3, 1 - 2 * l / 3), false);
  EXPECT_NEAR(w2 / w, 1.0, 1e-12);
}

TEST(ElementOmegaMax, StockyElementIsGovernedByBendingAndAboveTheAxialMode) {
  const ntn::ElementSpec e = ntn_test::element(0, 1, ntn_test::kSteel, kStocky, {0, 0, 1});
  const double l = 0.1, c = std::sqrt(e.E / e.rho);
  const double w = ntn::element_omega_max(e, node_at(0, 0, 0), node_at(l, 0, 0), false);
  std::printf("  stocky element: omega_max / (2 c / l) = %.4f\n", w / (2 * c / l));
  EXPECT_GT(w, 2 * c / l * 1.01);  // the CFL estimate would be unsafe here: the point of §6
  EXPECT_EQ(ntn::element_omega_max(e, node_at(0, 0, 0), node_at(0, 0, 0), false), 0.0);
}

// Amplification matrix of DESIGN §5 for one mode (unit mass, stiffness omega^2, damping
// c = alpha): state (u_n, v_{n-1/2}) -> (u_{n+1}, v_{n+1/2}), written from the equations, not
// from the kernel. Its spectral radius is 1 exactly at the stable step.
double spectral_radius(double omega, double alpha, double dt) {
  Eigen::Matrix2d A;
  for (int col = 0; col < 2; ++col) {
    const double u = col == 0 ? 1.0 : 0.0, v = col == 1 ? 1.0 : 0.0;
    const double a = -omega * omega * u - alpha * v;  // a_n = M^-1 (R_n - C v_{n-1/2})
    const double v1 = v + dt * a;                     // v_{n+1/2}
    const double u1 = u + dt * v1;                    // u_{n+1}
    A(0, col) = u1, A(1, col) = v1;
  }
  return A.eigenvalues().cwiseAbs().maxCoeff();
}

// Delta t_stable = (2 / omega)(sqrt(1 + xi^2) - xi) is where the update above loses stability:
// spectral radius <= 1 just below it and > 1 just above, for damping from 0 to 100 % of
// critical. Tolerance on the radius 1e-9 (a double eigen solve near a double root).
TEST(DampedStableStep, MatchesTheAmplificationMatrixOfTheUpdate) {
  const double omega = 1e4;
  for (double xi : {0.0, 0.01, 0.1, 0.3, 1.0}) {
    const double alpha = 2 * xi * omega;
    const double dt = ntn::damped_stable_step(omega, alpha);
    EXPECT_LE(spectral_radius(omega, alpha, dt * (1 - 1e-6)), 1.0 + 1e-9) << "xi " << xi;
    EXPECT_GT(spectral_radius(omega, alpha, dt * (1 + 1e-6)), 1.0 + 1e-7) << "xi " << xi;
  }
  EXPECT_EQ(ntn::damped_stable_step(0.0, 1.0), 0.0);
}

// With stiffness-proportional damping C = alpha M + beta K the mode omega has the damping
// alpha + beta omega^2 per unit mass: the three-argument step is where the same update with that
// damping loses stability (tolerances as above), for beta alone and with alpha, top-mode ratios
// up to 1. beta = 0 is the two-argument step to the bit; a negative or NaN beta gives 0.
TEST(DampedStableStep, StiffnessProportionalMatchesTheAmplificationMatrix) {
  const double omega = 1e4;
  for (double xi_a : {0.0, 0.05}) {
    for (double xi_b : {0.01, 0.1, 0.3, 0.95}) {
      const double alpha = 2 * xi_a * omega, beta = 2 * xi_b / omega;
      const double dt = ntn::damped_stable_step(omega, alpha, beta);
      const double c = alpha + beta * omega * omega;
      EXPECT_LE(spectral_radius(omega, c, dt * (1 - 1e-6)), 1.0 + 1e-9) << xi_a << " " << xi_b;
      EXPECT_GT(spectral_radius(omega, c, dt * (1 + 1e-6)), 1.0 + 1e-7) << xi_a << " " << xi_b;
      EXPECT_LT(dt, ntn::damped_stable_step(omega, alpha));  // beta only lowers the step
    }
  }
  for (double alpha : {0.0, 3.0, 1e4}) {
    const double a = ntn::damped_stable_step(omega, alpha, 0.0);
    const double b = ntn::damped_stable_step(omega, alpha);
    EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << alpha;
  }
  EXPECT_EQ(ntn::damped_stable_step(omega, 0.0, -1e-6), 0.0);
  EXPECT_EQ(ntn::damped_stable_step(omega, 0.0, std::nan("")), 0.0);
  EXPECT_EQ(ntn::damped_stable_step(omega, 0.0, 1e308), 0.0);  // alpha + beta omega^2 overflows
}

// The report names the governing element (the shortest of three otherwise equal slender
// elements), the CFL estimate l / c and its element; with alpha the step follows the damped
// formula.
TEST(StableTimeStep, ReportNamesTheGoverningElement) {
  constexpr ntn::Sizes S{.nodes = 4, .elements = 3};
  static ntn::ModelSpec<S> spec;
  spec = {};
  ntn_test::FrameBuilder<S> f(spec);
  const int a = f.add_node({0, 0, 0}), b = f.add_node({1, 0, 0}), c = f.add_node({1.5, 0, 0}),
            d = f.add_node({2.5, 0, 0});
  f.add_member(a, b, 1, ntn_test::kSteel, kSlender, {0, 0, 1});
  f.add_member(b, c, 1, ntn_test::kSteel, kSlender, {0, 0, 1});  // 0.5 m: governs
  f.add_member(c, d, 1, ntn_test::kSteel, kSlender, {0, 0, 1});
  ASSERT_TRUE(f.complete());
  const double wave = std::sqrt(ntn_test::kSteel.E / ntn_test::kSteel.rho);
  ntn::StableStepReport r = ntn::stable_time_step(ntn::view(spec));
  EXPECT_EQ(r.governing_element, 1);
  EXPECT_EQ(r.cfl_element, 1);
  EXPECT_NEAR(r.dt_cfl, 0.5 / wave, 1e-15);
  EXPECT_NEAR(r.omega_max, 2 * wave / 0.5, 1e-12 * r.omega_max);
  EXPECT_NEAR(r.dt_stable, 0.5 / wave, 1e-12 * r.dt_stable);  // axial governs: equals the CFL
  spec.settings.alpha = 0.2 * r.omega_max;
  spec.settings.damping_velocity = ntn::DampingVelocity::kLagged;  // alpha M at v_{n-1/2} (S 3)
  r = ntn::stable_time_step(ntn::view(spec));
  EXPECT_DOUBLE_EQ(r.dt_stable, ntn::damped_stable_step(r.omega_max, spec.settings.alpha));
  EXPECT_LT(r.dt_stable, r.dt_cfl);
  // beta: the element bound with alpha + beta omega_max^2.
  spec.settings.beta = 0.1 / r.omega_max;
  const ntn::StableStepReport rb = ntn::stable_time_step(ntn::view(spec));
  EXPECT_EQ(rb.dt_stable,
            ntn::damped_stable_step(r.omega_max, spec.settings.alpha, spec.settings.beta));
  EXPECT_LT(rb.dt_stable, r.dt_stable);
  // Central: alpha drops out of the bound (stable_step_alpha), beta stays.
  spec.settings.damping_velocity = ntn::DampingVelocity::kCentral;
  EXPECT_EQ(ntn::stable_time_step(ntn::view(spec)).dt_stable,
            ntn::damped_stable_step(r.omega_max, 0.0, spec.settings.beta));
}

// A model without elements (a point mass m on a hinge spring k with a dashpot c to the ground:
// the SDOF): the elements' part of the bound is what alpha alone allows (2 / alpha; 1e300 when
// nothing bounds the step), and the step is the oscillator's own, (2 / omega)(sqrt(1 + xi^2) - xi)
// with omega^2 = k / m and xi = (alpha + c / m) / (2 omega), where the update of DESIGN §5 loses
// stability (tolerances as above; 1e-12 on the step: the node bound's 6x6 eigenvalue is k / m
// up to rounding). init() builds such a model in compiled storage, std::arrays of no elements.
TEST(StableTimeStep, WithoutElementsItIsTheOscillatorsOwn) {
  constexpr ntn::Sizes S{.nodes = 1, .hinges = 1};
  static ntn::ModelSpec<S> spec;
  static ntn::Model<S> model;
  const double m = 1000, k = 4e5, omega = std::sqrt(k / m);
  for (const auto& [c, alpha] : {std::pair{0.0, 0.0}, std::pair{2e3, 0.0}, std::pair{2e3, 3.0}}) {
    spec = {};
    spec.nodes[0].added = {m, m, m, 0, 0, 0};
    spec.hinges[0] = ntn_test::hinge(0, ntn::kGround, ntn_test::kIdentity3);
    spec.hinges[0].behaviour[ntn::kUx] = ntn::HingeBehaviour::kLinear;
    spec.hinges[0].stiffness[ntn::kUx] = k;
    spec.hinges[0].dashpot[ntn::kUx] = c;
    spec.settings.alpha = alpha;
    spec.settings.damping_velocity = ntn::DampingVelocity::kLagged;  // spectral_radius's update
    spec.settings.dt = 1e-3;
    ASSERT_TRUE(ntn_test::init_model(spec, model).ok()) << c << " " << alpha;
    const ntn::StableStepReport& r = model.stable;
    const double damping = alpha + c / m;  // per unit mass
    EXPECT_NEAR(r.dt_stable / ntn::damped_stable_step(omega, damping), 1.0, 1e-12);
    EXPECT_LE(spectral_radius(omega, damping, r.dt_stable * (1 - 1e-6)), 1.0 + 1e-9);
    EXPECT_GT(spectral_radius(omega, damping, r.dt_stable * (1 + 1e-6)), 1.0 + 1e-7);
    EXPECT_EQ(r.dt_elements, alpha > 0 ? 2 / alpha : 1e300);
    EXPECT_EQ(r.governing_hinge, 0);
    EXPECT_EQ(r.hinge_direction, ntn::kUx);
    EXPECT_EQ(r.governing_element, -1);
    EXPECT_EQ(r.cfl_element, -1);
  }
  // A free mass alone: nothing bounds the step but alpha.
  constexpr ntn::Sizes S0{.nodes = 1};
  static ntn::ModelSpec<S0> free;
  free = {};
  free.nodes[0].added = {m, m, m, 1, 1, 1};
  const std::array<double, 6> mass = free.nodes[0].added;
  EXPECT_EQ(ntn::stable_time_step(ntn::view(free), mass).dt_stable, 1e300);
  free.settings.alpha = 4.0;
  free.settings.damping_velocity = ntn::DampingVelocity::kLagged;
  EXPECT_EQ(ntn::stable_time_step(ntn::view(free), mass).dt_stable, 0.5);
  free.settings.damping_velocity = ntn::DampingVelocity::kCentral;  // alpha drops out
  EXPECT_EQ(ntn::stable_time_step(ntn::view(free), mass).dt_stable, 1e300);
}

// dt = "auto": the largest period / N, N integer, not above 0.9 dt_stable.
TEST(AutoTimeStep, LargestIntegerDivisionOfTheFrameBelowNinetyPercent) {
  for (double dt_stable : {1e-3, 2e-4, 1.234e-5, 3.3e-6, 5e-2}) {
    const double frame = 1e-3;
    const double dt = ntn::auto_time_step(dt_stable, frame);
    const double n = std::round(frame / dt);
    EXPECT_NEAR(frame / dt, n, 1e-9 * n);
    EXPECT_LE(dt, 0.9 * dt_stable);
    if (n > 1) {
      EXPECT_GT(frame / (n - 1), 0.9 * dt_stable);
    }
  }
  EXPECT_EQ(ntn::auto_time_step(0.0, 1e-3), 0.0);
}

// --- Tightness of the bound on a free single element ---------------------------------------
//
// A free element's omega_max is exactly the one init reports (no assembly, no supports), so
// its stable step is exact: at 0.99 x the response must stay bounded, at 1.05 x the highest mode
// grows by a factor |lambda| ~ 1.5 - 1.9 per step and overflows long before 1e5 steps.
//
// "Bounded" is measured with the mechanical energy at whole steps,
// E_n = 1/2 v_n^T M v_n + 1/2 u_n^T K u_n with v_n = (v_{n-1/2} + v_{n+1/2}) / 2: starting from
// rest, each undamped mode of central difference has E_n = E_0 (1 - (omega dt)^2 / 4
// sin^2(n theta)) <= E_0, so max_n E_n <= E_0 exactly; the tolerance 1e-9 covers rounding.
// With damping, the energy must not grow: the maximum over the last 10 % of the run stays below
// that over the first 10 %.

constexpr ntn::Sizes kOne{.nodes = 2, .elements = 1};
ntn::ModelSpec<kOne> one_spec;
ntn::Model<kOne> one_model;
ntn::State<kOne> one_state;
ntn::Scratch<kOne> one_scratch;

struct FreeRun {
  bool diverged = false;
  long steps = 0;
  double e0 = 0, e_max = 0, first_max = 0, last_max = 0;
};

FreeRun run_free_element(double factor, long steps) {
  FreeRun r;
  one_spec.settings.dt = factor * ntn::stable_time_step(ntn::view(one_spec)).dt_stable;
  one_spec.settings.allow_unstable = factor > 1;  // init refuses it otherwise
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(-1e-3, 1e-3);
  one_state = {};
  for (double& x : one_state.u)
    x = u(rng);
  const ntn_test::EigenNoMalloc guard;
  if (!ntn_test::init_model(one_spec, one_model).ok()) return r;
  if (ntn::start(one_model, one_state, one_scratch, {}) != ntn::StepStatus::kOk) return r;
  std::array<double, 12> u_n{}, v_prev{};
  for (long n = 0; n < steps; ++n) {
    u_n = one_state.u, v_prev = one_state.v;
    const ntn::StepStatus st = ntn::step(one_model, one_state, one_scratch, {});
    r.steps = n + 1;
    if (st == ntn::StepStatus::kDiverged) {
      r.diverged = true;
      return r;
    }
    // The elastic force K u_n (Scratch::f holds beta K v_{n-1/2} too when beta > 0).
    double fe[12];
    ntn::beam_force(one_model.beam(0), u_n.data(), u_n.data() + 6, fe, fe + 6);
    double e = 0;
    for (std::size_t j = 0; j < 12; ++j) {
      const double v = 0.5 * (v_prev[j] + one_state.v[j]);
      e += 0.5 * one_model.mass[j] * v * v + 0.5 * fe[j] * u_n[j];
    }
    if (n == 0) r.e0 = e;
    r.e_max = std::max(r.e_max, e);
    if (n < steps / 10) r.first_max = std::max(r.first_max, e);
    if (n >= steps - steps / 10) r.last_max = std::max(r.last_max, e);
  }
  return r;
}

struct ElementCase {
  const char* name;
  ntn_test::Section section;
  double length;
  Vec3 axis, ref;
  double xi;  // fraction of critical damping of the highest mode from alpha M
  bool rotary_inertia;
  double xi_beta = 0;  // ... and from beta K (beta = 2 xi_beta / omega_max)
};

// Names the case in test listings (CTest shows gtest's parameter printout otherwise).
inline void PrintTo(const ElementCase& c, std::ostream* os) {
  *os << c.name;
}

class FreeElement : public ::testing::TestWithParam<ElementCase> {};

TEST_P(FreeElement, StableAt099AndDivergesAt105TimesTheReportedStep) {
  const ElementCase& c = GetParam();
  one_spec = {};
  ntn_test::straight_beam(one_spec, c.length, ntn_test::kSteel, c.section, 0, 0, c.axis, c.ref);
  one_spec.settings.rotary_inertia = c.rotary_inertia;
  const double omega = ntn::stable_time_step(ntn::view(one_spec)).omega_max;
  one_spec.settings.alpha = 2 * c.xi * omega;
  one_spec.settings.beta = 2 * c.xi_beta / omega;

  const FreeRun ok = run_free_element(0.99, 100'000);
  ASSERT_FALSE(ok.diverged) << "diverged after " << ok.steps << " steps at 0.99 dt_stable";
  ASSERT_EQ(ok.steps, 100'000);
  if (c.xi == 0 && c.xi_beta == 0) {
    EXPECT_LE(ok.e_max, ok.e0 * (1 + 1e-9));
  } else {
    EXPECT_LE(ok.last_max, ok.first_max);
  }
  const FreeRun bad = run_free_element(1.05, 100'000);
  std::printf(
      "  %s: 0.99 x: E_max / E_0 - 1 = %.1e, last/first 10 %% max = %.3e; 1.05 x: diverged "
      "after %ld steps\n",
      c.name, ok.e_max / ok.e0 - 1, ok.last_max / ok.first_max, bad.steps);
  EXPECT_TRUE(bad.diverged);
  EXPECT_NE(one_state.faults & ntn::kFaultDiverged, 0U);
}

INSTANTIATE_TEST_SUITE_P(
    Elements, FreeElement,
    ::testing::Values(
        ElementCase{"slender", kSlender, 1.0, {1, 0, 0}, {0, 0, 1}, 0.0, false},
        ElementCase{"stocky", kStocky, 0.1, {1, 0, 0}, {0, 0, 1}, 0.0, false},
        ElementCase{"slender_inclined", kSlender, 1.0, {1, 2, -0.5}, {0.3, -0.2, 1}, 0.0, false},
        ElementCase{"stocky_inclined", kStocky, 0.1, {1, 2, -0.5}, {0.3, -0.2, 1}, 0.0, false},
        ElementCase{"stocky_rotary_inertia", kStocky, 0.1, {1, 0, 0}, {0, 0, 1}, 0.0, true},
        ElementCase{"slender_damped", kSlender, 1.0, {1, 0, 0}, {0, 0, 1}, 0.15, false},
        ElementCase{"stocky_damped", kStocky, 0.1, {1, 0, 0}, {0, 0, 1}, 0.15, false},
        ElementCase{
            "stocky_inclined_damped", kStocky, 0.1, {1, 2, -0.5}, {0.3, -0.2, 1}, 0.5, false},
        // Stiffness-proportional damping: the top mode's ratio alpha / (2 omega) + beta omega / 2
        // sets the step (exact for one element's top mode).
        ElementCase{"slender_beta", kSlender, 1.0, {1, 0, 0}, {0, 0, 1}, 0.0, false, 0.15},
        ElementCase{"stocky_beta", kStocky, 0.1, {1, 0, 0}, {0, 0, 1}, 0.0, false, 0.3},
        ElementCase{"stocky_inclined_alpha_beta",
                    kStocky,
                    0.1,
                    {1, 2, -0.5},
                    {0.3, -0.2, 1},
                    0.1,
                    false,
                    0.4}),
    [](const ::testing::TestParamInfo<ElementCase>& i) { return std::string(i.param.name); });

}  // namespace time_step_test
