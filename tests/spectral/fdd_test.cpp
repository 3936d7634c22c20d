// Frequency domain decomposition: a three-storey shear chain under independent white-noise
// forces, simulated exactly mode by mode; the first singular value's peaks and vectors against
// the chain's own eigenproblem. And the shape utilities (real shape, collinearity, MAC).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

#include "ntn/spectral/error.hpp"
#include "ntn/spectral/fdd.hpp"
#include "ntn/spectral/welch.hpp"
#include "signals.hpp"

namespace ntn::spectral {
namespace fdd_test {

// Masses 2, 1.5, 1 kg; springs 800, 600, 400 N/m (ground-1, 1-2, 2-3); modal damping 1.5 %.
// K phi = w^2 M phi (Eigen, mass-normalized phi) gives the truth. Forces: independent white noise
// at every mass, held over each step; each modal coordinate q_j'' + 2 zeta w_j q_j' + w_j^2 q_j =
// phi_j^T f is advanced exactly (signals.hpp) and x = sum_j phi_j q_j: the simulation has exactly
// these modes. 20 Hz, 2^21 samples (29 h), Welch with 4096-sample segments (0.0049 Hz lines),
// 1023 averages.
// Tolerances: frequency 0.1 % (the issue's) against f_j, and against f_j sqrt(1 - 2 zeta^2),
// where the s1 peak of a displacement response sits (0.02 % lower; the other modes move it by
// less): the random error is about 0.02 % (1 sigma, over 40 noise seeds), so the second is a 5
// sigma bound. MAC >= 0.99 (the issue's) between the real FDD shape and phi_j; each mode
// dominates its peak (s2/s1 < 0.05); the modes are real (collinearity >= 0.99).
TEST(Fdd, ThreeStoreyChainModesAndShapes) {
  Eigen::Matrix3d m = Eigen::Vector3d(2.0, 1.5, 1.0).asDiagonal();
  const double k1 = 800, k2 = 600, k3 = 400;
  Eigen::Matrix3d k;
  k << k1 + k2, -k2, 0, -k2, k2 + k3, -k3, 0, -k3, k3;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> eig(k, m);
  ASSERT_EQ(eig.info(), Eigen::Success);
  const Eigen::Vector3d f_true = eig.eigenvalues().cwiseSqrt() / (2 * std::numbers::pi);
  const Eigen::Matrix3d phi = eig.eigenvectors();  // phi^T M phi = I

  const double fs = 20;
  const double zeta = 0.015;
  const std::size_t n = std::size_t{1} << 21;
  std::vector<std::vector<double>> force{
      test::white_noise(n, 1.0, 41), test::white_noise(n, 1.0, 42), test::white_noise(n, 1.0, 43)};
  std::vector<std::vector<double>> x(3, std::vector<double>(n, 0.0));
  for (int j = 0; j < 3; ++j) {
    std::vector<double> p(n);
    for (std::size_t i = 0; i < n; ++i)
      p[i] = phi(0, j) * force[0][i] + phi(1, j) * force[1][i] + phi(2, j) * force[2][i];
    const auto q = test::Sdof(f_true(j), zeta, 1 / fs).displacement(p);
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < n; ++i)
        x[static_cast<std::size_t>(c)][i] += phi(c, j) * q[i];
  }

  WelchOptions o;
  o.segment = 4096;
  const Fdd d = fdd(cross_spectral_matrix(x, fs, o));
  const auto modes = fdd_modes(d, {.relative_threshold = 1e-4, .min_prominence = 10});
  ASSERT_EQ(modes.size(), 3u);
  for (int j = 0; j < 3; ++j) {
    const OperationalMode& md = modes[static_cast<std::size_t>(j)];
    EXPECT_NEAR(md.peak.frequency, f_true(j), 1e-3 * f_true(j)) << "mode " << j;
    const double f_peak = f_true(j) * std::sqrt(1 - 2 * zeta * zeta);
    EXPECT_NEAR(md.peak.frequency, f_peak, 1e-3 * f_peak) << "mode " << j;
    const Eigen::VectorXd truth = phi.col(j);
    EXPECT_GE(mac(md.shape, truth), 0.99) << "mode " << j;
    EXPECT_GE(md.collinearity, 0.99) << "mode " << j;  // classical damping: real modes
    EXPECT_LT(md.separation, 0.05) << "mode " << j;
    EXPECT_NEAR(md.shape.norm(), 1.0, 1e-12);
  }
}

// real_shape undoes any complex scale: e^{i a} c v with v real gives v / |v| (largest component
// positive); collinearity is 1 for it and 0 for a circular vector (1, i); MAC is 1 for parallel
// and 0 for orthogonal shapes, and the complex MAC equals the real one on real vectors.
// Tolerance 1e-14: rounding of a few operations.
TEST(Fdd, ShapeUtilities) {
  const Eigen::Vector3d v(0.3, -1.2, 0.7);
  const Eigen::VectorXcd u = v.cast<std::complex<double>>() * std::polar(2.5, 2.1);
  const Eigen::VectorXd r = real_shape(u);
  EXPECT_LT((r - (-v / v.norm())).norm(), 1e-14);  // -1.2 is the largest: sign flips
  EXPECT_NEAR(collinearity(u), 1.0, 1e-14);
  Eigen::VectorXcd circ(2);
  circ << 1.0, std::complex<double>(0, 1);
  EXPECT_NEAR(collinearity(circ), 0.0, 1e-14);
  EXPECT_NEAR(mac(Eigen::VectorXd(v), Eigen::VectorXd(-3 * v)), 1.0, 1e-14);
  EXPECT_NEAR(
      mac(Eigen::VectorXd(Eigen::Vector3d(1, 0, 0)), Eigen::VectorXd(Eigen::Vector3d(0, 2, 0))),
      0.0, 1e-14);
  const Eigen::Vector3d w(1.0, 0.5, -0.2);
  EXPECT_NEAR(mac(Eigen::VectorXcd(v.cast<std::complex<double>>()),
                  Eigen::VectorXcd(w.cast<std::complex<double>>())),
              mac(Eigen::VectorXd(v), Eigen::VectorXd(w)), 1e-14);
  EXPECT_THROW((void)mac(Eigen::VectorXd(v), Eigen::VectorXd(Eigen::Vector2d(1, 2))), Error);
}

}  // namespace fdd_test
}  // namespace ntn::spectral
