// Unit tests of the rotations (kernel/include/ntn/rotation.hpp) against truth chosen elsewhere:
// libm's sin, cos and atan2 in long double, Eigen's quaternions, the variation of the logarithm.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "ntn/rotation.hpp"

namespace corotational_test {

using ntn::Matrix3;
using ntn::Quaternion;
using ntn::Vector3;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = 3.14159265358979323846;

// Distance to the next double above |x|: the unit the errors are counted in.
double ulp(double x) {
  const double a = std::fabs(x);
  return std::nextafter(a, std::numeric_limits<double>::infinity()) - a;
}

double norm(const Vector3& v) {
  return std::sqrt(ntn::dot(v, v));
}

Vector3 scaled(const Vector3& v, double s) {
  return {v[0] * s, v[1] * s, v[2] * s};
}

Vector3 plus(const Vector3& a, const Vector3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}

Vector3 minus(const Vector3& a, const Vector3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

// A random unit vector (normalized Gaussian triple).
Vector3 random_axis(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0, 1);
  const Vector3 v{n(rng), n(rng), n(rng)};
  return scaled(v, 1.0 / norm(v));
}

// The rotation by `angle` about `axis`, by libm in long double, rounded once.
Quaternion axis_angle(const Vector3& axis, double angle) {
  const long double a = angle, ax = axis[0], ay = axis[1], az = axis[2];
  const long double n = std::sqrt(ax * ax + ay * ay + az * az);
  const long double s = std::sin(a / 2) / n;
  return {static_cast<double>(std::cos(a / 2)), static_cast<double>(s * ax),
          static_cast<double>(s * ay), static_cast<double>(s * az)};
}

Eigen::Quaterniond to_eigen(const Quaternion& q) {
  return Eigen::Quaterniond(q.w, q.x, q.y, q.z);
}

// The exact log of the rounded q, in long double: 2 atan2(|v|, w) v/|v| with w >= 0.
std::array<long double, 3> reference_log(const Quaternion& q) {
  const long double sign = q.w < 0 ? -1.0L : 1.0L;
  const long double w = sign * q.w, x = sign * q.x, y = sign * q.y, z = sign * q.z;
  const long double s = std::sqrt(x * x + y * y + z * z);
  const long double f = s > 0 ? 2.0L * std::atan2(s, w) / s : 2.0L;
  return {f * x, f * y, f * z};
}

// |a - b| / |b|, with b exact (long double).
double relative_error(const Vector3& a, const std::array<long double, 3>& b) {
  long double d = 0, n = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    d += (a[k] - b[k]) * (a[k] - b[k]);
    n += b[k] * b[k];
  }
  return static_cast<double>(std::sqrt(d / n));
}

// exp for |theta| <= 0.5 against cos(|theta|/2) and sin(|theta|/2) theta/|theta| in long double,
// in ulps of the exact value (the rounding alone is 0.5): the Taylor sums measured 0.54 ulp in
// 50-digit arithmetic, and the products s theta_k add half an ulp. Bounds 1 ulp for w, 1.5 for
// the vector part.
TEST(Rotation, ExpIsWithinAnUlpOfLibmUpToHalfARadian) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(0, 0.5);
  double worst_w = 0, worst_v = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Vector3 theta = scaled(random_axis(rng), angle(rng));
    const Quaternion q = ntn::exp_rotation(theta);
    const long double tx = theta[0], ty = theta[1], tz = theta[2];
    const long double t = std::sqrt(tx * tx + ty * ty + tz * tz);
    const long double w = std::cos(t / 2), s = std::sin(t / 2) / t;
    worst_w = std::max(worst_w, static_cast<double>(std::fabs(q.w - w)) / ulp(double(w)));
    const long double v[3] = {s * tx, s * ty, s * tz};
    const double got[3] = {q.x, q.y, q.z};
    for (std::size_t k = 0; k < 3; ++k) {
      worst_v =
          std::max(worst_v, static_cast<double>(std::fabs(got[k] - v[k])) / ulp(double(v[k])));
    }
  }
  EXPECT_LE(worst_w, 1.0);
  EXPECT_LE(worst_v, 1.5);  // plus the rounding of s theta_k
  std::printf("  exp, |theta| <= 0.5: w within %.2f ulp, v within %.2f ulp\n", worst_w, worst_v);
}

// Above 0.5 rad exp halves the angle k times and squares back; each squaring doubles the
// error there was and adds its own rounding, so about 2^k eps (k = 3 up to 4 rad, k = 5 up to
// 16 rad; measured 0.7 2^k eps). Bound: 2^(k+1) eps, distance to the exact unit quaternion.
TEST(Rotation, ExpAboveHalfARadianLosesAnUlpPerDoubling) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> angle(0.5, 16.0);
  for (int trial = 0; trial < 20000; ++trial) {
    const double a = angle(rng);
    const Vector3 e = random_axis(rng);
    const Quaternion q = ntn::exp_rotation(scaled(e, a));
    const long double t = a, s = std::sin(t / 2);
    const long double err =
        std::sqrt(std::pow(q.w - std::cos(t / 2), 2) + std::pow(q.x - s * e[0], 2) +
                  std::pow(q.y - s * e[1], 2) + std::pow(q.z - s * e[2], 2));
    const int k = static_cast<int>(std::ceil(std::log2(a / 0.5)));
    ASSERT_LE(static_cast<double>(err), std::ldexp(kEps, k + 1)) << "angle " << a;
  }
}

// log against the long-double atan2 form over angles up to pi - 1e-3 (and for -q, the same
// rotation), relative to |theta|: angle_over_sine's 0.8 ulp and the products by v (measured
// 1.05 eps); bound 4 eps.
TEST(Rotation, LogIsWithinAFewUlpOfAtan2UpToNearlyPi) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> angle(0, kPi - 1e-3);
  double worst = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Quaternion q = axis_angle(random_axis(rng), angle(rng));
    if (trial % 2 == 1) q = {-q.w, -q.x, -q.y, -q.z};
    const Vector3 theta = ntn::log_rotation(q);
    worst = std::max(worst, relative_error(theta, reference_log(q)) / kEps);
  }
  EXPECT_LE(worst, 4.0);
  std::printf("  log (quaternion), angle <= pi - 1e-3: within %.2f eps relative\n", worst);
}

// The log of the rotation matrix carries the matrix's rounding divided by sin(theta)
// (rotation.hpp): bound 8 eps / sin(theta) relative, to pi - 1e-3; the c < 0 branch and both
// sides of the switch of polynomials (theta = 0.505) are inside the range.
TEST(Rotation, MatrixLogAgreesWithTheQuaternionLog) {
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> angle(0, kPi - 1e-3);
  double worst = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double a = angle(rng);
    const Quaternion q = axis_angle(random_axis(rng), a);
    const Vector3 theta = ntn::log_rotation(ntn::rotation_matrix(q));
    worst = std::max(worst, relative_error(theta, reference_log(q)) * std::sin(a) / kEps);
  }
  EXPECT_LE(worst, 8.0);
  std::printf("  log (matrix): within %.2f eps / sin(theta) relative\n", worst);
}

// log(exp(theta)) = theta for |theta| < pi, and exp(log(q)) = +-q: the two error budgets added
// (exp's 2^k ulp with k <= 3, log's few ulp): 16 eps.
TEST(Rotation, ExpAndLogAreInverse) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(0, kPi - 1e-3);
  for (int trial = 0; trial < 20000; ++trial) {
    const Vector3 theta = scaled(random_axis(rng), angle(rng));
    const Vector3 back = ntn::log_rotation(ntn::exp_rotation(theta));
    ASSERT_LE(norm(minus(back, theta)), 16 * kEps * std::max(norm(theta), 1e-300));
    Quaternion q = axis_angle(random_axis(rng), angle(rng));
    if (trial % 2 == 1) q = {-q.w, -q.x, -q.y, -q.z};
    const Quaternion p = ntn::exp_rotation(ntn::log_rotation(q));
    const double s = q.w < 0 ? -1.0 : 1.0;
    ASSERT_LE(std::fabs(p.w - s * q.w) + std::fabs(p.x - s * q.x) + std::fabs(p.y - s * q.y) +
                  std::fabs(p.z - s * q.z),
              16 * kEps);
  }
}

// Product, conjugate, rotate and matrix against Eigen's quaternions (Hamilton, q v q*): the same
// arithmetic in another order, so a few ulp of the unit norm (8 eps).
TEST(Rotation, QuaternionAlgebraAgreesWithEigen) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> angle(0, kPi), u(-2, 2);
  for (int trial = 0; trial < 1000; ++trial) {
    const Quaternion a = axis_angle(random_axis(rng), angle(rng));
    const Quaternion b = axis_angle(random_axis(rng), angle(rng));
    const Vector3 v{u(rng), u(rng), u(rng)};
    const Quaternion ab = ntn::product(a, b);
    const Eigen::Quaterniond eab = to_eigen(a) * to_eigen(b);
    EXPECT_NEAR(ab.w, eab.w(), 8 * kEps);
    EXPECT_NEAR(ab.x, eab.x(), 8 * kEps);
    EXPECT_NEAR(ab.y, eab.y(), 8 * kEps);
    EXPECT_NEAR(ab.z, eab.z(), 8 * kEps);
    const Eigen::Vector3d ev = to_eigen(a) * Eigen::Vector3d(v[0], v[1], v[2]);
    const Vector3 rv = ntn::rotate(a, v);
    const Matrix3 R = ntn::rotation_matrix(a);
    const Eigen::Matrix3d ER = to_eigen(a).toRotationMatrix();
    const Vector3 back = ntn::rotate(ntn::conjugate(a), rv);
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_NEAR(rv[k], ev[static_cast<Eigen::Index>(k)], 8 * kEps * 4);
      EXPECT_NEAR(back[k], v[k], 8 * kEps * 4);
      for (std::size_t c = 0; c < 3; ++c) {
        EXPECT_NEAR(R[3 * k + c], ER(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(c)),
                    8 * kEps);
      }
    }
  }
}

// One Newton step takes a norm 1 + d to 1 + O(d^2): from |q| = 1 + 1e-8 (far more drift than a
// step leaves) to within 2 eps of 1.
TEST(Rotation, RenormalizedIsUnitToRounding) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> angle(0, kPi), drift(-1e-8, 1e-8);
  for (int trial = 0; trial < 1000; ++trial) {
    Quaternion q = axis_angle(random_axis(rng), angle(rng));
    const double f = 1 + drift(rng);
    q = ntn::renormalized({q.w * f, q.x * f, q.y * f, q.z * f});
    const long double n = static_cast<long double>(q.w) * q.w +
                          static_cast<long double>(q.x) * q.x +
                          static_cast<long double>(q.y) * q.y + static_cast<long double>(q.z) * q.z;
    ASSERT_LE(std::fabs(static_cast<double>(std::sqrt(n) - 1)), 2 * kEps);
  }
}

// inverse_root against 1/sqrt in long double: near 1 the four Newton steps' last rounding
// (bound 2 ulp); elsewhere root's ulp and the division's (bound 2 ulp); across both switches.
TEST(Rotation, InverseRootIsWithinTwoUlp) {
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> near(0.9, 1.1), wide(-30, 30);
  double worst = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double x = trial % 2 == 0 ? near(rng) : std::exp2(wide(rng));
    const long double exact = 1.0L / std::sqrt(static_cast<long double>(x));
    const double e = static_cast<double>(std::fabs(ntn::inverse_root(x) - exact)) /
                     ulp(static_cast<double>(exact));
    worst = std::max(worst, e);
  }
  EXPECT_LE(worst, 2.0);
  std::printf("  inverse_root: within %.2f ulp\n", worst);
}

// T_s^-T is the transpose of the variation of log under a spatial spin: for
// theta(h) = log(exp(h b) exp(theta)), a . dtheta/dh = (T_s^-T a) . b. Central differences at
// h = 1e-5: truncation h^2 ~ 1e-10 and rounding eps/h ~ 1e-11 relative; bound 1e-8. Angles from
// 0 across the series/closed-form switch of eta (|theta| = 0.01) to 2.5 rad.
TEST(Rotation, TangentInverseIsTheVariationOfTheLog) {
  std::mt19937_64 rng(14);
  const double angles[] = {0.0, 1e-4, 0.0099, 0.0101, 0.1, 0.5, 1.0, 2.0, 2.5};
  const double h = 1e-5;
  for (const double a : angles) {
    for (int trial = 0; trial < 20; ++trial) {
      const Vector3 theta = scaled(random_axis(rng), a);
      const Vector3 va = random_axis(rng), vb = random_axis(rng);
      const Quaternion q = ntn::exp_rotation(theta);
      const Vector3 tp = ntn::log_rotation(ntn::product(ntn::exp_rotation(scaled(vb, h)), q));
      const Vector3 tm = ntn::log_rotation(ntn::product(ntn::exp_rotation(scaled(vb, -h)), q));
      const double fd = ntn::dot(va, minus(tp, tm)) / (2 * h);
      const double exact = ntn::dot(ntn::log_tangent_inverse_transpose(theta, va), vb);
      ASSERT_NEAR(fd, exact, 1e-8) << "angle " << a;
    }
  }
}

}  // namespace corotational_test
