// A hinge released about one bending axis: the frequencies the
// kernel's time stepping oscillates at equal those of the same structure with the rotation
// released exactly, computed independently here from the assembled matrices; and the time
// history agrees with the `penalty` method run at a step small enough for it.
//
// The reference: K and M of the cut structure (the kernel's element functions and lumped mass,
// tests/support/assemble.hpp), the hinge's rigid directions as exact constraints C u = 0 with
// C = the rigid rows of B = T [-I -E I 0; 0 -I 0 I] written from DESIGN §7, and the eigenproblem
// solved in the null space of C. The released rotation is thereby one DOF per side, everything
// else tied. Central difference advances a mode of frequency omega at
// omega_h = (2/dt) asin(omega dt / 2) per unit time (STYLE), so omega_h is what is compared.
#include <gtest/gtest.h>

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
#include "support/zero_crossings.hpp"

namespace hinge_release_test {

using ntn_test::dof;
using ntn_test::Vec3;
constexpr double kPi = 3.14159265358979323846;

// Clamped-clamped beam, 4 m, 8 elements, cut at midspan (nodes 4 and 9), 100 x 150 mm.
constexpr int kN = 8, kMid = 4, kExtra = 9, kQuarter = 2;
constexpr double kL = 4.0;
constexpr ntn_test::Section kSection = ntn_test::rectangle(0.1, 0.15);
constexpr ntn::Sizes kBeam{.nodes = kN + 2,
                           .elements = kN,
                           .time_functions = 1,
                           .time_points = 3,
                           .loads = 4,
                           .hinges = 1};

// Plane portal, columns 3 m (3 elements each, clamped), beam 6 m (4 elements) pinned to the left
// column top through a hinge released about the beam's local y (global y, in-plane rotation).
constexpr ntn::Sizes kPortal{.nodes = 12, .elements = 10, .hinges = 1};

constexpr std::uint8_t kReleaseRy = 1U << ntn::kRy;

using ntn_test::Sim;

Sim<kBeam> beam, beam2;
Sim<kPortal> portal;

// The cut beam; with `pulse` a load pulse at the quarter point in four directions (for time
// histories), else unloaded (free vibration).
void build_beam(ntn::ModelSpec<kBeam>& s, const ntn_test::Mat3& frame, std::uint8_t release,
                ntn::HingeMethod method, bool pulse = false) {
  s = {};
  ntn_test::split_beam(s, kL, ntn_test::kSteel, kSection, kMid, kExtra, ntn_test::kFixedAll,
                       ntn_test::kFixedAll);
  s.hinges[0] = ntn_test::hinge(kExtra, kMid, frame, ntn_test::released(release));
  s.settings.hinge_method = method;
  s.time_points = ntn_test::triangle_pulse(0.004);
  s.time_functions[0] = {0, 3};
  const double f = pulse ? 1.0 : 0.0;
  s.loads[0] = {kQuarter, ntn::kUz, -5e4 * f, 0};
  s.loads[1] = {kQuarter, ntn::kUy, 3e4 * f, 0};
  s.loads[2] = {kQuarter, ntn::kRx, 2e3 * f, 0};
  s.loads[3] = {kQuarter, ntn::kUx, 4e5 * f, 0};
  s.settings.dt = 0.9 * ntn_test::hinged_stable_step(s).dt_stable;
}

void build_portal(ntn::ModelSpec<kPortal>& s, std::uint8_t release) {
  s = {};
  ntn_test::FrameBuilder<kPortal> f(s);
  const int base_l = f.add_node({0, 0, 0}, ntn_test::kFixedAll);
  const int base_r = f.add_node({6, 0, 0}, ntn_test::kFixedAll);
  const int top_l = f.add_node({0, 0, 3});
  const int top_r = f.add_node({6, 0, 3});
  const int beam_start = f.add_node({0, 0, 3});
  constexpr ntn_test::Section kColumn = ntn_test::rectangle(0.2, 0.2);
  constexpr ntn_test::Section kGirder = ntn_test::rectangle(0.15, 0.3);
  f.add_member(base_l, top_l, 3, ntn_test::kSteel, kColumn, {1, 0, 0});
  f.add_member(base_r, top_r, 3, ntn_test::kSteel, kColumn, {1, 0, 0});
  f.add_member(beam_start, top_r, 4, ntn_test::kSteel, kGirder, {0, 0, 1});
  EXPECT_TRUE(f.complete());
  const ntn_test::Mat3 frame = ntn_test::member_frame({0, 0, 3}, {6, 0, 3}, {0, 0, 1});
  s.hinges[0] = ntn_test::hinge(beam_start, top_l, frame, ntn_test::released(release));
  s.settings.dt = 0.9 * ntn_test::hinged_stable_step(s).dt_stable;
}

// Free vibration from mode `i`'s shape: the modal coordinate phi_i^T M u(t) is a cosine at the
// discrete frequency; its zero crossings over ~30 periods give the frequency. Returns
// measured / omega_h - 1.
template <ntn::Sizes S>
double measured_frequency_error(Sim<S>& r, const ntn_test::Modes& m, Eigen::Index i) {
  r.state = {};
  double top = 0;
  for (Eigen::Index j = 0; j < m.shapes.rows(); ++j) {
    if (j % 6 < 3) top = std::max(top, std::abs(m.shapes(j, i)));
  }
  for (Eigen::Index j = 0; j < m.shapes.rows(); ++j)
    r.state.u[static_cast<std::size_t>(j)] = 1e-3 / top * m.shapes(j, i);
  const double dt = r.model.dt;
  const double omega_h = 2.0 / dt * std::asin(m.omega(i) * dt / 2.0);
  const auto steps = static_cast<long>(30.25 * 2 * kPi / omega_h / dt);
  ntn_test::ZeroCrossings zc(ntn_test::modal_coordinate(m, i, r.state.u.data()));
  {
    const ntn_test::EigenNoMalloc guard;
    EXPECT_EQ(ntn::start(r.model, r.state, r.scratch, {}), ntn::StepStatus::kOk);
    for (long n = 0; n < steps; ++n) {
      EXPECT_EQ(ntn::step(r.model, r.state, r.scratch, {}), ntn::StepStatus::kOk);
      zc.add(ntn_test::modal_coordinate(m, i, r.state.u.data()),
             static_cast<double>(r.state.tick) * dt, dt);
    }
  }
  EXPECT_GE(zc.count(), 50);  // 30 periods: 60 crossings for a single mode
  const double err = zc.omega() / omega_h - 1.0;
  std::printf("    mode %ld: omega %.6f rad/s, omega_h %.6f, measured %.6f (%d crossings): %+.2e\n",
              static_cast<long>(i + 1), m.omega(i), omega_h, zc.omega(), zc.count(), err);
  return err;
}

// The frequencies of a hinged structure differ from those of the same structure with the hinge
// rigid by far more than the tolerance (so the comparison can fail): the largest relative
// difference among the first `count` modes.
double release_effect(const ntn_test::Modes& hinged, const ntn_test::Modes& rigid, int count) {
  double d = 0;
  for (Eigen::Index i = 0; i < count; ++i)
    d = std::max(d, std::abs(hinged.omega(i) / rigid.omega(i) - 1.0));
  return d;
}

// Tolerance 0.1 %. A single mode advanced by central difference has the exact discrete
// phase, and the zero crossings resolve it to ~1e-8 over 30 periods (measured: at most 1.7e-8
// off omega_h), so what the test sees is whether the kernel integrates the constrained system: a
// wrong coupled mass (e.g. a diagonalized Schur complement) shifts the frequency and leaks energy
// into other modes (ntn_paper in the turned frame: 2 %). The 1e-6 bound below is this test's
// own, tighter, statement of the same, with margin over the measurement's resolution.
// ntn_paper in the turned frame is run and its figures printed, not asserted: it diagonalizes the
// hinge-frame mass (S 23, S 26), so it does not integrate this constrained system (see
// hinge_rotated_frame_test for how far its rigid directions drift).
constexpr double kIssueTolerance = 1e-3;
constexpr double kTight = 1e-6;

TEST(HingeRelease, BeamFrequenciesEqualTheExactlyReleasedStructure) {
  struct Case {
    const char* name;
    ntn_test::Mat3 frame;
    ntn::HingeMethod method;
    bool exact = true;  // false: reported only (ntn_paper in a turned frame, see below)
  };
  const ntn_test::Mat3 member = ntn_test::member_frame({0, 0, 0}, {1, 0, 0}, {0, 0, 1});
  const ntn_test::Mat3 turned =
      ntn_test::rotate_frame(member, ntn_test::rotation({1, 0, 0}, 30 * ntn_test::kDegree));
  for (const Case& c :
       {Case{"aligned, ntn_exact", member, ntn::HingeMethod::kNtnExact},
        Case{"aligned, ntn_paper", member, ntn::HingeMethod::kNtnPaper},
        Case{"turned 30 deg, ntn_exact", turned, ntn::HingeMethod::kNtnExact},
        Case{"turned 30 deg, ntn_paper", turned, ntn::HingeMethod::kNtnPaper, false}}) {
    build_beam(beam.spec, c.frame, kReleaseRy, c.method);
    build_beam(beam2.spec, c.frame, 0, c.method);
    const ntn_test::Modes m = ntn_test::constrained_modes(ntn::view(beam.spec));
    const ntn_test::Modes rigid = ntn_test::constrained_modes(ntn::view(beam2.spec));
    const double effect = release_effect(m, rigid, 4);
    std::printf("  beam, %s: release changes the first 4 frequencies by up to %.1f %%\n", c.name,
                100 * effect);
    EXPECT_GT(effect, 100 * kIssueTolerance);
    {
      const ntn_test::EigenNoMalloc guard;
      ASSERT_TRUE(ntn_test::init_model(beam.spec, beam.model).ok());
    }
    for (Eigen::Index i = 0; i < 4; ++i) {
      const double err = measured_frequency_error(beam, m, i);
      if (!c.exact) continue;
      EXPECT_LT(std::abs(err), kIssueTolerance) << c.name << " mode " << i + 1;
      EXPECT_LT(std::abs(err), kTight) << c.name << " mode " << i + 1;
    }
  }
}

TEST(HingeRelease, PortalFrequenciesEqualTheExactlyReleasedStructure) {
  build_portal(portal.spec, kReleaseRy);
  const ntn_test::Modes m = ntn_test::constrained_modes(ntn::view(portal.spec));
  static ntn::ModelSpec<kPortal> rigid_spec;
  build_portal(rigid_spec, 0);
  const double effect = release_effect(m, ntn_test::constrained_modes(ntn::view(rigid_spec)), 4);
  std::printf("  portal: release changes the first 4 frequencies by up to %.1f %%\n", 100 * effect);
  EXPECT_GT(effect, 100 * kIssueTolerance);
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(portal.spec, portal.model).ok());
  }
  for (Eigen::Index i = 0; i < 4; ++i) {
    const double err = measured_frequency_error(portal, m, i);
    EXPECT_LT(std::abs(err), kIssueTolerance) << "mode " << i + 1;
    EXPECT_LT(std::abs(err), kTight) << "mode " << i + 1;
  }
}

// The time history under a load pulse (4 ms triangle at the quarter point, in four directions)
// against the `penalty` method, whose rigid directions are springs k_p.
//
// 1. Both at the penalty model's step dt_p (0.9 of its stable step): the time discretization is
// the same, so what differs is the model. The penalty hinge yields by f / k_p where ntn_exact
// does not, an error O(k_struct / k_p): measured at k_p and at 10 k_p, the two differences must
// be in the ratio 10 within 20 % (first-order convergence of the penalty model to the
// constrained one, the truth here), and the difference at k_p = 1e3 x the element stiffness
// below 1e-3 of the peak displacement (measured 3.4e-4: the rotational penalty spring, 1e3 x
// 4 E I / l, against a half-beam's rotational stiffness ~ E I / (L / 2), gives ~1e-4).
// 2. ntn_exact at its own, ~50x larger, step dt against the penalty run (10 k_p): the
// difference is then central difference's discretization error for the short pulse at dt
// (~3 %; the same pulse on the uncut beam, which hinge_split_test shows is the rigid-hinge
// model to 1e-14, has the same order). It is reported; ntn_exact at dt / 2, dt / 4 ... dt / 16
// must approach the penalty history steadily (each halving at least 1.5x closer; second order is
// reached only once the pulse's highest modes have omega dt << 1) and end below 1e-3.
template <ntn::Sizes S>
double peak_of(const ntn::State<S>& s, double peak) {
  for (std::size_t j = 0; j < s.u.size(); ++j) {
    if (j % 6 < 3) peak = std::max(peak, std::abs(s.u[j]));
  }
  return peak;
}

constexpr int kRefinements = 5;  // ntn_exact at dt, dt / 2, ..., dt / 16

struct HistoryDifference {
  double same_step = 0;                    // max |u_exact - u_penalty| / peak, both at dt_p
  std::array<double, kRefinements> own{};  // ntn_exact at dt / 2^k (every m-th dt_p) vs penalty
};

Sim<kBeam> refined[kRefinements];

HistoryDifference compare_with_penalty(double kp, double kpr) {
  const ntn_test::Mat3 frame = ntn_test::member_frame({0, 0, 0}, {1, 0, 0}, {0, 0, 1});
  build_beam(beam.spec, frame, kReleaseRy, ntn::HingeMethod::kPenalty, true);
  beam.spec.settings.penalty_stiffness = kp;
  beam.spec.settings.penalty_rotational_stiffness = kpr;
  const double dt_p = 0.9 * ntn_test::hinged_stable_step(beam.spec).dt_stable;
  beam.spec.settings.dt = dt_p;
  build_beam(beam2.spec, frame, kReleaseRy, ntn::HingeMethod::kNtnExact, true);
  constexpr long kFine = 1L << (kRefinements - 1);
  // ntn_exact's own step, rounded down to a multiple of 16 dt_p
  const long ratio = kFine * static_cast<long>(beam2.spec.settings.dt / dt_p / kFine);
  EXPECT_GE(ratio, kFine);
  for (int k = 0; k < kRefinements; ++k) {
    refined[k].spec = beam2.spec;
    refined[k].spec.settings.dt = static_cast<double>(ratio >> k) * dt_p;
  }
  beam2.spec.settings.dt = dt_p;

  const double t_end = 0.1;  // s, three periods of the first mode
  const auto steps = static_cast<long>(t_end / dt_p);
  const ntn_test::EigenNoMalloc guard;
  auto begin = [](Sim<kBeam>& r) {
    EXPECT_TRUE(ntn_test::init_model(r.spec, r.model).ok());
    r.state = {};
    EXPECT_EQ(ntn::start(r.model, r.state, r.scratch, {}), ntn::StepStatus::kOk);
  };
  begin(beam), begin(beam2);
  for (Sim<kBeam>& r : refined)
    begin(r);
  auto max_diff = [](const ntn::State<kBeam>& a, const ntn::State<kBeam>& b, double& m) {
    for (std::size_t j = 0; j < a.u.size(); ++j) {
      if (j % 6 < 3) m = std::max(m, std::abs(a.u[j] - b.u[j]));
    }
  };
  double peak = 0, same = 0;
  std::array<double, kRefinements> own{};
  for (long n = 1; n <= steps; ++n) {
    EXPECT_EQ(ntn::step(beam.model, beam.state, beam.scratch, {}), ntn::StepStatus::kOk);
    EXPECT_EQ(ntn::step(beam2.model, beam2.state, beam2.scratch, {}), ntn::StepStatus::kOk);
    peak = peak_of(beam.state, peak);
    max_diff(beam.state, beam2.state, same);
    for (int k = 0; k < kRefinements; ++k) {
      if (n % (ratio >> k) != 0) continue;
      Sim<kBeam>& r = refined[k];
      EXPECT_EQ(ntn::step(r.model, r.state, r.scratch, {}), ntn::StepStatus::kOk);
      max_diff(beam.state, r.state, own[static_cast<std::size_t>(k)]);
    }
  }
  HistoryDifference out;
  out.same_step = same / peak;
  for (std::size_t k = 0; k < kRefinements; ++k)
    out.own[k] = own[k] / peak;
  std::printf(
      "  k_p %.2e N/m, %.2e N m/rad: dt_p %.3e s (%ld steps), peak %.3e m; max |difference| / "
      "peak %.3e at dt_p\n",
      kp, kpr, dt_p, steps, peak, out.same_step);
  std::printf("    ntn_exact at %.3e s / 1, 2, 4, 8, 16 vs penalty:", refined[0].model.dt);
  for (const double e : out.own)
    std::printf(" %.3e", e);
  std::printf("\n");
  return out;
}

TEST(HingeRelease, TimeHistoryAgreesWithPenalty) {
  // Element stiffness scales of this beam (l = 0.5 m): EA / l and 4 E Iy / l.
  const double l = kL / kN;
  const double axial = ntn_test::kSteel.E * kSection.A / l;
  const double bending = 4 * ntn_test::kSteel.E * kSection.Iy / l;
  const HistoryDifference a = compare_with_penalty(1e3 * axial, 1e3 * bending);
  const HistoryDifference b = compare_with_penalty(1e4 * axial, 1e4 * bending);
  const double order = a.same_step / b.same_step;
  std::printf("  same-step difference ratio k_p : 10 k_p = %.4f (first order: 10)\n", order);
  EXPECT_NEAR(order, 10.0, 2.0);
  EXPECT_LT(a.same_step, 1e-3);
  for (std::size_t k = 1; k < kRefinements; ++k)
    EXPECT_GT(b.own[k - 1], 1.5 * b.own[k]) << "refinement " << k;
  EXPECT_LT(b.own[kRefinements - 1], 1e-3);
}

}  // namespace hinge_release_test
