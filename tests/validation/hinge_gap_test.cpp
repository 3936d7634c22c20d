// Rigid branches of `curve` hinge directions (seed S 32-33,
// DESIGN §7.1): a gap hinge with 1 mm of play never opens further than 1 mm; the default,
// momentum-conserving clamp keeps a free-flying pair's linear momentum; and the seed's own clamp
// (clamp = "paper", S 33) gives the hand-computed numbers of equation 33.
//
// The gap: the curve (-1.1 mm, -1e9 N), (-1 mm, 0), (1 mm, 0), (1.1 mm, 1e9 N), whose outer
// segments (slope 1e13 N/m) are at least the limit stiffness 1e12 N/m: rigid branches beyond
// +-1 mm, no force inside.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ntn/kernel.hpp"
#include "support/assemble.hpp"
#include "support/builders.hpp"
#include "support/hinges.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"

namespace hinge_gap_test {

using ntn_test::dof;
using ntn_test::Mat3;
using B = ntn::HingeBehaviour;

constexpr double kPlay = 1e-3;  // m
constexpr std::array<ntn::CurvePoint, 4> kGap{
    {{-1.1e-3, -1e9}, {-kPlay, 0.0}, {kPlay, 0.0}, {1.1e-3, 1e9}}};

using ntn_test::Sim;

template <ntn::Sizes S>
void add_gap_curve(ntn::ModelSpec<S>& s) {
  s.curve_points = kGap;
  s.curves[0] = {0, 4};
  s.settings.limit_stiffness = 1e12;
  s.settings.limit_rotational_stiffness = 1e12;
}

const char* method_name(ntn::HingeMethod m, ntn::ClampRule c) {
  if (m == ntn::HingeMethod::kNtnPaper) return "ntn_paper (S 33)";
  if (m == ntn::HingeMethod::kPenalty)
    return c == ntn::ClampRule::kMomentum ? "penalty, momentum clamp" : "penalty, clamp paper";
  return c == ntn::ClampRule::kMomentum ? "ntn_exact, momentum clamp" : "ntn_exact, clamp paper";
}

// ---- 1. A clamped-clamped beam cut at midspan, the cut closed by a hinge with 1 mm of play
// across the beam (local uz, the curve) and rigid otherwise. A transverse pulse on the left half
// would open the cut by several mm (measured below with the play unlimited); the rigid branches
// must stop it at 1 mm. The relative displacement is recomputed from B (DESIGN §7) every step.
// Tolerance: the clamp puts d on the branch start to rounding of u (|u| ~ 1e-3 m, ulp ~ 2e-19),
// so |d| <= 1 mm + 1e-15 m.
constexpr int kN = 8, kMid = 4, kExtra = 9;
constexpr ntn::Sizes kBeam{.nodes = kN + 2,
                           .elements = kN,
                           .time_functions = 1,
                           .time_points = 3,
                           .loads = 2,
                           .hinges = 1,
                           .curves = 1,
                           .curve_points = 4};
Sim<kBeam> beam;

void build_beam(const Mat3& frame, ntn::HingeMethod method, ntn::ClampRule clamp, bool play) {
  ntn::ModelSpec<kBeam>& s = beam.spec;
  s = {};
  ntn_test::split_beam(s, 4.0, ntn_test::kSteel, ntn_test::rectangle(0.08, 0.12), kMid, kExtra,
                       ntn_test::kFixedAll, ntn_test::kFixedAll);
  s.hinges[0] = ntn_test::hinge(kExtra, kMid, frame);
  if (play) {
    s.hinges[0].behaviour[ntn::kUz] = B::kCurve;
    s.hinges[0].curve[ntn::kUz] = 0;
  } else {
    s.hinges[0].behaviour[ntn::kUz] = B::kFree;
  }
  add_gap_curve(s);
  s.settings.hinge_method = method;
  s.settings.clamp = clamp;
  s.settings.penalty_stiffness = 1e12;
  s.settings.penalty_rotational_stiffness = 1e10;
  s.time_points = ntn_test::triangle_pulse(0.01);
  s.time_functions[0] = {0, 3};
  s.loads[0] = {kMid - 1, ntn::kUz, 4e4, 0};
  s.loads[1] = {kMid - 1, ntn::kUy, 1e4, 0};
  const ntn::StableStepReport r = ntn_test::hinged_stable_step(s);
  const double exact = ntn_test::assembled_stable_step(
      ntn::view(s), method == ntn::HingeMethod::kPenalty ? s.settings.penalty_stiffness : 0,
      method == ntn::HingeMethod::kPenalty ? s.settings.penalty_rotational_stiffness : 0);
  s.settings.dt = 0.9 * std::min(r.dt_stable, exact);
}

// Max |d_L| in the gap direction over 0.2 s.
double max_opening() {
  const ntn::HingeSpec& h = beam.spec.hinges[0];
  const Eigen::MatrixXd Bm = ntn_test::hinge_b(ntn::view(beam.spec), h);
  const Eigen::Matrix<double, 6, 1> b1 = Bm.block<1, 6>(ntn::kUz, 6 * h.node1).transpose();
  const Eigen::Matrix<double, 6, 1> b2 = Bm.block<1, 6>(ntn::kUz, 6 * h.node2).transpose();
  double opening = 0;
  const ntn_test::EigenNoMalloc guard;
  EXPECT_TRUE(ntn_test::init_model(beam.spec, beam.model).ok());
  beam.state = {};
  EXPECT_EQ(ntn::start(beam.model, beam.state, beam.scratch, {}), ntn::StepStatus::kOk);
  const auto steps = static_cast<long>(0.2 / beam.model.dt);
  for (long n = 0; n < steps; ++n) {
    if (ntn::step(beam.model, beam.state, beam.scratch, {}) != ntn::StepStatus::kOk) {
      ADD_FAILURE() << "step " << n;
      break;
    }
    const double d =
        b1.dot(Eigen::Map<const Eigen::Matrix<double, 6, 1>>(&beam.state.u[6 * h.node1])) +
        b2.dot(Eigen::Map<const Eigen::Matrix<double, 6, 1>>(&beam.state.u[6 * h.node2]));
    opening = std::max(opening, std::abs(d));
  }
  return opening;
}

TEST(HingeGap, OpeningNeverExceedsThePlay) {
  const Mat3 aligned = ntn_test::kIdentity3;
  const Mat3 turned = ntn_test::rotate_frame(
      aligned, ntn_test::rotation({1, 0, 0}, 30 * ntn_test::kDegree));  // gap axis inclined
  build_beam(aligned, ntn::HingeMethod::kNtnExact, ntn::ClampRule::kMomentum, false);
  const double unlimited = max_opening();
  std::printf("  without the stops the cut opens %.3f mm\n", 1e3 * unlimited);
  EXPECT_GT(unlimited, 2 * kPlay);  // so the stops must act
  struct Case {
    ntn::HingeMethod method;
    ntn::ClampRule clamp;
    const Mat3* frame;
  };
  for (const Case& c : {Case{ntn::HingeMethod::kNtnExact, ntn::ClampRule::kMomentum, &aligned},
                        Case{ntn::HingeMethod::kNtnExact, ntn::ClampRule::kMomentum, &turned},
                        Case{ntn::HingeMethod::kNtnExact, ntn::ClampRule::kPaper, &aligned},
                        Case{ntn::HingeMethod::kNtnPaper, ntn::ClampRule::kPaper, &aligned},
                        Case{ntn::HingeMethod::kPenalty, ntn::ClampRule::kMomentum, &aligned}}) {
    build_beam(*c.frame, c.method, c.clamp, true);
    const double opening = max_opening();
    std::printf("  %s, %s frame: max |d| - 1 mm = %.2e m\n", method_name(c.method, c.clamp),
                c.frame == &aligned ? "global" : "turned", opening - kPlay);
    EXPECT_LE(opening, kPlay + 1e-15) << method_name(c.method, c.clamp);
    EXPECT_GT(opening, kPlay - 1e-9) << "the stop was reached";
  }
}

// ---- 2. A free-flying pair: two 1 m steel bars on one line, no supports, joined end to end by
// a hinge with 1 mm of axial play (local ux; free in every other direction, or rigid in them).
// Bar A flies at 1 m/s towards bar B at rest; they touch after 1 mm and keep hitting the stops.
// Linear momentum sum m v (over every node, each direction) is conserved by every force in the
// model and by the momentum clamp, which moves the pair about its mass-weighted centre. Tolerance
// 1e-12 of the initial momentum: the clamp's corrections du / dt cancel in m du to rounding
// (~1e-16 x |u| / dt per contact step). The seed's S 33 scales both absolute displacements, which
// moves the pair: its momentum change is printed, not asserted.
constexpr ntn::Sizes kPair{.nodes = 6, .elements = 4, .hinges = 1, .curves = 1, .curve_points = 4};
Sim<kPair> pair;

void build_pair(ntn::HingeMethod method, ntn::ClampRule clamp, bool rigid_others) {
  ntn::ModelSpec<kPair>& s = pair.spec;
  s = {};
  ntn_test::FrameBuilder<kPair> f(s);
  const int a0 = f.add_node({0, 0, 0});
  const int a1 = f.add_node({1, 0, 0});
  const int b0 = f.add_node({1, 0, 0});
  const int b1 = f.add_node({2, 0, 0});
  f.add_member(a0, a1, 2, ntn_test::kSteel, ntn_test::rectangle(0.05, 0.05), {0, 0, 1});
  f.add_member(b0, b1, 2, ntn_test::kSteel, ntn_test::rectangle(0.05, 0.08), {0, 0, 1});
  EXPECT_TRUE(f.complete());
  std::array<B, 6> b{};
  for (auto& x : b)
    x = rigid_others ? B::kRigid : B::kFree;
  b[ntn::kUx] = B::kCurve;
  s.hinges[0] = ntn_test::hinge(a1, b0, ntn_test::kIdentity3, b);
  s.hinges[0].curve[ntn::kUx] = 0;
  add_gap_curve(s);
  s.settings.hinge_method = method;
  s.settings.clamp = clamp;
  s.settings.penalty_stiffness = 1e11;
  s.settings.penalty_rotational_stiffness = 1e9;
  const double exact = ntn_test::assembled_stable_step(
      ntn::view(s), method == ntn::HingeMethod::kPenalty ? s.settings.penalty_stiffness : 0,
      method == ntn::HingeMethod::kPenalty ? s.settings.penalty_rotational_stiffness : 0);
  s.settings.dt = 0.9 * std::min(ntn_test::hinged_stable_step(s).dt_stable, exact);
}

struct Momentum {
  double drift = 0;    // max |p(t) - p0| / |p0| over the run, x direction
  double cross = 0;    // max |p_y|, |p_z| / |p0|
  double opening = 0;  // max |d_x| (m)
  int contacts = 0;    // steps on which the clamp acted (|d| at the stop)
};

Momentum fly() {
  ntn::State<kPair>& st = pair.state;
  st = {};
  for (int n = 0; n < 3; ++n)  // bar A: nodes 0, 1 and its middle node 4
    st.v[dof(n == 2 ? 4 : n, ntn::kUx)] = 1.0;
  auto momentum = [&](int d) {
    double p = 0;
    for (std::size_t n = 0; n < kPair.nodes; ++n)
      p += pair.model.mass[dof(n, d)] * st.v[dof(n, d)];
    return p;
  };
  Momentum out;
  const ntn_test::EigenNoMalloc guard;
  EXPECT_TRUE(ntn_test::init_model(pair.spec, pair.model).ok());
  const double p0 = momentum(ntn::kUx);
  EXPECT_EQ(ntn::start(pair.model, st, pair.scratch, {}), ntn::StepStatus::kOk);
  for (long n = 0; n < 20'000; ++n) {
    if (ntn::step(pair.model, st, pair.scratch, {}) != ntn::StepStatus::kOk) {
      ADD_FAILURE() << "step " << n;
      break;
    }
    // v is v_{n+1/2}: sum m v_{n+1/2} = sum m v_{n-1/2} + dt sum (forces) + clamp corrections.
    out.drift = std::max(out.drift, std::abs(momentum(ntn::kUx) - p0) / std::abs(p0));
    out.cross = std::max({out.cross, std::abs(momentum(ntn::kUy)) / std::abs(p0),
                          std::abs(momentum(ntn::kUz)) / std::abs(p0)});
    const double d = st.u[dof(2, ntn::kUx)] - st.u[dof(1, ntn::kUx)];
    out.opening = std::max(out.opening, std::abs(d));
    out.contacts += std::abs(d) >= kPlay * (1 - 1e-12) ? 1 : 0;
  }
  return out;
}

TEST(HingeGap, FreeFlyingPairKeepsItsMomentum) {
  struct Case {
    ntn::HingeMethod method;
    bool rigid_others;
  };
  for (const Case& c :
       {Case{ntn::HingeMethod::kNtnExact, false}, Case{ntn::HingeMethod::kNtnExact, true},
        Case{ntn::HingeMethod::kPenalty, false}, Case{ntn::HingeMethod::kPenalty, true}}) {
    build_pair(c.method, ntn::ClampRule::kMomentum, c.rigid_others);
    const Momentum m = fly();
    std::printf(
        "  %s, other directions %s: %d steps at a stop, max |d| - 1 mm = %.1e m, momentum drift "
        "%.2e, cross momentum %.2e\n",
        method_name(c.method, ntn::ClampRule::kMomentum), c.rigid_others ? "rigid" : "free",
        m.contacts, m.opening - kPlay, m.drift, m.cross);
    EXPECT_GT(m.contacts, 10);  // the bars do hit the stops
    EXPECT_LE(m.opening, kPlay + 1e-15);
    EXPECT_LT(m.drift, 1e-12);
    EXPECT_LT(m.cross, 1e-12);
  }
  // The seed's clamp on the same pair, reported.
  for (const ntn::HingeMethod method : {ntn::HingeMethod::kNtnExact, ntn::HingeMethod::kNtnPaper}) {
    build_pair(method, ntn::ClampRule::kPaper, false);
    const Momentum m = fly();
    std::printf("  %s: %d steps at a stop, momentum drift %.3e (reported, S 33 moves the pair)\n",
                method_name(method, ntn::ClampRule::kPaper), m.contacts, m.drift);
    RecordProperty(method == ntn::HingeMethod::kNtnPaper ? "ntn_paper_s33_momentum_drift"
                                                         : "clamp_paper_momentum_drift",
                   std::to_string(m.drift));
  }
}

// ---- 2b. The same in a rigid tree: bar A's end joins a joint node J (a 5 kg point mass) through
// the gap hinge (1 mm axial play, rigid in the other five directions), and bars B (along y) and C
// (along z) are joined rigidly to J through hinges in turned frames. A flies at 1 m/s along x
// (and everything at 0.3 m/s along y).
// When the stop acts, the whole tree J-B-C moves with J, so the clamp must correct with the
// constrained system's inverse mass (the forest's response to the pair of impulses along the
// gap direction), not the two nodes' own masses. Same tolerances as above.
constexpr ntn::Sizes kTree{.nodes = 10, .elements = 3, .hinges = 3, .curves = 1, .curve_points = 4};
Sim<kTree> tree;

TEST(HingeGap, FreeFlyingTreeKeepsItsMomentum) {
  for (const ntn::HingeMethod method : {ntn::HingeMethod::kNtnExact, ntn::HingeMethod::kPenalty}) {
    ntn::ModelSpec<kTree>& s = tree.spec;
    s = {};
    ntn_test::FrameBuilder<kTree> f(s);
    const int a0 = f.add_node({-1, 0, 0});
    const int a1 = f.add_node({0, 0, 0});
    const int joint = f.add_node({0, 0, 0});
    const int b0 = f.add_node({0, 0, 0});
    const int b1 = f.add_node({0, 1, 0});
    const int c0 = f.add_node({0, 0, 0});
    const int c1 = f.add_node({0, 0, 1});
    const ntn_test::Section sec = ntn_test::rectangle(0.05, 0.05);
    f.add_member(a0, a1, 1, ntn_test::kSteel, sec, {0, 0, 1});
    f.add_member(b0, b1, 1, ntn_test::kSteel, sec, {0, 0, 1});
    f.add_member(c0, c1, 1, ntn_test::kSteel, sec, {1, 0, 0});
    s.nodes[static_cast<std::size_t>(joint)].added = {5, 5, 5, 0.05, 0.05, 0.05};
    // Three unused nodes, held (no mass, no element): the sizes stay those of the other cases.
    for (int n = 7; n < 10; ++n)
      s.nodes[static_cast<std::size_t>(n)].fixed = ntn_test::kFixedAll;
    std::array<B, 6> gap = ntn_test::kAllRigid;
    gap[ntn::kUx] = B::kCurve;
    s.hinges[0] = ntn_test::hinge(a1, joint, ntn_test::kIdentity3, gap);
    s.hinges[0].curve[ntn::kUx] = 0;
    s.hinges[1] = ntn_test::hinge(
        b0, joint,
        ntn_test::rotate_frame(ntn_test::kIdentity3,
                               ntn_test::rotation({0, 1, 0}, 30 * ntn_test::kDegree)));
    s.hinges[2] = ntn_test::hinge(c0, joint, ntn_test::skewed_frame(ntn_test::kIdentity3));
    add_gap_curve(s);
    s.settings.hinge_method = method;
    s.settings.penalty_stiffness = 1e11;
    s.settings.penalty_rotational_stiffness = 1e9;
    const bool pen = method == ntn::HingeMethod::kPenalty;
    const double exact =
        ntn_test::assembled_stable_step(ntn::view(s), pen ? 1e11 : 0, pen ? 1e9 : 0);
    s.settings.dt = 0.9 * std::min(ntn_test::hinged_stable_step(s).dt_stable, exact);

    ntn::State<kTree>& st = tree.state;
    st = {};
    // A flies along the gap direction; the whole model drifts sideways: initial velocities that
    // the rigid directions allow (the run starts on the constraints).
    for (const int n : {a0, a1})
      st.v[dof(n, ntn::kUx)] = 1.0;
    for (int n = 0; n < 7; ++n)
      st.v[dof(n, ntn::kUy)] = 0.3;
    auto momentum = [&](int d) {
      double p = 0;
      for (std::size_t n = 0; n < kTree.nodes; ++n)
        p += tree.model.mass[dof(n, d)] * st.v[dof(n, d)];
      return p;
    };
    double drift = 0, opening = 0, vmax = 0;
    int contacts = 0;
    {
      const ntn_test::EigenNoMalloc guard;
      ASSERT_TRUE(ntn_test::init_model(s, tree.model).ok());
      const double p0[3] = {momentum(0), momentum(1), momentum(2)};
      ASSERT_EQ(ntn::start(tree.model, st, tree.scratch, {}), ntn::StepStatus::kOk);
      const auto steps = static_cast<long>(0.1 / tree.model.dt);
      for (long n = 0; n < steps; ++n) {
        ASSERT_EQ(ntn::step(tree.model, st, tree.scratch, {}), ntn::StepStatus::kOk);
        for (int d = 0; d < 3; ++d)
          drift = std::max(drift, std::abs(momentum(d) - p0[d]) / p0[0]);
        const double gap_d = st.u[dof(joint, ntn::kUx)] - st.u[dof(a1, ntn::kUx)];
        opening = std::max(opening, std::abs(gap_d));
        contacts += std::abs(gap_d) >= kPlay * (1 - 1e-12) ? 1 : 0;
        for (const double x : st.v)
          vmax = std::max(vmax, std::abs(x));
      }
    }
    std::printf(
        "  tree, %s: %d steps at a stop, max |d| - 1 mm = %.1e m, momentum drift %.2e, max |v| "
        "%.3f m/s\n",
        method_name(method, ntn::ClampRule::kMomentum), contacts, opening - kPlay, drift, vmax);
    EXPECT_GT(contacts, 10);
    EXPECT_LE(opening, kPlay + 1e-15);
    EXPECT_LT(drift, 1e-12);
  }
}

// ---- 3. Equation 33 by hand. Two bars (A: nodes 0-1, B: nodes 2-3, one element each), no loads,
// each displaced as a rigid body (so no element force), a hinge between nodes 1 and 2 whose frame
// is the global one turned 90 degrees about z (local x = global y, local y = -global x), gap in
// local x. A's nodes: u = (0.3, 0.5, 0) mm; B's: u = (0.7, 2.5, 0) mm. In the hinge frame
// U_L^1 = (0.5, -0.3, 0) mm, U_L^2 = (2.5, -0.7, 0) mm, so d = 2 mm in local x, past d_lim = 1 mm.
// One step with no force leaves u as it is; then S 33 scales local x of both nodes by
// d_lim / d = 1/2: U_L^1(x) = 0.25 mm, U_L^2(x) = 1.25 mm, i.e. u_y(1) = 0.25 mm, u_y(2) =
// 1.25 mm, everything else unchanged. S 35-37 with v_{-1/2} = 0: v_{1/2} = du / dt, a_0 = du /
// dt^2. The momentum clamp instead moves both nodes by 0.5 mm towards each other (equal masses):
// u_y(1) = 1.0 mm, u_y(2) = 2.0 mm. Tolerance: a few ulps of 1e-3 m (1e-18 m).
constexpr ntn::Sizes kTwo{.nodes = 4, .elements = 2, .hinges = 1, .curves = 1, .curve_points = 4};
Sim<kTwo> two;

void build_two(ntn::HingeMethod method, ntn::ClampRule clamp) {
  ntn::ModelSpec<kTwo>& s = two.spec;
  s = {};
  for (int n = 0; n < 4; ++n) {
    s.nodes[static_cast<std::size_t>(n)].x = static_cast<double>(n < 2 ? n : n - 1);
  }
  const ntn_test::Section sec = ntn_test::rectangle(0.05, 0.05);
  s.elements[0] = ntn_test::element(0, 1, ntn_test::kSteel, sec, {0, 0, 1});
  s.elements[1] = ntn_test::element(2, 3, ntn_test::kSteel, sec, {0, 0, 1});
  std::array<B, 6> b{};
  for (auto& x : b)
    x = B::kFree;
  b[ntn::kUx] = B::kCurve;
  s.hinges[0] = ntn_test::hinge(1, 2, {0, 1, 0, -1, 0, 0, 0, 0, 1}, b);
  s.hinges[0].curve[ntn::kUx] = 0;
  add_gap_curve(s);
  s.settings.hinge_method = method;
  s.settings.clamp = clamp;
  s.settings.dt = 1e-5;
}

TEST(HingeGap, Equation33ByHand) {
  struct Case {
    ntn::HingeMethod method;
    ntn::ClampRule clamp;
    double u1, u2;  // expected u_y of nodes 1 and 2 after the step, m
  };
  for (const Case& c :
       {Case{ntn::HingeMethod::kNtnExact, ntn::ClampRule::kPaper, 0.25e-3, 1.25e-3},
        Case{ntn::HingeMethod::kPenalty, ntn::ClampRule::kPaper, 0.25e-3, 1.25e-3},
        Case{ntn::HingeMethod::kNtnPaper, ntn::ClampRule::kPaper, 0.25e-3, 1.25e-3},
        Case{ntn::HingeMethod::kNtnPaper, ntn::ClampRule::kMomentum, 0.25e-3,
             1.25e-3},  // ntn_paper always uses S 33
        Case{ntn::HingeMethod::kNtnExact, ntn::ClampRule::kMomentum, 1.0e-3, 2.0e-3}}) {
    const char* name = method_name(c.method, c.clamp);
    build_two(c.method, c.clamp);
    ntn::State<kTwo>& st = two.state;
    st = {};
    for (int n = 0; n < 4; ++n) {
      st.u[dof(n, ntn::kUx)] = n < 2 ? 0.3e-3 : 0.7e-3;
      st.u[dof(n, ntn::kUy)] = n < 2 ? 0.5e-3 : 2.5e-3;
    }
    {
      const ntn_test::EigenNoMalloc guard;
      ASSERT_TRUE(ntn_test::init_model(two.spec, two.model).ok()) << name;
      ASSERT_EQ(ntn::start(two.model, st, two.scratch, {}), ntn::StepStatus::kOk);
      ASSERT_EQ(ntn::step(two.model, st, two.scratch, {}), ntn::StepStatus::kOk);
    }
    const double dt = two.spec.settings.dt;
    constexpr double kUlps = 1e-18;  // m
    EXPECT_NEAR(st.u[dof(1, ntn::kUy)], c.u1, kUlps) << name;
    EXPECT_NEAR(st.u[dof(2, ntn::kUy)], c.u2, kUlps) << name;
    EXPECT_NEAR(st.u[dof(2, ntn::kUy)] - st.u[dof(1, ntn::kUy)], kPlay, kUlps) << name;
    // Untouched: local y of both nodes (global x), the outer nodes, every other DOF.
    EXPECT_EQ(st.u[dof(1, ntn::kUx)], 0.3e-3) << name;
    EXPECT_EQ(st.u[dof(2, ntn::kUx)], 0.7e-3) << name;
    EXPECT_EQ(st.u[dof(0, ntn::kUy)], 0.5e-3) << name;
    EXPECT_EQ(st.u[dof(3, ntn::kUy)], 2.5e-3) << name;
    // S 35-37: the velocity and acceleration of the moved DOFs follow the move.
    EXPECT_NEAR(st.v[dof(1, ntn::kUy)] * dt, c.u1 - 0.5e-3, kUlps) << name;
    EXPECT_NEAR(st.v[dof(2, ntn::kUy)] * dt, c.u2 - 2.5e-3, kUlps) << name;
    EXPECT_NEAR(two.scratch.a[dof(1, ntn::kUy)] * dt * dt, c.u1 - 0.5e-3, kUlps) << name;
    EXPECT_EQ(st.v[dof(0, ntn::kUy)], 0.0) << name;
  }
}

}  // namespace hinge_gap_test
