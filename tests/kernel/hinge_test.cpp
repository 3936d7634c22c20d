// hinge.hpp alone (DESIGN §7, seed S 11-16): the kernel's hinge geometry on hand-made hinges and
// node vectors, without a model or a step, against truth written elsewhere:
// - hinge_relative, hinge_direction and hinge_scatter against B of ntn_test::hinge_b (dense, from
//   the equations d_L = T [u2 - u1 - phi1 x e ; phi2 - phi1], in assemble.cpp) and against each
//   other (a row of B, B u, B^T f: virtual work f_L . d_L = f . x);
// - check_axes against R R^T - I and det R worked out by hand for a one-entry perturbation;
// - curve_branches and curve_force on curves whose segments' slopes are chosen here;
// - hinge_inverse_mass against b^T M^-1 b summed densely;
// - bilinear_update (hysteresis.hpp) along a deformation path worked out by hand.
// Each test states its tolerance and why.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <span>
#include <vector>

#include "ntn/hinge.hpp"
#include "ntn/hysteresis.hpp"
#include "support/assemble.hpp"
#include "support/hinges.hpp"

namespace hinge_test {

using ntn_test::Mat3;

// A frame turned about two axes: a skew member's frame (x along (3, 1, 2)), turned 30 degrees
// about its x axis and 20 degrees about the turned z axis. No entry is 0 or 1.
Mat3 hg_frame() {
  return ntn_test::skewed_frame(ntn_test::member_frame({0, 0, 0}, {3, 1, 2}, {0, 0, 1}));
}

constexpr ntn_test::Vec3 kHgEccentricity{0.4, -1.3, 2.1};  // m, |e| = 2.50
constexpr int kHgNodes = 3;

// The kernel's HingeData of a spec (resolve_hinge: also checks the frame and the ground rule).
ntn::HingeData hg_data(const ntn::HingeSpec& spec) {
  ntn::HingeData h;
  const std::array<ntn::CurveSpec, 0> no_curves{};
  const std::array<ntn::CurvePoint, 0> no_points{};
  EXPECT_TRUE(ntn::resolve_hinge(
      spec, ntn::Settings{}, kHgNodes, no_curves, no_points, h, [](std::size_t) { return true; },
      [](std::size_t) { return false; }));
  return h;
}

// The two hinges of the tests: node 2 to node 0, turned and eccentric (node order reversed so that
// a column mix-up shows), and node 1 to the ground, turned, centric (the only ground hinge the
// kernel accepts).
ntn::HingeSpec hg_eccentric() {
  return ntn_test::hinge(2, 0, hg_frame(), ntn_test::kAllRigid, kHgEccentricity);
}
ntn::HingeSpec hg_ground() {
  return ntn_test::hinge(1, ntn::kGround, hg_frame());
}

// hinge_b needs only the node count of the spec.
Eigen::MatrixXd hg_dense_b(const ntn::HingeSpec& spec) {
  static const std::array<ntn::NodeSpec, kHgNodes> nodes{};
  ntn::SpecView v;
  v.nodes = nodes;
  return ntn_test::hinge_b(v, spec);
}

// Random displacements, rotations and forces of order 1 (fixed seed).
Eigen::VectorXd hg_random(std::mt19937_64& rng, Eigen::Index n) {
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i)
    x(i) = dist(rng);
  return x;
}

const double* hg_node(const Eigen::VectorXd& u, int node) {
  return node == ntn::kGround ? nullptr : u.data() + ntn::kDofsPerNode * node;
}

// max(1, |e|): the scale of B's entries (T and T E), m.
double hg_scale(const ntn::HingeSpec& s) {
  const auto& e = s.eccentricity;
  return std::max(1.0, std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]));
}

// Tolerance of the geometry tests: 1e-13 |u| max(1, |e|). d_L sums a handful of products of
// order |u| |e| in a different order than Eigen's B u, each rounding by 1e-16 relative; 1e-13
// leaves three orders of margin, while a wrong sign, lever arm or node column is of order |u|.
double hg_tol(const ntn::HingeSpec& s, const Eigen::VectorXd& u) {
  return 1e-13 * u.norm() * hg_scale(s);
}

TEST(HingeGeometry, RelativeDisplacementIsBTimesU) {
  std::mt19937_64 rng(20240611);
  for (const ntn::HingeSpec& spec : {hg_eccentric(), hg_ground()}) {
    const ntn::HingeData h = hg_data(spec);
    const Eigen::MatrixXd B = hg_dense_b(spec);
    for (int trial = 0; trial < 8; ++trial) {
      const Eigen::VectorXd u = hg_random(rng, B.cols());
      const Eigen::VectorXd want = B * u;
      double d[6];
      ntn::hinge_relative(h, hg_node(u, h.node1), hg_node(u, h.node2), d);
      for (int k = 0; k < 6; ++k)
        EXPECT_NEAR(d[k], want(k), hg_tol(spec, u)) << "node2 " << h.node2 << " direction " << k;
    }
  }
}

// Rows of B: d_k = b1 . x1 + b2 . x2 equals hinge_relative's d[k], and (b1, b2) is row k of the
// dense B in node 1's and node 2's columns (zero elsewhere; for the ground, b2 is not used). Same
// tolerance as above. The HingeData overload is the frame-and-eccentricity one: bit for bit.
TEST(HingeGeometry, DirectionIsARowOfB) {
  std::mt19937_64 rng(7);
  for (const ntn::HingeSpec& spec : {hg_eccentric(), hg_ground()}) {
    const ntn::HingeData h = hg_data(spec);
    const Eigen::MatrixXd B = hg_dense_b(spec);
    const Eigen::VectorXd u = hg_random(rng, B.cols());
    const double* x1 = hg_node(u, h.node1);
    const double* x2 = hg_node(u, h.node2);
    double d[6];
    ntn::hinge_relative(h, x1, x2, d);
    for (std::size_t k = 0; k < 6; ++k) {
      double b1[6], b2[6], c1[6], c2[6];
      ntn::hinge_direction(h, k, b1, b2);
      ntn::hinge_direction(spec.frame, spec.eccentricity, k, c1, c2);
      Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(B.cols());
      double dk = 0;
      for (int c = 0; c < 6; ++c) {
        EXPECT_EQ(b1[c], c1[c]);
        EXPECT_EQ(b2[c], c2[c]);
        row(ntn::kDofsPerNode * h.node1 + c) += b1[c];
        dk += b1[c] * x1[c];
        if (x2 != nullptr) {
          row(ntn::kDofsPerNode * h.node2 + c) += b2[c];
          dk += b2[c] * x2[c];
        }
      }
      const auto kk = static_cast<Eigen::Index>(k);
      EXPECT_LE((row - B.row(kk)).cwiseAbs().maxCoeff(), 1e-13 * hg_scale(spec)) << k;
      EXPECT_NEAR(dk, d[k], hg_tol(spec, u)) << "node2 " << h.node2 << " direction " << k;
    }
  }
}

// hinge_scatter adds B^T f_L: the virtual work of f_L on d_L = B x equals that of the scattered
// nodal forces on x, f_L . d_L = f1 . x1 + f2 . x2, and both equal f_L . (B x) with the dense B.
// Tolerance 1e-13 |f_L| |x| max(1, |e|): the same sums of products as above, once more.
TEST(HingeGeometry, ScatterIsTheAdjointOfRelative) {
  std::mt19937_64 rng(99);
  for (const ntn::HingeSpec& spec : {hg_eccentric(), hg_ground()}) {
    const ntn::HingeData h = hg_data(spec);
    const Eigen::MatrixXd B = hg_dense_b(spec);
    for (int trial = 0; trial < 8; ++trial) {
      const Eigen::VectorXd x = hg_random(rng, B.cols());
      const Eigen::VectorXd fl = hg_random(rng, 6);
      Eigen::VectorXd f = Eigen::VectorXd::Zero(B.cols());
      double* f2 = h.node2 == ntn::kGround ? nullptr : f.data() + ntn::kDofsPerNode * h.node2;
      ntn::hinge_scatter(h, fl.data(), f.data() + ntn::kDofsPerNode * h.node1, f2);
      double d[6];
      ntn::hinge_relative(h, hg_node(x, h.node1), hg_node(x, h.node2), d);
      const double work_local = fl.dot(Eigen::Map<const Eigen::VectorXd>(d, 6));
      const double tol = hg_tol(spec, x) * fl.norm();
      EXPECT_NEAR(work_local, f.dot(x), tol);
      EXPECT_NEAR(work_local, fl.dot(B * x), tol);
      EXPECT_LE((f - B.transpose() * fl).cwiseAbs().maxCoeff(), tol);
    }
  }
}

// check_axes against R R^T - I worked out by hand. Identity with R[1] = delta: row 0 . row 1 =
// delta exactly, (R R^T)_00 - 1 = delta^2, so `worst` is delta bit for bit and det R = 1. With
// R[0] = 1 + delta: worst = 2 delta + delta^2, det = 1 + delta, to a few roundings of numbers near
// 1 (1e-15 absolute). A rotated frame's entries come from sines and cosines: worst within 1e-15
// of 0 and det within 1e-15 of +1 (their rounding), and its perturbation by delta at (a, j) gives
// worst = max(|2 delta R_aj + delta^2|, delta max_b!=a |R_bj|) to the same 1e-15.
TEST(HingeGeometry, AxesCheckReportsTheDeviationAndTheHandedness) {
  const ntn::AxesCheck id = ntn::check_axes(ntn_test::kIdentity3);
  EXPECT_TRUE(id.ok());
  EXPECT_EQ(id.worst, 0.0);
  EXPECT_EQ(id.det, 1.0);

  const Mat3 R = hg_frame();
  const ntn::AxesCheck turned = ntn::check_axes(R);
  EXPECT_TRUE(turned.ok());
  EXPECT_LE(turned.worst, 1e-15);
  EXPECT_NEAR(turned.det, 1.0, 1e-15);

  // A reflection (row y negated): orthonormal, det = -1, refused.
  Mat3 mirror = R;
  for (std::size_t c = 3; c < 6; ++c)
    mirror[c] = -mirror[c];
  const ntn::AxesCheck m = ntn::check_axes(mirror);
  EXPECT_TRUE(m.orthonormal);
  EXPECT_FALSE(m.right_handed);
  EXPECT_FALSE(m.ok());
  EXPECT_NEAR(m.det, -1.0, 1e-15);

  // Off-diagonal entry of the identity: worst == delta exactly, on both sides of the tolerance.
  for (const double delta : {1e-7, 1.1 * ntn::kAxesTolerance, 0.9 * ntn::kAxesTolerance, 1e-12}) {
    Mat3 p = ntn_test::kIdentity3;
    p[1] = delta;
    const ntn::AxesCheck c = ntn::check_axes(p);
    EXPECT_EQ(c.worst, delta);
    EXPECT_EQ(c.det, 1.0);
    EXPECT_EQ(c.ok(), delta < ntn::kAxesTolerance) << delta;
  }
  // Diagonal entry of the identity, and an entry of the turned frame.
  for (const double delta : {1e-7, 1e-12}) {
    Mat3 p = ntn_test::kIdentity3;
    p[0] = 1.0 + delta;
    const ntn::AxesCheck c = ntn::check_axes(p);
    EXPECT_NEAR(c.worst, 2 * delta + delta * delta, 1e-15);
    EXPECT_NEAR(c.det, 1.0 + delta, 1e-15);
    EXPECT_EQ(c.ok(), delta < 1e-9) << delta;

    const std::size_t a = 1, j = 2;  // entry (y axis, global z)
    Mat3 q = R;
    q[3 * a + j] += delta;
    double want = std::abs(2 * delta * R[3 * a + j] + delta * delta);
    for (std::size_t b = 0; b < 3; ++b)
      if (b != a) want = std::max(want, delta * std::abs(R[3 * b + j]));
    const ntn::AxesCheck t = ntn::check_axes(q);
    EXPECT_NEAR(t.worst, want, 1e-15);
    EXPECT_EQ(t.ok(), delta < 1e-9) << delta;
  }

  // A NaN entry: passed over by `worst` (the other entries of the identity are exact) but refused.
  Mat3 nan = ntn_test::kIdentity3;
  nan[4] = std::numeric_limits<double>::quiet_NaN();
  const ntn::AxesCheck n = ntn::check_axes(nan);
  EXPECT_EQ(n.worst, 0.0);
  EXPECT_FALSE(n.orthonormal);
  EXPECT_FALSE(n.ok());
}

// Curves with slopes chosen here, k_lim = 1e4 N/m; a segment is rigid when its slope is >= k_lim.
// The points are looked up from c.first (curves share one point array). Branch starts are point
// abscissas, so they are compared bit for bit; the steepest spring slope is one division of
// exact differences (1e-15 relative).
TEST(HingeGeometry, CurveBranchesSplitRigidEndsFromTheSpringPart) {
  constexpr double kLim = 1e4;
  // Point 0 is padding (part of no curve). Points 1-5, steep ends (slopes 49000, 1000, 2000,
  // 49000): rigid branches below -0.1 and above 0.1. Points 6-9, all soft (slopes 100, 9999.5,
  // -50: softening too): no branch. Points 10-14, soft, steep (exactly k_lim: rigid), steep,
  // soft: invalid, decided by segment 1.
  const std::vector<ntn::CurvePoint> pts{{9, 9},          {-0.2, -5000}, {-0.1, -100}, {0.0, 0.0},
                                         {0.1, 200},      {0.2, 5100},   {-1, -100},   {0, 0},
                                         {0.002, 19.999}, {1, -29.901},  {0, 0},       {1, 10},
                                         {2, 10010},      {3, 30010},    {4, 30020}};
  const std::span<const ntn::CurvePoint> span(pts);

  const ntn::CurveBranches ends = ntn::curve_branches(span, {1, 5}, kLim);
  EXPECT_TRUE(ends.valid);
  EXPECT_EQ(ends.lower, -0.1);
  EXPECT_EQ(ends.upper, 0.1);
  EXPECT_EQ(ends.first, 1);
  EXPECT_EQ(ends.last, 2);
  EXPECT_EQ(ends.inner, -1);
  EXPECT_NEAR(ends.max_slope, 2000, 2000 * 1e-15);

  const ntn::CurveBranches soft = ntn::curve_branches(span, {6, 4}, kLim);
  EXPECT_TRUE(soft.valid);
  EXPECT_EQ(soft.lower, -1e300);
  EXPECT_EQ(soft.upper, 1e300);
  EXPECT_EQ(soft.first, 0);
  EXPECT_EQ(soft.last, 2);
  EXPECT_NEAR(soft.max_slope, 9999.5, 9999.5 * 1e-12);  // 19.999 / 0.002: inexact decimals

  const ntn::CurveBranches inner = ntn::curve_branches(span, {10, 5}, kLim);
  EXPECT_FALSE(inner.valid);
  EXPECT_EQ(inner.inner, 1);
  EXPECT_EQ(inner.first, 0);

  // Only a lower branch; and a curve rigid throughout (no spring segment at all).
  const ntn::CurveBranches lower = ntn::curve_branches(span, {1, 4}, kLim);
  EXPECT_TRUE(lower.valid);
  EXPECT_EQ(lower.lower, -0.1);
  EXPECT_EQ(lower.upper, 1e300);
  const ntn::CurveBranches rigid = ntn::curve_branches(span, {11, 3}, kLim);
  EXPECT_FALSE(rigid.valid);
  EXPECT_EQ(rigid.first, -1);
}

// curve_force: linear inside each segment, the end segments extended beyond the end points.
// Values worked out by hand on (0, 0), (1, 10), (3, 14); 1e-14 relative: one interpolation of
// numbers of order 10.
TEST(HingeGeometry, CurveForceInterpolatesAndExtrapolatesTheEnds) {
  const std::array<ntn::CurvePoint, 3> p{{{0, 0}, {1, 10}, {3, 14}}};
  const std::array<std::array<double, 2>, 7> cases{
      {{-1, -10}, {0, 0}, {0.5, 5}, {1, 10}, {2, 12}, {3, 14}, {5, 18}}};
  for (const auto& [d, want] : cases)
    EXPECT_NEAR(ntn::curve_force(p.data(), 3, d), want, 1e-14 * 18) << d;
  // Two points: one segment, extrapolated both ways.
  EXPECT_NEAR(ntn::curve_force(p.data(), 2, -2.0), -20.0, 1e-14 * 20);
  EXPECT_NEAR(ntn::curve_force(p.data(), 2, 4.0), 40.0, 1e-14 * 40);
}

// b^T M^-1 b with diagonal masses, summed densely over row k of B (Eigen), different in every
// DOF (0.5..6.5 kg, kg m^2). 1e-14 relative: a sum of at most 12 positive terms, in another
// order. A zero mass under a non-zero entry of b is an infinitely fast mode: +inf; under a zero
// entry it is not seen.
TEST(HingeGeometry, InverseMassIsBTransposeMInverseB) {
  std::array<double, 6 * kHgNodes> mass{};
  for (std::size_t i = 0; i < mass.size(); ++i)
    mass[i] = 0.5 + static_cast<double>((5 * i + 3) % 13) / 2.0;
  for (const ntn::HingeSpec& spec : {hg_eccentric(), hg_ground()}) {
    const ntn::HingeData h = hg_data(spec);
    const Eigen::MatrixXd B = hg_dense_b(spec);
    const Eigen::Map<const Eigen::VectorXd> m(mass.data(), static_cast<Eigen::Index>(mass.size()));
    const double* m1 = mass.data() + 6 * h.node1;
    const double* m2 = h.node2 == ntn::kGround ? nullptr : mass.data() + 6 * h.node2;
    for (std::size_t k = 0; k < 6; ++k) {
      const auto row = B.row(static_cast<Eigen::Index>(k));
      const double want = (row.array().square() / m.transpose().array()).sum();
      EXPECT_NEAR(ntn::hinge_inverse_mass(h, k, m1, m2), want, 1e-14 * want) << k;
    }
  }
  // Turned hinge: every b entry of the rotation is non-zero, so a zero rotational mass is +inf.
  std::array<double, 6 * kHgNodes> zero = mass;
  const ntn::HingeData h = hg_data(hg_eccentric());
  zero[6 * 2 + 3] = 0;  // node 1 of the hinge is node 2: its rx
  EXPECT_EQ(ntn::hinge_inverse_mass(h, 3, zero.data() + 12, zero.data()),
            std::numeric_limits<double>::infinity());
  // Aligned centric hinge, direction x: b = (-1, 0, ...; 1, 0, ...); a zero mass in uy is unseen.
  const ntn::HingeData a = hg_data(ntn_test::hinge(0, 1, ntn_test::kIdentity3));
  zero = mass;
  zero[1] = 0;
  EXPECT_EQ(ntn::hinge_inverse_mass(a, 0, zero.data(), zero.data() + 6),
            1.0 / mass[0] + 1.0 / mass[6]);
}

// The return mapping along a path worked out by hand: k = 100, yield 10 (positive) and 5
// (negative), b = 0.2, so H = b k / (1 - b) = 25 and k + H = 125.
//   d = 0.05: trial k d = 5 inside [-5, 10]: elastic, d_p = 0.
//   d = 0.2: trial 20 exceeds 10 by 10: d_p = 10 / 125 = 0.08, f = k (d - d_p) = 12 = H d_p + 10
//     (on the edge); plastic work = integral_0^0.08 (10 + 25 x) dx = 0.8 + 0.08 = 0.88.
//   d = 0.1: trial relative to q: 100 (0.1 - 0.08) - 25 0.08 = 0: elastic.
//   d = 0: trial -8 - 2 = -10 is 5 below -5: d_p = 0.08 - 5 / 125 = 0.04, f = -4 = H d_p - 5;
//     work = integral_0.08^0.04 (25 x - 5) dx = 0.14 (positive: force and flow both negative).
//   d = 0.04: trial 0 - 1 = -1: elastic (a reversal inside the range).
// 1e-15 relative to numbers of order 1: a handful of roundings.
TEST(Hysteresis, ReturnMappingFollowsAHandComputedPath) {
  const ntn::HysteresisData h = ntn::make_hysteresis({10.0, 5.0, 0.2}, 100.0);
  EXPECT_NEAR(h.H, 25.0, 1e-14);
  double dp = 0, w = 0, peak = 0;
  struct Step {
    double d, dp, f, work;
  };
  for (const Step& s :
       {Step{0.05, 0.0, 5.0, 0.0}, Step{0.2, 0.08, 12.0, 0.88}, Step{0.1, 0.08, 2.0, 0.88},
        Step{0.0, 0.04, -4.0, 1.02}, Step{0.04, 0.04, 0.0, 1.02}}) {
    ntn::bilinear_update(h, s.d, dp, w, peak);
    EXPECT_NEAR(dp, s.dp, 1e-15) << "d = " << s.d;
    EXPECT_NEAR(100.0 * (s.d - dp), s.f, 1e-13) << "d = " << s.d;
    EXPECT_NEAR(w, s.work, 1e-15) << "d = " << s.d;
  }
  EXPECT_NEAR(peak, 0.08, 1e-15);  // the largest |d_p| on the path
  // Perfectly plastic (b = 0): the force is clipped to the yields, the work is yield x flow.
  const ntn::HysteresisData p = ntn::make_hysteresis({10.0, 5.0, 0.0}, 100.0);
  dp = 0, w = 0, peak = 0;
  ntn::bilinear_update(p, 0.3, dp, w, peak);  // trial 30: d_p = 0.2, f = 10, work 10 x 0.2
  EXPECT_NEAR(dp, 0.2, 1e-15);
  EXPECT_NEAR(w, 2.0, 1e-14);
  ntn::bilinear_update(p, -0.1, dp, w,
                       peak);  // trial -30: d_p = 0.2 - 0.25, f = -5, work 5 x 0.25
  EXPECT_NEAR(dp, -0.05, 1e-15);
  EXPECT_NEAR(w, 3.25, 1e-14);
  EXPECT_NEAR(peak, 0.2, 1e-15);  // |d_p| went 0.2, then 0.05
}

}  // namespace hinge_test
