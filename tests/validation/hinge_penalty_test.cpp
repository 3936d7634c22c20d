// ntn_exact against the `penalty` method on the three shapes the
// seed's algorithm cannot take: a star joint (four members, four different hinge frames on one
// node), a chain of hinges (a tree two levels deep), and an eccentric rigid hinge.
//
// Truth and tolerance. The penalty model is the same structure with each rigid direction a
// spring k_p (K = B^T K_p B, DESIGN §7); as k_p grows it converges to the constrained structure
// that ntn_exact integrates, at first order: its rigid directions yield by d = f / k_p, and the
// response differs by the effect of those slips. Both methods run at the penalty model's (small)
// stable step, so the time discretization is identical and only the model differs. The test
// measures the penalty run's own slips, s = max |d_rigid| (rotations times the members' length,
// to compare displacements), relative to the peak displacement, and requires
//   - the history difference at k_p to be at most 10 s (the slips f / k_p, propagated through the
//     structure with a dynamic amplification of order one; 10 leaves room for that),
//   - the difference at 10 k_p to be ten times smaller, within 25 % (first order in 1 / k_p:
//     ntn_exact is the limit the penalty model converges to, not merely close to it),
//   - and the difference at k_p below 1e-3 of the peak (the "agrees").
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ntn/kernel.hpp"
#include "support/assemble.hpp"
#include "support/builders.hpp"
#include "support/hinged_models.hpp"
#include "support/hinges.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"

namespace hinge_penalty_test {

using ntn_test::Mat3;
using ntn_test::Vec3;
using B = ntn::HingeBehaviour;

constexpr ntn_test::Section kMember = ntn_test::rectangle(0.08, 0.12);
constexpr ntn_test::Section kColumn = ntn_test::rectangle(0.15, 0.15);

using ntn_test::Sim;

// A triangle pulse (time function 0) at node n in all six directions, scaled by f.
template <ntn::Sizes S>
void pulse_at(ntn::ModelSpec<S>& s, int first_load, int n, double f) {
  const double load[6] = {3e4, -2e4, 2.5e4, 1e3, -1.5e3, 2e3};
  for (int d = 0; d < 6; ++d)
    s.loads[static_cast<std::size_t>(first_load + d)] = {n, d, f * load[d], 0};
}

// ---- Star joint (support/hinged_models.hpp): four members, four hinge frames on one node, with
// a pulse at the joint (node 0) and at the middle of member 1 (node 3).
constexpr ntn::Sizes kStar =
    ntn_test::star_joint_sizes({.time_functions = 1, .time_points = 3, .loads = 12});

void build_star(ntn::ModelSpec<kStar>& s) {
  EXPECT_TRUE(ntn_test::star_joint(s, kMember));
  s.time_points = ntn_test::triangle_pulse(0.004);
  s.time_functions[0] = {0, 3};
  pulse_at(s, 0, 0, 1.0);
  pulse_at(s, 6, 3, -0.5);
}

// ---- Chain (support/hinged_models.hpp): B (node 2) is the root, D hangs two hinges below it;
// a pulse at A (node 1, the left beam's end at the hinges) and at the plate B.
constexpr ntn::Sizes kChain =
    ntn_test::hinge_chain_sizes({.time_functions = 1, .time_points = 3, .loads = 12});

void build_chain(ntn::ModelSpec<kChain>& s) {
  EXPECT_TRUE(ntn_test::hinge_chain(s, kMember));
  s.time_points = ntn_test::triangle_pulse(0.004);
  s.time_functions[0] = {0, 3};
  pulse_at(s, 0, 1, 1.0);
  pulse_at(s, 6, 2, -0.7);
}

// ---- Eccentric rigid hinge: a beam whose end A sits 0.15 m above and 0.1 m beside the column
// top C it is rigidly connected to (e = x_C - x_A), as where a beam meets a column face. Column
// 3 m (3 elements) clamped at its base, beam 3 m (3 elements) clamped at its far end.
constexpr ntn::Sizes kEccentric{
    .nodes = 8, .elements = 6, .time_functions = 1, .time_points = 3, .loads = 12, .hinges = 1};

void build_eccentric(ntn::ModelSpec<kEccentric>& s) {
  s = {};
  ntn_test::FrameBuilder<kEccentric> f(s);
  const int base = f.add_node({0, 0, -3}, ntn_test::kFixedAll);
  const int top = f.add_node({0, 0, 0});
  const int a = f.add_node({0, 0.1, 0.15});
  const int far = f.add_node({3, 0.1, 0.15}, ntn_test::kFixedAll);
  f.add_member(base, top, 3, ntn_test::kSteel, kColumn, {1, 0, 0});
  f.add_member(a, far, 3, ntn_test::kSteel, kMember, {0, 0, 1});
  EXPECT_TRUE(f.complete());
  s.hinges[0] =
      ntn_test::hinge(a, top, ntn_test::kIdentity3, ntn_test::kAllRigid, {0.0, -0.1, -0.15});
  s.time_points = ntn_test::triangle_pulse(0.004);
  s.time_functions[0] = {0, 3};
  pulse_at(s, 0, top, 1.0);
  pulse_at(s, 6, 6, 0.5);  // the beam's first inner node
}

struct Comparison {
  double difference = 0;  // max |u_exact - u_penalty| over translations / peak
  double slip = 0;        // penalty's max rigid |d| (rotations x length) / peak
  double peak = 0;
  long steps = 0;
};

// Runs penalty (stiffness kp, kpr) and ntn_exact at the penalty model's step over t_end.
template <ntn::Sizes S>
Comparison compare(Sim<S>& pen, Sim<S>& ex, void (*build)(ntn::ModelSpec<S>&), double kp,
                   double kpr, double length, double t_end) {
  build(pen.spec);
  pen.spec.settings.hinge_method = ntn::HingeMethod::kPenalty;
  pen.spec.settings.penalty_stiffness = kp;
  pen.spec.settings.penalty_rotational_stiffness = kpr;
  // 0.9 of the kernel's stable step, as dt = "auto" takes it. That step is a strict bound
  // (time_step.hpp; a per-spring estimate was 1.26-1.47x too large at these joints, and a run at
  // 0.9 of it diverged): checked against the exact stable step of the assembled penalty system
  // (1e-9: rounding of the eigenvalue solvers), and how conservative it is is printed.
  const double bound = ntn_test::hinged_stable_step(pen.spec).dt_stable;
  const double exact_step = ntn_test::assembled_stable_step(ntn::view(pen.spec), kp, kpr);
  std::printf("    stable step: kernel %.4e s, exact (assembled) %.4e s, kernel / exact %.4f\n",
              bound, exact_step, bound / exact_step);
  EXPECT_LE(bound, exact_step * (1 + 1e-9));
  pen.spec.settings.dt = 0.9 * bound;
  build(ex.spec);
  ex.spec.settings.hinge_method = ntn::HingeMethod::kNtnExact;
  ex.spec.settings.dt = pen.spec.settings.dt;
  // B of each hinge, node-1 and node-2 columns, for the penalty run's slips.
  Eigen::Matrix<double, 6, 6> b1[S.hinges], b2[S.hinges];
  for (std::size_t h = 0; h < S.hinges; ++h) {
    const ntn::HingeSpec& hs = pen.spec.hinges[h];
    const Eigen::MatrixXd Bh = ntn_test::hinge_b(ntn::view(pen.spec), hs);
    b1[h] = Bh.block<6, 6>(0, 6 * hs.node1);
    b2[h] = Bh.block<6, 6>(0, 6 * hs.node2);
  }
  Comparison out;
  out.steps = static_cast<long>(t_end / pen.spec.settings.dt);
  const ntn_test::EigenNoMalloc guard;
  for (Sim<S>* r : {&pen, &ex}) {
    EXPECT_TRUE(ntn_test::init_model(r->spec, r->model).ok());
    r->state = {};
    EXPECT_EQ(ntn::start(r->model, r->state, r->scratch, {}), ntn::StepStatus::kOk);
  }
  double diff = 0, slip = 0;
  for (long n = 0; n < out.steps; ++n) {
    if (ntn::step(pen.model, pen.state, pen.scratch, {}) != ntn::StepStatus::kOk ||
        ntn::step(ex.model, ex.state, ex.scratch, {}) != ntn::StepStatus::kOk) {
      ADD_FAILURE() << "step " << n << " did not return kOk";
      break;
    }
    for (std::size_t j = 0; j < pen.state.u.size(); ++j) {
      if (j % 6 >= 3) continue;
      out.peak = std::max(out.peak, std::abs(pen.state.u[j]));
      diff = std::max(diff, std::abs(pen.state.u[j] - ex.state.u[j]));
    }
    for (std::size_t h = 0; h < S.hinges; ++h) {
      const ntn::HingeSpec& hs = pen.spec.hinges[h];
      const Eigen::Map<const Eigen::Matrix<double, 6, 1>> u1(&pen.state.u[6 * hs.node1]);
      const Eigen::Map<const Eigen::Matrix<double, 6, 1>> u2(&pen.state.u[6 * hs.node2]);
      const Eigen::Matrix<double, 6, 1> d = b1[h] * u1 + b2[h] * u2;
      for (std::size_t k = 0; k < 6; ++k) {
        if (hs.behaviour[k] != B::kRigid) continue;
        slip = std::max(slip, std::abs(d(static_cast<Eigen::Index>(k))) * (k < 3 ? 1 : length));
      }
    }
  }
  out.difference = diff / out.peak;
  out.slip = slip / out.peak;
  std::printf(
      "    k_p %.2e N/m, %.2e N m/rad: dt %.3e s, %ld steps, peak %.3e m; penalty slip / peak "
      "%.3e, max |u_exact - u_penalty| / peak %.3e\n",
      kp, kpr, pen.spec.settings.dt, out.steps, out.peak, out.slip, out.difference);
  return out;
}

template <ntn::Sizes S>
void check_against_penalty(const char* name, void (*build)(ntn::ModelSpec<S>&), double length,
                           double t_end) {
  static Sim<S> pen, ex;
  // Penalty stiffness 1e3 x the members' axial EA / l and bending 4 E I / l (l = 1 m).
  const double axial = ntn_test::kSteel.E * kMember.A;
  const double bending = 4 * ntn_test::kSteel.E * kMember.Iy;
  std::printf("  %s:\n", name);
  const Comparison a = compare(pen, ex, build, 1e3 * axial, 1e3 * bending, length, t_end);
  const Comparison b = compare(pen, ex, build, 1e4 * axial, 1e4 * bending, length, t_end);
  EXPECT_GT(a.peak, 1e-5) << name;
  EXPECT_LT(a.difference, 10 * a.slip) << name;
  EXPECT_LT(a.difference, 1e-3) << name;
  const double order = a.difference / b.difference;
  std::printf("    difference ratio k_p : 10 k_p = %.3f (first order: 10)\n", order);
  EXPECT_NEAR(order, 10.0, 2.5) << name;
}

TEST(HingePenalty, StarJointWithFourFrames) {
  check_against_penalty<kStar>("star joint", build_star, 2.0, 0.05);
}

TEST(HingePenalty, ChainOfHinges) {
  // The forest is two levels deep: some edge's parent is itself a child.
  static Sim<kChain> r;
  build_chain(r.spec);
  r.spec.settings.dt = 0.9 * ntn_test::hinged_stable_step(r.spec).dt_stable;
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(r.spec, r.model).ok());
  }
  ASSERT_EQ(r.model.num_edges, 3);
  ASSERT_EQ(r.model.num_roots, 1);
  EXPECT_EQ(r.model.roots[0].node, 2);  // B
  bool deep = false;
  for (int k = 0; k < r.model.num_edges; ++k) {
    for (int j = 0; j < r.model.num_edges; ++j)
      deep |= r.model.edges[static_cast<std::size_t>(k)].parent ==
              r.model.edges[static_cast<std::size_t>(j)].child;
  }
  EXPECT_TRUE(deep);
  check_against_penalty<kChain>("chain", build_chain, 2.0, 0.05);
}

TEST(HingePenalty, EccentricRigidHinge) {
  check_against_penalty<kEccentric>("eccentric rigid hinge", build_eccentric, 3.0, 0.05);
}

}  // namespace hinge_penalty_test
