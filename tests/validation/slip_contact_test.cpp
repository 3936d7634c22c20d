// The rest of the connections that stick, slip, stop and break, against closed forms:
// 1. Hardening with the slip (rigid_plastic with a parallel spring H): under a suddenly applied
//    force P (Y < P <= 3Y) the block slides as m x'' = P - Y - H x, reaches 2 (P - Y) / H at
//    t = pi sqrt(m / H) and sticks there; the force while sliding is Y + H x.
// 2. fixed_if on its own force (a one-sided stop at d = 0): a block resting on its support under
//    gravity, pulled off by a ramp c t: it stays put while the reaction would be compression and
//    lifts off at t* = m g / c, flying as c (t - t*)^3 / 6m after: the support never pulls. And
//    a propped cantilever (a model file through the compiler) lifting off its prop when the
//    propped cantilever's reaction would turn to tension.
// 3. fixed_if with a control: a block pressed onto a compression-only spring holds a side force
//    exactly while the spring is compressed and accelerates at H / m once it lifts off.
// 4. A spring that breaks (`linear` + `failure`, HysteresisRule::kBrittle) under every method: a
//    suddenly applied P > F loads it as P/k (1 - cos wt) until k x first passes F (t_b =
//    arccos(1 - F/P) / w), then nothing holds the mass; the energy the spring held is dissipated.
// 5. The friction circle: a block pulled obliquely past mu M g slides along the pull at
//    (P - mu M g) / M where two independent friction directions would hold it.
// The block: the oscillator of support/plastic_models.hpp (1000 kg at node 0, a soft element of
// 1 N/m and 1 g to a clamped node), its hinge 0 to the ground with d = +u_x.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "ntn/hil/yield_report.hpp"
#include "ntn/kernel.hpp"
#include "propped_liftoff_model.hpp"
#include "support/builders.hpp"
#include "support/hinges.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"
#include "support/plastic_models.hpp"

namespace slip_contact_test {

using ntn_test::dof;
using ntn_test::kSdofMass;
using K = ntn::OutputKind;

constexpr double kG = 9.80665;
constexpr double kPi = 3.14159265358979323846;

// The block with one constant load slot (node 0, ux), room for a curve of 3 points, and channels:
// hinge 0's force, slip state and relative velocity in ux, the mass's velocity, and hinge 0's
// force in uz.
constexpr ntn::Sizes kBlock = [] {
  ntn::Sizes z = ntn_test::sdof_sizes({.time_functions = 1,
                                       .time_points = 2,
                                       .loads = 2,
                                       .outputs = 5,
                                       .curves = 1,
                                       .curve_points = 3});
  z.hystereses = 2;  // the level block's two friction directions
  return z;
}();

ntn_test::Sim<kBlock> sim;

// The oscillator with hinge 0's ux `behaviour` (its law in slot 0), load 0 = `p` on ux
// (constant) and load 1 = `c` t on ux (c = 0: none).
void block(ntn::HingeBehaviour behaviour, const ntn::HysteresisSpec& law, double p, double c) {
  ntn::ModelSpec<kBlock>& s = sim.spec;
  ntn_test::plastic_oscillator(s, law);
  s.hinges[0].behaviour[ntn::kUx] = behaviour;
  s.hinges[0].stiffness[ntn::kUx] = 0;
  s.time_points = {{{0.0, 0.0}, {100.0, 100.0}}};
  s.time_functions[0] = {0, 2};
  s.loads[0] = {0, ntn::kUx, p, ntn::kConstant};
  s.loads[1] = {0, ntn::kUx, c, 0};
  s.outputs[0] = ntn_test::hinge_channel(K::kHingeForce);
  s.outputs[1] = ntn_test::hinge_channel(K::kHingeSlipState);
  s.outputs[2] = ntn_test::hinge_channel(K::kHingeVelocity);
  s.outputs[3] = {};
  s.outputs[3].kind = K::kVelocity;
  s.outputs[3].node = 0;
  s.outputs[3].dof = ntn::kUx;
  s.outputs[4] = ntn_test::hinge_channel(K::kHingeForce, 0, ntn::kUz);
  s.settings.dt = 1e-4;
}

void start() {
  const ntn_test::EigenNoMalloc guard;
  const ntn::InitStatus st = ntn_test::init_model(sim.spec, sim.model);
  ASSERT_TRUE(st.ok()) << ntn::to_string(st.error) << " at " << st.where;
  sim.state = {};
  ntn::initial_state(sim.model, sim.state);
  ASSERT_EQ(ntn::start(sim.model, sim.state, sim.scratch, {}), ntn::StepStatus::kOk);
}

double mass() {
  return sim.model.mass[dof(0, ntn::kUx)];
}

TEST(SlipHardening, SlidesToTwiceTheExcessOverHAndSticks) {
  // Truth: m x'' = P - Y - H x from rest: x = (P - Y)/H (1 - cos wt), w = sqrt(H/m), until the
  // velocity returns to 0 at t = pi / w, x = 2 (P - Y)/H; there the force to hold it, P - H x =
  // 2Y - P, lies within the yield (P <= 3Y), so it sticks for good. Tolerances: the extreme to
  // 1e-5 relative (the scheme's (w dt)^2 = 1e-5 and the soft element's 1 N/m, 1e-6 of H), its
  // time to 2 steps; the force while sliding Y + H x to rounding (1e-9 of Y).
  const double Y = 1e4, H = 1e6, P = 2e4;
  ntn::HysteresisSpec law;
  law.yield_pos = law.yield_neg = Y;
  block(ntn::HingeBehaviour::kRigidPlastic, law, P, 0);
  sim.spec.hinges[0].stiffness[ntn::kUx] = H;  // hardening with the slip
  start();
  const double w = std::sqrt(H / mass());
  double peak = 0, t_peak = 0, force_worst = 0;
  int slid = 0, stuck_after = 0;
  const ntn_test::EigenNoMalloc guard;
  for (long n = 0; n < 10'000; ++n) {
    const double x_n = sim.state.u[dof(0, ntn::kUx)];  // d at t_n
    ASSERT_EQ(ntn::step(sim.model, sim.state, sim.scratch, {}), ntn::StepStatus::kOk);
    const double x = sim.state.u[dof(0, ntn::kUx)];
    const int state = static_cast<int>(sim.scratch.outputs[1]);
    if (state == 1) {
      ++slid;  // the force at t_n: the slider's yield and the hardening spring's H d_n
      force_worst = std::fmax(force_worst, std::fabs(sim.scratch.outputs[0] - (Y + H * x_n)));
    }
    if (x > peak) peak = x, t_peak = static_cast<double>(n + 1) * 1e-4;
    if (static_cast<double>(n) * 1e-4 > 1.5 * kPi / w && state == 0) ++stuck_after;
    // Hinge velocity of d = u_x: the mass's own, bit for bit.
    EXPECT_EQ(sim.scratch.outputs[2], sim.scratch.outputs[3]) << n;
  }
  const double expect = 2 * (P - Y) / H;
  std::printf(
      "  peak slide %.9f m (closed form %.9f m) at t = %.5f s (pi/w = %.5f s), %d steps "
      "sliding, force - (Y + H d) <= %.2e N\n",
      peak, expect, t_peak, kPi / w, slid, force_worst);
  EXPECT_NEAR(peak, expect, 1e-5 * expect);
  EXPECT_NEAR(t_peak, kPi / w, 2e-4);
  EXPECT_GT(slid, 900);                            // it slid for about pi/w = 0.099 s
  EXPECT_GT(stuck_after, 1000);                    // and stuck after
  EXPECT_EQ(sim.state.slip_state[0], 0);           // for good
  EXPECT_NEAR(sim.state.plastic[0], peak, 1e-12);  // the slip is where it stopped
  EXPECT_LE(force_worst, 1e-9 * Y);
}

// The stop the model compiler makes of `fixed_if = "negative"` on a direction's own force: the
// curve [[-1, -1e300], [0, 0], [1, 0]], rigid against d < 0, no force for d > 0.
void own_stop(ntn::ModelSpec<kBlock>& s, std::size_t k) {
  s.hinges[0].behaviour[k] = ntn::HingeBehaviour::kCurve;
  s.hinges[0].curve[k] = 0;
  s.curves[0] = {0, 3};
  s.curve_points = {{{-1.0, -1e300}, {0.0, 0.0}, {1.0, 0.0}}};
}

TEST(FixedIf, ABlockOnItsSupportLiftsOffWhenTheReactionWouldTurnToTension) {
  // Truth: a block of mass M on a support that only pushes, under gravity M g toward it and a
  // pull c t away from it: the reaction M g - c t holds it until t* = M g / c, after which
  // M u'' = c (t - t*): u = c (t - t*)^3 / 6M. Tolerances: no penetration and no motion before t*
  // to 1e-15 m (the stop lands d on 0); the flight 0.5 s after t* to 2e-3 relative (t*'s
  // quantization to the step, 3 dt / 0.5 s = 6e-4, and the soft element, 1e-4).
  const double c = 1e4;
  block(ntn::HingeBehaviour::kCurve, {}, 0, c);
  own_stop(sim.spec, ntn::kUx);
  sim.spec.hystereses[0] = {};
  sim.spec.hinges[0].hysteresis[ntn::kUx] = 0;
  sim.spec.settings.gravity = {-kG, 0, 0};
  start();
  const double t_star = mass() * kG / c;
  const double dt = 1e-4;
  double before_worst = 0, below = 0;
  const auto steps = std::lround((t_star + 0.5) / dt);
  const ntn_test::EigenNoMalloc guard;
  for (long n = 0; n < steps; ++n) {
    ASSERT_EQ(ntn::step(sim.model, sim.state, sim.scratch, {}), ntn::StepStatus::kOk);
    const double u = sim.state.u[dof(0, ntn::kUx)];
    if (static_cast<double>(n + 1) * dt < t_star)
      before_worst = std::fmax(before_worst, std::fabs(u));
    below = std::fmin(below, u);
  }
  const double t = static_cast<double>(steps) * dt - t_star;
  const double expect = c * t * t * t / (6 * mass());
  const double u = sim.state.u[dof(0, ntn::kUx)];
  std::printf(
      "  lift-off at t* = %.4f s; before it |u| <= %.1e m, lowest %.1e m; %.3f s later "
      "u = %.6f m (closed form %.6f m)\n",
      t_star, before_worst, below, t, u, expect);
  EXPECT_LE(before_worst, 1e-15);
  EXPECT_GE(below, -1e-15);
  EXPECT_NEAR(u, expect, 2e-3 * expect);
}

TEST(FixedIf, AProppedCantileverLiftsOffItsPropWhenTheReactionWouldTurnToTension) {
  // tests/validation/propped_liftoff.toml, compiled by the model compiler (its fixed_if becomes
  // the stop). Truth: the propped cantilever's reaction under point loads P_i at a_i from the
  // clamp, R = sum P_i a_i^2 (3L - a_i) / 2L^3 (exact for the Euler-Bernoulli elements under
  // their lumped weights), so with the upward load P = c (t - 2) at the prop the reaction
  // R_0 - P turns to tension at t* = 2 + R_0 / c; after it the free cantilever's tip rises by
  // (P - R_0) / (3 E I / L^3). Tolerances: the damped beam follows the ramp a little late, by
  // about 2 zeta / omega = 4 ms at the free cantilever's first mode (omega = 94 rad/s, zeta about
  // 0.2), so t* is seen within 6 ms (the gap read against 1e-7 m adds 1e-4 s) and the lifted tip
  // is 0.3 % short of the static rise at t = 5 s (within 1 %); before t*, no gap and no
  // penetration to 1e-12 m (the stop lands d on 0).
  namespace pl = ntn::models::propped_liftoff;
  constexpr ntn::Sizes S = pl::kSizes;
  const auto m = std::make_unique<ntn::Model<S>>();
  const auto st = std::make_unique<ntn::State<S>>();
  const auto w = std::make_unique<ntn::Scratch<S>>();
  ASSERT_TRUE(ntn_test::init_model(pl::kSpec, *m).ok());
  const double L = 4.0, EI = 210e9 * 1943e-8, c = 200.0;
  double R0 = 0;
  for (std::size_t n = 0; n < S.nodes; ++n) {
    const double a = pl::kSpec.nodes[n].x;
    R0 += m->mass[dof(static_cast<int>(n), ntn::kUz)] * kG * a * a * (3 * L - a) / (2 * L * L * L);
  }
  const double t_star = 2.0 + R0 / c;
  ntn::initial_state(*m, *st);
  ASSERT_EQ(ntn::start(*m, *st, *w, {}), ntn::StepStatus::kOk);
  const long steps = std::lround(5.0 / m->dt);
  double before = 0, lowest = 0, t_lift = -1;
  for (long n = 0; n < steps; ++n) {
    ASSERT_EQ(ntn::step(*m, *st, *w, {}), ntn::StepStatus::kOk);
    const double t = static_cast<double>(n) * m->dt, gap = w->outputs[0];  // at t_n
    if (t < t_star - 0.005) before = std::fmax(before, std::fabs(gap));
    lowest = std::fmin(lowest, gap);
    if (t_lift < 0 && gap > 1e-7) t_lift = t;
  }
  const double rise = (c * 3.0 - R0) / (3 * EI / (L * L * L));
  const double tip = st->u[dof(1, ntn::kUz)];  // node 2 of the file: model node 1
  std::printf(
      "  R_0 = %.3f N: lift-off at t* = %.4f s, seen at %.4f s; before it |gap| <= %.1e m, "
      "lowest %.1e m; at t = 5 s the tip at %.6e m (free cantilever %.6e m)\n",
      R0, t_star, t_lift, before, lowest, tip, rise);
  EXPECT_NEAR(t_lift, t_star, 6e-3);
  EXPECT_LE(before, 1e-12);
  EXPECT_GE(lowest, -1e-12);
  EXPECT_NEAR(tip, rise, 0.01 * rise);
}

TEST(FixedIf, ASideForceIsHeldExactlyWhilePressedAndFreeOnceLifted) {
  // A block on a compression-only spring (the normal uz, 1e7 N/m, d_z < 0 pressed) under gravity,
  // pulled off by c t; its ux is fixed_if negative on uz, with a side force Q on it. Truth, step
  // by step (the rule itself): while the normal force at t_n is negative, u_x does not move (to
  // 1e-15 m); otherwise the block moves freely, M (u_{n+1} - 2 u_n + u_{n-1}) / dt^2 = Q - k_el
  // u_n (the central difference identity, to 1e-9 of Q / M). And it does lift off and slide.
  const double c = 1e4, Q = 500.0, kn = 1e7, dt = 1e-4;
  ntn::HysteresisSpec law;
  law.fixed_if = -1;
  law.normal = ntn::kUz;
  block(ntn::HingeBehaviour::kRigidPlastic, law, 0, 0);
  ntn::ModelSpec<kBlock>& s = sim.spec;
  s.nodes[0].fixed =
      static_cast<std::uint8_t>(ntn_test::kFixedAll & ~((1U << ntn::kUx) | (1U << ntn::kUz)));
  s.hinges[0].behaviour[ntn::kUz] = ntn::HingeBehaviour::kCurve;  // d_z = -u_z (kReversedX)
  s.hinges[0].curve[ntn::kUz] = 0;
  s.curves[0] = {0, 3};
  s.curve_points = {{{-1.0, -kn}, {0.0, 0.0}, {1.0, 0.0}}};
  s.settings.gravity = {0, 0, kG};  // presses d_z < 0
  s.loads[0] = {0, ntn::kUx, Q, ntn::kConstant};
  s.loads[1] = {0, ntn::kUz, -c, 0};
  {
    ntn::Model<kBlock>& m = sim.model;  // the static sag, from the lumped mass
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(s, m).ok());
    s.nodes[0].u0[ntn::kUz] = m.mass[dof(0, ntn::kUz)] * kG / kn;
  }
  start();
  const double M = mass(), k_el = ntn_test::kSdofElementK;
  double held_worst = 0, free_worst = 0, u_prev = 0;
  long held = 0, free = 0;
  const ntn_test::EigenNoMalloc guard;
  for (long n = 0; n < 13'000; ++n) {
    const double u_n = sim.state.u[dof(0, ntn::kUx)];
    ASSERT_EQ(ntn::step(sim.model, sim.state, sim.scratch, {}), ntn::StepStatus::kOk);
    const double u_next = sim.state.u[dof(0, ntn::kUx)];
    const double normal = sim.scratch.outputs[4];  // N at t_n
    if (normal < 0) {
      ++held;
      held_worst = std::fmax(held_worst, std::fabs(u_next - u_n));
    } else if (n > 0) {
      ++free;
      const double a = (u_next - 2 * u_n + u_prev) / (dt * dt);
      free_worst = std::fmax(free_worst, std::fabs(M * a - (Q - k_el * u_n)) / Q);
    }
    u_prev = u_n;
  }
  const double t_end = 1.3, u = sim.state.u[dof(0, ntn::kUx)];
  std::printf(
      "  %ld steps held (|du| <= %.1e m), %ld free (Newton's law to %.1e of Q); slid "
      "%.4f m by t = %.1f s\n",
      held, held_worst, free, free_worst, u, t_end);
  EXPECT_GT(held, 9000);  // pressed until about t = M g / c = 0.98 s
  EXPECT_GT(free, 2000);
  EXPECT_LE(held_worst, 1e-15);
  EXPECT_LE(free_worst, 1e-9);
  EXPECT_GT(u, 0.5 * Q / M * 0.25 * 0.25);  // it slid at Q / M for at least the last 0.25 s
}

// A spring that breaks, run under `method`: the final state, and the break's tick.
struct Broken {
  double x = 0, dissipated = 0, force_peak = 0;
  std::int64_t first = 0;
  double x_b = 0, v_b = 0;  // u and v_{n+1/2} after the break step
  long break_step = -1;
};

Broken break_spring(ntn::HingeMethod method) {
  const double k = 1e6, F = 5e3, P = 1e4;
  ntn::HysteresisSpec law;
  law.rule = ntn::HysteresisRule::kBrittle;
  law.yield_pos = law.yield_neg = F;
  block(ntn::HingeBehaviour::kPlastic, law, P, 0);
  sim.spec.hinges[0].stiffness[ntn::kUx] = k;
  sim.spec.settings.hinge_method = method;
  start();
  Broken r;
  const ntn_test::EigenNoMalloc guard;
  for (long n = 0; n < 2'000; ++n) {
    EXPECT_EQ(ntn::step(sim.model, sim.state, sim.scratch, {}), ntn::StepStatus::kOk);
    r.force_peak = std::fmax(r.force_peak, std::fabs(sim.scratch.outputs[0]));
    if (r.break_step < 0 && sim.state.first_slip[0] != 0) {
      r.break_step = n;
      r.x_b = sim.state.u[dof(0, ntn::kUx)], r.v_b = sim.state.v[dof(0, ntn::kUx)];
    }
  }
  r.x = sim.state.u[dof(0, ntn::kUx)];
  r.dissipated = sim.state.dissipated[0];
  r.first = sim.state.first_slip[0];
  return r;
}

TEST(BrittleSpring, BreaksWhenItsForceFirstPassesTheLimitUnderEveryMethod) {
  // Truth: a mass on a spring k under a suddenly applied P: x = P/k (1 - cos wt) while it holds,
  // its force k x first reaches F at t_b = arccos(1 - F/P) / w (w = sqrt(k/M)); the step after
  // which it passes F the spring carries nothing, and the mass then moves under P alone:
  // M (u_{n+1} - u_n) / dt = v, v grows by P dt / M a step (the soft element: 1e-6 of k).
  // Tolerances: t_b to one step; the peak force within F (it breaks before it carries more);
  // the energy it held, (k x_b)^2 / 2k, between F^2 / 2k and (F + k v dt)^2 / 2k (the step's
  // overshoot); 0.2 s later the free flight to 1e-4 relative (the soft element pulls k_el x / P
  // = 2e-5 of the load, its integral stays below that). The same bits under every
  // method (the model has no rigid direction: the spring is the same spring).
  const double k = 1e6, F = 5e3, P = 1e4, dt = 1e-4;
  const Broken exact = break_spring(ntn::HingeMethod::kNtnExact);
  const double w = std::sqrt(k / mass());
  const double t_b = std::acos(1 - F / P) / w;
  const double t_seen = static_cast<double>(exact.first - 1) * dt;
  const double v = P / k * w * std::sin(w * t_b);
  std::printf(
      "  broke at t = %.4f s (closed form %.4f s), peak force %.1f N, energy released "
      "%.4f J (F^2/2k = %.4f J)\n",
      t_seen, t_b, exact.force_peak, exact.dissipated, F * F / (2 * k));
  EXPECT_NEAR(t_seen, t_b, dt);
  EXPECT_LE(exact.force_peak, F);
  EXPECT_GE(exact.dissipated, F * F / (2 * k));
  EXPECT_LE(exact.dissipated, (F + k * v * dt) * (F + k * v * dt) / (2 * k));
  const double tau = static_cast<double>(1999 - exact.break_step) * dt;
  const double flight = exact.x_b + exact.v_b * tau + 0.5 * P / mass() * tau * (tau + dt);
  EXPECT_NEAR(exact.x, flight, 1e-4 * exact.x);
  const auto y = ntn::hil::yielded_directions(sim.model, sim.state);
  ASSERT_EQ(y.size(), 1U);
  EXPECT_TRUE(y[0].failed);
  EXPECT_EQ(y[0].first_slip, t_seen);
  for (const auto method : {ntn::HingeMethod::kPenalty, ntn::HingeMethod::kNtnPaper}) {
    const Broken other = break_spring(method);
    EXPECT_EQ(other.first, exact.first);
    EXPECT_EQ(other.x, exact.x);
    EXPECT_EQ(other.dissipated, exact.dissipated);
  }
}

// A block on a level support: node 0 on a ground hinge whose z points into the support (x =
// global x, y = -global y, z = -global z), rigid in uz (the normal) and the rotations, ux and uy
// friction mu on uz, with or without the circle; gravity -g z; loads[0], loads[1] on ux, uy.
void level_block(double mu, bool circle, double px, double py) {
  ntn::HysteresisSpec law;
  law.normal = ntn::kUz;
  law.mu = mu;
  block(ntn::HingeBehaviour::kRigidPlastic, law, 0, 0);
  ntn::ModelSpec<kBlock>& s = sim.spec;
  s.nodes[0].fixed = 0;  // the hinge holds it: a support with its own axes
  s.hinges[0] =
      ntn_test::hinge(0, ntn::kGround, {1, 0, 0, 0, -1, 0, 0, 0, -1}, ntn_test::released(0));
  s.hinges[0].behaviour[ntn::kUx] = s.hinges[0].behaviour[ntn::kUy] =
      ntn::HingeBehaviour::kRigidPlastic;
  s.hinges[0].hysteresis[ntn::kUx] = 0, s.hinges[0].hysteresis[ntn::kUy] = 1;
  s.hystereses[0] = s.hystereses[1] = law;
  if (circle) s.hystereses[0].circle = ntn::kUy, s.hystereses[1].circle = ntn::kUx;
  s.settings.gravity = {0, 0, -kG};
  s.loads[0] = {0, ntn::kUx, px, ntn::kConstant};
  s.loads[1] = {0, ntn::kUy, py, ntn::kConstant};
}

TEST(FrictionCircle, ABlockPulledObliquelySlidesAlongThePullOnceItPassesTheCircle) {
  // Truth: isotropic Coulomb friction on a level support holds a block while the horizontal pull
  // P is below mu M g, in any direction; past it the block slides along P at (P - mu M g) / M.
  // Pull at 45 degrees, P = 1.2 mu M g: each component is 0.85 mu M g, below the limit of a
  // direction on its own, so two independent directions (a box) would hold it; the circle lets it
  // slide (its friction work mu M g times the path, to 1e-9). And P = 0.9 mu M g at 30 degrees:
  // held by the circle. Tolerance 1e-9 of the expected
  // acceleration (the soft element's pull over the first 10 steps is below 1e-10 of it); held:
  // no motion to 1e-15 m.
  const double mu = 0.3, dt = 1e-4;
  const double M = [&] {
    level_block(mu, true, 0, 0);
    start();
    return mass();
  }();
  const double limit = mu * M * kG;
  struct Case {
    double p, angle;
    bool circle;
    double expect;  // acceleration along the pull
  };
  const double deg = kPi / 180;
  for (const Case c :
       {Case{1.2 * limit, 45 * deg, true, (1.2 * limit - limit) / M},
        Case{1.2 * limit, 45 * deg, false, 0.0}, Case{0.9 * limit, 30 * deg, true, 0.0}}) {
    level_block(mu, c.circle, c.p * std::cos(c.angle), c.p * std::sin(c.angle));
    start();
    double worst = 0, vx = 0, vy = 0, moved = 0;
    const ntn_test::EigenNoMalloc guard;
    for (int n = 0; n < 10; ++n) {
      ASSERT_EQ(ntn::step(sim.model, sim.state, sim.scratch, {}), ntn::StepStatus::kOk);
      const double nx = sim.state.v[dof(0, ntn::kUx)], ny = sim.state.v[dof(0, ntn::kUy)];
      if (n >= 1) {
        const double ax = (nx - vx) / dt, ay = (ny - vy) / dt;  // global x, y
        worst = std::fmax(worst, std::fabs(ax - c.expect * std::cos(c.angle)));
        worst = std::fmax(worst, std::fabs(ay - c.expect * std::sin(c.angle)));
      }
      vx = nx, vy = ny;
      moved = std::fmax(moved,
                        std::hypot(sim.state.u[dof(0, ntn::kUx)], sim.state.u[dof(0, ntn::kUy)]));
    }
    std::printf(
        "  pull %.2f mu M g at %.0f deg, %s: acceleration %.6f m/s^2 expected, error "
        "%.2e, moved %.2e m\n",
        c.p / limit, c.angle / deg, c.circle ? "circle" : "box", c.expect, worst, moved);
    if (c.expect > 0) {
      EXPECT_LE(worst, 1e-9 * c.expect);
      // The friction work: the force at the limit along the slide, mu M g times the path.
      const double work = sim.state.dissipated[0] + sim.state.dissipated[1];
      EXPECT_NEAR(work, limit * moved, 1e-9 * work);
    } else {
      EXPECT_LE(moved, 1e-15);
    }
  }
}

}  // namespace slip_contact_test
