// The stable step with hinges (DESIGN §6): rigid NTN directions
// add no stiffness, so ntn_exact keeps the elements' step, while `penalty` must make its rigid
// directions stiff enough to be rigid, and its step collapses. The same model under both: the
// clamped-clamped beam of hinge_release_test, cut at midspan by a hinge released about y.
//
// The penalty stiffness is not chosen by taste: it is the smallest power of ten (times the
// elements' own stiffness EA / l, 4 E I / l) at which the hinge's relative displacement in its
// rigid directions stays below 1e-6 of the peak displacement (translations against the peak
// translation, rotations against the peak rotation) under the load pulse, and the test shows
// both that it does and that a tenth of it does not.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "ntn/kernel.hpp"
#include "support/assemble.hpp"
#include "support/builders.hpp"
#include "support/hinges.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"

namespace hinge_time_step_test {

using ntn_test::dof;

constexpr int kN = 8, kMid = 4, kExtra = 9, kQuarter = 2;
constexpr double kL = 4.0;
constexpr ntn_test::Section kSection = ntn_test::rectangle(0.1, 0.15);
constexpr ntn::Sizes kS{.nodes = kN + 2,
                        .elements = kN,
                        .time_functions = 1,
                        .time_points = 3,
                        .loads = 4,
                        .hinges = 1};

ntn::ModelSpec<kS> spec;
ntn::Model<kS> model;
ntn::State<kS> state;
ntn::Scratch<kS> scratch;

// Element stiffness scales (l = 0.5 m).
const double kAxial = ntn_test::kSteel.E * kSection.A / (kL / kN);
const double kBending = 4 * ntn_test::kSteel.E * kSection.Iy / (kL / kN);

void build(ntn::HingeMethod method, double penalty_factor = 0) {
  spec = {};
  ntn_test::split_beam(spec, kL, ntn_test::kSteel, kSection, kMid, kExtra, ntn_test::kFixedAll,
                       ntn_test::kFixedAll);
  spec.hinges[0] =
      ntn_test::hinge(kExtra, kMid, ntn_test::kIdentity3, ntn_test::released(1U << ntn::kRy));
  spec.settings.hinge_method = method;
  spec.settings.penalty_stiffness = penalty_factor * kAxial;
  spec.settings.penalty_rotational_stiffness = penalty_factor * kBending;
  spec.time_points = ntn_test::triangle_pulse(0.004);
  spec.time_functions[0] = {0, 3};
  spec.loads[0] = {kQuarter, ntn::kUz, -5e4, 0};
  spec.loads[1] = {kQuarter, ntn::kUy, 3e4, 0};
  spec.loads[2] = {kQuarter, ntn::kRx, 2e3, 0};
  spec.loads[3] = {kQuarter, ntn::kUx, 4e5, 0};
  spec.settings.dt = 0.9 * ntn_test::hinged_stable_step(spec).dt_stable;
}

// Max rigid |d| relative to the peak, translations and rotations, over 0.05 s (1.5 periods of
// the first mode: the pulse's response and its first swing).
double rigid_slip() {
  const Eigen::MatrixXd B = ntn_test::hinge_b(ntn::view(spec), spec.hinges[0]);
  const Eigen::Matrix<double, 6, 6> b1 = B.block<6, 6>(0, 6 * kExtra);
  const Eigen::Matrix<double, 6, 6> b2 = B.block<6, 6>(0, 6 * kMid);
  double peak_t = 0, peak_r = 0, slip_t = 0, slip_r = 0;
  const ntn_test::EigenNoMalloc guard;
  EXPECT_TRUE(ntn_test::init_model(spec, model).ok());
  state = {};
  EXPECT_EQ(ntn::start(model, state, scratch, {}), ntn::StepStatus::kOk);
  const auto steps = static_cast<long>(0.05 / model.dt);
  for (long n = 0; n < steps; ++n) {
    if (ntn::step(model, state, scratch, {}) != ntn::StepStatus::kOk) {
      ADD_FAILURE() << "step " << n;
      break;
    }
    for (std::size_t j = 0; j < state.u.size(); ++j) {
      double& p = j % 6 < 3 ? peak_t : peak_r;
      p = std::max(p, std::abs(state.u[j]));
    }
    const Eigen::Matrix<double, 6, 1> d =
        b1 * Eigen::Map<const Eigen::Matrix<double, 6, 1>>(&state.u[dof(kExtra, 0)]) +
        b2 * Eigen::Map<const Eigen::Matrix<double, 6, 1>>(&state.u[dof(kMid, 0)]);
    for (int k = 0; k < 6; ++k) {
      if (k == ntn::kRy) continue;
      double& s = k < 3 ? slip_t : slip_r;
      s = std::max(s, std::abs(d(k)));
    }
  }
  const double slip = std::max(slip_t / peak_t, slip_r / peak_r);
  std::printf("    %ld steps of %.3e s: peak %.3e m, %.3e rad; rigid slip / peak %.2e, %.2e\n",
              steps, model.dt, peak_t, peak_r, slip_t / peak_t, slip_r / peak_r);
  return slip;
}

TEST(HingeTimeStep, PenaltyCollapsesTheStepNtnExactKeepsIt) {
  // ntn_exact: no hinge spring at all, the step is the elements' bound.
  build(ntn::HingeMethod::kNtnExact);
  const ntn::StableStepReport exact = ntn_test::hinged_stable_step(spec);
  EXPECT_EQ(exact.dt_stable, exact.dt_elements);
  EXPECT_EQ(exact.governing_hinge, -1);
  EXPECT_EQ(exact.dt_hinges, 1e300);
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
  }
  EXPECT_EQ(model.stable.dt_stable, exact.dt_elements);  // what init stores is the same

  // penalty: the smallest stiffness factor (a power of ten) that keeps the slip below 1e-6.
  double factor = 0;
  for (double f = 1e3; f <= 1e7; f *= 10) {
    std::printf("  penalty stiffness %.0e x (EA / l, 4 E I / l):\n", f);
    build(ntn::HingeMethod::kPenalty, f);
    if (rigid_slip() < 1e-6) {
      factor = f;
      break;
    }
  }
  ASSERT_GT(factor, 0) << "no penalty stiffness up to 1e7 x keeps the hinge rigid to 1e-6";
  build(ntn::HingeMethod::kPenalty, factor);
  const ntn::StableStepReport pen = ntn_test::hinged_stable_step(spec);
  const double ratio = exact.dt_stable / pen.dt_stable;
  std::printf(
      "  dt_stable: ntn_exact %.4e s (elements' bound, element %d), penalty %.4e s (hinge %d, "
      "direction %d, k_p %.2e N/m, %.2e N m/rad): ratio %.1f\n",
      exact.dt_stable, exact.governing_element, pen.dt_stable, pen.governing_hinge,
      pen.hinge_direction, factor * kAxial, factor * kBending, ratio);
  RecordProperty("dt_ratio_exact_over_penalty", std::to_string(ratio));
  EXPECT_EQ(pen.governing_hinge, 0);
  EXPECT_EQ(pen.dt_elements, exact.dt_elements);
  EXPECT_GT(ratio, 10.0);  // "much smaller"
  // The reported penalty step against the exact stable step of the assembled penalty system
  // (dense eigenvalues, tests/support/assemble.hpp). The kernel's step is a strict bound
  // (time_step.hpp), so never above it; for this aligned, centric hinge it is the hinge's
  // two-node frequency plus the elements' omega^2 (Weyl), which k_p far above the elements'
  // stiffness makes negligible: within 1 %.
  const double assembled =
      ntn_test::assembled_stable_step(ntn::view(spec), factor * kAxial, factor * kBending);
  std::printf(
      "  penalty: reported %.4e s, exact for the assembled system %.4e s, exact / reported "
      "%.5f\n",
      pen.dt_stable, assembled, assembled / pen.dt_stable);
  EXPECT_LE(pen.dt_stable, assembled * (1 + 1e-9));
  EXPECT_GT(pen.dt_stable / assembled, 0.99);
}

// The step is a strict bound where springs share DOFs (time_step.hpp): several penalty hinges on
// one joint node (their stiffnesses add on the joint's mass), an eccentric hinge (the
// translational springs' lever arm e x t and the rotational springs both load node 1's
// rotations), a turned frame over unequal rotational masses. Each spring taken alone as a
// two-node oscillator, omega^2 = k b^T M^-1 b, gave 1.06x and 1.14x too large a step for the two
// small cases below (1.47x, 1.30x and 1.26x for hinge_penalty_test's star joint, chain and
// eccentric hinge, where a run at 0.9 of it diverged). Truth: the exact stable step of the
// assembled system, 2 / sqrt(lambda_max(M^-1/2 K M^-1/2)) over the free DOFs (elements, and
// B^T K_p B for every hinge, written from the equations in tests/support/assemble.hpp). The
// kernel's step must not exceed it (1e-9: rounding of the two eigenvalue solvers), and should
// not be below 0.9 of it: a bound more conservative than the 10 % margin dt = "auto" keeps
// would cost more steps than the margin itself.
constexpr ntn::Sizes kEccentric{.nodes = 4, .elements = 2, .hinges = 1};
constexpr ntn::Sizes kShared{.nodes = 5, .elements = 2, .hinges = 2};
ntn::ModelSpec<kEccentric> eccentric;
ntn::ModelSpec<kShared> shared;

// Two cantilevers (1 m, one element each) whose tips meet at x = 1 m, the second one `rise`
// higher; returns the tip nodes (1 and 2).
template <ntn::Sizes S>
void two_cantilevers(ntn::ModelSpec<S>& s, double rise) {
  const ntn_test::Section sec = ntn_test::rectangle(0.08, 0.12);
  s = {};
  s.nodes[0] = {0, 0, 0, ntn_test::kFixedAll, {}};
  s.nodes[1] = {1, 0, 0, 0, {}};
  s.nodes[2] = {1, 0, rise, 0, {}};
  s.nodes[3] = {2, 0, rise, ntn_test::kFixedAll, {}};
  s.elements[0] = ntn_test::element(0, 1, ntn_test::kSteel, sec, {0, 0, 1});
  s.elements[1] = ntn_test::element(2, 3, ntn_test::kSteel, sec, {0, 0, 1});
  s.settings.hinge_method = ntn::HingeMethod::kPenalty;
  s.settings.penalty_stiffness = 1e3 * ntn_test::kSteel.E * sec.A;
  s.settings.penalty_rotational_stiffness = 4e3 * ntn_test::kSteel.E * sec.Iy;
}

template <ntn::Sizes S>
double reported_over_exact(const char* name, const ntn::ModelSpec<S>& s) {
  ntn::StableStepReport r;
  {
    const ntn_test::EigenNoMalloc guard;  // what init runs: no heap
    r = ntn_test::hinged_stable_step(s);
  }
  const double exact = ntn_test::assembled_stable_step(ntn::view(s), s.settings.penalty_stiffness,
                                                       s.settings.penalty_rotational_stiffness);
  std::printf(
      "  %s: reported %.4e s (hinge %d, direction %d), exact %.4e s, reported / exact %.4f "
      "(omega bound / omega_max %.4f)\n",
      name, r.dt_stable, r.governing_hinge, r.hinge_direction, exact, r.dt_stable / exact,
      exact / r.dt_stable);
  EXPECT_GE(r.governing_hinge, 0) << name;  // the penalty springs set the step
  return r.dt_stable / exact;
}

TEST(HingeTimeStep, PenaltyStepIsConservativeForEccentricAndSharedJoints) {
  // (a) The tips joined by one rigid hinge with a 0.2 m eccentricity.
  two_cantilevers(eccentric, 0.2);
  eccentric.hinges[0] =
      ntn_test::hinge(1, 2, ntn_test::kIdentity3, ntn_test::kAllRigid, {0, 0, 0.2});
  const double a = reported_over_exact("eccentric hinge", eccentric);
  EXPECT_LE(a, 1 + 1e-9);
  EXPECT_GT(a, 0.9);
  // (b) The tips joined through a joint node (20 kg, 0.2 kg m^2) by two rigid hinges, one turned
  // 30 degrees about the beam axis.
  two_cantilevers(shared, 0.0);
  shared.nodes[4] = {1, 0, 0, 0, {20, 20, 20, 0.2, 0.2, 0.2}};
  shared.hinges[0] = ntn_test::hinge(1, 4, ntn_test::kIdentity3);
  shared.hinges[1] = ntn_test::hinge(
      2, 4,
      ntn_test::rotate_frame(ntn_test::kIdentity3,
                             ntn_test::rotation({1, 0, 0}, 30 * ntn_test::kDegree)));
  const double b = reported_over_exact("two hinges on a joint node", shared);
  EXPECT_LE(b, 1 + 1e-9);
  EXPECT_GT(b, 0.9);
}

// A joint node with 40 penalty hinges: 40 one-element members (1 m, directions spread over a
// sphere) clamped at their far ends, each rigidly hinged in its own member frame to the joint
// (40 kg, 0.4 kg m^2). Numbered so that the joint's pass of the kernel's bound reaches 40
// member ends, more than one window of partners (time_step.hpp). Truth and tolerances as above.
constexpr int kArms = 40;
constexpr ntn::Sizes kStar{.nodes = 1 + 2 * kArms, .elements = kArms, .hinges = kArms};
ntn::ModelSpec<kStar> star;

TEST(HingeTimeStep, PenaltyStepIsConservativeForManyHingesOnOneJoint) {
  const ntn_test::Section sec = ntn_test::rectangle(0.08, 0.12);
  star = {};
  star.nodes[0] = {0, 0, 0, 0, {40, 40, 40, 0.4, 0.4, 0.4}};
  for (int a = 0; a < kArms; ++a) {
    // Fibonacci sphere: z from 1 to -1, longitude by the golden angle.
    const double z = 1 - (2.0 * a + 1) / kArms, rho = std::sqrt(1 - z * z);
    const double phi = a * 2.39996322972865332;
    const ntn_test::Vec3 far{rho * std::cos(phi), rho * std::sin(phi), z};
    const ntn_test::Vec3 ref =
        std::abs(z) > 0.9 ? ntn_test::Vec3{1, 0, 0} : ntn_test::Vec3{0, 0, 1};
    const int tip = 1 + a, end = 1 + kArms + a;
    star.nodes[static_cast<std::size_t>(tip)] = {far[0], far[1], far[2], ntn_test::kFixedAll, {}};
    star.nodes[static_cast<std::size_t>(end)] = {0, 0, 0, 0, {}};
    star.elements[static_cast<std::size_t>(a)] =
        ntn_test::element(end, tip, ntn_test::kSteel, sec, ref);
    star.hinges[static_cast<std::size_t>(a)] =
        ntn_test::hinge(end, 0, ntn_test::member_frame({0, 0, 0}, far, ref));
  }
  star.settings.hinge_method = ntn::HingeMethod::kPenalty;
  star.settings.penalty_stiffness = 1e3 * ntn_test::kSteel.E * sec.A;
  star.settings.penalty_rotational_stiffness = 4e3 * ntn_test::kSteel.E * sec.Iy;
  const double ratio = reported_over_exact("40 hinges on a joint node", star);
  EXPECT_LE(ratio, 1 + 1e-9);
  EXPECT_GT(ratio, 0.9);
}

// Dashpots and mass-proportional damping: the same two joints with every direction a linear
// spring of a tenth of the elements' stiffness scale EA / l, 4 E I / l (so that the elements'
// part and the springs' part of the bound are of a size) and a dashpot, alpha = 20 1/s. Truth: the
// central difference recursion of the assembled system with the damping lagged to v_{n-1/2} (S 3),
//   u_{n+1} = (2 I - dt^2 M^-1 K - dt M^-1 C) u_n + (dt M^-1 C - I) u_{n-1},
// C = alpha M + sum c b b^T: its amplification matrix must have spectral radius <= 1 at the
// kernel's step (1e-9: rounding of the dense eigenvalue solver; every mode is damped, so a step
// above the true limit gives a radius measurably above 1). The true limit, found by bisection on
// the radius, is printed: how conservative the damped bound is.
double spectral_radius(const Eigen::MatrixXd& A, const Eigen::MatrixXd& D, double dt) {
  const Eigen::Index n = A.rows();
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  G.topLeftCorner(n, n) = 2 * I - dt * dt * A - dt * D;
  G.topRightCorner(n, n) = dt * D - I;
  G.bottomLeftCorner(n, n) = I;
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(G, false);
  return eig.eigenvalues().cwiseAbs().maxCoeff();
}

template <ntn::Sizes S>
void damped_check(const char* name, ntn::ModelSpec<S>& s, double xi_beta = 0) {
  const ntn_test::Section sec = ntn_test::rectangle(0.08, 0.12);
  const double kt = 0.1 * ntn_test::kSteel.E * sec.A, kr = 0.4 * ntn_test::kSteel.E * sec.Iy;
  s.settings.hinge_method = ntn::HingeMethod::kNtnExact;
  s.settings.alpha = 20;
  s.settings.damping_velocity = ntn::DampingVelocity::kLagged;  // the truth's recursion (S 3)
  // beta K_el with the ratio xi_beta at the elements' highest frequency.
  s.settings.beta = 0;
  s.settings.beta = 2 * xi_beta / ntn::stable_time_step(ntn::view(s)).omega_max;
  for (ntn::HingeSpec& h : s.hinges) {
    for (std::size_t k = 0; k < 6; ++k) {
      h.behaviour[k] = ntn::HingeBehaviour::kLinear;
      h.stiffness[k] = k < 3 ? kt : kr;
      h.dashpot[k] = 5e-5 * h.stiffness[k];  // s: xi of the springs about 0.2-0.4
    }
  }
  ntn::StableStepReport r;
  {
    const ntn_test::EigenNoMalloc guard;
    r = ntn_test::hinged_stable_step(s);
  }
  // The assembled M, K, C on the free DOFs, scaled: A = M^-1/2 K M^-1/2, D = M^-1/2 C M^-1/2.
  const ntn::SpecView v = ntn::view(s);
  const Eigen::VectorXd m = ntn_test::lumped_mass(v);
  Eigen::MatrixXd K = ntn_test::global_stiffness(v) + ntn_test::hinge_spring_stiffness(v);
  Eigen::MatrixXd C = s.settings.alpha * Eigen::MatrixXd(m.asDiagonal()) +
                      s.settings.beta * ntn_test::global_stiffness(v);
  for (const ntn::HingeSpec& h : s.hinges) {
    const Eigen::MatrixXd B = ntn_test::hinge_b(v, h);
    for (int k = 0; k < 6; ++k)
      C += h.dashpot[static_cast<std::size_t>(k)] * B.row(k).transpose() * B.row(k);
  }
  const std::vector<Eigen::Index> d = ntn_test::free_dofs(v);
  Eigen::VectorXd sc(static_cast<Eigen::Index>(d.size()));
  for (std::size_t i = 0; i < d.size(); ++i)
    sc(static_cast<Eigen::Index>(i)) = 1.0 / std::sqrt(m(d[i]));
  const Eigen::MatrixXd A = sc.asDiagonal() * ntn_test::restrict_to(K, d) * sc.asDiagonal();
  const Eigen::MatrixXd D = sc.asDiagonal() * ntn_test::restrict_to(C, d) * sc.asDiagonal();
  const double at_bound = spectral_radius(A, D, r.dt_stable);
  // The true limit: stable at lo, unstable at hi.
  double lo = r.dt_stable, hi = 2 * r.dt_stable;
  EXPECT_GT(spectral_radius(A, D, hi), 1 + 1e-6) << name;
  for (int it = 0; it < 50; ++it) {
    const double mid = 0.5 * (lo + hi);
    (spectral_radius(A, D, mid) <= 1 + 1e-12 ? lo : hi) = mid;
  }
  const double undamped =
      2.0 / std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, Eigen::EigenvaluesOnly)
                          .eigenvalues()
                          .maxCoeff());
  std::printf(
      "  %s, damped: reported %.4e s (dt_elements %.4e, dt_hinges %.4e, hinge %d), spectral radius "
      "there %.6f; true damped limit %.4e s (undamped %.4e s): reported / true %.4f\n",
      name, r.dt_stable, r.dt_elements, r.dt_hinges, r.governing_hinge, at_bound, lo, undamped,
      r.dt_stable / lo);
  EXPECT_LE(at_bound, 1 + 1e-9) << name;
  EXPECT_LE(r.dt_stable, lo * (1 + 1e-9)) << name;
  EXPECT_LT(r.dt_stable, r.dt_elements) << name;  // the springs count
}

TEST(HingeTimeStep, DampedSpringStepIsConservative) {
  two_cantilevers(eccentric, 0.2);
  eccentric.hinges[0] =
      ntn_test::hinge(1, 2, ntn_test::kIdentity3, ntn_test::kAllRigid, {0, 0, 0.2});
  damped_check("eccentric hinge", eccentric);
  two_cantilevers(shared, 0.0);
  shared.nodes[4] = {1, 0, 0, 0, {20, 20, 20, 0.2, 0.2, 0.2}};
  shared.hinges[0] = ntn_test::hinge(1, 4, ntn_test::kIdentity3);
  shared.hinges[1] = ntn_test::hinge(
      2, 4,
      ntn_test::rotate_frame(ntn_test::kIdentity3,
                             ntn_test::rotation({1, 0, 0}, 30 * ntn_test::kDegree)));
  damped_check("two hinges on a joint node", shared);
}

// Stiffness-proportional damping beta K_el as well (xi 0.3 at the elements' top frequency): the
// node bound's eta_n = alpha + lambda_max(beta E_n + Q_n) must stay below the assembled system's
// true limit (same truth and tolerances as above, C = alpha M + beta K_el + sum c b b^T).
TEST(HingeTimeStep, StiffnessProportionalDampedSpringStepIsConservative) {
  two_cantilevers(eccentric, 0.2);
  eccentric.hinges[0] =
      ntn_test::hinge(1, 2, ntn_test::kIdentity3, ntn_test::kAllRigid, {0, 0, 0.2});
  damped_check("eccentric hinge, beta", eccentric, 0.3);
  two_cantilevers(shared, 0.0);
  shared.nodes[4] = {1, 0, 0, 0, {20, 20, 20, 0.2, 0.2, 0.2}};
  shared.hinges[0] = ntn_test::hinge(1, 4, ntn_test::kIdentity3);
  shared.hinges[1] = ntn_test::hinge(
      2, 4,
      ntn_test::rotate_frame(ntn_test::kIdentity3,
                             ntn_test::rotation({1, 0, 0}, 30 * ntn_test::kDegree)));
  damped_check("two hinges on a joint node, beta", shared, 0.3);
}

}  // namespace hinge_time_step_test
