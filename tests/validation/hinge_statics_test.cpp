// Hinge forces against statics: the force and moment a hinge
// transmits in a statically determinate structure follow from equilibrium alone, whatever the
// stiffnesses, so a hand calculation is the truth. The structures are brought to rest under
// constant loads by damped dynamic relaxation with the kernel itself, and the kernel's
// kHingeForce channels (force on node 1 in the hinge frame: ntn_exact's constraint force lambda,
// ntn_paper's T (m1 a1 - R1), the spring force for penalty and for linear directions) are
// compared with the hand values.
//
// Tolerance: 0.5 %. The relaxation is run to 1e-10 in residual and motion, so the
// forces should be right to ~1e-8 of the largest; the test also holds them to 1e-6 of it (its
// own, tighter bound), and every hand-zero component to 1e-6 of the largest.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "ntn/kernel.hpp"
#include "support/builders.hpp"
#include "support/hinges.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"
#include "support/relaxation.hpp"

namespace hinge_statics_test {

using ntn_test::Mat3;
using B = ntn::HingeBehaviour;

constexpr double kL = 4.0;  // m
constexpr int kN = 8, kExtra = kN + 1;
constexpr ntn_test::Section kSection = ntn_test::rectangle(0.05, 0.1);
constexpr ntn::Sizes kS{.nodes = kN + 2, .elements = kN, .loads = 4, .outputs = 12, .hinges = 1};

ntn::ModelSpec<kS> spec;
ntn::Model<kS> model;
ntn::State<kS> state;
ntn::Scratch<kS> scratch;

// Member frame of the beam (along x, reference z): the global frame.
const Mat3 kMember = ntn_test::member_frame({0, 0, 0}, {1, 0, 0}, {0, 0, 1});

// A beam of kN elements along x cut at node `cut` (node kExtra is the right member's end, node 1
// of the hinge; the cut node is node 2). Outputs 0-5: hinge force, 6-11: hinge displacement.
void build(int cut, std::uint8_t fixed_last, const Mat3& frame, const std::array<B, 6>& behaviour,
           ntn::HingeMethod method) {
  spec = {};
  ntn_test::split_beam(spec, kL, ntn_test::kSteel, kSection, cut, kExtra, ntn_test::kFixedAll,
                       fixed_last);
  spec.hinges[0] = ntn_test::hinge(kExtra, cut, frame, behaviour);
  for (int k = 0; k < 6; ++k) {
    ntn::OutputSpec& f = spec.outputs[static_cast<std::size_t>(k)];
    f.kind = ntn::OutputKind::kHingeForce, f.hinge = 0, f.dof = k;
    ntn::OutputSpec& d = spec.outputs[static_cast<std::size_t>(k + 6)];
    d.kind = ntn::OutputKind::kHingeDisplacement, d.hinge = 0, d.dof = k;
  }
  spec.settings.hinge_method = method;
  // Penalty stiffness: 100 x the elements' EA / l and 4 E I / l. The statics of a determinate
  // structure do not depend on it.
  const double l = kL / kN;
  spec.settings.penalty_stiffness = 100 * ntn_test::kSteel.E * kSection.A / l;
  spec.settings.penalty_rotational_stiffness = 400 * ntn_test::kSteel.E * kSection.Iy / l;
  // Mass-proportional damping near critical for the softer plane's first cantilever mode:
  // alpha = 2 omega_1, omega_1 = 3.516 / L^2 sqrt(E Iz / (rho A)).
  const double w1 =
      3.516 / (kL * kL) *
      std::sqrt(ntn_test::kSteel.E * kSection.Iz / (ntn_test::kSteel.rho * kSection.A));
  spec.settings.alpha = 2 * w1;
  spec.settings.dt = 0.9 * ntn_test::hinged_stable_step(spec).dt_stable;
}

// Relaxes the model; returns the six hinge-force channels, checking convergence.
std::array<double, 6> relaxed_hinge_force() {
  ntn_test::RelaxationResult r;
  {
    const ntn_test::EigenNoMalloc guard;
    EXPECT_TRUE(ntn_test::init_model(spec, model).ok());
    state = {};
    r = ntn_test::relax_hinged(model, state, scratch, 1e-10, 3'000'000);
  }
  EXPECT_TRUE(r.converged) << "residual " << r.residual << " motion " << r.motion;
  std::array<double, 6> f{};
  for (std::size_t k = 0; k < 6; ++k)
    f[k] = scratch.outputs[k];
  return f;
}

// The hand value in the hinge frame: T_R F and T_R M for global F, M.
std::array<double, 6> to_frame(const Mat3& R, const std::array<double, 6>& g) {
  std::array<double, 6> l{};
  for (std::size_t r = 0; r < 3; ++r) {
    for (std::size_t c = 0; c < 3; ++c) {
      l[r] += R[3 * r + c] * g[c];
      l[r + 3] += R[3 * r + c] * g[c + 3];
    }
  }
  return l;
}

void expect_forces(const char* name, const std::array<double, 6>& got,
                   const std::array<double, 6>& hand, std::uint8_t check = 0x3f) {
  double scale = 0;
  for (const double x : hand)
    scale = std::max(scale, std::abs(x));
  std::printf("  %s:\n", name);
  for (std::size_t k = 0; k < 6; ++k) {
    if (!((check >> k) & 1U)) continue;
    const double err = std::abs(got[k] - hand[k]);
    std::printf("    direction %zu: kernel %+.9e, hand %+.9e, |difference| / max %.1e\n", k, got[k],
                hand[k], err / scale);
    if (std::abs(hand[k]) > 1e-9 * scale) {
      EXPECT_LT(err, 5e-3 * std::abs(hand[k])) << name << ", direction " << k;
    }
    EXPECT_LT(err, 1e-6 * scale) << name << ", direction " << k;
  }
}

// 1. Cantilever (clamped at x = 0) cut at midspan (x = 2 m) by a hinge rigid in all six
// directions, loaded at the tip by N = 3 kN, Py = 400 N, Pz = -600 N and a torque T = 150 N m.
// The part beyond the cut is held by the hinge alone: the hinge force on it (node 1) is
// F = -P, M = -(L/2) x x P - M_tip = (-T, (L/2) Pz, -(L/2) Py) in global axes, in the hinge
// frame T_R F, T_R M. Checked in the member frame and in the skewed frame, for every
// method.
TEST(HingeStatics, CantileverWithARigidHingeAtMidspan) {
  constexpr double N = 3e3, Py = 400, Pz = -600, T = 150;
  const std::array<double, 6> hand_global{-N, -Py, -Pz, -T, kL / 2 * Pz, -kL / 2 * Py};
  const Mat3 skewed = ntn_test::skewed_frame(kMember);
  struct Case {
    const char* name;
    const Mat3* frame;
    ntn::HingeMethod method;
  };
  for (const Case& c : {Case{"ntn_exact, member frame", &kMember, ntn::HingeMethod::kNtnExact},
                        Case{"ntn_exact, skewed frame", &skewed, ntn::HingeMethod::kNtnExact},
                        Case{"ntn_paper, member frame", &kMember, ntn::HingeMethod::kNtnPaper},
                        Case{"penalty, member frame", &kMember, ntn::HingeMethod::kPenalty},
                        Case{"penalty, skewed frame", &skewed, ntn::HingeMethod::kPenalty}}) {
    build(kN / 2, 0, *c.frame, ntn_test::kAllRigid, c.method);
    spec.loads[0] = {kN, ntn::kUx, N, ntn::kConstant};
    spec.loads[1] = {kN, ntn::kUy, Py, ntn::kConstant};
    spec.loads[2] = {kN, ntn::kUz, Pz, ntn::kConstant};
    spec.loads[3] = {kN, ntn::kRx, T, ntn::kConstant};
    expect_forces(c.name, relaxed_hinge_force(), to_frame(*c.frame, hand_global));
  }
}

// 2. Gerber beam: clamped at x = 0, hinge at x = a = 1.5 m released about y (no bending moment
// in the x-z plane), the end x = L = 4 m on a roller (uz held). A load P = 2 kN down at
// x = c = 3 m on the suspended span: by moments about the roller, the hinge carries
// V = P (L - c) / (L - a) = 0.4 P, pushing the suspended span up: force on node 1 (its end)
// +0.4 P along z. Everything else through the hinge is zero, and its relative rotation about y
// is not (the hinge does turn).
TEST(HingeStatics, GerberBeamShearThroughAPin) {
  constexpr double P = 2e3, a = 1.5, c = 3.0;
  constexpr int cut = 3, load_node = 6;  // x = 1.5 m, x = 3 m
  const std::array<double, 6> hand{0, 0, P * (kL - c) / (kL - a), 0, 0, 0};
  for (const ntn::HingeMethod m :
       {ntn::HingeMethod::kNtnExact, ntn::HingeMethod::kNtnPaper, ntn::HingeMethod::kPenalty}) {
    build(cut, std::uint8_t{1U << ntn::kUz}, kMember, ntn_test::released(1U << ntn::kRy), m);
    spec.loads[0] = {load_node, ntn::kUz, -P, ntn::kConstant};
    const std::array<double, 6> f = relaxed_hinge_force();
    expect_forces(m == ntn::HingeMethod::kNtnExact   ? "ntn_exact"
                  : m == ntn::HingeMethod::kNtnPaper ? "ntn_paper"
                                                     : "penalty",
                  f, hand);
    EXPECT_GT(std::abs(scratch.outputs[6 + ntn::kRy]), 1e-6);  // relative rotation at the pin
  }
}

// 3. The cantilever of case 1 with its hinge a rotational spring about y (k = 2e5 N m/rad) and
// rigid otherwise: the moment through the spring is still (L/2) Pz (determinate), so the spring
// force channel must read it and the relative rotation must be M / k.
TEST(HingeStatics, LinearSpringCarriesTheStaticMoment) {
  constexpr double Pz = -600, k = 2e5;
  std::array<B, 6> b = ntn_test::kAllRigid;
  b[ntn::kRy] = B::kLinear;
  for (const ntn::HingeMethod m : {ntn::HingeMethod::kNtnExact, ntn::HingeMethod::kPenalty}) {
    build(kN / 2, 0, kMember, b, m);
    spec.hinges[0].stiffness[ntn::kRy] = k;
    spec.settings.dt = 0.9 * ntn_test::hinged_stable_step(spec).dt_stable;
    spec.loads[0] = {kN, ntn::kUz, Pz, ntn::kConstant};
    const std::array<double, 6> f = relaxed_hinge_force();
    const double M = kL / 2 * Pz;
    expect_forces(
        m == ntn::HingeMethod::kNtnExact ? "ntn_exact, spring about y" : "penalty, spring about y",
        f, {0, 0, -Pz, 0, M, 0});
    const double rotation = scratch.outputs[6 + ntn::kRy];
    std::printf("    relative rotation %.9e rad, M / k %.9e rad\n", rotation, M / k);
    EXPECT_NEAR(rotation, M / k, 1e-6 * std::abs(M / k));
  }
}

}  // namespace hinge_statics_test
