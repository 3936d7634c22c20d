// The stable step with hinges (issue 3, "What must be shown" 8; DESIGN §6): rigid NTN directions
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
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ntn/kernel.hpp"
#include "support/assemble.hpp"
#include "support/builders.hpp"
#include "support/hinges.hpp"
#include "support/no_heap.hpp"

namespace {

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
  EXPECT_TRUE(ntn::init(spec, model).ok());
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
    ASSERT_TRUE(ntn::init(spec, model).ok());
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
  // (dense eigenvalues, tests/support/assemble.hpp): for this aligned, centric hinge the
  // per-spring estimate must be within 1 % of it.
  const double assembled =
      ntn_test::assembled_stable_step(ntn::view(spec), factor * kAxial, factor * kBending);
  std::printf("  penalty: reported %.4e s, exact for the assembled system %.4e s\n", pen.dt_stable,
              assembled);
  EXPECT_NEAR(pen.dt_stable / assembled, 1.0, 0.01);
}

// KNOWN KERNEL ISSUE, disabled until time_step.hpp is fixed (reported with issue 3's hinge
// tests). stable_time_step(spec, mass) takes each spring direction of each hinge as its own
// two-node oscillator, omega^2 = k b^T M^-1 b (DESIGN §6). That is not conservative when springs
// load the same DOFs together: several penalty hinges on one joint node (their stiffnesses add
// on the joint's mass), an eccentric hinge (the translational springs' lever arm e x t and the
// rotational springs both load node 1's rotation), a turned frame over unequal rotational
// masses. The exact stable step of the assembled system is then smaller than the reported one:
// 1.06x and 1.14x for the two small cases below, 1.47x, 1.30x and 1.26x for hinge_penalty_test's
// star joint, chain and eccentric hinge, where a penalty run at 0.9 of the reported step (what
// dt = "auto" picks) diverges. A conservative estimate would bound each hinge's springs together
// (the largest eigenvalue of K_p^1/2 B M_h^-1 B^T K_p^1/2, with each node's mass shared among
// the spring hinges on it) and add the elements' omega^2.
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
  const double reported = ntn_test::hinged_stable_step(s).dt_stable;
  const double exact = ntn_test::assembled_stable_step(ntn::view(s), s.settings.penalty_stiffness,
                                                       s.settings.penalty_rotational_stiffness);
  std::printf("  %s: reported %.4e s, exact %.4e s, reported / exact %.3f\n", name, reported, exact,
              reported / exact);
  return reported / exact;
}

TEST(HingeTimeStep, DISABLED_PenaltyStepIsConservativeForEccentricAndSharedJoints) {
  // (a) The tips joined by one rigid hinge with a 0.2 m eccentricity.
  two_cantilevers(eccentric, 0.2);
  eccentric.hinges[0] =
      ntn_test::hinge(1, 2, ntn_test::kIdentity3, ntn_test::kAllRigid, {0, 0, 0.2});
  EXPECT_LE(reported_over_exact("eccentric hinge", eccentric), 1 + 1e-9);
  // (b) The tips joined through a joint node (20 kg, 0.2 kg m^2) by two rigid hinges, one turned
  // 30 degrees about the beam axis.
  two_cantilevers(shared, 0.0);
  shared.nodes[4] = {1, 0, 0, 0, {20, 20, 20, 0.2, 0.2, 0.2}};
  shared.hinges[0] = ntn_test::hinge(1, 4, ntn_test::kIdentity3);
  shared.hinges[1] = ntn_test::hinge(
      2, 4,
      ntn_test::rotate_frame(ntn_test::kIdentity3,
                             ntn_test::rotation({1, 0, 0}, 30 * ntn_test::kDegree)));
  EXPECT_LE(reported_over_exact("two hinges on a joint node", shared), 1 + 1e-9);
}

}  // namespace
