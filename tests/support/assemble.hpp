// Dense global matrices of a model, for reference solutions in tests (heap and exceptions
// allowed here, never in the kernel). Built with the kernel's own element functions
// (ntn::beam_geometry, ntn::beam_stiffness, ntn::beam_global_stiffness,
// ntn::assemble_lumped_mass) so that what is compared is the kernel's discrete model.
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <initializer_list>
#include <span>
#include <stdexcept>
#include <vector>

#include "ntn/beam.hpp"
#include "ntn/model.hpp"
#include "ntn/model_spec.hpp"

namespace ntn_test {

inline Eigen::Index dofs_of(const ntn::SpecView& spec) {
  return static_cast<Eigen::Index>(ntn::kDofsPerNode * spec.nodes.size());
}

// K = sum over elements of the 12x12 T^T K_L T scattered to the elements' nodes.
inline Eigen::MatrixXd global_stiffness(const ntn::SpecView& spec) {
  const Eigen::Index n = dofs_of(spec);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (const ntn::ElementSpec& e : spec.elements) {
    const ntn::BeamGeometry g =
        ntn::beam_geometry(spec.nodes[static_cast<std::size_t>(e.node_i)],
                           spec.nodes[static_cast<std::size_t>(e.node_j)], e);
    if (g.check != ntn::ElementCheck::kOk) throw std::invalid_argument("bad element geometry");
    ntn::BeamData b;
    b.node_i = e.node_i, b.node_j = e.node_j;
    b.rotation = g.rotation;
    b.k = ntn::beam_stiffness(e, g.length);
    const ntn::Matrix12 Ke = ntn::beam_global_stiffness(b);
    const int node[2] = {e.node_i, e.node_j};
    for (int r = 0; r < 12; ++r) {
      for (int c = 0; c < 12; ++c) {
        const Eigen::Index gr = ntn::kDofsPerNode * node[r / 6] + r % 6;
        const Eigen::Index gc = ntn::kDofsPerNode * node[c / 6] + c % 6;
        K(gr, gc) += Ke[static_cast<std::size_t>(r * 12 + c)];
      }
    }
  }
  return K;
}

// Diagonal of the lumped (HRZ + point) mass, as ntn::init assembles it.
inline Eigen::VectorXd lumped_mass(const ntn::SpecView& spec) {
  Eigen::VectorXd m(dofs_of(spec));
  ntn::assemble_lumped_mass(spec, std::span<double>(m.data(), static_cast<std::size_t>(m.size())));
  return m;
}

// Global indices of the DOFs not held by a support, ascending.
inline std::vector<Eigen::Index> free_dofs(const ntn::SpecView& spec) {
  std::vector<Eigen::Index> out;
  for (std::size_t n = 0; n < spec.nodes.size(); ++n) {
    for (int d = 0; d < ntn::kDofsPerNode; ++d) {
      if (((spec.nodes[n].fixed >> d) & 1U) == 0) {
        out.push_back(static_cast<Eigen::Index>(ntn::kDofsPerNode * n) + d);
      }
    }
  }
  return out;
}

inline Eigen::MatrixXd restrict_to(const Eigen::MatrixXd& A, const std::vector<Eigen::Index>& d) {
  const auto n = static_cast<Eigen::Index>(d.size());
  Eigen::MatrixXd out(n, n);
  for (Eigen::Index r = 0; r < n; ++r) {
    for (Eigen::Index c = 0; c < n; ++c) {
      out(r, c) = A(d[static_cast<std::size_t>(r)], d[static_cast<std::size_t>(c)]);
    }
  }
  return out;
}

// Undamped modes of K phi = omega^2 M phi on the free DOFs, with M diagonal: the symmetric
// problem M^-1/2 K M^-1/2 y = omega^2 y, phi = M^-1/2 y. Ascending omega; shapes full-size
// (zeros at supported DOFs) and mass-normalized (phi^T M phi = 1).
struct Modes {
  Eigen::VectorXd omega;   // rad/s
  Eigen::MatrixXd shapes;  // dofs x modes
  Eigen::VectorXd mass;    // the lumped mass diagonal used
};

inline Modes modes(const ntn::SpecView& spec) {
  const std::vector<Eigen::Index> d = free_dofs(spec);
  const Eigen::MatrixXd K = global_stiffness(spec);
  Modes out;
  out.mass = lumped_mass(spec);
  const auto n = static_cast<Eigen::Index>(d.size());
  Eigen::VectorXd s(n);  // M^-1/2 on the free DOFs
  for (Eigen::Index i = 0; i < n; ++i)
    s(i) = 1.0 / std::sqrt(out.mass(d[static_cast<std::size_t>(i)]));
  const Eigen::MatrixXd A = s.asDiagonal() * restrict_to(K, d) * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A);
  if (eig.info() != Eigen::Success) throw std::runtime_error("eigen solver failed");
  out.omega = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  out.shapes = Eigen::MatrixXd::Zero(dofs_of(spec), n);
  for (Eigen::Index i = 0; i < n; ++i) {
    out.shapes.row(d[static_cast<std::size_t>(i)]) = s(i) * eig.eigenvectors().row(i);
  }
  return out;
}

// Share of a mode's kinetic energy (phi^T M phi restricted to some node DOFs): 1 for a mode that
// moves only in those DOFs.
inline double energy_fraction(const Modes& m, Eigen::Index mode, std::initializer_list<int> dofs) {
  double part = 0, all = 0;
  for (Eigen::Index j = 0; j < m.shapes.rows(); ++j) {
    const double e = m.mass(j) * m.shapes(j, mode) * m.shapes(j, mode);
    all += e;
    for (int d : dofs) {
      if (j % ntn::kDofsPerNode == d) part += e;
    }
  }
  return part / all;
}

// Modes (indices, ascending frequency) with more than `share` of their energy in `dofs`.
inline std::vector<Eigen::Index> modes_in(const Modes& m, std::initializer_list<int> dofs,
                                          double share = 0.99) {
  std::vector<Eigen::Index> out;
  for (Eigen::Index i = 0; i < m.omega.size(); ++i) {
    if (energy_fraction(m, i, dofs) > share) out.push_back(i);
  }
  return out;
}

// Static displacement K u = P on the free DOFs (full-size result, zeros at supports).
inline Eigen::VectorXd static_displacement(const ntn::SpecView& spec, const Eigen::VectorXd& P) {
  const std::vector<Eigen::Index> d = free_dofs(spec);
  const Eigen::MatrixXd K = restrict_to(global_stiffness(spec), d);
  Eigen::VectorXd p(static_cast<Eigen::Index>(d.size()));
  for (std::size_t i = 0; i < d.size(); ++i)
    p(static_cast<Eigen::Index>(i)) = P(d[i]);
  const Eigen::VectorXd x = K.fullPivLu().solve(p);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(dofs_of(spec));
  for (std::size_t i = 0; i < d.size(); ++i)
    u(d[i]) = x(static_cast<Eigen::Index>(i));
  return u;
}

}  // namespace ntn_test
