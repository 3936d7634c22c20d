// The modal analysis' eigensolvers (modal.cpp, stage 5): the lowest eigenpairs of the reduced
// standard problem A y = omega^2 y, dense (Eigen) or by shift-invert Lanczos (Spectra).
#pragma once

#include <string>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "ntn/modal/modal.hpp"

namespace ntn::modal::detail {

// A number in a note or an error, to six significant digits.
std::string num(double v);

// Every eigenpair of A (its lower triangle read), dense; the lowest `want` kept. False, with
// r.error, when the solver did not converge; r.solver set.
bool solve_dense(const Eigen::SparseMatrix<double>& A, int want, ModalResult& r,
                 Eigen::VectorXd& lambda, Eigen::MatrixXd& Y);

// The lowest `want` eigenpairs of A (np x np) about options.shift (-1 when A is singular at 0).
// False, with r.error, when the factorization or the iteration failed; r.solver, r.shift,
// r.iterations and r.operations set, a note when the shift moved.
bool solve_sparse(const Eigen::SparseMatrix<double>& A, int np, int want,
                  const ModalOptions& options, ModalResult& r, Eigen::VectorXd& lambda,
                  Eigen::MatrixXd& Y);

}  // namespace ntn::modal::detail
