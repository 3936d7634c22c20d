// Finite rotations without libm (the step calls none): unit quaternions, the exponential and
// logarithm maps of SO(3) and the inverse tangent of the logarithm, by polynomials only.
#pragma once

#include <array>
#include <cstddef>

#include "ntn/root.hpp"

namespace ntn {

using Vector3 = std::array<double, 3>;
using Matrix3 = std::array<double, 9>;  // row-major

// A rotation by the angle theta about the unit axis e as the unit quaternion
// (w, x, y, z) = (cos(theta/2), sin(theta/2) e); q and -q are the same rotation.
struct Quaternion {
  double w = 1, x = 0, y = 0, z = 0;
};

inline double dot(const Vector3& a, const Vector3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

inline Vector3 cross(const Vector3& a, const Vector3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

constexpr Quaternion conjugate(const Quaternion& q) {
  return {q.w, -q.x, -q.y, -q.z};
}

// Hamilton product: a b = (a_w b_w - a_v . b_v, a_w b_v + b_w a_v + a_v x b_v), so that the
// rotation a b is b then a.
inline Quaternion product(const Quaternion& a, const Quaternion& b) {
  return {
      a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
      a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

// q v q*, as v + w t + q_v x t with t = 2 q_v x v (unit q).
inline Vector3 rotate(const Quaternion& q, const Vector3& v) {
  const Vector3 u{q.x, q.y, q.z};
  const Vector3 c = cross(u, v);
  const Vector3 t{2.0 * c[0], 2.0 * c[1], 2.0 * c[2]};
  const Vector3 ut = cross(u, t);
  return {v[0] + q.w * t[0] + ut[0], v[1] + q.w * t[1] + ut[1], v[2] + q.w * t[2] + ut[2]};
}

// The matrix Q of a unit q (Q v = rotate(q, v)), row-major.
inline Matrix3 rotation_matrix(const Quaternion& q) {
  const double xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
  const double xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
  const double wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
  return {1.0 - 2.0 * (yy + zz), 2.0 * (xy - wz),       2.0 * (xz + wy),
          2.0 * (xy + wz),       1.0 - 2.0 * (xx + zz), 2.0 * (yz - wx),
          2.0 * (xz - wy),       2.0 * (yz + wx),       1.0 - 2.0 * (xx + yy)};
}

// q / |q| for |q| near 1: one Newton step of 1/sqrt(n) from 1, 1 + (1 - n)/2 with n = |q|^2
// (error 3 (1 - n)^2 / 8: rounding for the drift of a product of unit quaternions), applied as
// q + q d so that the small d is not rounded into 1 + d.
inline Quaternion renormalized(const Quaternion& q) {
  const double n = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
  const double d = 0.5 * (1.0 - n);
  return {q.w + q.w * d, q.x + q.x * d, q.y + q.y * d, q.z + q.z * d};
}

// 1/sqrt(x) for finite x > 0. Near 1 (|x - 1| <= 1/16), four Newton steps from 1,
// y <- y + y (1 - x y^2)/2, with no division: the relative error e of y goes to -3 e^2 / 2, from
// 1/32 to below 1e-21, so the result is the last step's rounding (within 2 ulp, tested). Elsewhere
// 1 / root(x). For lengths and norms that small strains keep near a known value.
inline double inverse_root(double x) {
  if (!(x >= 0.9375 && x <= 1.0625)) return 1.0 / root(x);
  double y = 1.0;
  for (int i = 0; i < 4; ++i)
    y = y + 0.5 * y * (1.0 - x * y * y);
  return y;
}

namespace detail {

// c[0] + x (c[1] + x (c[2] + ...)), innermost first.
template <std::size_t N>
double horner(const std::array<double, N>& c, double x) {
  double r = c[N - 1];
  for (std::size_t k = N - 1; k-- > 0;)
    r = r * x + c[k];
  return r;
}

// Taylor series in p = (theta/2)^2 of cos(theta/2) and sin(theta/2)/(theta/2), coefficients
// (-1)^k / (2k)! and (-1)^k / (2k+1)!, k = 0..6: the first omitted terms are below 2^-60 of the
// sums for theta <= 0.5 (p <= 1/16).
inline constexpr std::array<double, 7> kCosHalf{
    1.0, -1.0 / 2, 1.0 / 24, -1.0 / 720, 1.0 / 40320, -1.0 / 3628800, 1.0 / 479001600};
inline constexpr std::array<double, 7> kSincHalf{
    1.0, -1.0 / 6, 1.0 / 120, -1.0 / 5040, 1.0 / 362880, -1.0 / 39916800, 1.0 / 6227020800};

// theta / sin(theta) = atan2(s, c) / s with c = cos(theta) = 1 - t, s = sin(theta), as a
// polynomial in t alone (no root: the function is even in theta, so analytic in c; its nearest
// singularity is theta = pi, t = 2). On [0, 1/8] (theta <= 0.505) degree 9 in t; on [1/8, 1]
// (theta <= pi/2) degree 20 in t - 9/16. Chebyshev interpolants at 50 digits, rounded to double;
// evaluated in double by horner (no contraction) within 0.8 ulp of the exact function of the
// rounded t on a 4000-point grid of each range.
inline constexpr std::array<double, 10> kAngleOverSineNear{1.0,
                                                           0.33333333333333437,
                                                           0.13333333333306488,
                                                           0.05714285717026778,
                                                           0.025396823977912493,
                                                           0.011544053634831556,
                                                           0.005327247840311676,
                                                           0.002494790419205288,
                                                           0.00111458330730877,
                                                           0.0007516983523280625};
inline constexpr std::array<double, 21> kAngleOverSineFar{
    1.2432794066991208,    0.564022736471973,      0.31103354748886924,   0.18454243877607004,
    0.11375904887818163,   0.07178969664439358,    0.04602791970773253,   0.029849774820321643,
    0.01952561104988228,   0.012858586950550541,   0.008513952549077167,  0.005662603922191758,
    0.0037799987058099085, 0.0025284808933871625,  0.0016977156892983203, 0.001161194340294125,
    0.0007832205626163304, 0.00045201330226667536, 0.0003056168659261754, 0.0003862461312695294,
    0.00026237686778713564};

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace detail

// theta / sin(theta) for t = 1 - cos(theta) in [0, 1] (theta in [0, pi/2]); a t slightly below 0
// or above 1 (rounding of a cosine) extends the polynomials smoothly.
inline double angle_over_sine(double t) {
  if (t <= 0.125) return detail::horner(detail::kAngleOverSineNear, t);
  return detail::horner(detail::kAngleOverSineFar, t - 0.5625);
}

// cos(theta/2) and sin(theta/2)/theta of an angle given by its square theta2 = theta^2 (even
// functions: no root). Taylor series for theta <= 0.5; above, theta is halved k times
// (theta2 / 4^k <= 1/4) and the half-angle pair doubled back k times, (c, s) -> (c^2 - s^2
// theta_k^2, c s) at each theta_k = theta / 2^k (the square of the quaternion (c, s theta_k)).
struct HalfAngle {
  double cos_half = 1;               // cos(theta/2)
  double sin_half_over_angle = 0.5;  // sin(theta/2) / theta
};

inline HalfAngle half_angle(double theta2) {
  int k = 0;
  double a2 = theta2;
  while (a2 > 0.25 && k < 64) {  // 64: a bound for an infinite or huge argument
    a2 *= 0.25;
    ++k;
  }
  const double p = 0.25 * a2;  // (theta_k / 2)^2
  HalfAngle h{detail::horner(detail::kCosHalf, p), 0.5 * detail::horner(detail::kSincHalf, p)};
  for (; k > 0; --k) {
    // cos(2a) = c^2 - s^2 theta_k^2 and sin(2a)/(2 theta_k) = cos(a) sin(a)/theta_k.
    const double c = h.cos_half * h.cos_half - h.sin_half_over_angle * h.sin_half_over_angle * a2;
    h.sin_half_over_angle = h.cos_half * h.sin_half_over_angle;
    h.cos_half = c;
    a2 *= 4.0;
  }
  return h;
}

// exp of the rotation vector theta: (cos(|theta|/2), sin(|theta|/2)/|theta| theta). For
// |theta| <= 0.5 each component within 1 ulp of the exact value (measured against libm in long
// double: 0.54 ulp for w, 0.97 for the products s theta_k). Above, each of the k doublings
// (k = ceil(log2(2 |theta|))) doubles the error there was and adds its rounding: within
// 0.7 2^k eps of the unit quaternion (measured; 5.7 eps for 2 < |theta| <= 4, k = 3).
inline Quaternion exp_rotation(const Vector3& theta) {
  const HalfAngle h = half_angle(dot(theta, theta));
  return {h.cos_half, h.sin_half_over_angle * theta[0], h.sin_half_over_angle * theta[1],
          h.sin_half_over_angle * theta[2]};
}

// log of a unit quaternion: theta = 2 atan2(|v|, w) v/|v| with w >= 0 (q or -q), angle in
// [0, pi]. With c = w = cos(theta/2), 2 atan2(|v|, w)/|v| is 2 angle_over_sine(1 - w): no root,
// no atan of its own. Relative error of theta within 1.1 eps of the exact log of the rounded q
// (measured against atan2 in long double for angles up to pi - 1e-3): angle_over_sine's 0.8 ulp
// and the products by v's components.
inline Vector3 log_rotation(const Quaternion& q) {
  const double sign = q.w < 0 ? -1.0 : 1.0;
  const double f = 2.0 * sign * angle_over_sine(1.0 - sign * q.w);
  return {f * q.x, f * q.y, f * q.z};
}

// log of a rotation matrix R (row-major): with v = vee(R - R^T)/2 = sin(theta) e and
// c = (trace R - 1)/2 = cos(theta), theta = angle_over_sine(1 - c) v for theta <= pi/2. Above,
// theta/sin(theta) = pi/s - (pi - theta)/sin(pi - theta) with s = |v| (one root). The
// components carry R's rounding divided by sin(theta): within 2.4 eps / sin(theta) relative
// (measured against the quaternion's exact log), so ~1e-16 / theta for small angles and
// ~1e-16 / (pi - theta) near pi (use the quaternion form there).
inline Vector3 log_rotation(const Matrix3& R) {
  const Vector3 v{0.5 * (R[7] - R[5]), 0.5 * (R[2] - R[6]), 0.5 * (R[3] - R[1])};
  const double c = 0.5 * (R[0] + R[4] + R[8] - 1.0);
  double f;
  if (c >= 0) {
    f = angle_over_sine(1.0 - c);
  } else {
    const double s = root(dot(v, v));
    f = detail::kPi / s - angle_over_sine(1.0 + c);
  }
  return {f * v[0], f * v[1], f * v[2]};
}

// T_s(theta)^-T m, with T_s the tangent of the spatial spin of exp: for R = exp(theta),
// dR R^T = skew(T_s(theta) dtheta), T_s = I + (1 - cos t)/t^2 Th + (t - sin t)/t^3 Th^2
// (Th = skew(theta), t = |theta|), so dtheta = T_s^-1 dw with T_s^-1 = I - Th/2 + eta Th^2,
// eta = (1 - (t/2) cot(t/2)) / t^2 (Battini & Pacoste 2002 write the same inverse as
// (t/2)/tan(t/2) I + (1 - (t/2)/tan(t/2)) e e^T - Th/2, e = theta/t). The
// transpose, m + theta x m / 2 + eta theta x (theta x m), maps moments conjugate to theta to
// moments conjugate to the spin. eta by its Taylor series 1/12 + t^2/720 + t^4/30240 for
// t^2 < 1e-4 (next term below 1e-18), else from half_angle: (t/2) cot(t/2) = cos(t/2) /
// (2 sin(t/2)/t); eta's rounding there is ~1e-16 / t^2, and it multiplies a term of size t^2.
inline Vector3 log_tangent_inverse_transpose(const Vector3& theta, const Vector3& m) {
  const double t2 = dot(theta, theta);
  double eta;
  if (t2 < 1e-4) {
    eta = 1.0 / 12 + t2 * (1.0 / 720 + t2 * (1.0 / 30240));
  } else {
    const HalfAngle h = half_angle(t2);
    eta = (1.0 - h.cos_half / (2.0 * h.sin_half_over_angle)) / t2;
  }
  const Vector3 a = cross(theta, m);
  const Vector3 b = cross(theta, a);
  return {m[0] + 0.5 * a[0] + eta * b[0], m[1] + 0.5 * a[1] + eta * b[1],
          m[2] + 0.5 * a[2] + eta * b[2]};
}

}  // namespace ntn
