// `plastic` hinge directions (HingeBehaviour::kPlastic, ntn/hysteresis.hpp) run by the
// kernel against closed forms of the bilinear elasto-plastic law and against equivalent models:
// 1. an elastic-perfectly-plastic oscillator under a suddenly applied constant force: its peak
//    displacement F_y^2 / (2 k (F_y - P0)) for F_y / 2 < P0 < F_y, and 2 P0 / k below F_y / 2;
// 2. symmetric displacement cycles imposed on a kinematic bilinear hinge (b = 0.1 and 0): the
//    loop area 4 (1 - b) F_y (u_a - u_y), the hinge_dissipated_energy channel the sum of the loop
//    areas, and the work of the hinge force the dissipated plus the elastic energy;
// 3. a hinged cantilever whose plastic hinge never yields gives the bits of the same model with
//    linear directions;
// 4. asymmetric yields: the force stays in [q - yield_neg, q + yield_pos] every step, and the
//    loop's plateaus are the two yields (b = 0); in a forced vibration, the energy balance holds
//    every step.
// The oscillator (support/plastic_models.hpp): a 1000 kg mass on a hinge of k = 1e6 N/m, F_y =
// 1e4 N (u_y = 1 cm), omega = 31.6 rad/s, T = 0.199 s, plus a soft element (E A / L = 1 N/m = 1e-6
// k in parallel, 1e-6 m of mass) that the kernel needs. Each test states its tolerance and why.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>
#include <vector>

#include "ntn/kernel.hpp"
#include "support/builders.hpp"
#include "support/hinges.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"
#include "support/plastic_models.hpp"

namespace plastic_hinge_test {

using ntn_test::dof;
using ntn_test::kSdofElementK;
using ntn_test::kSdofK;
using ntn_test::kSdofMass;
using ntn_test::kSdofYield;
using B = ntn::HingeBehaviour;
using K = ntn::OutputKind;

constexpr double kPi = 3.14159265358979323846;
const double kOmega = std::sqrt(kSdofK / kSdofMass);  // rad/s
const double kPeriod = 2 * kPi / kOmega;              // s

using ntn_test::Sim;

// Oscillator with one nodal load at the mass (constant: from t = 0 on) and one force input at it;
// channels: the hinge's force, deformation, plastic deformation, dissipated energy.
constexpr ntn::Sizes kOsc = ntn_test::sdof_sizes({.loads = 1, .inputs = 1, .outputs = 4});
Sim<kOsc> osc;

void build_oscillator(const ntn::HysteresisSpec& law, double load, double dt) {
  ntn::ModelSpec<kOsc>& s = osc.spec;
  ntn_test::plastic_oscillator(s, law);
  s.loads[0] = {0, ntn::kUx, load, ntn::kConstant};
  s.inputs[0] = {ntn::InputKind::kNodalForce, 0, ntn::kUx, 1.0, -1e300, 1e300};
  s.outputs[0] = ntn_test::hinge_channel(K::kHingeForce);
  s.outputs[1] = ntn_test::hinge_channel(K::kHingeDisplacement);
  s.outputs[2] = ntn_test::hinge_channel(K::kHingePlastic);
  s.outputs[3] = ntn_test::hinge_channel(K::kHingeDissipated);
  s.settings.dt = dt;
  EXPECT_LT(dt, ntn_test::hinged_stable_step(s).dt_stable);
  const ntn_test::EigenNoMalloc guard;
  const ntn::InitStatus st = ntn_test::init_model(s, osc.model);
  EXPECT_TRUE(st.ok()) << ntn::to_string(st.error) << " at " << st.where;
  osc.state = {};
  EXPECT_EQ(ntn::start(osc.model, osc.state, osc.scratch, {0.0}), ntn::StepStatus::kOk);
}

// ---- 1. Sudden constant force on the elastic-perfectly-plastic oscillator (b = 0, undamped).
// Energy balance at the peak (v = 0): P0 u_max = F_y^2 / (2 k) + F_y (u_max - u_y) if it yields,
// so u_max = F_y^2 / (2 k (F_y - P0)); it yields iff the elastic peak 2 P0 / k exceeds u_y, i.e.
// P0 > F_y / 2. Undamped, every later maximum equals the first; the max over six periods is taken
// (at P0 = 0.95 F_y the plastic excursion alone lasts about 3 T).
double peak_under(double load, double dt, double& dissipated) {
  build_oscillator({kSdofYield, kSdofYield, 0.0}, load, dt);
  double peak = 0;
  const auto steps = static_cast<long>(6 * kPeriod / dt);
  const ntn_test::EigenNoMalloc guard;
  for (long n = 0; n < steps; ++n) {
    EXPECT_EQ(ntn::step(osc.model, osc.state, osc.scratch, {0.0}), ntn::StepStatus::kOk);
    peak = std::max(peak, osc.state.u[dof(0, ntn::kUx)]);
  }
  dissipated = osc.state.dissipated[0];
  return peak;
}

constexpr double kOscSteps = 2000;  // dt = T / 2000: omega dt = 3.1e-3

TEST(PlasticOscillator, YieldingPeakIsTheEnergyBalance) {
  // Tolerance against F_y^2 / (2 k (F_y - P0)): the 0.5 %. The model differs from the
  // ideal oscillator by the element's k_e = 1e-6 k in parallel, which lowers the peak by
  // (k_e / k)(u_max / u_y)^2 (1e-4 at P0 = 0.95 F_y); with it, the energy balance reads
  // P0 u = k u_y^2 / 2 + F_y (u - u_y) + k_e u^2 / 2, u = F_y u_y / ((F_y - P0) +
  // sqrt((F_y - P0)^2 + k_e F_y u_y)), and against that the tolerance is (omega dt)^2 = 1e-5: the
  // central difference's second-order error, the yield point falling between two steps (the
  // return mapping acts at t_n) included. The energy the hinge absorbed on the way up is the
  // plastic work F_y (u_max - u_y) (b = 0), to the same 0.5 %.
  const double dt = kPeriod / kOscSteps;
  const double uy = kSdofYield / kSdofK;
  for (const double ratio : {0.55, 0.7, 0.8, 0.9, 0.95}) {
    const double p0 = ratio * kSdofYield;
    double dissipated = 0;
    const double peak = peak_under(p0, dt, dissipated);
    const double closed = kSdofYield * kSdofYield / (2 * kSdofK * (kSdofYield - p0));
    const double gap = kSdofYield - p0;
    const double with_element =
        kSdofYield * uy / (gap + std::sqrt(gap * gap + kSdofElementK * kSdofYield * uy));
    std::printf(
        "  P0 = %.2f F_y: peak %.6f mm, closed form %.6f mm (%+.2e), with the element "
        "%.6f mm (%+.2e), dissipated %.1f J\n",
        ratio, 1e3 * peak, 1e3 * closed, peak / closed - 1, 1e3 * with_element,
        peak / with_element - 1, dissipated);
    EXPECT_NEAR(peak / closed, 1.0, 5e-3) << "P0 = " << ratio << " F_y";
    EXPECT_NEAR(peak / with_element, 1.0, (kOmega * dt) * (kOmega * dt)) << "P0 = " << ratio;
    EXPECT_NEAR(dissipated / (kSdofYield * (closed - uy)), 1.0, 5e-3);
  }
}

TEST(PlasticOscillator, BelowHalfTheYieldItIsLinear) {
  // The central difference with the kernel's start (v_{-1/2} = v_0 - dt/2 a_0) solves the
  // undamped step response exactly as u_n = (P0 / k)(1 - cos(Omega t_n)), 2 - 2 cos(Omega dt) =
  // (omega dt)^2 (u_1 = (omega dt)^2 / 2 P0 / k is both the start's and that solution's): its
  // peak is 2 P0 / k, of which the sampled maximum misses at most 1 - cos(Omega dt / 2) <
  // (omega dt)^2 / 8 relative. The element in parallel lowers it by k_e / k = 1e-6. Tolerance:
  // the sum of the two, plus 1e-12 for rounding. No plastic deformation, no dissipation: exactly.
  const double dt = kPeriod / kOscSteps;
  const double tol = (kOmega * dt) * (kOmega * dt) / 8 + kSdofElementK / kSdofK + 1e-12;
  for (const double ratio : {0.1, 0.3, 0.45, 0.49}) {
    const double p0 = ratio * kSdofYield;
    double dissipated = 0;
    const double peak = peak_under(p0, dt, dissipated);
    const double closed = 2 * p0 / kSdofK;
    std::printf("  P0 = %.2f F_y: peak %.9f mm, 2 P0 / k %.9f mm, error %+.2e (tolerance %.1e)\n",
                ratio, 1e3 * peak, 1e3 * closed, peak / closed - 1, tol);
    EXPECT_NEAR(peak / closed, 1.0, tol) << "P0 = " << ratio << " F_y";
    EXPECT_EQ(osc.state.plastic[0], 0.0);
    EXPECT_EQ(dissipated, 0.0);
  }
}

// ---- 2. and 4. Displacement cycles imposed through the kernel's step: before each step the
// mass's u_x is set to the prescribed u(t_n) (a triangle wave: 0 -> u_a, then full cycles
// u_a -> -u_a -> u_a) and its v_{n-1/2} to the prescribed rate; the step's hinge-spring stage
// runs the return mapping at d_n = u_n and the outputs give the force, d_p and the dissipated
// energy at t_n. The step's own update of u is overwritten by the next prescribed value.
struct Cycles {
  std::vector<double> d, f, dp, dissipated;  // per sample
  long quarter = 0;                          // samples per quarter cycle
};

Cycles impose_cycles(const ntn::HysteresisSpec& law, double amplitude, int cycles, long quarter) {
  const double dt = 1e-4;
  build_oscillator(law, 0.0, dt);
  Cycles c;
  c.quarter = quarter;
  const long samples = quarter * (1 + 4 * cycles) + 1;
  const double du = amplitude / static_cast<double>(quarter);
  auto u_at = [&](long n) {  // triangle wave, exact at the vertices
    if (n <= quarter) return du * static_cast<double>(n);
    const long p = (n - quarter) % (4 * quarter);  // 0 at +u_a
    return p <= 2 * quarter ? amplitude - du * static_cast<double>(p)
                            : -amplitude + du * static_cast<double>(p - 2 * quarter);
  };
  ntn::State<kOsc>& s = osc.state;
  const ntn_test::EigenNoMalloc guard;
  for (long n = 0; n < samples; ++n) {
    s.u[dof(0, ntn::kUx)] = u_at(n);
    s.v[dof(0, ntn::kUx)] = n > 0 ? (u_at(n) - u_at(n - 1)) / dt : 0.0;
    EXPECT_EQ(ntn::step(osc.model, s, osc.scratch, {0.0}), ntn::StepStatus::kOk);
    c.f.push_back(osc.scratch.outputs[0]);
    c.d.push_back(osc.scratch.outputs[1]);
    c.dp.push_back(osc.scratch.outputs[2]);
    c.dissipated.push_back(osc.scratch.outputs[3]);
    EXPECT_EQ(c.d.back(), u_at(n));  // d = +u_x (the reversed frame)
  }
  return c;
}

// Integral of f dd over samples [a, b] (trapezoids): the force is exact at each sample (the
// bilinear law at d_n), piecewise linear in d between samples except across a kink (yield or
// reversal), where a trapezoid errs by at most |change of slope| dd^2 / 8 <= k dd^2 / 8.
double work(const Cycles& c, long a, long b) {
  double w = 0;
  for (long n = a; n < b; ++n) {
    const auto i = static_cast<std::size_t>(n);
    w += 0.5 * (c.f[i] + c.f[i + 1]) * (c.d[i + 1] - c.d[i]);
  }
  return w;
}

TEST(PlasticCycles, LoopAreaAndDissipatedEnergy) {
  // Truth: the stabilized loop of a kinematic bilinear hinge under symmetric cycles is a
  // parallelogram of area 4 (1 - b) F_y (u_a - u_y) (elastic sides of slope k, hardening sides of
  // slope b k; kinematic hardening is stable from the first full cycle on). Over a closed cycle
  // the elastic work integral k d_e dd_e vanishes, so the loop area is the plastic work the
  // dissipated channel integrates along the edge. From the start, the work of the hinge force is
  // the channel plus the elastic energy f^2 / (2 k) = k (d - d_p)^2 / 2: the channel is the
  // plastic work integral f dd_p, which holds the hardening's H d_p^2 / 2 too (the energy that
  // elastic unloading does not give back, earthquake engineering's hysteretic energy E_H).
  // Tolerances: the loop area to the 0.5 %; the dissipated per cycle against the sampled
  // loop and the work balance to the trapezoids' kink error, 4 k dd^2 / 8 per cycle (four kinks),
  // plus 1e-12 relative for rounding.
  const double amplitude = 3.0 * kSdofYield / kSdofK;  // u_a = 3 u_y
  constexpr int kCycles = 4;
  constexpr long kQuarter = 617;  // so that the yield points fall between samples
  const double dd = amplitude / kQuarter;
  for (const double b : {0.1, 0.0}) {
    const Cycles c = impose_cycles({kSdofYield, kSdofYield, b}, amplitude, kCycles, kQuarter);
    const double closed = 4 * (1 - b) * kSdofYield * (amplitude - kSdofYield / kSdofK);
    const double kink = 4 * kSdofK * dd * dd / 8;
    double loops = 0;
    for (int k = 0; k < kCycles; ++k) {
      const long a = kQuarter * (1 + 4 * k), e = a + 4 * kQuarter;  // +u_a to +u_a
      const double area = work(c, a, e);
      const double diss =
          c.dissipated[static_cast<std::size_t>(e)] - c.dissipated[static_cast<std::size_t>(a)];
      loops += area;
      std::printf(
          "  b = %.1f cycle %d: loop %.4f J, closed form %.4f J (%+.2e), dissipated %.4f J "
          "(%+.2e)\n",
          b, k, area, closed, area / closed - 1, diss, diss / area - 1);
      EXPECT_NEAR(area / closed, 1.0, 5e-3) << "b = " << b << ", cycle " << k;
      EXPECT_NEAR(diss, area, kink + 1e-12 * area) << "b = " << b << ", cycle " << k;
    }
    // The channel's energy over the stabilized cycles is the sum of their loop areas.
    const double over_cycles =
        c.dissipated.back() - c.dissipated[static_cast<std::size_t>(kQuarter)];
    EXPECT_NEAR(over_cycles, loops, kCycles * kink + 1e-12 * loops);
    // Work balance over the whole path, the first loading included.
    const double de = c.d.back() - c.dp.back();
    const double stored = 0.5 * kSdofK * de * de;
    const double total = work(c, 0, static_cast<long>(c.d.size()) - 1);
    std::printf("  b = %.1f: work %.4f J = dissipated %.4f J + elastic %.4f J (%+.2e)\n", b, total,
                c.dissipated.back(), stored, (c.dissipated.back() + stored) / total - 1);
    EXPECT_NEAR(total, c.dissipated.back() + stored,
                (4 * kCycles + 2) * kSdofK * dd * dd / 8 + 1e-12 * total);
  }
}

TEST(PlasticCycles, AsymmetricYieldsBoundTheForceAndAreThePlateaus) {
  // Yield 1e4 N in the positive sense, 6e3 N in the negative. Every sample: f - q in
  // [-yield_neg, yield_pos], q = H d_p from the plastic channel; tolerance 1e-9 F_y, the rounding
  // of k (d - d_p) (|k d| <= 3e4 N, ulp 4e-12 N) with margin. With b = 0 the loop's top and bottom
  // are the two yields (same tolerance) and its area (F_p + F_n)(2 u_a - (F_p + F_n) / k), the
  // parallelogram of height F_p + F_n and plateau length 2 u_a - (F_p + F_n) / k, to 0.5 %.
  const double fp = kSdofYield, fn = 0.6 * kSdofYield;
  const double amplitude = 3.0 * kSdofYield / kSdofK;
  constexpr long kQuarter = 600;
  for (const double b : {0.0, 0.1}) {
    const Cycles c = impose_cycles({fp, fn, b}, amplitude, 3, kQuarter);
    const double H = b * kSdofK / (1 - b);
    double lo = 1e300, hi = -1e300, worst = 0;
    for (std::size_t n = 0; n < c.f.size(); ++n) {
      const double rel = c.f[n] - H * c.dp[n];
      worst = std::max({worst, rel - fp, -fn - rel});
      if (std::cmp_greater_equal(n, kQuarter * 5))
        lo = std::min(lo, c.f[n]), hi = std::max(hi, c.f[n]);
    }
    std::printf("  b = %.1f: force in [%.6f, %.6f] kN over the last cycles, worst excess %.2e N\n",
                b, 1e-3 * lo, 1e-3 * hi, worst);
    EXPECT_LE(worst, 1e-9 * kSdofYield) << "b = " << b;
    if (b == 0.0) {
      EXPECT_NEAR(hi, fp, 1e-9 * kSdofYield);
      EXPECT_NEAR(lo, -fn, 1e-9 * kSdofYield);
      const long a = kQuarter * 5;
      const double area = work(c, a, a + 4 * kQuarter);
      const double closed = (fp + fn) * (2 * amplitude - (fp + fn) / kSdofK);
      std::printf("  b = 0: loop %.4f J, closed form %.4f J (%+.2e)\n", area, closed,
                  area / closed - 1);
      EXPECT_NEAR(area / closed, 1.0, 5e-3);
    } else {
      EXPECT_GT(hi, fp);  // kinematic hardening: the top rises above the initial yield
    }
  }
}

TEST(PlasticCycles, AsymmetricYieldsBoundTheForceInAForcedVibration) {
  // The same bound in the dynamic oscillator driven by a force input 1.2 F_y sin(omega t / 1.1)
  // (near resonance, it yields both ways) over 20 periods, b = 0.05 and b = 0: every step
  // f - H d_p in [-yield_neg, yield_pos] to 1e-9 F_y (rounding, as above), both edges reached.
  // And the energy balance every step: the work of the input, integral P du (trapezoids), equals
  // the kinetic energy m v_n^2 / 2 (v_n the mean of the half-step velocities), the hinge's
  // elastic energy f^2 / (2 k), the element's k_e u^2 / 2 and the dissipated channel (undamped,
  // no dashpot). Tolerance (omega dt)^2 = 1e-5 of the largest input work: the central difference
  // conserves a discrete energy that differs from this one by O((omega dt)^2), and a yield onset
  // or reversal between two samples adds an error of that order (measured: below 2e-6).
  const double fp = kSdofYield, fn = 0.6 * kSdofYield;
  for (const double b : {0.05, 0.0}) {
    const double dt = kPeriod / kOscSteps;
    build_oscillator({fp, fn, b}, 0.0, dt);
    const double H = b * kSdofK / (1 - b);
    const double mass = osc.model.mass[dof(0, ntn::kUx)];
    double worst = -1e300, at_pos = 0, at_neg = 0;
    double work = 0, work_max = 0, energy_error = 0, p_prev = 0, u_prev = 0;
    const auto steps = static_cast<long>(20 * kPeriod / dt);
    const ntn_test::EigenNoMalloc guard;
    for (long n = 0; n < steps; ++n) {
      const double t = static_cast<double>(n) * dt;
      const double p = 1.2 * kSdofYield * std::sin(kOmega * t / 1.1);
      const double u = osc.state.u[dof(0, ntn::kUx)], v_before = osc.state.v[dof(0, ntn::kUx)];
      EXPECT_EQ(ntn::step(osc.model, osc.state, osc.scratch, {p}), ntn::StepStatus::kOk);
      const double f = osc.scratch.outputs[0];
      const double rel = f - H * osc.scratch.outputs[2];
      worst = std::max({worst, rel - fp, -fn - rel});
      at_pos += rel > fp * (1 - 1e-9) ? 1 : 0;
      at_neg += rel < -fn * (1 - 1e-9) ? 1 : 0;
      if (n > 0) work += 0.5 * (p_prev + p) * (u - u_prev);
      p_prev = p, u_prev = u;
      const double v = 0.5 * (v_before + osc.state.v[dof(0, ntn::kUx)]);
      const double energy = 0.5 * mass * v * v + f * f / (2 * kSdofK) +
                            0.5 * kSdofElementK * u * u + osc.scratch.outputs[3];
      work_max = std::max(work_max, std::abs(work));
      energy_error = std::max(energy_error, std::abs(energy - work));
    }
    std::printf(
        "  b = %.2f: %ld steps, %.0f on the positive edge, %.0f on the negative, worst "
        "excess %.2e N, dissipated %.1f J, input work up to %.1f J, energy balance off by %.2e "
        "of it\n",
        b, steps, at_pos, at_neg, worst, osc.state.dissipated[0], work_max,
        energy_error / work_max);
    EXPECT_LE(worst, 1e-9 * kSdofYield);
    EXPECT_GT(at_pos, 0);
    EXPECT_GT(at_neg, 0);
    EXPECT_LE(energy_error, (kOmega * dt) * (kOmega * dt) * work_max);
  }
}

// ---- 3. Below yield, plastic = linear. The hinged cantilever (support/plastic_models.hpp) with
// its bending rotations ry, rz `plastic` (k = 2e6 N m/rad) against the same with `linear`
// directions of the same k, under a tip pulse in y and z. While no direction yields, d_p stays
// 0.0 and the force k (d - 0.0) + c d_dot is k d + c d_dot to the bit (d - 0.0 == d exactly), so
// the runs must be bit-identical (memcmp of u every step), not merely close. The yields are set
// 1.25 times the linear run's peak moments (so they are approached, not reached); with the yields
// at 0.5 times the peaks the runs must differ (the test can fail).
constexpr ntn::Sizes kCant = ntn_test::hinged_cantilever_sizes(
    {.time_functions = 1, .time_points = 3, .loads = 2, .outputs = 4});
Sim<kCant> lin, pla;

void build_cantilever(Sim<kCant>& r, B behaviour, double yield_y, double yield_z) {
  ntn::ModelSpec<kCant>& s = r.spec;
  ntn_test::hinged_cantilever(s, behaviour, 2e6);
  s.hystereses[0] = {yield_y, yield_y, 0.02};
  s.hystereses[1] = {yield_z, 0.8 * yield_z, 0.0};
  s.time_points = ntn_test::triangle_pulse(0.01);
  s.time_functions[0] = {0, 3};
  s.loads[0] = {4, ntn::kUz, 2e4, 0};
  s.loads[1] = {4, ntn::kUy, -1.5e4, 0};
  s.outputs[0] = ntn_test::hinge_channel(K::kHingeForce, 0, ntn::kRy);
  s.outputs[1] = ntn_test::hinge_channel(K::kHingeForce, 0, ntn::kRz);
  s.outputs[2] = ntn_test::hinge_channel(K::kHingeDissipated, 0, ntn::kRy);
  s.outputs[3] = ntn_test::hinge_channel(K::kHingeDissipated, 0, ntn::kRz);
  s.settings.dt = 0.9 * ntn_test::hinged_stable_step(s).dt_stable;
  const ntn_test::EigenNoMalloc guard;
  ASSERT_TRUE(ntn_test::init_model(s, r.model).ok());
  r.state = {};
  ASSERT_EQ(ntn::start(r.model, r.state, r.scratch, {}), ntn::StepStatus::kOk);
}

// Runs both for 0.1 s; returns the number of steps whose u differ, and the peak |moments|.
long compare_cantilevers(double& peak_y, double& peak_z) {
  long differ = 0;
  peak_y = peak_z = 0;
  const auto steps = static_cast<long>(0.1 / lin.model.dt);
  const ntn_test::EigenNoMalloc guard;
  for (long n = 0; n < steps; ++n) {
    EXPECT_EQ(ntn::step(lin.model, lin.state, lin.scratch, {}), ntn::StepStatus::kOk);
    EXPECT_EQ(ntn::step(pla.model, pla.state, pla.scratch, {}), ntn::StepStatus::kOk);
    differ += std::memcmp(lin.state.u.data(), pla.state.u.data(), sizeof(lin.state.u)) != 0;
    peak_y = std::max(peak_y, std::abs(lin.scratch.outputs[0]));
    peak_z = std::max(peak_z, std::abs(lin.scratch.outputs[1]));
  }
  return differ;
}

TEST(PlasticBelowYield, IsBitIdenticalToLinear) {
  double peak_y = 0, peak_z = 0;
  build_cantilever(lin, B::kLinear, 1, 1);
  build_cantilever(pla, B::kPlastic, 1e300 / 2, 1e300 / 2);  // first run: the peaks
  compare_cantilevers(peak_y, peak_z);
  std::printf("  linear run: peak moments %.1f N m (ry), %.1f N m (rz)\n", peak_y, peak_z);
  ASSERT_GT(peak_y, 0.0);
  ASSERT_GT(peak_z, 0.0);
  build_cantilever(lin, B::kLinear, 1, 1);
  build_cantilever(pla, B::kPlastic, 1.25 * peak_y, 1.25 / 0.8 * peak_z);
  double py = 0, pz = 0;
  EXPECT_EQ(compare_cantilevers(py, pz), 0) << "steps whose u differ";
  EXPECT_EQ(pla.state.plastic[0], 0.0);
  EXPECT_EQ(pla.state.plastic[1], 0.0);
  EXPECT_EQ(pla.state.dissipated[0] + pla.state.dissipated[1], 0.0);
  EXPECT_EQ(std::memcmp(lin.scratch.outputs.data(), pla.scratch.outputs.data(), 2 * sizeof(double)),
            0);  // the moments too
  // Yields at half the peaks: now it must yield, dissipate and differ.
  build_cantilever(lin, B::kLinear, 1, 1);
  build_cantilever(pla, B::kPlastic, 0.5 * peak_y, 0.5 / 0.8 * peak_z);
  const long differ = compare_cantilevers(py, pz);
  std::printf("  yields at half the peaks: %ld steps differ, dissipated %.2f J (ry), %.2f J (rz)\n",
              differ, pla.state.dissipated[0], pla.state.dissipated[1]);
  EXPECT_GT(differ, 0);
  EXPECT_GT(pla.state.dissipated[0], 0.0);
  EXPECT_GT(pla.state.dissipated[1], 0.0);
}

}  // namespace plastic_hinge_test
