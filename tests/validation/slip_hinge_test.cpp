// `rigid_plastic` hinge directions (HingeBehaviour::kRigidPlastic, ntn/slip.hpp) under
// ntn_exact, against truth no one here chose:
// 1. Newmark's sliding block (Newmark 1965): a rigid block on a rigid-plastic hinge to the ground
//    (yield m N) under a rectangular base-acceleration pulse of amplitude A > N and length t0
//    slides (A t0)^2 (A - N) / (2 A N) for good; the friction work is the yield times the slide.
// 2. The Coulomb oscillator: a mass on a linear spring k and a rigid-plastic hinge of limit F,
//    released from u0: each half cycle loses 2F/k exactly, the half period stays pi sqrt(m/k),
//    and it stops inside +-F/k.
// 3. Stick without drift: after the slide, a base shaking below the yield for 10^6 steps leaves
//    the slip where it was (to 1e-12 of the peak displacement).
// 4. The penalty method's elasto-plastic spring (the comparison the issue asks for) approaches the
//    exact slide as 1/sqrt(k) (its loading time to the yield).
// 5. A block on an inclined support (friction, mu N with N the rigid normal direction's force):
//    it stays put when tan(theta) <= mu, else it accelerates at g (sin theta - mu cos theta).
// 6. A bolt (`failure`) between a free-flying pair pulled apart by a ramp: it breaks when its
//    force reaches the limit, the pair's momentum is kept through the event, and afterwards each
//    mass moves under its own load.
//    Under `penalty` the bolt is a penalty spring that breaks at the same limit.
// 7. Bit-identical repeat runs; ntn_paper refuses the direction.
// The block: the oscillator of support/plastic_models.hpp (1000 kg at node 0 along x, a soft
// element of 1 N/m and 1 g to a clamped node), its hinge rigid-plastic in ux.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "ntn/hil/energy.hpp"
#include "ntn/hil/yield_report.hpp"
#include "ntn/kernel.hpp"
#include "support/builders.hpp"
#include "support/hinges.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"
#include "support/plastic_models.hpp"

namespace slip_hinge_test {

using ntn_test::dof;
using ntn_test::kSdofMass;
using K = ntn::OutputKind;

constexpr double kG = 9.80665;
constexpr double kPi = 3.14159265358979323846;

// The block with one ground-acceleration input (in m/s^2) and, with `spring` > 0, a second hinge
// from the mass to the ground: a linear spring of that stiffness in ux. Channels: the slip
// hinge's force, plastic deformation (its slip) and dissipated energy; the mass's u_x.
constexpr ntn::Sizes kBlock = [] {
  ntn::Sizes z = ntn_test::sdof_sizes({.inputs = 1, .outputs = 4});
  z.hinges = 2;
  return z;
}();

using ntn_test::Sim;
Sim<kBlock> sim;

ntn::InitStatus build(double yield, double spring, double dt,
                      ntn::HingeMethod method = ntn::HingeMethod::kNtnExact, double penalty_k = 0) {
  ntn::ModelSpec<kBlock>& s = sim.spec;
  ntn::HysteresisSpec law;
  law.yield_pos = law.yield_neg = yield;
  ntn_test::plastic_oscillator(s, law);
  s.hinges[0].behaviour[ntn::kUx] = ntn::HingeBehaviour::kRigidPlastic;
  s.hinges[0].stiffness[ntn::kUx] = 0;
  s.hinges[1] = ntn_test::hinge(0, ntn::kGround, ntn_test::kReversedX, ntn_test::released(0x3f));
  if (spring > 0) {
    s.hinges[1].behaviour[ntn::kUx] = ntn::HingeBehaviour::kLinear;
    s.hinges[1].stiffness[ntn::kUx] = spring;
  }
  s.inputs[0] = {ntn::InputKind::kGroundAcceleration, 0, ntn::kUx, 1.0, -1e300, 1e300};
  s.outputs[0] = ntn_test::hinge_channel(K::kHingeForce);
  s.outputs[1] = ntn_test::hinge_channel(K::kHingePlastic);
  s.outputs[2] = ntn_test::hinge_channel(K::kHingeDissipated);
  s.outputs[3] = {};
  s.outputs[3].kind = K::kDisplacement;
  s.outputs[3].node = 0;
  s.outputs[3].dof = ntn::kUx;
  s.settings.dt = dt;
  s.settings.hinge_method = method;
  if (penalty_k > 0) s.settings.penalty_stiffness = penalty_k;
  const ntn_test::EigenNoMalloc guard;
  const ntn::InitStatus st = ntn_test::init_model(s, sim.model);
  if (!st.ok()) return st;
  sim.state = {};
  EXPECT_EQ(ntn::start(sim.model, sim.state, sim.scratch, {0.0}), ntn::StepStatus::kOk);
  return st;
}

// Newmark's block: A = 0.5 g for t0 = 0.4 s, yield acceleration N = 0.2 g.
constexpr double kA = 0.5 * kG, kN = 0.2 * kG, kT0 = 0.4;
const double kNewmarkSlide = (kA * kT0) * (kA * kT0) * (kA - kN) / (2 * kA * kN);  // 0.588 m

struct Slide {
  double slip = 0, dissipated = 0, force_peak = 0;
  long steps = 0;
};

// Runs the pulse and then until the block has stuck for 0.2 s after its last slide.
Slide run_pulse(double dt) {
  Slide r;
  const auto pulse_steps = std::lround(kT0 / dt);
  double last = 0;
  long stuck = 0;
  const ntn_test::EigenNoMalloc guard;
  for (long n = 0; n < 400'000; ++n) {
    const double ag = n < pulse_steps ? kA : 0.0;  // -ag on the block: it slides toward -x
    EXPECT_EQ(ntn::step(sim.model, sim.state, sim.scratch, {ag}), ntn::StepStatus::kOk);
    r.force_peak = std::fmax(r.force_peak, std::fabs(sim.scratch.outputs[0]));
    const double slip = sim.scratch.outputs[1];
    stuck = slip == last ? stuck + 1 : 0;
    last = slip;
    r.steps = n + 1;
    if (n > pulse_steps && static_cast<double>(stuck) * dt > 0.2) break;
  }
  r.slip = sim.state.plastic[0];
  r.dissipated = sim.state.dissipated[0];
  return r;
}

TEST(SlipNewmark, SlidingBlockSlidesNewmarksDistance) {
  // Truth: Newmark (1965), rigid-plastic block: relative deceleration N resists, so the relative
  // velocity reaches (A - N) t0 at the pulse's end and N stops it: (A t0)^2 (A - N) / (2 A N).
  // Tolerance 0.5 % (the issue's); the scheme's error is O(dt) at the stick event (one step of
  // 1e-4 s out of 1.0 s of sliding).
  ASSERT_TRUE(build(kSdofMass * kN, 0, 1e-4).ok());
  const Slide r = run_pulse(1e-4);
  std::printf("  slide %.6f m (Newmark %.6f m), friction work %.3f J, %ld steps\n", -r.slip,
              kNewmarkSlide, r.dissipated, r.steps);
  EXPECT_NEAR(-r.slip, kNewmarkSlide, 0.005 * kNewmarkSlide);
  // The friction force never exceeds the yield, and it reaches it.
  EXPECT_LE(r.force_peak, kSdofMass * kN * (1 + 1e-15));
  EXPECT_EQ(r.force_peak, kSdofMass * kN);
  // Friction work = yield x slide (one way): f is the yield through every slip step. Rounding:
  // 1e-12 relative over the sum of about 10^4 terms.
  EXPECT_NEAR(r.dissipated, kSdofMass * kN * -r.slip, 1e-12 * r.dissipated);
}

TEST(SlipNewmark, EnergyBalanceClosesWithTheFrictionWork) {
  // Truth: the discrete work-energy identity of the central difference scheme (hil/energy.hpp),
  // the slip directions' forces in the friction account: the books close to rounding (1e-10 of
  // the input work). The friction account is the dissipated record and the elastic one the soft
  // element's energy (1 N/m x (0.59 m)^2 / 2 = 0.17 J); the
  // balance weighs each step's force by the midpoint increment (u_{n+1} - u_{n-1}) / 2, the
  // dissipated record by the slip increment, which differ by half a step's slide at each end of
  // the slide (about 2e3 N x 6e-5 m): 1e-3 of the friction work, with margin.
  ASSERT_TRUE(build(kSdofMass * kN, 0, 1e-4).ok());
  ntn::hil::EnergyBalance<kBlock> e;
  e.begin(sim.model, sim.state);
  const auto pulse_steps = std::lround(kT0 / 1e-4);
  for (long n = 0; n < 12'000; ++n) {
    const double ag = n < pulse_steps ? kA : 0.0;
    ASSERT_EQ(ntn::step(sim.model, sim.state, sim.scratch, {ag}), ntn::StepStatus::kOk);
    e.after_step(sim.model, sim.state, sim.scratch);
  }
  const ntn::hil::EnergyAccounts a = e.accounts(sim.model, sim.state);
  std::printf(
      "  external %.3f J, elastic %.3f J, friction %.3f J (dissipated record %.3f J), kinetic "
      "%.3e J, residual %.2e J\n",
      a.external, a.elastic, a.friction, sim.state.dissipated[0], a.kinetic, a.residual);
  EXPECT_LE(std::fabs(e.residual()), 1e-10 * e.input_scale());
  EXPECT_LE(std::fabs(a.residual), 1e-10 * a.input_scale);
  const double u = sim.state.u[dof(0, ntn::kUx)];
  EXPECT_NEAR(a.friction, sim.state.dissipated[0], 1e-3 * sim.state.dissipated[0]);
  EXPECT_NEAR(a.elastic, 0.5 * ntn_test::kSdofElementK * u * u, 1e-3 * sim.state.dissipated[0]);
}

TEST(SlipNewmark, StickHoldsWithoutDriftForAMillionSteps) {
  // After the slide, shake the base at 0.15 g < N for 10^6 steps: the block must not creep.
  // Truth: a rigid-plastic contact below its yield does not move. Tolerance 1e-12 of the peak
  // displacement (the issue's), against rounding: each step lands d back on the slip exactly.
  const double dt = 1e-4;
  ASSERT_TRUE(build(kSdofMass * kN, 0, dt).ok());
  (void)run_pulse(dt);
  const double held = sim.state.plastic[0];
  const double u_held = sim.state.u[dof(0, ntn::kUx)];
  double worst = 0;
  const ntn_test::EigenNoMalloc guard;
  for (long n = 0; n < 1'000'000; ++n) {
    const double ag = 0.15 * kG * std::sin(2 * kPi * 2.0 * static_cast<double>(n) * dt);
    ASSERT_EQ(ntn::step(sim.model, sim.state, sim.scratch, {ag}), ntn::StepStatus::kOk);
    worst = std::fmax(worst, std::fabs(sim.state.u[dof(0, ntn::kUx)] - u_held));
  }
  std::printf("  held at %.9f m: largest creep %.3e m over 10^6 steps\n", held, worst);
  EXPECT_EQ(sim.state.plastic[0], held);
  EXPECT_LE(worst, 1e-12 * std::fabs(held));
}

TEST(SlipCoulomb, EachHalfCycleLoses2FOverK) {
  // Truth: the Coulomb oscillator m u'' + k u + F sgn(u') = 0 from rest at u0: each half cycle is
  // a half oscillation about +-F/k, so successive extremes are u0 - 2 n F / k, each half cycle
  // lasts pi sqrt(m/k), and motion stops once |u| <= F/k. dt = T / 20000: the discrete extremes
  // and the one-step stick at each reversal err by about (omega dt)^2 ~ 1e-7, within the issue's
  // 1e-6 (relative to u0) for the extremes.
  const double k = 1e6, F = 1e3, u0 = 0.0123;  // F / k = 1 mm: about 6 half cycles
  const double T = 2 * kPi * std::sqrt(kSdofMass / k);
  const double dt = T / 20000;
  ASSERT_TRUE(build(F, k, dt).ok());
  sim.state = {};
  sim.state.u[dof(0, ntn::kUx)] = u0;
  sim.state.plastic[0] = u0;  // released from rest at u0, not slid there
  ASSERT_EQ(ntn::start(sim.model, sim.state, sim.scratch, {0.0}), ntn::StepStatus::kOk);
  std::vector<double> extremes{u0};
  std::vector<long> at{0};
  double prev = u0, prev2 = u0;
  const ntn_test::EigenNoMalloc guard;
  for (long n = 1; n < 20 * 20000; ++n) {
    ASSERT_EQ(ntn::step(sim.model, sim.state, sim.scratch, {0.0}), ntn::StepStatus::kOk);
    const double u = sim.scratch.outputs[3];
    // A turning point: the middle sample of three is a strict extreme (a stuck stretch counts
    // once, at its first sample).
    if ((prev > prev2 && prev >= u) || (prev < prev2 && prev <= u)) {
      extremes.push_back(prev), at.push_back(n - 1);
    }
    prev2 = prev, prev = u;
  }
  const double last = sim.state.u[dof(0, ntn::kUx)];
  std::printf("  %zu extremes; stopped at %.6e m (F/k = %.1e m)\n", extremes.size(), last, F / k);
  ASSERT_GE(extremes.size(), 6U);
  for (std::size_t i = 1; i < extremes.size(); ++i) {
    const double expect = (i % 2 == 1 ? -1.0 : 1.0) * (u0 - 2.0 * static_cast<double>(i) * F / k);
    if (std::fabs(expect) <= F / k) break;  // it stuck before this one
    EXPECT_NEAR(extremes[i], expect, 1e-6 * u0) << "extreme " << i;
    const double half = static_cast<double>(at[i] - at[i - 1]) * dt;
    EXPECT_NEAR(half, T / 2, 3 * dt) << "half cycle " << i;  // a step each way, and the stick
  }
  EXPECT_LE(std::fabs(last), F / k);
}

TEST(SlipPenalty, ElastoPlasticPenaltySpringsApproachTheExactSlideAs1OverSqrtK) {
  // The comparison: under `penalty` the direction is an elasto-plastic spring of the
  // penalty stiffness; its slide (the plastic deformation) approaches the exact one. Truth: the
  // ntn_exact slide of the same block (Newmark's within 0.5 %, above) and the mechanics of the
  // spring: at the pulse's onset it takes t1 = arccos(1 - N/A) / omega, omega = sqrt(k/m), to
  // load to the yield, while the block gains velocity the rigid-plastic one does not, so the
  // error is first order in 1/omega, i.e. 1/sqrt(k) (not 1/k as the issue expected): measured,
  // about sqrt(10) = 3.2 times smaller per tenfold k (2 to 5 accepted: the step adds its own).
  const double exact_dt = 1e-4;
  ASSERT_TRUE(build(kSdofMass * kN, 0, exact_dt).ok());
  const double exact = run_pulse(exact_dt).slip;
  double previous_error = 0;
  for (const double kp : {1e6, 1e7, 1e8}) {
    const double dt = std::fmin(1e-4, 0.5 * 2.0 / std::sqrt(kp / kSdofMass));
    ASSERT_TRUE(build(kSdofMass * kN, 0, dt, ntn::HingeMethod::kPenalty, kp).ok());
    const Slide r = run_pulse(dt);
    const double error = std::fabs(r.slip - exact) / std::fabs(exact);
    std::printf("  penalty k %.0e N/m: dt %.2e s, %ld steps, slide error %.3e\n", kp, dt, r.steps,
                error);
    if (previous_error > 0) {
      EXPECT_LT(error, previous_error / 2);
      EXPECT_GT(error, previous_error / 5);
    }
    previous_error = error;
  }
}

// The inclined block: node 0 (1000 kg) on a ground hinge whose frame is the incline's: x down
// the slope (cos t, 0, -sin t), z into the support (-sin t, 0, -cos t), y = z x x = -global y.
// Local x: friction mu on the normal z; every other direction rigid (node 0 has no supports:
// the hinge is its support with the incline's axes). Gravity -g z. The soft element of the
// oscillator stays (1 N/m along x; read off in the first steps, it is 1e-10 of the block's forces).
constexpr ntn::Sizes kIncline = ntn_test::sdof_sizes({.outputs = 2});
Sim<kIncline> incline;

ntn::InitStatus build_incline(double theta, double mu) {
  ntn::ModelSpec<kIncline>& s = incline.spec;
  ntn::HysteresisSpec law;
  law.normal = ntn::kUz;
  law.mu = mu;
  ntn_test::plastic_oscillator(s, law);
  s.nodes[0].fixed = 0;  // the hinge holds it: a support with the incline's axes
  const double c = std::cos(theta), sn = std::sin(theta);
  s.hinges[0] = ntn_test::hinge(0, ntn::kGround, {c, 0, -sn, 0, -1, 0, -sn, 0, -c},
                                ntn_test::released(0));  // rigid but along the slope
  s.hinges[0].behaviour[ntn::kUx] = ntn::HingeBehaviour::kRigidPlastic;
  s.hinges[0].hysteresis[ntn::kUx] = 0;
  s.outputs[0] = ntn_test::hinge_channel(K::kHingeForce, 0, ntn::kUx);
  s.outputs[1] = ntn_test::hinge_channel(K::kHingeForce, 0, ntn::kUz);
  s.settings.gravity = {0, 0, -kG};
  s.settings.dt = 1e-4;
  const ntn_test::EigenNoMalloc guard;
  const ntn::InitStatus st = ntn_test::init_model(s, incline.model);
  if (!st.ok()) return st;
  incline.state = {};
  EXPECT_EQ(ntn::start(incline.model, incline.state, incline.scratch, {}), ntn::StepStatus::kOk);
  return st;
}

TEST(SlipFriction, BlockOnAnInclineSticksOrSlidesAtCoulombsAcceleration) {
  // Truth: Coulomb friction on an incline: the normal force is m g cos(theta); the block stays
  // when tan(theta) <= mu, else slides at g (sin theta - mu cos theta). Tolerance 1e-9 (the
  // issue's): the acceleration per step, (v_{n+1/2} - v_{n-1/2}) / dt along the slope, over
  // steps 1 to 9 (the soft element's pull, k_el u / m, is then below 2e-10 m/s^2; by step 50 it
  // is 3e-8). The block's mass is the node's lumped mass (1000 kg and half the element's 1 g).
  const double mu = 0.3;
  for (const double deg : {30.0, 10.0}) {
    const double theta = deg * kPi / 180;
    const ntn::InitStatus st = build_incline(theta, mu);
    ASSERT_TRUE(st.ok()) << deg << ": " << ntn::to_string(st.error) << " at " << st.where;
    const double t[3] = {std::cos(theta), 0, -std::sin(theta)};
    const double mass = incline.model.mass[dof(0, ntn::kUx)];
    double v_prev = 0, worst = 0, force = 0, normal = 0;
    const double expect =
        std::tan(theta) <= mu ? 0.0 : kG * (std::sin(theta) - mu * std::cos(theta));
    const ntn_test::EigenNoMalloc guard;
    for (int n = 0; n < 50; ++n) {
      ASSERT_EQ(ntn::step(incline.model, incline.state, incline.scratch, {}), ntn::StepStatus::kOk);
      const double v =
          incline.state.v[dof(0, ntn::kUx)] * t[0] + incline.state.v[dof(0, ntn::kUz)] * t[2];
      if (n >= 1 && n < 10) worst = std::fmax(worst, std::fabs((v - v_prev) / 1e-4 - expect));
      v_prev = v;
      if (n == 9) force = incline.scratch.outputs[0], normal = incline.scratch.outputs[1];
    }
    std::printf(
        "  %.0f deg: friction %.3f N, normal %.3f N (m g cos = %.3f N), acceleration "
        "error %.2e m/s^2 (expected %.6f)\n",
        deg, force, normal, mass * kG * std::cos(theta), worst, expect);
    EXPECT_LE(worst, 1e-9 * kG) << deg << " deg";
    EXPECT_NEAR(normal, -mass * kG * std::cos(theta), 1e-9 * mass * kG) << deg;
    // Sticking: the friction holds m g sin(theta) (on node 1, up the slope: negative along x).
    const double holds = expect == 0 ? std::sin(theta) : mu * std::cos(theta);
    EXPECT_NEAR(force, -holds * mass * kG, 1e-9 * mass * kG) << deg;
  }
}

// The pair: nodes 0 and 1 at the origin (1000 kg each along x), joined by a hinge whose ux is a
// failure direction of limit 5 kN (the other directions free: every DOF but ux is held on every
// node); the soft element runs from node 1 to node 2 (1 m along x). Loads: -c t on node 0 and
// +c t on node 1 (c = 1e4 N/s), so the bolt carries c t and breaks at t = 0.5 s.
constexpr ntn::Sizes kPair{.nodes = 3,
                           .elements = 1,
                           .time_functions = 1,
                           .time_points = 2,
                           .loads = 2,
                           .outputs = 1,
                           .hinges = 1,
                           .hystereses = 1};
Sim<kPair> pair;

// in_tree: no supports, the bolt rigid in every other direction, so that nodes 0 and 1 form a
// rigid tree and the slip stage solves the bolt in it (slip_tree_solve); else every DOF but ux
// held and the bolt's other directions free (two lone nodes: Gauss-Seidel).
// Under `penalty` (not in a tree) the bolt is a penalty spring of 1e9 N/m that breaks: it rings
// at omega = sqrt(2k/m) with c / omega = 7 N about c t, so it breaks within 10 steps of F / c.
void bolt_breaks(bool in_tree, ntn::HingeMethod method = ntn::HingeMethod::kNtnExact) {
  const double c = 1e4, F = 5e3, dt = 1e-4;
  ntn::ModelSpec<kPair>& s = pair.spec;
  s = {};
  const auto ux_only = static_cast<std::uint8_t>(ntn_test::kFixedAll & ~(1U << ntn::kUx));
  for (int n = 0; n < 3; ++n) {
    s.nodes[static_cast<std::size_t>(n)] = {};
    s.nodes[static_cast<std::size_t>(n)].fixed = in_tree ? 0 : ux_only;
  }
  s.nodes[2].x = 1.0;
  const double J = in_tree ? 10.0 : 0.0;  // kg m^2: the free pair's rotations need inertia
  s.nodes[0].added = {kSdofMass, in_tree ? kSdofMass : 0, in_tree ? kSdofMass : 0, J, J, J};
  s.nodes[1].added = s.nodes[0].added;
  s.settings.rotary_inertia = in_tree;  // the soft element's free end
  s.elements[0] =
      ntn_test::element(1, 2, ntn_test::kSdofMaterial, ntn_test::kSdofSection, {0, 0, 1});
  s.hinges[0] = ntn_test::hinge(0, 1, ntn_test::kIdentity3, ntn_test::released(in_tree ? 0 : 0x3f));
  s.hinges[0].behaviour[ntn::kUx] = ntn::HingeBehaviour::kRigidPlastic;
  s.hinges[0].hysteresis[ntn::kUx] = 0;
  s.hystereses[0].yield_pos = s.hystereses[0].yield_neg = F;
  s.hystereses[0].rule = ntn::HysteresisRule::kBrittle;
  s.time_points = {{{0.0, 0.0}, {10.0, 10.0}}};
  s.time_functions[0] = {0, 2};
  s.loads[0] = {0, ntn::kUx, -c, 0};
  s.loads[1] = {1, ntn::kUx, c, 0};
  s.outputs[0] = ntn_test::hinge_channel(K::kHingeForce);
  s.settings.dt = dt;
  s.settings.hinge_method = method;
  s.settings.penalty_stiffness = 1e9;
  const bool penalty = method == ntn::HingeMethod::kPenalty;
  {
    const ntn_test::EigenNoMalloc guard;
    const ntn::InitStatus st = ntn_test::init_model(s, pair.model);
    ASSERT_TRUE(st.ok()) << ntn::to_string(st.error) << " at " << st.where;
    pair.state = {};
    ASSERT_EQ(ntn::start(pair.model, pair.state, pair.scratch, {}), ntn::StepStatus::kOk);
  }
  double momentum_worst = 0, force_peak = 0;
  const long steps = 10'000;  // 1 s
  const ntn_test::EigenNoMalloc guard;
  for (long n = 0; n < steps; ++n) {
    ASSERT_EQ(ntn::step(pair.model, pair.state, pair.scratch, {}), ntn::StepStatus::kOk);
    force_peak = std::fmax(force_peak, std::fabs(pair.scratch.outputs[0]));
    double p = 0;
    for (int node = 0; node < 3; ++node)
      p += pair.model.mass[dof(node, ntn::kUx)] * pair.state.v[dof(node, ntn::kUx)];
    momentum_worst = std::fmax(momentum_worst, std::fabs(p));
  }
  const double t_break = static_cast<double>(pair.state.first_slip[0] - 1) * dt;
  const double t_end = static_cast<double>(steps) * dt;
  const double v0 = pair.state.v[dof(0, ntn::kUx)];  // v_{N-1/2}
  const double expect_v0 =
      -c / (2 * pair.model.mass[dof(0, ntn::kUx)]) * ((t_end - dt / 2) * (t_end - dt / 2) - 0.25);
  std::printf(
      "  broke at t = %.4f s (F / c = %.4f s), peak bolt force %.1f N, |momentum| <= "
      "%.2e N s, v0 %.6f m/s (closed form %.6f)\n",
      t_break, F / c, force_peak, momentum_worst, v0, expect_v0);
  ASSERT_GT(pair.state.first_slip[0], 0);
  EXPECT_NEAR(t_break, F / c, (penalty ? 10 : 2) * dt);
  EXPECT_LE(force_peak, F);
  // Momentum: the sum of m v over 10^4 steps of rounding, against m v ~ 1e3 N s.
  EXPECT_LE(momentum_worst, 1e-9);
  // After the break each mass is on its own: within the step's offset of the break (v changes
  // by c t_b dt / m = 5e-4 m/s per misplaced step; penalty: up to 10 steps).
  EXPECT_NEAR(v0, expect_v0, (penalty ? 10 : 2) * 5e-4);
  const auto y = ntn::hil::yielded_directions(pair.model, pair.state);
  ASSERT_EQ(y.size(), 1U);
  EXPECT_TRUE(y[0].failed);
  EXPECT_EQ(y[0].first_slip, t_break);
}

TEST(SlipFailure, ABoltBreaksAtItsLimitAndThePairKeepsItsMomentum) {
  // Truth: statics of the joined pair (the bolt carries the load c t until it reaches its limit
  // F: t_b = F / c), momentum conservation (the loads sum to zero at every instant, and the break
  // is internal), and each mass's own motion after it: v = (c / 2m) (t^2 - t_b^2) outward.
  bolt_breaks(false);
}

TEST(SlipFailure, ABoltInARigidTreeBreaksTheSameWay) {
  // The same truth with the bolt's nodes in one rigid tree: the tree's block solve.
  bolt_breaks(true);
}

TEST(SlipFailure, APenaltyBoltBreaksAtTheSameLimit) {
  // The same truth with the `penalty` method: the bolt a penalty spring that breaks (brittle).
  bolt_breaks(false, ntn::HingeMethod::kPenalty);
}

TEST(SlipRules, RepeatRunsAreBitIdenticalAndNtnPaperRefuses) {
  ASSERT_TRUE(build(kSdofMass * kN, 0, 1e-4).ok());
  const Slide a = run_pulse(1e-4);
  const ntn::State<kBlock> first = sim.state;
  ASSERT_TRUE(build(kSdofMass * kN, 0, 1e-4).ok());
  const Slide b = run_pulse(1e-4);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(std::memcmp(first.u.data(), sim.state.u.data(), sizeof(first.u)), 0);
  EXPECT_EQ(std::memcmp(first.plastic.data(), sim.state.plastic.data(), sizeof(first.plastic)), 0);
  EXPECT_EQ(first.dissipated, sim.state.dissipated);
  // ntn_paper has no constraint force to test against the yield.
  const ntn::InitStatus st = build(kSdofMass * kN, 0, 1e-4, ntn::HingeMethod::kNtnPaper);
  EXPECT_EQ(st.error, ntn::InitError::kBadHinge);
  EXPECT_EQ(st.where, 0);
}

}  // namespace slip_hinge_test
