// Unit tests of the frame element (kernel/include/ntn/beam.hpp): local frame conventions,
// stiffness symmetry and rigid-body null space, on-the-fly force against the stored matrix, HRZ
// lumped mass against the consistent mass it comes from, and closed-form cantilever solutions
// (Euler-Bernoulli and Timoshenko).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <random>

#include "ntn/kernel.hpp"
#include "support/assemble.hpp"
#include "support/builders.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"
#include "support/relaxation.hpp"
#include "support/signed_order.hpp"

namespace beam_test {

using Mat12 = Eigen::Matrix<double, 12, 12, Eigen::RowMajor>;
using Vec12 = Eigen::Matrix<double, 12, 1>;
using ntn_test::Vec3;

Mat12 to_eigen(const ntn::Matrix12& k) {
  return Eigen::Map<const Mat12>(k.data());
}

ntn::NodeSpec node_at(double x, double y, double z) {
  ntn::NodeSpec n;
  n.x = x, n.y = y, n.z = z;
  return n;
}

Eigen::Matrix3d rotation_of(const ntn::BeamGeometry& g) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(g.rotation.data());
}

ntn::BeamData beam_data(const ntn::NodeSpec& a, const ntn::NodeSpec& b, const ntn::ElementSpec& e) {
  const ntn::BeamGeometry g = ntn::beam_geometry(a, b, e);
  ntn::BeamData d;
  d.rotation = g.rotation;
  d.k = ntn::beam_stiffness(e, g.length);
  return d;
}

const ntn_test::Section kRect = ntn_test::rectangle(0.05, 0.02);
const ntn_test::Section kThick = ntn_test::rectangle(0.1, 0.2, /*timoshenko=*/true);

// Conventions (DESIGN §3): local x from node i to node j; local z in the plane of x and the
// orientation vector, on its side; y = z x x; (x, y, z) orthonormal and right-handed. Exact
// geometry, so tolerances are rounding (1e-15).
TEST(BeamGeometry, MemberAlongXWithReferenceZIsTheGlobalFrame) {
  const ntn::ElementSpec e = ntn_test::element(0, 1, ntn_test::kSteel, kRect, {0, 0, 1});
  const ntn::BeamGeometry g = ntn::beam_geometry(node_at(1, 2, 3), node_at(3.5, 2, 3), e);
  ASSERT_EQ(g.check, ntn::ElementCheck::kOk);
  EXPECT_DOUBLE_EQ(g.length, 2.5);
  EXPECT_TRUE(rotation_of(g).isApprox(Eigen::Matrix3d::Identity(), 1e-15));
}

TEST(BeamGeometry, VerticalColumnWithReferenceX) {
  // x = +z; z = +x (the reference); y = z x x = x_g x z_g = -y_g.
  const ntn::ElementSpec e = ntn_test::element(0, 1, ntn_test::kSteel, kRect, {1, 0, 0});
  const ntn::BeamGeometry g = ntn::beam_geometry(node_at(0, 0, 0), node_at(0, 0, 3), e);
  ASSERT_EQ(g.check, ntn::ElementCheck::kOk);
  Eigen::Matrix3d expected;
  expected << 0, 0, 1, 0, -1, 0, 1, 0, 0;
  EXPECT_TRUE(rotation_of(g).isApprox(expected, 1e-15));
}

TEST(BeamGeometry, GeneralOrientationIsRightHandedWithZTowardsTheReference) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const ntn::NodeSpec a = node_at(u(rng), u(rng), u(rng)), b = node_at(u(rng), u(rng), u(rng));
    const Vec3 ref{u(rng), u(rng), u(rng)};
    const ntn::ElementSpec e = ntn_test::element(0, 1, ntn_test::kSteel, kRect, ref);
    const ntn::BeamGeometry g = ntn::beam_geometry(a, b, e);
    ASSERT_EQ(g.check, ntn::ElementCheck::kOk);
    const Eigen::Matrix3d R = rotation_of(g);
    const Eigen::Vector3d x = R.row(0), y = R.row(1), z = R.row(2);
    const Eigen::Vector3d d(b.x - a.x, b.y - a.y, b.z - a.z), r(ref[0], ref[1], ref[2]);
    EXPECT_NEAR(g.length, d.norm(), 1e-15 * d.norm());
    EXPECT_TRUE(x.isApprox(d / d.norm(), 1e-14));
    EXPECT_TRUE((R * R.transpose()).isApprox(Eigen::Matrix3d::Identity(), 1e-14));
    EXPECT_NEAR(R.determinant(), 1.0, 1e-14);      // right-handed
    EXPECT_TRUE(y.isApprox(z.cross(x), 1e-14));    // y = z x x
    EXPECT_NEAR(y.dot(r), 0.0, 1e-14 * r.norm());  // z lies in plane(x, ref)...
    EXPECT_GT(z.dot(r), 0.0);                      // ...on the reference's side
  }
}

TEST(BeamGeometry, DegenerateInputsAreReported) {
  const ntn::ElementSpec along = ntn_test::element(0, 1, ntn_test::kSteel, kRect, {2, 0, 0});
  EXPECT_EQ(ntn::beam_geometry(node_at(0, 0, 0), node_at(1, 0, 0), along).check,
            ntn::ElementCheck::kOrientationParallel);
  const ntn::ElementSpec zero_ref = ntn_test::element(0, 1, ntn_test::kSteel, kRect, {0, 0, 0});
  EXPECT_EQ(ntn::beam_geometry(node_at(0, 0, 0), node_at(1, 0, 0), zero_ref).check,
            ntn::ElementCheck::kOrientationParallel);
  const ntn::ElementSpec ok = ntn_test::element(0, 1, ntn_test::kSteel, kRect, {0, 0, 1});
  EXPECT_EQ(ntn::beam_geometry(node_at(1, 1, 1), node_at(1, 1, 1), ok).check,
            ntn::ElementCheck::kZeroLength);
}

// K_L is symmetric, positive semi-definite of rank 6, and its null space is exactly the six
// rigid-body motions: three translations and three small rotations about node i, where node j
// moves by theta x (l, 0, 0). Tolerances: rounding relative to the largest entry (1e-12; entries
// span ~1e6 between axial and bending terms).
void check_local_stiffness(const ntn::ElementSpec& e, double l) {
  const Mat12 K = to_eigen(ntn::beam_local_stiffness(ntn::beam_stiffness(e, l)));
  const double kmax = K.cwiseAbs().maxCoeff();
  EXPECT_LT((K - K.transpose()).cwiseAbs().maxCoeff(), 1e-15 * kmax);
  for (int mode = 0; mode < 6; ++mode) {
    Vec12 d = Vec12::Zero();
    if (mode < 3) {
      d(mode) = d(6 + mode) = 1.0;  // translation
    } else {
      Eigen::Vector3d th = Eigen::Vector3d::Zero();
      th(mode - 3) = 1.0;  // rotation about node i
      const Eigen::Vector3d uj = th.cross(Eigen::Vector3d(l, 0, 0));
      d.segment<3>(3) = th, d.segment<3>(6) = uj, d.segment<3>(9) = th;
    }
    EXPECT_LT((K * d).cwiseAbs().maxCoeff(), 1e-12 * kmax * d.cwiseAbs().maxCoeff())
        << "rigid mode " << mode;
  }
  const Eigen::SelfAdjointEigenSolver<Mat12> eig(K);
  int zero = 0;
  for (int i = 0; i < 12; ++i) {
    EXPECT_GT(eig.eigenvalues()(i), -1e-12 * kmax);
    if (eig.eigenvalues()(i) < 1e-12 * kmax) ++zero;
  }
  EXPECT_EQ(zero, 6);
}

TEST(BeamStiffness, LocalMatrixIsSymmetricWithRigidBodyNullSpace) {
  check_local_stiffness(ntn_test::element(0, 1, ntn_test::kSteel, kRect, {0, 0, 1}), 0.1);
  check_local_stiffness(ntn_test::element(0, 1, ntn_test::kSteel, kRect, {0, 0, 1}), 3.0);
  check_local_stiffness(ntn_test::element(0, 1, ntn_test::kSteel, kThick, {0, 0, 1}), 0.3);
}

// In global axes, for an arbitrarily oriented element: u = t + theta x (x_node - x_i) and
// rotations theta give no force. Same rounding tolerance.
TEST(BeamStiffness, GlobalMatrixHasRigidBodyNullSpaceForAnyOrientation) {
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    const ntn::NodeSpec a = node_at(u(rng), u(rng), u(rng)), b = node_at(u(rng), u(rng), u(rng));
    const ntn::ElementSpec e = ntn_test::element(0, 1, ntn_test::kSteel, trial % 2 ? kThick : kRect,
                                                 {u(rng), u(rng), u(rng)});
    const Mat12 K = to_eigen(ntn::beam_global_stiffness(beam_data(a, b, e)));
    const double kmax = K.cwiseAbs().maxCoeff();
    EXPECT_LT((K - K.transpose()).cwiseAbs().maxCoeff(), 1e-14 * kmax);
    const Eigen::Vector3d t(u(rng), u(rng), u(rng)), th(u(rng), u(rng), u(rng));
    const Eigen::Vector3d ab(b.x - a.x, b.y - a.y, b.z - a.z);
    Vec12 d;
    d << t, th, t + th.cross(ab), th;
    EXPECT_LT((K * d).cwiseAbs().maxCoeff(), 1e-12 * kmax * d.cwiseAbs().maxCoeff());
  }
}

// The force step() applies on the fly, f = T^T K_L T u, equals the stored 12x12 product (same
// arithmetic in another order: rounding, 1e-13 of |K| |u|).
TEST(BeamForce, OnTheFlyEqualsStoredGlobalMatrix) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    const ntn::NodeSpec a = node_at(u(rng), u(rng), u(rng)), b = node_at(u(rng), u(rng), u(rng));
    const ntn::ElementSpec e = ntn_test::element(0, 1, ntn_test::kSteel, trial % 2 ? kThick : kRect,
                                                 {u(rng), u(rng), u(rng)});
    const ntn::BeamData data = beam_data(a, b, e);
    const Mat12 K = to_eigen(ntn::beam_global_stiffness(data));
    Vec12 d;
    for (int i = 0; i < 12; ++i)
      d(i) = 1e-3 * u(rng);
    Vec12 f;
    ntn::beam_force(data, d.data(), d.data() + 6, f.data(), f.data() + 6);
    const double scale = K.cwiseAbs().maxCoeff() * d.cwiseAbs().maxCoeff();
    EXPECT_LT((f - K * d).cwiseAbs().maxCoeff(), 1e-13 * scale);
    // The local end forces are in equilibrium: forces sum to zero, and so do moments about
    // node i (M_i + M_j + (l, 0, 0) x F_j = 0).
    const auto fl = ntn::beam_local_end_forces(data, d.data(), d.data() + 6);
    const double l = ntn::beam_geometry(a, b, e).length;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(fl[static_cast<std::size_t>(c)] + fl[static_cast<std::size_t>(6 + c)], 0.0,
                  1e-12 * scale);
    EXPECT_NEAR(fl[3] + fl[9], 0.0, 1e-12 * scale);
    EXPECT_NEAR(fl[4] + fl[10] - l * fl[8], 0.0, 1e-12 * scale);
    EXPECT_NEAR(fl[5] + fl[11] + l * fl[7], 0.0, 1e-12 * scale);
  }
}

// The 48 signed orders of the axes, zeros all +0.0 or all -0.0.
std::array<double, 9> signed_order(int which, bool negative_zeros) {
  return ntn_test::signed_order(static_cast<std::size_t>(which),
                                [&](std::size_t) { return negative_zeros ? -0.0 : 0.0; });
}

// An aligned element (beam.hpp, AxisMap) rotates by picks: the map reads each of the 48 signed
// orders back, any other rotation is general, and the picks equal the full products as values
// (a product by 0 adds a zero: only the sign of a zero result can differ).
TEST(AxisMap, SignedOrdersArePicksOfTheFullProducts) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> x(-1, 1);
  for (int which = 0; which < 48; ++which) {
    for (const bool nz : {false, true}) {
      const auto R = signed_order(which, nz);
      const ntn::AxisMap m = ntn::axis_map(R);
      ASSERT_NE(m, ntn::kGeneralAxes) << which;
      for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(R[3 * k + ntn::axis_of(m, k)], ntn::axis_negated(m, k) ? -1.0 : 1.0);
      }
      for (int trial = 0; trial < 20; ++trial) {
        const double g[3] = {x(rng), trial % 4 == 0 ? 0.0 : x(rng), x(rng)};
        double full[3], picked[3], back_full[3], back_picked[3];
        ntn::rotate_to_local(R, g, full);
        ntn::beam_to_local(m, R, g, picked);
        ntn::rotate_to_global(R, g, back_full);
        ntn::beam_to_global(m, R, g, back_picked);
        for (int c = 0; c < 3; ++c) {
          EXPECT_EQ(full[c], picked[c]);
          EXPECT_EQ(back_full[c], back_picked[c]);
        }
      }
    }
  }
  // Not a signed order: general.
  EXPECT_EQ(ntn::axis_map({0.6, 0.0, -0.8, 0.0, 1.0, 0.0, 0.8, 0.0, 0.6}), ntn::kGeneralAxes);
  EXPECT_EQ(ntn::axis_map({1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0}), ntn::kGeneralAxes);
  EXPECT_EQ(ntn::axis_map({1.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0}), ntn::kGeneralAxes);
  EXPECT_EQ(ntn::axis_map({1.0, 0.0, 0.0, 0.0, 1.0 + 1e-16 * 2.3, 0.0, 0.0, 0.0, 1.0}),
            ntn::kGeneralAxes);
  EXPECT_EQ(ntn::axis_map({}), ntn::kGeneralAxes);
  // Members of a building frame: along x, y and z with their usual orientation vectors.
  const ntn::ElementSpec along_x = ntn_test::element(0, 1, ntn_test::kSteel, kRect, {0, 0, 1});
  const ntn::ElementSpec column = ntn_test::element(0, 1, ntn_test::kSteel, kRect, {1, 0, 0});
  EXPECT_NE(ntn::axis_map(ntn::beam_geometry(node_at(0, 0, 3), node_at(6, 0, 3), along_x).rotation),
            ntn::kGeneralAxes);
  EXPECT_NE(ntn::axis_map(ntn::beam_geometry(node_at(0, 6, 3), node_at(0, 0, 3), along_x).rotation),
            ntn::kGeneralAxes);
  EXPECT_NE(
      ntn::axis_map(ntn::beam_geometry(node_at(2, 1, 0), node_at(2, 1, 3.5), column).rotation),
      ntn::kGeneralAxes);
  EXPECT_EQ(
      ntn::axis_map(ntn::beam_geometry(node_at(0, 0, 0), node_at(6, 0, 3.5), column).rotation),
      ntn::kGeneralAxes);
}

// right_handed() is the sign of the determinant: +1 for 24 of the 48 signed orders (the rotations),
// -1 for their mirror images; beam_geometry's frames (y = z x x) are all right-handed; and
// aligned_axes() codes each map axis_map() reads.
TEST(AxisMap, RightHandedIsAPositiveDeterminant) {
  int right = 0;
  for (int which = 0; which < 48; ++which) {
    const auto R = signed_order(which, which % 2 == 0);
    const double det = R[0] * (R[4] * R[8] - R[5] * R[7]) - R[1] * (R[3] * R[8] - R[5] * R[6]) +
                       R[2] * (R[3] * R[7] - R[4] * R[6]);
    ASSERT_EQ(std::abs(det), 1.0) << which;
    const ntn::AxisMap m = ntn::axis_map(R);
    EXPECT_EQ(ntn::right_handed(m), det > 0) << which;
    EXPECT_EQ(ntn::aligned_axes(ntn::axis_of(m, 0), ntn::axis_of(m, 1), ntn::negated_axes(m)), m);
    right += det > 0 ? 1 : 0;
  }
  EXPECT_EQ(right, 24);
  const ntn::ElementSpec beam = ntn_test::element(0, 1, ntn_test::kSteel, kRect, {0, 0, 1});
  const ntn::ElementSpec column = ntn_test::element(0, 1, ntn_test::kSteel, kRect, {1, 0, 0});
  const ntn::NodeSpec ends[][2] = {{node_at(0, 0, 3), node_at(6, 0, 3)},
                                   {node_at(6, 0, 3), node_at(0, 0, 3)},
                                   {node_at(0, 0, 3), node_at(0, 6, 3)},
                                   {node_at(0, 6, 3), node_at(0, 0, 3)}};
  for (const auto& end : ends) {
    const ntn::AxisMap m = ntn::axis_map(ntn::beam_geometry(end[0], end[1], beam).rotation);
    ASSERT_NE(m, ntn::kGeneralAxes);
    EXPECT_TRUE(ntn::right_handed(m));
  }
  for (const double top : {3.5, -3.5}) {
    const ntn::AxisMap m =
        ntn::axis_map(ntn::beam_geometry(node_at(2, 1, 0), node_at(2, 1, top), column).rotation);
    ASSERT_NE(m, ntn::kGeneralAxes);
    EXPECT_TRUE(ntn::right_handed(m));
  }
}

// The element force of an aligned element by picks equals the full products' as values, for
// every signed order, Euler-Bernoulli and Timoshenko (the same operations on the same values).
TEST(AxisMap, AlignedForceEqualsTheFullProductsAsValues) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int which = 0; which < 48; ++which) {
    ntn::BeamData b =
        beam_data(node_at(0, 0, 0), node_at(2.5, 0, 0),
                  ntn_test::element(0, 1, ntn_test::kSteel, which % 2 ? kThick : kRect, {0, 0, 1}));
    b.rotation = signed_order(which, which % 3 == 0);
    ntn::BeamData general = b;
    b.axes = ntn::axis_map(b.rotation);
    ASSERT_NE(b.axes, ntn::kGeneralAxes);
    for (int trial = 0; trial < 10; ++trial) {
      double d[12], f[12], g[12];
      for (double& x : d)
        x = trial == 0 ? 0.0 : 1e-3 * u(rng);
      ntn::beam_force(b, d, d + 6, f, f + 6);
      ntn::beam_force(general, d, d + 6, g, g + 6);
      for (int c = 0; c < 12; ++c)
        EXPECT_EQ(f[c], g[c]) << which << ", DOF " << c;
    }
  }
}

// HRZ lumping (Hinton, Rock, Zienkiewicz 1976): keep the diagonal of the consistent mass and
// scale it so the translational diagonal sums to the element's mass. The consistent bending
// mass (rho A l / 420)[156, 4 l^2, ...] gives translations rho A l / 2 and bending rotations
// (4 l^2 / 420) rho A l (420 / 312) = rho A l^3 / 78; the consistent torsion mass
// rho I_p l / 3 on the diagonal, scaled the same way, gives rho I_p l / 2. Computed here from
// the consistent matrix, compared to 1e-15.
TEST(BeamMass, HrzEndMassComesFromTheConsistentMass) {
  const ntn::ElementSpec e = ntn_test::element(0, 1, ntn_test::kSteel, kRect, {0, 0, 1});
  const double l = 0.7;
  const ntn::BeamGeometry g = ntn::beam_geometry(node_at(0, 0, 0), node_at(l, 0, 0), e);
  const double mass = e.rho * e.A * l;
  const double translational_diagonal_sum = 2 * 156.0 / 420.0 * mass;  // w_i, w_j of one plane
  const double scale = mass / translational_diagonal_sum;
  const double bend = 4.0 * l * l / 420.0 * mass * scale;
  const double torsion = e.rho * (e.Iy + e.Iz) * l / 3.0 * 1.5;  // (1/3 diagonal) x (3/2)
  const auto m = ntn::beam_end_mass(e, g, /*rotary_inertia=*/false);
  EXPECT_NEAR(m[0], mass / 2, 1e-15 * mass);
  EXPECT_NEAR(m[1], 156.0 / 420.0 * mass * scale, 1e-15 * mass);
  EXPECT_NEAR(m[2], mass / 2, 1e-15 * mass);
  EXPECT_NEAR(m[3], torsion, 1e-15 * torsion);
  EXPECT_NEAR(m[4], bend, 1e-15 * bend);
  EXPECT_NEAR(m[5], bend, 1e-15 * bend);
  EXPECT_NEAR(bend, e.rho * e.A * l * l * l / 78.0, 1e-15 * bend);
  // Rotary inertia of the section (DESIGN §4): + rho I l / 2 about the same local axis.
  const auto mr = ntn::beam_end_mass(e, g, /*rotary_inertia=*/true);
  EXPECT_NEAR(mr[4] - m[4], e.rho * e.Iy * l / 2, 1e-12 * mr[4]);
  EXPECT_NEAR(mr[5] - m[5], e.rho * e.Iz * l / 2, 1e-12 * mr[5]);
}

// For an inclined member the rotational masses are the diagonal of R^T D R (beam.hpp): the trace
// (sum of the three) is kept and translations are unchanged.
TEST(BeamMass, InclinedMemberKeepsTotalsAndTrace) {
  const ntn::ElementSpec e = ntn_test::element(0, 1, ntn_test::kSteel, kRect, {0.3, -0.2, 1});
  const ntn::BeamGeometry g = ntn::beam_geometry(node_at(0, 0, 0), node_at(0.4, 0.8, -0.5), e);
  const ntn::ElementSpec ea = ntn_test::element(0, 1, ntn_test::kSteel, kRect, {0, 0, 1});
  const ntn::BeamGeometry ga = ntn::beam_geometry(node_at(0, 0, 0), node_at(g.length, 0, 0), ea);
  const auto m = ntn::beam_end_mass(e, g, true), ma = ntn::beam_end_mass(ea, ga, true);
  for (int d = 0; d < 3; ++d)
    EXPECT_DOUBLE_EQ(m[static_cast<std::size_t>(d)], ma[static_cast<std::size_t>(d)]);
  EXPECT_NEAR(m[3] + m[4] + m[5], ma[3] + ma[4] + ma[5], 1e-14 * (ma[3] + ma[4] + ma[5]));
}

// One-element cantilever, Euler-Bernoulli: the cubic element is exact for end loads, so the
// tip displacements equal the closed forms P L^3 / 3EI, P L^2 / 2EI, N L / EA, T L / GJ to
// rounding (tolerance 1e-10) in both bending planes, also for an element along a skew axis.
TEST(BeamStiffness, OneElementCantileverMatchesClosedForms) {
  constexpr ntn::Sizes S{.nodes = 2, .elements = 1};
  static ntn::ModelSpec<S> spec;
  const double L = 1.7;
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, -0.5).normalized();
  spec = {};
  ntn_test::straight_beam(spec, L, ntn_test::kSteel, kRect, ntn_test::kFixedAll, 0,
                          {axis(0), axis(1), axis(2)}, {0, 0, 1});
  const ntn::ElementSpec& e = spec.elements[0];
  const Eigen::Matrix3d R = rotation_of(ntn::beam_geometry(spec.nodes[0], spec.nodes[1], e));
  // A unit load along each local axis at the tip, force then moment; response in local axes.
  for (int k = 0; k < 6; ++k) {
    Eigen::VectorXd P = Eigen::VectorXd::Zero(12);
    P.segment<3>(6 + 3 * (k / 3)) = R.row(k % 3).transpose();
    const Eigen::VectorXd u = ntn_test::static_displacement(ntn::view(spec), P);
    const Eigen::Vector3d t = R * u.segment<3>(6), r = R * u.segment<3>(9);
    double expected_t[3] = {0, 0, 0}, expected_r[3] = {0, 0, 0};
    switch (k) {
      case 0:
        expected_t[0] = L / (e.E * e.A);
        break;
      case 1:  // force along y: bending about z (Iz)
        expected_t[1] = L * L * L / (3 * e.E * e.Iz), expected_r[2] = L * L / (2 * e.E * e.Iz);
        break;
      case 2:  // force along z: bending about y (Iy), rotation about -y
        expected_t[2] = L * L * L / (3 * e.E * e.Iy), expected_r[1] = -L * L / (2 * e.E * e.Iy);
        break;
      case 3:
        expected_r[0] = L / (e.G * e.J);
        break;
      case 4:  // moment about y
        expected_r[1] = L / (e.E * e.Iy), expected_t[2] = -L * L / (2 * e.E * e.Iy);
        break;
      case 5:  // moment about z
        expected_r[2] = L / (e.E * e.Iz), expected_t[1] = L * L / (2 * e.E * e.Iz);
        break;
    }
    const double scale = std::max(t.cwiseAbs().maxCoeff(), r.cwiseAbs().maxCoeff());
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(t(c), expected_t[c], 1e-10 * scale) << "load " << k << " translation " << c;
      EXPECT_NEAR(r(c), expected_r[c], 1e-10 * scale) << "load " << k << " rotation " << c;
    }
  }
}

// Timoshenko: a short thick cantilever (L = 0.5 m, 100 x 200 mm, kappa = 5/6) under a tip load
// deflects P L^3 / 3EI + P L / (kappa G A); shear adds 12 % (uz, depth 200) or 3 % (uy). The
// element with Phi = 12 EI / (kappa G A l^2) reproduces this exactly at any mesh, so the dense
// static solve must agree to rounding and the kernel's dynamic relaxation to its convergence
// tolerance; both are held to 0.5 %, measured ~1e-10.
template <int N>
void check_timoshenko_cantilever(int load_dof) {
  constexpr ntn::Sizes S{.nodes = N + 1, .elements = N, .loads = 1};
  static ntn::ModelSpec<S> spec;
  static ntn::Model<S> model;
  static ntn::State<S> state;
  static ntn::Scratch<S> scratch;
  const double L = 0.5, P = 1e5;
  spec = {};
  ntn_test::straight_beam(spec, L, ntn_test::kSteel, kThick);
  spec.loads[0] = {N, load_dof, P, ntn::kConstant};
  const double I = load_dof == ntn::kUz ? kThick.Iy : kThick.Iz;
  const double kGA = ntn_test::kSteel.G * (5.0 / 6.0) * kThick.A;
  const double expected = P * L * L * L / (3 * ntn_test::kSteel.E * I) + P * L / kGA;
  const double bending_only = P * L * L * L / (3 * ntn_test::kSteel.E * I);

  Eigen::VectorXd load = Eigen::VectorXd::Zero(6 * (N + 1));
  load(6 * N + load_dof) = P;
  const double dense = ntn_test::static_displacement(ntn::view(spec), load)(6 * N + load_dof);
  EXPECT_NEAR(dense / expected, 1.0, 5e-3);
  EXPECT_GT(dense / bending_only - 1.0, 0.02);  // the shear term is there (3 % or 12 %)

  // Kernel: damping critical for the first mode, estimated from the static stiffness and the
  // Rayleigh quotient mass of a cantilever (~0.24 of the beam on the tip): alpha = 2 omega_1.
  const double omega1 = std::sqrt(P / expected / (0.24 * spec.elements[0].rho * kThick.A * L));
  spec.settings.alpha = 2 * omega1;
  spec.settings.dt = 0.9 * ntn::stable_time_step(ntn::view(spec)).dt_stable;
  state = {};
  ntn_test::RelaxationResult r;
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
    r = ntn_test::relax(model, state, scratch, 1e-10, 5'000'000);
  }
  ASSERT_TRUE(r.converged);
  const double tip = state.u[static_cast<std::size_t>(6 * N + load_dof)];
  std::printf("  N = %d, dof %d: dense %.3e, kernel %.3e relative error (%lld steps)\n", N,
              load_dof, dense / expected - 1, tip / expected - 1, static_cast<long long>(r.steps));
  EXPECT_NEAR(tip / expected, 1.0, 5e-3);
}

TEST(BeamStiffness, TimoshenkoShortThickCantilever) {
  check_timoshenko_cantilever<1>(ntn::kUz);
  check_timoshenko_cantilever<1>(ntn::kUy);
  check_timoshenko_cantilever<4>(ntn::kUz);
  check_timoshenko_cantilever<4>(ntn::kUy);
}

}  // namespace beam_test
