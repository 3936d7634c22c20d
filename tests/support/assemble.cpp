// The dense reference matrices and eigenproblems of assemble.hpp, compiled once.
#include "support/assemble.hpp"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <initializer_list>
#include <span>
#include <stdexcept>
#include <vector>

namespace ntn_test {

Eigen::Index dofs_of(const ntn::SpecView& spec) {
  return static_cast<Eigen::Index>(ntn::kDofsPerNode * spec.nodes.size());
}

Eigen::MatrixXd global_stiffness(const ntn::SpecView& spec) {
  const Eigen::Index n = dofs_of(spec);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  const int bad =
      ntn::modal::for_each_element_stiffness(spec, [&K](int r, int c, double v) { K(r, c) += v; });
  if (bad >= 0) throw std::invalid_argument("bad element geometry or properties");
  return K;
}

Eigen::VectorXd lumped_mass(const ntn::SpecView& spec) {
  const std::vector<double> mass = ntn::modal::lumped_mass(spec);
  return Eigen::Map<const Eigen::VectorXd>(mass.data(), static_cast<Eigen::Index>(mass.size()));
}

std::vector<Eigen::Index> free_dofs(const ntn::SpecView& spec) {
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

Eigen::MatrixXd restrict_to(const Eigen::MatrixXd& A, const std::vector<Eigen::Index>& d) {
  const auto n = static_cast<Eigen::Index>(d.size());
  Eigen::MatrixXd out(n, n);
  for (Eigen::Index r = 0; r < n; ++r) {
    for (Eigen::Index c = 0; c < n; ++c) {
      out(r, c) = A(d[static_cast<std::size_t>(r)], d[static_cast<std::size_t>(c)]);
    }
  }
  return out;
}

Modes modes(const ntn::SpecView& spec) {
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

double energy_fraction(const Modes& m, Eigen::Index mode, std::initializer_list<int> dofs) {
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

std::vector<Eigen::Index> modes_in(const Modes& m, std::initializer_list<int> dofs, double share) {
  std::vector<Eigen::Index> out;
  for (Eigen::Index i = 0; i < m.omega.size(); ++i) {
    if (energy_fraction(m, i, dofs) > share) out.push_back(i);
  }
  return out;
}

Eigen::VectorXd static_displacement(const ntn::SpecView& spec, const Eigen::VectorXd& P) {
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

Eigen::MatrixXd hinge_b(const ntn::SpecView& spec, const ntn::HingeSpec& h) {
  Eigen::Matrix3d T;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c)
      T(r, c) = h.frame[static_cast<std::size_t>(3 * r + c)];
  }
  const double ex = h.eccentricity[0], ey = h.eccentricity[1], ez = h.eccentricity[2];
  Eigen::Matrix3d E;  // (S 16)
  E << 0, ez, -ey, -ez, 0, ex, ey, -ex, 0;
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(6, dofs_of(spec));
  const Eigen::Index n1 = ntn::kDofsPerNode * h.node1;
  B.block<3, 3>(0, n1) = -T;
  B.block<3, 3>(0, n1 + 3) = -T * E;
  B.block<3, 3>(3, n1 + 3) = -T;
  if (h.node2 != ntn::kGround) {
    const Eigen::Index n2 = ntn::kDofsPerNode * h.node2;
    B.block<3, 3>(0, n2) = T;
    B.block<3, 3>(3, n2 + 3) = T;
  }
  return B;
}

Eigen::Matrix<double, 6, 1> hinge_relative_displacement(const ntn::SpecView& spec,
                                                        const ntn::HingeSpec& h, const double* u) {
  const Eigen::MatrixXd B = hinge_b(spec, h);
  return B * Eigen::Map<const Eigen::VectorXd>(u, B.cols());
}

Eigen::MatrixXd rigid_constraints(const ntn::SpecView& spec) {
  std::vector<Eigen::VectorXd> rows;
  for (const ntn::HingeSpec& h : spec.hinges) {
    const Eigen::MatrixXd B = hinge_b(spec, h);
    for (int k = 0; k < 6; ++k) {
      if (h.behaviour[static_cast<std::size_t>(k)] == ntn::HingeBehaviour::kRigid)
        rows.push_back(B.row(k).transpose());
    }
  }
  Eigen::MatrixXd C(static_cast<Eigen::Index>(rows.size()), dofs_of(spec));
  for (std::size_t i = 0; i < rows.size(); ++i)
    C.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
  return C;
}

Eigen::MatrixXd hinge_spring_stiffness(const ntn::SpecView& spec, double penalty_t,
                                       double penalty_r) {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(dofs_of(spec), dofs_of(spec));
  for (const ntn::HingeSpec& h : spec.hinges) {
    const Eigen::MatrixXd B = hinge_b(spec, h);
    for (int k = 0; k < 6; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      double s = 0;
      if (h.behaviour[kk] == ntn::HingeBehaviour::kLinear) s = h.stiffness[kk];
      if (h.behaviour[kk] == ntn::HingeBehaviour::kRigid) s = k < 3 ? penalty_t : penalty_r;
      if (s != 0) K += s * B.row(k).transpose() * B.row(k);
    }
  }
  return K;
}

Modes constrained_modes(const ntn::SpecView& spec) {
  const std::vector<Eigen::Index> d = free_dofs(spec);
  const auto n = static_cast<Eigen::Index>(d.size());
  const Eigen::MatrixXd Kfull = global_stiffness(spec) + hinge_spring_stiffness(spec);
  const Eigen::MatrixXd Cfull = rigid_constraints(spec);
  Modes out;
  out.mass = lumped_mass(spec);
  Eigen::MatrixXd C(Cfull.rows(), n);
  for (Eigen::Index i = 0; i < n; ++i)
    C.col(i) = Cfull.col(d[static_cast<std::size_t>(i)]);
  Eigen::MatrixXd Z;
  if (C.rows() == 0) {
    Z = Eigen::MatrixXd::Identity(n, n);
  } else {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeFullV);
    const Eigen::VectorXd sv = svd.singularValues();
    Eigen::Index rank = 0;
    for (Eigen::Index i = 0; i < sv.size(); ++i)
      rank += sv(i) > 1e-12 * sv(0) ? 1 : 0;
    Z = svd.matrixV().rightCols(n - rank);
  }
  Eigen::VectorXd m(n);
  for (Eigen::Index i = 0; i < n; ++i)
    m(i) = out.mass(d[static_cast<std::size_t>(i)]);
  const Eigen::MatrixXd K = Z.transpose() * restrict_to(Kfull, d) * Z;
  const Eigen::MatrixXd M = Z.transpose() * m.asDiagonal() * Z;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
  if (eig.info() != Eigen::Success) throw std::runtime_error("constrained eigen solver failed");
  out.omega = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const Eigen::MatrixXd phi = Z * eig.eigenvectors();  // free DOFs x modes, phi^T M phi = I
  out.shapes = Eigen::MatrixXd::Zero(dofs_of(spec), phi.cols());
  for (Eigen::Index i = 0; i < n; ++i)
    out.shapes.row(d[static_cast<std::size_t>(i)]) = phi.row(i);
  return out;
}

double assembled_stable_step(const ntn::SpecView& spec, double penalty_t, double penalty_r) {
  const Eigen::VectorXd m = lumped_mass(spec);
  std::vector<Eigen::Index> d;
  for (const Eigen::Index j : free_dofs(spec)) {
    if (m(j) > 0) d.push_back(j);
  }
  const Eigen::MatrixXd K =
      global_stiffness(spec) + hinge_spring_stiffness(spec, penalty_t, penalty_r);
  const auto n = static_cast<Eigen::Index>(d.size());
  Eigen::VectorXd s(n);
  for (Eigen::Index i = 0; i < n; ++i)
    s(i) = 1.0 / std::sqrt(m(d[static_cast<std::size_t>(i)]));
  const Eigen::MatrixXd A = s.asDiagonal() * restrict_to(K, d) * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A, Eigen::EigenvaluesOnly);
  if (eig.info() != Eigen::Success) throw std::runtime_error("eigen solver failed");
  return 2.0 / std::sqrt(eig.eigenvalues().maxCoeff());
}

double modal_coordinate(const Modes& m, Eigen::Index mode, const double* u) {
  double q = 0;
  for (Eigen::Index j = 0; j < m.shapes.rows(); ++j)
    q += m.shapes(j, mode) * m.mass(j) * u[j];
  return q;
}

}  // namespace ntn_test
