// The gravity preload ([initial] gravity = "static"): the default frame under gravity,
// started from the model compiler's static solution of the kernel's own K, against truth that
// needs no reference values:
// - statics: a run from the preload with no other load stays at rest (the kernel's residual
//   P - F(u_0) is zero to rounding), and the support reactions carry the whole weight;
// - linearity: the frame is linear, so a run from rest with gravity applied suddenly is the run
//   from the preload plus the free ringing about the static state, at every step;
// - the column axial forces against the tributary loads (reported; see the test for the bound).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "fixed_beam_udl_model.hpp"
#include "frame3d_gravity_static_model.hpp"
#include "frame3d_gravity_sudden_model.hpp"
#include "ntn/kernel.hpp"
#include "support/init_model.hpp"

namespace preload_test {

namespace preload = ntn::models::frame3d_gravity_static;
namespace sudden = ntn::models::frame3d_gravity_sudden;
constexpr ntn::Sizes kS = preload::kSizes;
static_assert(kS.nodes == sudden::kSizes.nodes && kS.hinges == sudden::kSizes.hinges);
constexpr double kG = 9.80665;  // m/s^2, the variants' gravity (tests/validation/CMakeLists.txt)

struct Frame {
  std::unique_ptr<ntn::Model<kS>> model = std::make_unique<ntn::Model<kS>>();
  std::unique_ptr<ntn::State<kS>> state = std::make_unique<ntn::State<kS>>();
  std::unique_ptr<ntn::Scratch<kS>> scratch = std::make_unique<ntn::Scratch<kS>>();

  explicit Frame(const ntn::ModelSpec<kS>& spec) {
    EXPECT_TRUE(ntn_test::init_model(spec, *model).ok());
    ntn::initial_state(*model, *state);
  }
  // The ground acceleration at step n (m/s^2 = the input in g x 9.80665): zero, or a smooth
  // 2.5 s pulse of 0.2 g at 1.5 Hz, near the frame's first sway modes.
  static double ground(long n, double dt, bool shake) {
    const double t = static_cast<double>(n) * dt;
    if (!shake || t > 2.5) return 0.0;
    const double envelope = std::sin(std::numbers::pi * t / 2.5);
    return 0.2 * envelope * envelope * std::sin(2 * std::numbers::pi * 1.5 * t);
  }
  ntn::StepStatus start(bool shake) {
    return ntn::start(*model, *state, *scratch, {ground(0, model->dt, shake)});
  }
  ntn::StepStatus step(long n, bool shake) {
    return ntn::step(*model, *state, *scratch, {ground(n, model->dt, shake)});
  }
};

double max_abs(const std::array<double, ntn::Model<kS>::kDofs>& x) {
  double m = 0;
  for (double v : x)
    m = std::max(m, std::abs(v));
  return m;
}

// At rest in equilibrium: 10 s of the preloaded frame with no input. The velocity scale of the
// same frame when gravity is applied suddenly is its ringing, max |v| ~ omega_1 |u_static|; the
// preloaded frame must stay below 1e-9 of it. The residual P - F(u_0) is rounding
// (~1e-16 of the largest force), which moves the frame by ~1e-16 relative: far below 1e-9.
TEST(GravityPreload, FrameStaysAtRestFor10Seconds) {
  Frame pre(preload::kSpec), sud(sudden::kSpec);
  ASSERT_GT(max_abs(pre.model->u0), 1e-4);  // the preload is there (mm of sag)
  ASSERT_EQ(max_abs(sud.model->u0), 0.0);   // the sudden variant starts undeformed
  ASSERT_EQ(pre.start(false), ntn::StepStatus::kOk);
  ASSERT_EQ(sud.start(false), ntn::StepStatus::kOk);
  const long steps = std::lround(10.0 / pre.model->dt);
  double v_pre = 0, v_sud = 0, drift = 0;
  for (long n = 0; n < steps; ++n) {
    ASSERT_EQ(pre.step(n, false), ntn::StepStatus::kOk);
    ASSERT_EQ(sud.step(n, false), ntn::StepStatus::kOk);
    v_pre = std::max(v_pre, max_abs(pre.state->v));
    v_sud = std::max(v_sud, max_abs(sud.state->v));
  }
  for (std::size_t j = 0; j < pre.state->u.size(); ++j)
    drift = std::max(drift, std::abs(pre.state->u[j] - pre.model->u0[j]));
  std::printf(
      "  10 s: max |v| from the preload %.3e m/s, gravity applied suddenly %.3e m/s "
      "(ratio %.1e); max |u - u_0| %.3e m of |u_0| %.3e m\n",
      v_pre, v_sud, v_pre / v_sud, drift, max_abs(pre.model->u0));
  EXPECT_LE(v_pre, 1e-9 * v_sud);
  EXPECT_LE(drift, 1e-9 * max_abs(pre.model->u0));
}

// Equilibrium at t_0: the support reactions F - P (the kernel's reaction channel: the column's
// force and the weight of the mass lumped at the support node itself) sum to the weight of the
// whole model (1e-9: the sum of ~600 terms of rounding), and each column carries about its
// tributary load. The tributary load of a column line is the weight of every lumped mass not on
// a support that is nearest to it in plan (masses midway between two lines are shared). The frame
// is hyperstatic (beams continuous over line B, moment-connected along y), so the columns' axial
// forces (F at the base) differ from it by the redistribution of the beams' own weight and of
// the bending that the floor loads cause: bounded here by 3 % of the column's load (the beams
// weigh ~4 % of the floors' masses; measured: +0.6 % on line B, -0.5 % at the corners).
TEST(GravityPreload, ReactionsCarryTheWeightAndColumnsTheirTributaryLoads) {
  Frame pre(preload::kSpec);
  ASSERT_EQ(pre.start(false), ntn::StepStatus::kOk);
  const ntn::Model<kS>& m = *pre.model;
  const auto& nodes = preload::kSpec.nodes;
  double weight = 0, reactions = 0;
  std::array<double, 6> column{}, tributary{};  // base nodes 0..5 (user nodes 1..6)
  auto plan = [&](std::size_t a, std::size_t b) {
    return std::hypot(nodes[a].x - nodes[b].x, nodes[a].y - nodes[b].y);
  };
  for (std::size_t n = 0; n < kS.nodes; ++n) {
    const double w = m.mass[6 * n + 2] * kG;
    weight += w;
    if ((nodes[n].fixed >> 2) & 1U) continue;
    double best = 1e300;
    for (std::size_t c = 0; c < 6; ++c)
      best = std::min(best, plan(n, c));
    int ties = 0;
    for (std::size_t c = 0; c < 6; ++c)
      ties += plan(n, c) <= best + 1e-9 ? 1 : 0;
    for (std::size_t c = 0; c < 6; ++c) {
      if (plan(n, c) <= best + 1e-9) tributary[c] += w / ties;
    }
  }
  for (std::size_t c = 0; c < 6; ++c) {
    ASSERT_EQ(nodes[c].fixed, 0x3F) << "base node " << c;
    const std::size_t j = 6 * c + 2;
    column[c] = pre.scratch->f[j];  // the column's force on its base node: its axial force
    reactions += pre.scratch->f[j] - ntn::external_load(m, *pre.scratch, j);
  }
  std::printf("  weight %.6g N, sum of vertical reactions %.6g N\n", weight, reactions);
  EXPECT_NEAR(reactions, weight, 1e-9 * weight);
  for (std::size_t c = 0; c < 6; ++c) {
    std::printf("  column at (%g, %g): axial %.6g N, tributary %.6g N (%+.2f %%)\n", nodes[c].x,
                nodes[c].y, column[c], tributary[c], 100 * (column[c] / tributary[c] - 1));
    EXPECT_NEAR(column[c], tributary[c], 0.03 * tributary[c]);
  }
}

// Linearity: u_sudden+record(t) - u_preload+record(t) = u_sudden(t) - u_0 at every step, since
// the responses to gravity and to the record add. Rounding of three runs of 4 s: 1e-9 of the
// largest displacement. What starting from the preload changes: a sudden start rings about the
// static state with the static sag as amplitude (a constant load applied at once gives
// u_0 (1 - cos omega t) per mode), so at the DOF of the largest sag the two runs differ by at
// least 0.9 |u_0| within the first vibration (the damping, 2 % at 1.74 Hz and less above, takes
// less than 10 % in half a period).
TEST(GravityPreload, RunWithRecordDiffersFromTheSuddenStartByTheFreeRinging) {
  Frame a(preload::kSpec), b(sudden::kSpec), c(sudden::kSpec);
  ASSERT_EQ(a.start(true), ntn::StepStatus::kOk);
  ASSERT_EQ(b.start(true), ntn::StepStatus::kOk);
  ASSERT_EQ(c.start(false), ntn::StepStatus::kOk);
  std::size_t sag = 0;  // the DOF of the largest static displacement
  for (std::size_t j = 0; j < a.model->u0.size(); ++j) {
    if (std::abs(a.model->u0[j]) > std::abs(a.model->u0[sag])) sag = j;
  }
  const long steps = std::lround(4.0 / a.model->dt);
  double worst = 0, scale = 0, apart = 0;
  for (long n = 0; n < steps; ++n) {
    ASSERT_EQ(a.step(n, true), ntn::StepStatus::kOk);
    ASSERT_EQ(b.step(n, true), ntn::StepStatus::kOk);
    ASSERT_EQ(c.step(n, false), ntn::StepStatus::kOk);
    for (std::size_t j = 0; j < a.state->u.size(); ++j) {
      const double lhs = b.state->u[j] - a.state->u[j];
      const double rhs = c.state->u[j] - a.model->u0[j];
      worst = std::max(worst, std::abs(lhs - rhs));
      scale = std::max(scale, std::abs(b.state->u[j]));
    }
    apart = std::max(apart, std::abs(b.state->u[sag] - a.state->u[sag]));
  }
  std::printf(
      "  superposition error %.3e m of max |u| %.3e m; at the largest sag (DOF %zu, "
      "u_0 = %.4e m) the sudden start departs from the preloaded run by up to %.4e m\n",
      worst, scale, sag, a.model->u0[sag], apart);
  EXPECT_LE(worst, 1e-9 * scale);
  EXPECT_GE(apart, 0.9 * std::abs(a.model->u0[sag]));
}

// Element end forces under a member load: a fixed-fixed beam under q started from its preload.
// The element-force channels are K_L T u minus the element's own load (ElementLoadSpec), the end
// forces of the loaded element, so they read the beam's closed form at the element ends: support
// moments q L^2 / 12, midspan q L^2 / 24 (internal moment M(x) = q (6 x L - 6 x^2 - L^2) / 12),
// support shear q L / 2, midspan shear 0. The channel at an element's start is -M(x), at its end
// +M(x) (the forces the nodes exert on the element). The preload is exact for consistent loads,
// so the tolerance is rounding: 1e-9 of q L^2 / 12 and of q L / 2. Without the element's own load
// the support moment would be off by q h^2 / 12 (h = L / 4: 6 %).
TEST(MemberLoadForces, ElementChannelsReadTheLoadedBeamsEndForces) {
  namespace beam = ntn::models::fixed_beam_udl;
  constexpr ntn::Sizes kB = beam::kSizes;
  static_assert(kB.element_loads == 4);
  const auto m = std::make_unique<ntn::Model<kB>>();
  const auto s = std::make_unique<ntn::State<kB>>();
  const auto w = std::make_unique<ntn::Scratch<kB>>();
  ASSERT_TRUE(ntn_test::init_model(beam::kSpec, *m).ok());
  ntn::initial_state(*m, *s);
  ASSERT_EQ(ntn::start(*m, *s, *w, {}), ntn::StepStatus::kOk);
  ASSERT_EQ(ntn::step(*m, *s, *w, {}), ntn::StepStatus::kOk);  // outputs at t_0
  const double q = 10e3, L = 6.0;
  const double m_support = q * L * L / 12, v_support = q * L / 2;
  const auto& out = w->outputs;  // My_start, Vz_start, My_mid, Vz_mid, My_end
  std::printf(
      "  My support %.9g N m (q L^2/12 = %.9g), midspan %.9g (q L^2/24 = %.9g), other "
      "support %.9g; Vz support %.9g N, midspan %.3g N\n",
      out[0], m_support, out[2], m_support / 2, out[4], out[1], out[3]);
  EXPECT_NEAR(std::abs(out[0]), m_support, 1e-9 * m_support);
  EXPECT_NEAR(out[2], out[0] / 2, 1e-9 * m_support);  // the same sign: -M(0) and +M(L/2)
  EXPECT_NEAR(out[4], -out[0], 1e-9 * m_support);     // +M(L) = M(0)
  EXPECT_NEAR(out[1], v_support, 1e-9 * v_support);   // upward at the start (local z = +Z)
  EXPECT_NEAR(out[3], 0.0, 1e-9 * v_support);
}

}  // namespace preload_test
