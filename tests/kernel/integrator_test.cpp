// Central difference (kernel/include/ntn/integrator.hpp, DESIGN §5): the start and the update
// against the equations written with dense matrices, the discrete frequency of the highest mode,
// and energy over 1e5 undamped steps at 0.9 dt_stable.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "ntn/kernel.hpp"
#include "support/assemble.hpp"
#include "support/builders.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"

namespace integrator_test {

using ntn_test::dof;

// 20-element steel cantilever as in cantilever_test, plus a time-varying tip load.
constexpr int kN = 20;
constexpr ntn::Sizes kS{
    .nodes = kN + 1, .elements = kN, .time_functions = 1, .time_points = 3, .loads = 2};
constexpr ntn_test::Section kSection = ntn_test::rectangle(0.05, 0.02);

ntn::ModelSpec<kS> spec;
ntn::Model<kS> model;
ntn::State<kS> state;
ntn::Scratch<kS> scratch;

void build(double alpha, double dt_factor, bool loaded) {
  spec = {};
  ntn_test::straight_beam(spec, 2.0, ntn_test::kSteel, kSection, ntn_test::kFixedAll, 0,
                          {1, 0.2, -0.3}, {0, 0, 1});  // skew, so every DOF couples
  spec.time_points = {{{0.0, 0.0}, {1e-3, 1.0}, {2e-3, -0.5}}};
  spec.time_functions[0] = {0, 3};
  spec.loads[0] = {kN, ntn::kUz, loaded ? 500.0 : 0.0, 0};
  spec.loads[1] = {kN / 2, ntn::kRx, loaded ? 20.0 : 0.0, ntn::kConstant};
  spec.settings.alpha = alpha;
  spec.settings.dt = dt_factor * ntn::stable_time_step(ntn::view(spec)).dt_stable;
}

void random_displacement(std::uint64_t seed, double amplitude) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  state = {};
  for (int n = 1; n <= kN; ++n) {  // node 0 is clamped
    for (int d = 0; d < 6; ++d)
      state.u[dof(n, d)] = u(rng);
  }
}

// The kernel against DESIGN §5 written out with a dense K, the lumped M and C = alpha M:
// a_n = M^-1 (P_n - K u_n - C v_{n-1/2}), v_{n+1/2} = v_{n-1/2} + dt a_n, u_{n+1} = u_n + dt
// v_{n+1/2}, started by v_{-1/2} = v_0 - dt/2 a_0 (C v_0 in a_0). With damping_velocity =
// "central" C acts at v_n: (M + C dt/2) a_n = P_n - K u_n - C v_{n-1/2}, and a_0 as before (v_0 is
// known). Same equations, different summation order: agreement to rounding, 1e-11 relative over
// 300 steps.
class IntegratorModes : public ::testing::TestWithParam<ntn::DampingVelocity> {};

TEST_P(IntegratorModes, MatchesTheCentralDifferenceEquations) {
  const bool central = GetParam() == ntn::DampingVelocity::kCentral;
  build(/*alpha=*/30.0, 0.9, /*loaded=*/true);
  spec.settings.damping_velocity = GetParam();
  const auto view = ntn::view(spec);
  const Eigen::MatrixXd K = ntn_test::global_stiffness(view);
  const Eigen::VectorXd M = ntn_test::lumped_mass(view);
  const std::vector<Eigen::Index> free = ntn_test::free_dofs(view);
  random_displacement(1, 1e-4);
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> vel(-1e-2, 1e-2);
  for (Eigen::Index j : free)
    state.v[static_cast<std::size_t>(j)] = vel(rng);

  const Eigen::Index n = K.rows();
  Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(state.u.data(), n);
  Eigen::VectorXd v = Eigen::Map<const Eigen::VectorXd>(state.v.data(), n);
  const double dt = spec.settings.dt, alpha = spec.settings.alpha;
  const double factor = central ? 1 + alpha * dt / 2 : 1.0;  // M_e = factor M in a step
  auto accel = [&](double t, double mass_factor) {
    Eigen::VectorXd p = Eigen::VectorXd::Zero(n);
    for (const ntn::LoadSpec& l : spec.loads) {
      p(6 * l.node + l.dof) +=
          l.value * ntn::load_factor(spec.time_points, spec.time_functions, l.time_function, t);
    }
    const Eigen::VectorXd r = p - K * u - alpha * M.cwiseProduct(v);
    Eigen::VectorXd a = Eigen::VectorXd::Zero(n);
    for (Eigen::Index j : free)
      a(j) = r(j) / (M(j) * mass_factor);
    return a;
  };
  v -= 0.5 * dt * accel(0.0, 1.0);
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
    ASSERT_EQ(ntn::start(model, state, scratch, {}), ntn::StepStatus::kOk);
  }
  for (int step = 0; step < 300; ++step) {
    const Eigen::VectorXd a = accel(step * dt, factor);
    v += dt * a;
    u += dt * v;
    {
      const ntn_test::EigenNoMalloc guard;
      ASSERT_EQ(ntn::step(model, state, scratch, {}), ntn::StepStatus::kOk);
    }
  }
  const Eigen::VectorXd ku = Eigen::Map<const Eigen::VectorXd>(state.u.data(), n);
  const Eigen::VectorXd kv = Eigen::Map<const Eigen::VectorXd>(state.v.data(), n);
  EXPECT_LT((ku - u).cwiseAbs().maxCoeff(), 1e-11 * u.cwiseAbs().maxCoeff());
  EXPECT_LT((kv - v).cwiseAbs().maxCoeff(), 1e-11 * v.cwiseAbs().maxCoeff());
  EXPECT_EQ(state.tick, 300);
  for (int d = 0; d < 6; ++d) {  // the clamped node never moves
    EXPECT_EQ(state.u[dof(0, d)], 0.0);
    EXPECT_EQ(state.v[dof(0, d)], 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(Integrator, IntegratorModes,
                         ::testing::Values(ntn::DampingVelocity::kLagged,
                                           ntn::DampingVelocity::kCentral),
                         [](const ::testing::TestParamInfo<ntn::DampingVelocity>& i) {
                           return i.param == ntn::DampingVelocity::kCentral ? "Central" : "Lagged";
                         });

// The highest mode of the 20-element model, alone: central difference advances it by the phase
// theta with cos(theta) = 1 - (omega dt)^2 / 2, i.e. omega_h = (2/dt) asin(omega dt / 2)
// (STYLE, "Numerics to remember"), and keeps its amplitude. Measured on the modal coordinate
// q_n = phi^T M u_n by least squares on q_{n+1} + q_{n-1} = 2 cos(theta) q_n. At 0.9 dt_stable
// this mode has omega dt = 1.73 and omega_h / omega - 1 = 21 %, so the comparison separates
// omega_h from omega by far; tolerance 1e-9 (rounding over 2e4 steps).
TEST(Integrator, HighestModeOscillatesAtTheDiscreteFrequency) {
  build(0.0, 0.9, false);
  const ntn_test::Modes m = ntn_test::modes(ntn::view(spec));
  const Eigen::Index top = m.omega.size() - 1;
  const Eigen::VectorXd phi = m.shapes.col(top);
  state = {};
  for (Eigen::Index j = 0; j < phi.size(); ++j)
    state.u[static_cast<std::size_t>(j)] = 1e-6 * phi(j);
  auto modal = [&]() {
    double q = 0;
    for (Eigen::Index j = 0; j < phi.size(); ++j) {
      q += phi(j) * m.mass(j) * state.u[static_cast<std::size_t>(j)];
    }
    return q;
  };
  std::vector<double> q{modal()};
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
    ASSERT_EQ(ntn::start(model, state, scratch, {}), ntn::StepStatus::kOk);
  }
  q.reserve(20'001);
  for (int step = 0; step < 20'000; ++step) {
    {
      const ntn_test::EigenNoMalloc guard;
      ASSERT_EQ(ntn::step(model, state, scratch, {}), ntn::StepStatus::kOk);
    }
    q.push_back(modal());
  }
  double num = 0, den = 0, amp = 0;
  for (std::size_t k = 1; k + 1 < q.size(); ++k) {
    num += q[k] * (q[k + 1] + q[k - 1]);
    den += 2 * q[k] * q[k];
    amp = std::max(amp, std::abs(q[k]));
  }
  const double dt = model.dt, omega = m.omega(top);
  const double theta = std::acos(num / den);
  const double omega_h = 2.0 / dt * std::asin(omega * dt / 2.0);
  std::printf("  omega dt = %.4f: measured / omega_h - 1 = %.2e, omega_h / omega - 1 = %.4f\n",
              omega * dt, theta / dt / omega_h - 1.0, omega_h / omega - 1.0);
  EXPECT_NEAR(theta / dt / omega_h, 1.0, 1e-9);
  EXPECT_GT(omega_h / omega - 1.0, 0.05);
  EXPECT_NEAR(amp / std::abs(q[0]), 1.0, 1e-6);  // undamped: no growth, no decay
}

// Undamped free vibration from a random initial displacement (all modes, fixed seed), 1e5
// steps at 0.9 dt_stable. Two energies:
//  - the quantity central difference conserves exactly for a linear undamped system,
//    E_h = 1/2 v_{n+1/2}^T M v_{n+1/2} + 1/2 u_n^T K u_{n+1} (K u_n is the kernel's F_n): it
//    must stay at its initial value to rounding (tolerance 1e-9 relative: ~1e5 steps of
//    ~1e-16 errors, accumulated as a random walk; measured 1e-14);
//  - the mechanical energy at whole steps with v_n = (v_{n-1/2} + v_{n+1/2}) / 2, which for a
//    start from rest never exceeds its initial value (each mode: E_0 (1 - (omega dt)^2 / 4
//    sin^2 n theta)), to the same tolerance.
// And the criterion, no growth: the maximum over the last 10 % of the run is not above
// the maximum over the first 10 %.
TEST(Integrator, UndampedEnergyIsConservedOver1e5Steps) {
  build(0.0, 0.9, false);
  random_displacement(42, 1e-4);
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
    ASSERT_EQ(ntn::start(model, state, scratch, {}), ntn::StepStatus::kOk);
  }
  constexpr long kSteps = 100'000;
  double eh0 = 0, e0 = 0, eh_dev = 0, e_max = 0, first = 0, last = 0;
  std::array<double, ntn::State<kS>::kDofs> u_n{}, v_prev{};
  const ntn_test::EigenNoMalloc guard;
  for (long n = 0; n < kSteps; ++n) {
    u_n = state.u, v_prev = state.v;
    ASSERT_EQ(ntn::step(model, state, scratch, {}), ntn::StepStatus::kOk);
    double eh = 0, e = 0;
    for (std::size_t j = 0; j < u_n.size(); ++j) {
      const double vn = 0.5 * (v_prev[j] + state.v[j]);
      eh += 0.5 * model.mass[j] * state.v[j] * state.v[j] + 0.5 * scratch.f[j] * state.u[j];
      e += 0.5 * model.mass[j] * vn * vn + 0.5 * scratch.f[j] * u_n[j];
    }
    if (n == 0) eh0 = eh, e0 = e;
    eh_dev = std::max(eh_dev, std::abs(eh / eh0 - 1.0));
    e_max = std::max(e_max, e);
    if (n < kSteps / 10) first = std::max(first, eh);
    if (n >= kSteps - kSteps / 10) last = std::max(last, eh);
  }
  std::printf(
      "  max |E_h / E_h0 - 1| = %.2e, max E_n / E_0 - 1 = %.2e, last/first 10 %% max - 1 = "
      "%.2e\n",
      eh_dev, e_max / e0 - 1.0, last / first - 1.0);
  EXPECT_LT(eh_dev, 1e-9);
  EXPECT_LE(e_max, e0 * (1 + 1e-9));
  EXPECT_LE(last, first * (1 + 1e-9));
}

}  // namespace integrator_test

namespace integrator_test {

// initial_state(): the model's u_0 and v_0 (NodeSpec::u0, v0) into the state, every counter of
// a previous run reset; a run from it equals a run whose caller wrote the same u_0, v_0 into a
// fresh State (the same bits after 200 steps).
TEST(Integrator, InitialStateIsTheModelsU0AndV0) {
  build(/*alpha=*/5.0, 0.9, /*loaded=*/true);
  spec.nodes[kN].u0 = {1e-3, -2e-3, 5e-4, 0, 1e-3, -1e-3};
  spec.nodes[kN / 2].v0 = {0, 0.1, 0, 0.2, 0, 0};
  ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
  state.tick = 77, state.faults = 3, state.inputs_held = 2, state.u[dof(1, 0)] = 9;
  ntn::initial_state(model, state);
  EXPECT_EQ(state.tick, 0);
  EXPECT_EQ(state.faults, 0U);
  EXPECT_EQ(state.inputs_held, 0U);
  for (int n = 0; n <= kN; ++n) {
    for (int d = 0; d < 6; ++d) {
      EXPECT_EQ(state.u[dof(n, d)],
                spec.nodes[static_cast<std::size_t>(n)].u0[static_cast<std::size_t>(d)]);
      EXPECT_EQ(state.v[dof(n, d)],
                spec.nodes[static_cast<std::size_t>(n)].v0[static_cast<std::size_t>(d)]);
    }
  }
  const auto run = [](ntn::State<kS>& s) {
    EXPECT_EQ(ntn::start(model, s, scratch, {}), ntn::StepStatus::kOk);
    for (int n = 0; n < 200; ++n)
      EXPECT_EQ(ntn::step(model, s, scratch, {}), ntn::StepStatus::kOk);
  };
  run(state);
  ntn::State<kS> own{};
  own.u[dof(kN, 0)] = 1e-3, own.u[dof(kN, 1)] = -2e-3, own.u[dof(kN, 2)] = 5e-4;
  own.u[dof(kN, 4)] = 1e-3, own.u[dof(kN, 5)] = -1e-3;
  own.v[dof(kN / 2, 1)] = 0.1, own.v[dof(kN / 2, 3)] = 0.2;
  run(own);
  EXPECT_EQ(std::memcmp(own.u.data(), state.u.data(), sizeof own.u), 0);
  EXPECT_EQ(std::memcmp(own.v.data(), state.v.data(), sizeof own.v), 0);
}

}  // namespace integrator_test
