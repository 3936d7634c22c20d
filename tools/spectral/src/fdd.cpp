#include "ntn/spectral/fdd.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <string>

#include "ntn/spectral/error.hpp"

namespace ntn::spectral {

Spectrum Fdd::singular_spectrum(std::size_t i) const {
  if (i >= channels) throw Error("singular_spectrum: no singular value " + std::to_string(i + 1));
  Spectrum s{grid, Scale::kPower, std::vector<double>(grid.lines())};
  for (std::size_t k = 0; k < s.values.size(); ++k)
    s.values[k] = singular_values[k * channels + i];
  return s;
}

Eigen::VectorXcd Fdd::first_vector(std::size_t k) const {
  Eigen::VectorXcd u(static_cast<Eigen::Index>(channels));
  for (std::size_t i = 0; i < channels; ++i)
    u(static_cast<Eigen::Index>(i)) = first_vectors[k * channels + i];
  return u;
}

Fdd fdd(const CrossSpectralMatrix& g) {
  const std::size_t n = g.channels;
  const std::size_t lines = g.grid.lines();
  if (n == 0 || g.values.size() != lines * n * n)
    throw Error("fdd: the cross-spectral matrix is empty or inconsistent");
  Fdd out;
  out.grid = g.grid;
  out.channels = n;
  out.singular_values.resize(lines * n);
  out.first_vectors.resize(lines * n);
  Eigen::MatrixXcd gk(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  Eigen::JacobiSVD<Eigen::MatrixXcd> svd(gk.rows(), gk.cols(), Eigen::ComputeThinU);
  for (std::size_t k = 0; k < lines; ++k) {
    gk = g.at(k);
    svd.compute(gk, Eigen::ComputeThinU);
    const Eigen::VectorXd& s = svd.singularValues();  // descending
    for (std::size_t i = 0; i < n; ++i) {
      out.singular_values[k * n + i] = s(static_cast<Eigen::Index>(i));
      out.first_vectors[k * n + i] = svd.matrixU()(static_cast<Eigen::Index>(i), 0);
    }
  }
  return out;
}

Eigen::VectorXd real_shape(const Eigen::VectorXcd& u) {
  // |Re(e^{i theta} u)|^2 = (|u|^2 + Re(e^{2 i theta} sum u_i^2)) / 2 is largest at
  // theta = -arg(sum u_i^2) / 2.
  const std::complex<double> s = (u.array() * u.array()).sum();
  const double theta = -0.5 * std::arg(s);
  Eigen::VectorXd v = (u * std::polar(1.0, theta)).real();
  const double norm = v.norm();
  if (norm > 0) v /= norm;
  Eigen::Index imax = 0;
  if (v.size() > 0) v.cwiseAbs().maxCoeff(&imax);
  if (v.size() > 0 && v(imax) < 0) v = -v;
  return v;
}

double collinearity(const Eigen::VectorXcd& u) {
  const double d = u.squaredNorm();
  if (!(d > 0)) return 0;
  return std::norm((u.array() * u.array()).sum()) / (d * d);
}

double mac(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() != b.size())
    throw Error("mac: shapes of different length (" + std::to_string(a.size()) + " and " +
                std::to_string(b.size()) + ")");
  const double d = a.squaredNorm() * b.squaredNorm();
  if (!(d > 0)) return 0;
  const double ab = a.dot(b);
  return ab * ab / d;
}

double mac(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b) {
  if (a.size() != b.size())
    throw Error("mac: shapes of different length (" + std::to_string(a.size()) + " and " +
                std::to_string(b.size()) + ")");
  const double d = a.squaredNorm() * b.squaredNorm();
  if (!(d > 0)) return 0;
  return std::norm(a.dot(b)) / d;  // Eigen's dot conjugates the first vector: a^H b
}

std::vector<OperationalMode> fdd_modes(const Fdd& f, const PeakOptions& options) {
  const Spectrum s1 = f.singular_spectrum(0);
  std::vector<OperationalMode> modes;
  for (const Peak& p : find_peaks(s1, options)) {
    OperationalMode m;
    m.peak = p;
    m.half_power = half_power(s1, p);
    m.complex_shape = f.first_vector(p.line);
    m.shape = real_shape(m.complex_shape);
    m.collinearity = collinearity(m.complex_shape);
    const double s1k = f.singular_values[p.line * f.channels];
    m.separation =
        f.channels > 1 && s1k > 0 ? f.singular_values[p.line * f.channels + 1] / s1k : 0.0;
    modes.push_back(std::move(m));
  }
  return modes;
}

}  // namespace ntn::spectral
