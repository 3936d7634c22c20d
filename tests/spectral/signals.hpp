// Test signals with known spectra: Gaussian white noise, and single-degree-of-freedom oscillators
// simulated exactly (zero-order-hold state transition) with their exact discrete transfer
// function.
#pragma once

#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <random>
#include <span>
#include <vector>

namespace ntn::spectral::test {

// Independent N(0, sigma^2) samples, reproducible from the seed.
inline std::vector<double> white_noise(std::size_t n, double sigma, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> dist(0.0, sigma);
  std::vector<double> x(n);
  for (double& v : x)
    v = dist(rng);
  return x;
}

// x'' + 2 zeta w x' + w^2 x = u(t), with u held over each step (u(t) = u_k on [k dt, (k+1) dt)).
// The state [x, x'] advances exactly: s_{k+1} = P s_k + g u_k, P = exp(A dt) in closed form for
// 0 < zeta < 1, g = A^{-1} (P - I) [0, 1]^T. So the simulated response has exactly the poles
// exp((-zeta w +- i w_d) dt) and the transfer function transfer() below, with no integration
// error.
struct Sdof {
  double wn = 0;  // rad/s
  double zeta = 0;
  double dt = 0;  // s
  double p11 = 0, p12 = 0, p21 = 0, p22 = 0, g1 = 0, g2 = 0;

  Sdof(double f_hz, double zeta_, double dt_)
      : wn(2 * std::numbers::pi * f_hz), zeta(zeta_), dt(dt_) {
    const double sigma = zeta * wn;
    const double wd = wn * std::sqrt(1 - zeta * zeta);
    const double e = std::exp(-sigma * dt);
    const double c = std::cos(wd * dt);
    const double s = std::sin(wd * dt);
    p11 = e * (c + sigma / wd * s);
    p12 = e * s / wd;
    p21 = -e * wn * wn / wd * s;
    p22 = e * (c - sigma / wd * s);
    g1 = (1 - p22 - 2 * zeta * wn * p12) / (wn * wn);
    g2 = p12;
  }

  // x_k for k = 0..n-1 from rest (x_0 = 0), input u_k.
  std::vector<double> displacement(std::span<const double> u) const {
    std::vector<double> x(u.size());
    double a = 0;
    double b = 0;
    for (std::size_t k = 0; k < u.size(); ++k) {
      x[k] = a;
      const double a1 = p11 * a + p12 * b + g1 * u[k];
      const double b1 = p21 * a + p22 * b + g2 * u[k];
      a = a1;
      b = b1;
    }
    return x;
  }

  // X(z) / U(z) at z = exp(i 2 pi f dt): [1 0] (z I - P)^{-1} g.
  std::complex<double> transfer(double f_hz) const {
    const std::complex<double> z = std::polar(1.0, 2 * std::numbers::pi * f_hz * dt);
    const std::complex<double> det = (z - p11) * (z - p22) - p12 * p21;
    return ((z - p22) * g1 + p12 * g2) / det;
  }

  // The frequency of the largest |transfer|, Hz, by golden-section search in [lo, hi].
  double peak_frequency(double lo, double hi) const {
    const double r = 0.5 * (std::sqrt(5.0) - 1);
    double a = lo;
    double b = hi;
    for (int i = 0; i < 200 && b - a > 1e-13 * hi; ++i) {
      const double c = b - r * (b - a);
      const double d = a + r * (b - a);
      if (std::abs(transfer(c)) > std::abs(transfer(d)))
        b = d;
      else
        a = c;
    }
    return 0.5 * (a + b);
  }
};

// Population variance (mean removed), summed in order.
inline double variance(std::span<const double> x) {
  double m = 0;
  for (double v : x)
    m += v;
  m /= static_cast<double>(x.size());
  double s = 0;
  for (double v : x)
    s += (v - m) * (v - m);
  return s / static_cast<double>(x.size());
}

// Sum of PSD values times df: the integral of a one-sided PSD over its lines.
template <class S>
double integral(const S& psd) {
  double s = 0;
  for (double v : psd.values)
    s += v;
  return s * psd.grid.df();
}

}  // namespace ntn::spectral::test
