// Dense global matrices of a model, for reference solutions in tests (heap and exceptions
// allowed here, never in the kernel). Built with the kernel's own element functions
// (ntn::beam_geometry, ntn::beam_stiffness, ntn::beam_global_stiffness through
// ntn::modal::for_each_element_stiffness, and ntn::assemble_lumped_mass) so that what is compared
// is the kernel's discrete model. The eigenproblems and hinge rows below are written here from
// the equations, independently of the modal analysis library (tools/modal), which the tests
// check against them. The definitions are compiled once, in assemble.cpp (Eigen's dense
// eigensolvers, LU and SVD are costly to instantiate in every test).
#pragma once

#include <Eigen/Core>
#include <initializer_list>
#include <span>
#include <stdexcept>
#include <vector>

#include "ntn/beam.hpp"
#include "ntn/modal/assembly.hpp"
#include "ntn/model.hpp"
#include "ntn/model_spec.hpp"

namespace ntn_test {

Eigen::Index dofs_of(const ntn::SpecView& spec);

// K = sum over elements of the 12x12 T^T K_L T scattered to the elements' nodes (the element
// visitor ntn::modal::for_each_element_stiffness, shared with the modal analysis library).
Eigen::MatrixXd global_stiffness(const ntn::SpecView& spec);

// Diagonal of the lumped (HRZ + point) mass, as ntn::init assembles it.
Eigen::VectorXd lumped_mass(const ntn::SpecView& spec);

// Global indices of the DOFs not held by a support, ascending.
std::vector<Eigen::Index> free_dofs(const ntn::SpecView& spec);

Eigen::MatrixXd restrict_to(const Eigen::MatrixXd& A, const std::vector<Eigen::Index>& d);

// Undamped modes of K phi = omega^2 M phi on the free DOFs, with M diagonal: the symmetric
// problem M^-1/2 K M^-1/2 y = omega^2 y, phi = M^-1/2 y. Ascending omega; shapes full-size
// (zeros at supported DOFs) and mass-normalized (phi^T M phi = 1).
struct Modes {
  Eigen::VectorXd omega;   // rad/s
  Eigen::MatrixXd shapes;  // dofs x modes
  Eigen::VectorXd mass;    // the lumped mass diagonal used
};

Modes modes(const ntn::SpecView& spec);

// Share of a mode's kinetic energy (phi^T M phi restricted to some node DOFs): 1 for a mode that
// moves only in those DOFs.
double energy_fraction(const Modes& m, Eigen::Index mode, std::initializer_list<int> dofs);

// Modes (indices, ascending frequency) with more than `share` of their energy in `dofs`.
std::vector<Eigen::Index> modes_in(const Modes& m, std::initializer_list<int> dofs,
                                   double share = 0.99);

// Static displacement K u = P on the free DOFs (full-size result, zeros at supports).
Eigen::VectorXd static_displacement(const ntn::SpecView& spec, const Eigen::VectorXd& P);

// ---- Hinges (DESIGN §7), written from the equations, not from the kernel's hinge code ----

// B of one hinge (6 x dofs): d_L = B u with B = T [-I -E I 0; 0 -I 0 I], E the seed's (S 16)
// eccentricity matrix of e = x2 - x1. A ground hinge (node2 = kGround) has no node-2 columns.
Eigen::MatrixXd hinge_b(const ntn::SpecView& spec, const ntn::HingeSpec& h);

// Relative displacement d_L of hinge h for a full displacement vector u.
Eigen::Matrix<double, 6, 1> hinge_relative_displacement(const ntn::SpecView& spec,
                                                        const ntn::HingeSpec& h, const double* u);

// The rigid rows of every hinge's B, stacked: the constraints C u = 0 that ntn_exact holds.
Eigen::MatrixXd rigid_constraints(const ntn::SpecView& spec);

// Stiffness of the hinges' linear springs, sum B^T diag(k) B over `linear` directions (DESIGN
// §7); with `penalty_t` / `penalty_r` > 0 the rigid directions become springs of that stiffness.
Eigen::MatrixXd hinge_spring_stiffness(const ntn::SpecView& spec, double penalty_t = 0,
                                       double penalty_r = 0);

// Undamped modes of the hinged structure with its rigid hinge directions as exact constraints:
// K phi = omega^2 M phi on the free DOFs restricted to the null space of C (rigid_constraints),
// solved as Z^T K Z y = omega^2 Z^T M Z y with Z an orthonormal basis of that null space (SVD of
// C), phi = Z y. K includes the hinges' linear springs. Shapes are full-size and mass-normalized.
Modes constrained_modes(const ntn::SpecView& spec);

// Central difference's undamped stable step 2 / omega_max of the assembled system: elements,
// the hinges' linear springs and, with penalty_t / penalty_r > 0, penalty springs in the rigid
// directions, with the lumped mass on the free DOFs that have mass. The exact bound for that
// system, to check the kernel's estimate (DESIGN §6) against and to run penalty models safely.
double assembled_stable_step(const ntn::SpecView& spec, double penalty_t = 0, double penalty_r = 0);

// Modal coordinate of a displacement vector: phi_i^T M u (mass-normalized shapes).
double modal_coordinate(const Modes& m, Eigen::Index mode, const double* u);

}  // namespace ntn_test
