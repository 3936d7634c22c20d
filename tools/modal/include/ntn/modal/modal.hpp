// Modal analysis of a model as the kernel sees it (DESIGN §9): the undamped generalized
// eigenproblem K phi = omega^2 M phi of the kernel's own element stiffness and lumped (HRZ) mass,
// with supports and rigid hinge directions tied exactly (u = T q, constraints.hpp), linear hinge
// directions as springs, mechanisms removed and massless coordinates condensed statically.
// Frequencies, mass-normalized mode shapes, participation factors, effective modal masses, MAC.
// tools/modal/README.md gives the equations.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "ntn/model_spec.hpp"

namespace ntn::modal {

enum class Solver : std::uint8_t {
  kAuto,    // dense up to ModalOptions::dense_limit reduced DOFs, sparse above
  kDense,   // Eigen::SelfAdjointEigenSolver on the whole reduced problem
  kSparse,  // Spectra, symmetric Lanczos in shift-invert mode (sparse LDL^T of A - sigma I)
};

struct ModalOptions {
  int modes = 12;  // lowest modes wanted; <= 0: all of them (dense)
  Solver solver = Solver::kAuto;
  int dense_limit = 3000;           // kAuto: dense when the reduced problem is at most this
  double shift = 0.0;               // rad^2/s^2, sparse: the shift sigma (modes nearest it)
  double tolerance = 1e-12;         // sparse: Spectra's relative tolerance on Ritz values
  int max_iterations = 1000;        // sparse: restarts of the Lanczos iteration
  int lanczos_vectors = 0;          // sparse: Spectra's ncv; 0 = max(2 modes + 1, 20)
  bool penalty_as_springs = false;  // rigid hinge directions as the model's penalty springs
                                    // (what `penalty` integrates) instead of exact ties
  // The geometric stiffness of the preload's axial forces (p_delta, leaning and corotational
  // elements); false: K alone, the frequencies of the same model without second-order geometry.
  bool geometric = true;
};

// DOFs removed as a mechanism: zero effective mass and no stiffness (the kernel holds them at
// zero, the model compiler reports them). Bits as NodeSpec::fixed, global axes.
struct Mechanism {
  int node = 0;
  std::uint8_t dofs = 0;
};

struct ModalResult {
  std::string error;  // empty: ok
  bool ok() const { return error.empty(); }

  // Sizes: physical DOFs (6 per node), independent coordinates after supports and rigid hinge
  // directions, and the eigenproblem solved (after mechanisms and massless coordinates).
  int dofs = 0;
  int coordinates = 0;
  int reduced = 0;
  int trees = 0;                  // rigid hinge trees
  int mechanism_dofs = 0;         // coordinates removed as mechanisms
  int condensed = 0;              // massless coordinates with stiffness, condensed statically
  Solver solver = Solver::kAuto;  // the one used
  double shift = 0;               // rad^2/s^2, sparse: the shift used
  int iterations = 0;             // sparse: Lanczos restarts
  int operations = 0;             // sparse: solves with the factorization
  // Wall time of the stages, s: assembly of K, M and T, T^T K T and T^T M T; the reduction to
  // the standard problem (mass blocks, mechanisms, condensation); the eigensolver (with the
  // sparse factorization); shapes, participation and effective masses.
  struct Seconds {
    double assembly = 0, reduction = 0, eigensolver = 0, results = 0;
  } seconds;

  Eigen::VectorXd omega;               // rad/s, ascending
  Eigen::VectorXd frequency;           // Hz
  Eigen::VectorXd period;              // s (infinity for a rigid-body mode)
  Eigen::MatrixXd shapes;              // dofs x modes, phi^T M phi = 1; the first entry of at least
                                       // a tenth of the largest magnitude is positive
  Eigen::MatrixXd participation;       // modes x 3: Gamma = phi^T M iota_d, d = x, y, z (kg^1/2)
  Eigen::MatrixXd effective_mass;      // modes x 3: Gamma^2, kg
  std::array<double, 3> total_mass{};  // kg: lumped mass of the DOFs no support holds
  std::array<double, 3> reachable_mass{};  // kg: effective masses summed over all modes
  Eigen::VectorXd damping_ratio;  // alpha / (2 omega) + beta omega / 2: the model's Rayleigh
                                  // damping C = alpha M + beta K_el (hinge dashpots left out)

  std::vector<Mechanism> mechanisms;
  std::vector<std::string> notes;

  int modes() const { return static_cast<int>(omega.size()); }
  // Mode `mode`'s value at node DOF (node, dof), global axes.
  double shape(int mode, int node, int dof) const;
  // Effective mass of `mode` along d (0..2) as a fraction of total_mass[d], and the cumulative
  // fraction of modes 0..mode.
  double mass_fraction(int mode, int d) const;
  double cumulative_fraction(int mode, int d) const;
};

ModalResult modal_analysis(const SpecView& spec, const ModalOptions& options = {});

// The static displacement under a constant load (DESIGN §5, the gravity preload): K u = P with
// the kernel's own K (elements and hinge springs, as modal_analysis assembles it), supports and
// rigid hinge directions tied exactly (u = T q; under the `penalty` method rigid directions are
// its penalty springs, as the kernel integrates them), curves linearized about u = 0
// (linearize_hinges, whose notes are passed on). Solved once with a sparse LDL^T. Coordinates
// with no stiffness (mechanisms, which the kernel holds at zero) are left at zero; a load on one,
// or a structure that can move as a rigid body, is an error.
struct StaticResult {
  std::string error;  // empty: ok
  bool ok() const { return error.empty(); }
  std::vector<double> u;           // 6 per node, global axes
  double relative_residual = 0;    // |T^T (K u - P)| / |T^T P| of the solution
  std::vector<std::string> notes;  // how curves were linearized
};

StaticResult static_solution(const SpecView& spec, std::span<const double> load);

// A measured channel: node DOF in global axes.
struct Channel {
  int node = 0;
  int dof = 0;
};

// The modes' values at the channels: channels x modes (a mode shape as sensors see it).
Eigen::MatrixXd shapes_at(const ModalResult& r, std::span<const Channel> channels);

// Modal assurance criterion |a^H b|^2 / ((a^H a)(b^H b)): 1 for parallel shapes, 0 for
// orthogonal ones (Allemang and Brown). 0 when either vector is zero.
double mac(const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& b);
double mac(const Eigen::Ref<const Eigen::VectorXcd>& a,
           const Eigen::Ref<const Eigen::VectorXcd>& b);
// MAC of every column of A against every column of B (A.cols() x B.cols()).
Eigen::MatrixXd mac_matrix(const Eigen::Ref<const Eigen::MatrixXd>& A,
                           const Eigen::Ref<const Eigen::MatrixXd>& B);

// The mode table: mode, frequency (Hz), period (s), effective mass along x, y, z in % of the
// total mass and its cumulative sum; then the totals, mechanisms and notes.
std::string mode_table(const ModalResult& r);
void print_mode_table(std::FILE* out, const ModalResult& r);

}  // namespace ntn::modal
