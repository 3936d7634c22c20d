// Frequency domain decomposition (Brincker, Zhang & Andersen 2001): the SVD of the cross-spectral
// matrix at every line, G(f_k) = U S U^H. Near a mode that dominates, G ~ s1 u1 u1^H: the first
// singular value spectrum s1(f) peaks at the mode's frequency and u1 there is its operational
// shape (up to scale and phase).
#pragma once

#include <complex>
#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "ntn/spectral/peaks.hpp"
#include "ntn/spectral/spectrum.hpp"

namespace ntn::spectral {

struct Fdd {
  Grid grid;
  std::size_t channels = 0;
  std::vector<double> singular_values;              // line k: s_1 >= ... >= s_n from k n
  std::vector<std::complex<double>> first_vectors;  // line k: u_1 (unit norm) from k n

  Spectrum singular_spectrum(std::size_t i = 0) const;  // s_{i+1}(f), Scale::kPower
  Eigen::VectorXcd first_vector(std::size_t k) const;
};

// One JacobiSVD (Eigen) per line. Throws Error on an empty matrix.
Fdd fdd(const CrossSpectralMatrix& g);

struct OperationalMode {
  Peak peak;                            // on s1
  std::optional<HalfPower> half_power;  // on s1 (a mode well separated from the others)
  Eigen::VectorXcd complex_shape;       // u1 at the peak line
  Eigen::VectorXd shape;                // real_shape(complex_shape)
  double collinearity = 0;              // modal phase collinearity of u1, 1 for a real mode
  double separation = 0;                // s2 / s1 at the peak line; small: one mode dominates
};

// Peaks of s1 (find_peaks with `options`) and the shape at each.
std::vector<OperationalMode> fdd_modes(const Fdd& fdd, const PeakOptions& options = {});

// The real shape of a complex vector: rotated by the phase theta = -arg(sum u_i^2) / 2 that makes
// the real part largest, real part taken, scaled to unit length, sign so that the component of
// largest magnitude is positive.
Eigen::VectorXd real_shape(const Eigen::VectorXcd& u);

// Modal phase collinearity |sum u_i^2|^2 / (sum |u_i|^2)^2 (Pappa et al. 1993, without
// centring): 1 when every component has the same phase (mod pi), 0 for a circular shape.
double collinearity(const Eigen::VectorXcd& u);

// Modal assurance criterion |a^H b|^2 / ((a^H a)(b^H b)) (Allemang & Brown 1982); 0 when either
// vector is zero. Throws Error on different lengths.
double mac(const Eigen::VectorXd& a, const Eigen::VectorXd& b);
double mac(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b);

}  // namespace ntn::spectral
