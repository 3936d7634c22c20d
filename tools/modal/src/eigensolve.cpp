#include "eigensolve.hpp"

#include <Spectra/SymEigsShiftSolver.h>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>

namespace ntn::modal::detail {
namespace {

using SpMat = Eigen::SparseMatrix<double>;

// Shift-invert operator for Spectra: y = (A - sigma I)^-1 x by a sparse LDL^T (AMD ordering).
class ShiftSolve {
 public:
  using Scalar = double;
  explicit ShiftSolve(const SpMat& a) : a_(a) {}
  Eigen::Index rows() const { return a_.rows(); }
  Eigen::Index cols() const { return a_.cols(); }
  void set_shift(const double& sigma) {
    if (factored_ && sigma == sigma_) return;  // Spectra's constructor sets it again
    factored_ = true, sigma_ = sigma;
    SpMat s = a_;
    if (sigma != 0.0) {
      for (Eigen::Index i = 0; i < s.rows(); ++i)
        s.coeffRef(i, i) -= sigma;
    }
    ldlt_.compute(s);
    ok_ = ldlt_.info() == Eigen::Success;
    if (ok_) {
      const Eigen::VectorXd d = ldlt_.vectorD();
      // Positive definite to working precision; a pivot near zero is a rigid-body mode at sigma.
      ok_ = d.minCoeff() > 1e-13 * d.cwiseAbs().maxCoeff();
    }
  }
  void perform_op(const double* x, double* y) const {
    Eigen::Map<Eigen::VectorXd>(y, a_.rows()) =
        ldlt_.solve(Eigen::Map<const Eigen::VectorXd>(x, a_.rows()));
  }
  bool ok() const { return ok_; }

 private:
  const SpMat& a_;
  Eigen::SimplicialLDLT<SpMat, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt_;
  bool ok_ = false;
  bool factored_ = false;
  double sigma_ = 0;
};

}  // namespace

bool solve_dense(const SpMat& A, int want, ModalResult& r, Eigen::VectorXd& lambda,
                 Eigen::MatrixXd& Y) {
  r.solver = Solver::kDense;
  const Eigen::MatrixXd Ad = Eigen::MatrixXd(A);  // the solver reads the lower triangle
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Ad);
  if (es.info() != Eigen::Success) {
    r.error = "the dense eigensolver did not converge";
    return false;
  }
  lambda = es.eigenvalues().head(want);
  Y = es.eigenvectors().leftCols(want);
  return true;
}

bool solve_sparse(const SpMat& A, int np, int want, const ModalOptions& options, ModalResult& r,
                  Eigen::VectorXd& lambda, Eigen::MatrixXd& Y) {
  r.solver = Solver::kSparse;
  const SpMat Al = SpMat(A.triangularView<Eigen::Lower>());
  ShiftSolve op(Al);
  double sigma = options.shift;
  op.set_shift(sigma);
  if (!op.ok() && sigma == 0.0) {
    sigma = -1.0;
    op.set_shift(sigma);
    r.notes.push_back("the stiffness is singular (rigid-body modes): shift -1 rad^2/s^2");
  }
  if (!op.ok()) {
    r.error =
        "the sparse factorization of A - sigma I failed (sigma = " + num(sigma) + " rad^2/s^2)";
    return false;
  }
  r.shift = sigma;
  const int ncv = std::min(
      np, options.lanczos_vectors > 0 ? options.lanczos_vectors : std::max(2 * want + 1, 20));
  try {
    Spectra::SymEigsShiftSolver<ShiftSolve> eigs(op, want, ncv, sigma);
    eigs.init();
    const Eigen::Index nconv = eigs.compute(Spectra::SortRule::LargestMagn, options.max_iterations,
                                            options.tolerance, Spectra::SortRule::SmallestAlge);
    r.iterations = static_cast<int>(eigs.num_iterations());
    r.operations = static_cast<int>(eigs.num_operations());
    if (eigs.info() != Spectra::CompInfo::Successful || nconv < want) {
      r.error = "the sparse eigensolver converged " + std::to_string(nconv) + " of " +
                std::to_string(want) + " modes in " + std::to_string(r.iterations) +
                " restarts (raise max_iterations or lanczos_vectors)";
      return false;
    }
    lambda = eigs.eigenvalues();
    Y = eigs.eigenvectors();
  } catch (const std::exception& e) {
    r.error = std::string("the sparse eigensolver failed: ") + e.what();
    return false;
  }
  return true;
}

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

}  // namespace ntn::modal::detail
