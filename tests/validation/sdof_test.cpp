// The single-degree-of-freedom oscillator without members (config/sdof.toml: m = 1000 kg on a
// spring k = 400 kN/m to the ground along x, the other directions rigid; omega = 20 rad/s), run
// by the kernel from the model file's text in run-time storage (ntn::hil::LoadedModel, as ntn-run
// loads it), with the hinge's dashpot taken out, against truth of its own:
//
// - Free vibration from u_0, v_0 = 0: central difference is the recurrence
//   u_{n+1} - 2 u_n + u_{n-1} = -(omega dt)^2 u_n started with u_1 = u_0 (1 - (omega dt)^2 / 2)
//   (v_{-1/2} = v_0 - dt/2 a_0, DESIGN §5), whose solution is exactly
//   u_n = u_0 cos(omega_h n dt),  omega_h = (2 / dt) asin(omega dt / 2)
//   (cos(omega_h dt) = 1 - 2 sin^2(omega_h dt / 2) = 1 - (omega dt)^2 / 2). Tolerance 1e-9 u_0
//   over 10^4 steps: rounding only (each step adds a few ulp of u_0; the closed form's own cos of
//   a growing argument is good to about 1e-13).
// - A step load F_0 from t = 0 (a [[loads]] table added to the text): the same recurrence about
//   the static displacement F_0 / k, u_n = (F_0 / k)(1 - cos(omega_h n dt)), to 1e-9 F_0 / k.
// - A harmonic ground acceleration a_g = A sin(Omega t) fed to the model's input ag_x at every
//   step, against the exact response of the continuous oscillator from rest,
//   u(t) = -A / (omega^2 - Omega^2) (sin(Omega t) - (Omega / omega) sin(omega t)).
//   Tolerance: central difference shortens each period by (omega dt)^2 / 24 of itself (the
//   frequency omega_h above), so the free part of amplitude (Omega / omega) A / (omega^2 - Omega^2)
//   drifts in phase by omega t (omega dt)^2 / 24 by time t; twice that bound at the run's end (the
//   forced part's error, (Omega dt)^2 / 24 relative, and the amplitudes' O((omega dt)^2) are far
//   below it). The error found is about half the allowance; a step of the wrong sign or size
//   (a ground acceleration in g taken as m/s^2: x 9.8) fails by far.
//
// Both element-pass paths (SIMD and the scalar reference: no elements, no blocks) and the
// compiled header of config/sdof.toml (compiled storage, std::arrays of no elements) give the
// same bits as the run-time storage.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "ntn/hil/loaded_model.hpp"
#include "ntn/kernel.hpp"
#include "ntn/modelc/load_model.hpp"
#include "sdof_model.hpp"
#include "support/temp_files.hpp"
#include "text_model.hpp"

namespace sdof_test {

constexpr double kM = 1000.0, kK = 4.0e5;  // kg, N/m: config/sdof.toml
const double kOmega = std::sqrt(kK / kM);  // 20 rad/s
constexpr double kG = 9.80665;             // m/s^2 per g: the input's units

// config/sdof.toml without the dashpot, and `tables` appended.
std::string undamped(const std::string& tables = "") {
  std::string t = ntn_test::read_file(NTN_CONFIG_DIR "/sdof.toml");
  const std::string damped = "ux = { linear = 4.0e5, dashpot = 2.0e3 }";
  const std::size_t at = t.find(damped);
  if (at == std::string::npos) return "";
  t.replace(at, damped.size(), "ux = { linear = 4.0e5 }");
  return t + "\n" + tables + "\n";
}

std::unique_ptr<ntn::hil::LoadedModel> load(const std::string& text) {
  return ntn_test::load_text_model(text, "sdof.toml");
}

// u at t_n (the channel "u", outputs[0]) for n = 0 .. steps - 1, from u_0 along x at rest, with
// the ground acceleration ag(n) in g.
template <class Ag>
std::vector<double> run(ntn::hil::LoadedModel& rt, ntn::ElementPass path, double u0, long steps,
                        Ag ag) {
  ntn::Model<ntn::kRunTime>& m = rt.model();
  ntn::State<ntn::kRunTime>& s = rt.state();
  ntn::Scratch<ntn::kRunTime>& w = rt.scratch();
  m.element_pass = path;
  ntn::initial_state(m, s);
  s.u[ntn::kUx] = u0;
  std::vector<double> in = {ag(0)};
  EXPECT_EQ(ntn::start(m, s, w, std::span<const double>(in)), ntn::StepStatus::kOk);
  std::vector<double> u;
  for (long n = 0; n < steps; ++n) {
    in[0] = ag(n);
    EXPECT_EQ(ntn::step(m, s, w, std::span<const double>(in)), ntn::StepStatus::kOk);
    u.push_back(w.outputs[0]);
  }
  return u;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

double omega_h(double dt) {
  return 2.0 / dt * std::asin(kOmega * dt / 2.0);
}

TEST(Sdof, FreeVibrationIsTheDiscreteClosedForm) {
  const auto rt = load(undamped());
  ASSERT_NE(rt, nullptr);
  const double dt = rt->model().dt;
  ASSERT_EQ(dt, 1e-3);
  ASSERT_EQ(rt->model().sizes.elements, 0U);
  constexpr double u0 = 0.01;     // m
  constexpr long kSteps = 10000;  // 10 s, 32 periods
  const auto none = [](long) { return 0.0; };
  const std::vector<double> simd = run(*rt, ntn::ElementPass::kSimd, u0, kSteps, none);
  const std::vector<double> scalar = run(*rt, ntn::ElementPass::kScalar, u0, kSteps, none);
  EXPECT_TRUE(same_bits(simd, scalar));
  double worst = 0;
  for (long n = 0; n < kSteps; ++n) {
    const double exact = u0 * std::cos(omega_h(dt) * static_cast<double>(n) * dt);
    worst = std::max(worst, std::abs(simd[static_cast<std::size_t>(n)] - exact));
  }
  std::printf("  free vibration: largest |u_n - u0 cos(omega_h n dt)| = %.3g u0 over %ld steps\n",
              worst / u0, kSteps);
  EXPECT_LE(worst, 1e-9 * u0);
  // Not the undamped oscillator's own cos(omega n dt): 32 periods shift it by 2e-3 rad.
  EXPECT_GT(std::abs(simd.back() - u0 * std::cos(kOmega * (kSteps - 1) * dt)), 1e-5 * u0);
}

TEST(Sdof, StepLoadIsTheDiscreteClosedForm) {
  constexpr double f0 = 1.0e4;  // N
  const auto rt = load(undamped("[[loads]]\nnode = 1\ndof = \"ux\"\nvalue = 1.0e4\n"));
  ASSERT_NE(rt, nullptr);
  const double dt = rt->model().dt;
  constexpr long kSteps = 10000;
  const std::vector<double> u =
      run(*rt, ntn::ElementPass::kSimd, 0.0, kSteps, [](long) { return 0.0; });
  const double u_static = f0 / kK;  // 0.025 m
  double worst = 0, peak = 0;
  for (long n = 0; n < kSteps; ++n) {
    const double exact = u_static * (1 - std::cos(omega_h(dt) * static_cast<double>(n) * dt));
    worst = std::max(worst, std::abs(u[static_cast<std::size_t>(n)] - exact));
    peak = std::max(peak, u[static_cast<std::size_t>(n)]);
  }
  std::printf("  step load: peak %.6f m (2 F0 / k = %.6f m), largest error %.3g F0 / k\n", peak,
              2 * u_static, worst / u_static);
  EXPECT_LE(worst, 1e-9 * u_static);
}

TEST(Sdof, HarmonicGroundAccelerationMatchesTheExactResponse) {
  const auto rt = load(undamped());
  ASSERT_NE(rt, nullptr);
  const double dt = rt->model().dt;
  constexpr double kAg = 0.1;           // g
  const double A = kAg * kG;            // m/s^2
  const double Omega = 2 * M_PI * 1.5;  // rad/s, below omega = 20 rad/s
  constexpr long kSteps = 5000;         // 5 s, 16 periods of the oscillator
  const std::vector<double> u = run(*rt, ntn::ElementPass::kSimd, 0.0, kSteps, [&](long n) {
    return kAg * std::sin(Omega * static_cast<double>(n) * dt);
  });
  const double amplitude = A / (kOmega * kOmega - Omega * Omega);
  double worst = 0, peak = 0;
  for (long n = 0; n < kSteps; ++n) {
    const double t = static_cast<double>(n) * dt;
    const double exact = -amplitude * (std::sin(Omega * t) - Omega / kOmega * std::sin(kOmega * t));
    worst = std::max(worst, std::abs(u[static_cast<std::size_t>(n)] - exact));
    peak = std::max(peak, std::abs(exact));
  }
  const double t_end = static_cast<double>(kSteps - 1) * dt;
  const double drift = Omega / kOmega * amplitude * kOmega * t_end * (kOmega * dt) * (kOmega * dt) /
                       24;  // the free part's phase drift
  std::printf("  harmonic a_g: peak %.6g m, largest error %.3g m, allowed %.3g m (2 x drift)\n",
              peak, worst, 2 * drift);
  EXPECT_LE(worst, 2 * drift);
  EXPECT_GT(peak, 1e-3);  // it moved: 4.7 mm
}

// Compiled storage (the header of config/sdof.toml, damped as the file is): the same bits as the
// same file in run-time storage, under the same harmonic ground acceleration.
namespace sdof = ntn::models::sdof;
ntn::Model<sdof::kSizes> g_model;
ntn::State<sdof::kSizes> g_state;
ntn::Scratch<sdof::kSizes> g_scratch;
ntn::InitWorkspace<sdof::kSizes> g_work;

TEST(Sdof, CompiledStorageGivesTheRunTimeBits) {
  static_assert(sdof::kSizes.elements == 0 && sdof::kSizes.nodes == 1);
  const auto rt = load(ntn_test::read_file(NTN_CONFIG_DIR "/sdof.toml"));
  ASSERT_NE(rt, nullptr);
  ASSERT_TRUE(ntn::init(sdof::kSpec, g_model, g_work).ok());
  ASSERT_EQ(g_model.dt, rt->model().dt);
  const double dt = g_model.dt;
  const auto ag = [&](long n) {
    return 0.1 * std::sin(2 * M_PI * 1.5 * static_cast<double>(n) * dt);
  };
  constexpr long kSteps = 3000;
  for (const ntn::ElementPass path : {ntn::ElementPass::kSimd, ntn::ElementPass::kScalar}) {
    const std::vector<double> u_rt = run(*rt, path, 0.0, kSteps, ag);
    g_model.element_pass = path;
    ntn::initial_state(g_model, g_state);
    ASSERT_EQ(ntn::start(g_model, g_state, g_scratch, {ag(0)}), ntn::StepStatus::kOk);
    std::vector<double> u_c;
    for (long n = 0; n < kSteps; ++n) {
      ASSERT_EQ(ntn::step(g_model, g_state, g_scratch, {ag(n)}), ntn::StepStatus::kOk);
      u_c.push_back(g_scratch.outputs[0]);
    }
    EXPECT_TRUE(same_bits(u_rt, u_c));
    EXPECT_GT(*std::max_element(u_c.begin(), u_c.end()), 1e-3);
  }
}

}  // namespace sdof_test
