// The kinematics of a model's supports and hinges for modal analysis (DESIGN §7, §7.1): every
// admissible displacement is u = T q, with q the independent coordinates left after the supports
// and the rigid hinge directions are tied exactly.
//
// T is built over the kernel's own constraint forest (ntn::forest_topology, the one ntn_exact's
// step uses): rigid hinge directions join nodes into trees, rooted at the ground (a hinge to the
// ground: an inclined support), at the supported node, or at the node with the most rigid hinges
// (then the heaviest, then the lowest index). A root's unsupported DOFs are
// coordinates. A child c joined to its parent p by hinge h (frame T_R, T = diag(T_R, T_R),
// eccentricity e, X(e) = [I E; 0 I] with E phi = phi x e, G / H selecting the rigid / other rows)
// takes the hinge-frame motion q_h = Y x_c, Y = T X(e) when c is node 1 and Y = T when c is
// node 2, whose rigid rows equal those of the parent's, Y_p x_p with Y_p = T (c node 1) or
// T X(e) (c node 2), and whose other rows are new coordinates s:
//
//     x_c = Y^-1 (G G^T Y_p x_p + H s)        (x_p = 0 for the ground)
//
// which is DESIGN §7's d_L = T [u2 - u1 - phi1 x e; phi2 - phi1] with G^T d_L = 0, solved for
// the child. Chains and several hinges per node follow by recursion down the tree; columns are
// numbered group by group (a tree, or a node in no tree), so T^T M T is block diagonal with one
// block per group.
#pragma once

#include <Eigen/SparseCore>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "ntn/model_spec.hpp"

namespace ntn::modal {

// A hinge as modal analysis sees it: each local direction tied exactly (`rigid` bit), a linear
// spring, or free (stiffness 0). Dashpots are left out: undamped modes.
struct LinearHinge {
  std::uint8_t rigid = 0;             // bit k: direction k is tied exactly
  std::array<double, 6> stiffness{};  // N/m or N m/rad in the other directions (0: free)
};

struct HingeLinearization {
  std::vector<LinearHinge> hinges;  // one per spec hinge
  std::vector<std::string> notes;   // how curves were read, dashpots left out
  std::string error;                // empty: ok
};

// Linearizes every hinge about the undeformed state (u = 0):
// - rigid: tied (or, with `penalty_as_springs`, a spring of the model's penalty stiffness);
// - free: free; linear: a spring k (0: free); the dashpot is left out;
// - curve: split into its spring part and rigid branches with the model's limit stiffness, as the
//   kernel does (ntn::curve_branches). When the origin lies strictly on a rigid branch (d = 0
//   outside the spring part) the direction is tied; otherwise it is a spring whose stiffness is
//   the curve's slope at d = 0 (an end segment extrapolated if 0 lies beyond the points). Where 0
//   is a breakpoint the two adjacent slopes differ, and the mean is used, with a note; at the
//   start of a rigid branch (a stop touching at rest) the spring side's slope is used, with a
//   note: a small vibration there is one-sided and has no single linear frequency.
// Errors: a hinge the kernel would refuse (ntn::make_hinge_data), or penalty springs asked for
// without a penalty stiffness.
HingeLinearization linearize_hinges(const SpecView& spec, bool penalty_as_springs = false);

// A set of coordinates of T: a rigid tree, or one node in no tree. Its columns touch only the
// DOFs of its nodes.
struct ConstraintGroup {
  int first_column = 0;  // columns [first_column, first_column + columns)
  int columns = 0;
  std::vector<int> nodes;  // ascending
  int root = -2;           // root node of a tree, kGround (-1), or -2 for a node in no tree
};

struct ConstraintMap {
  Eigen::SparseMatrix<double> T;  // dofs x coordinates, u = T q
  std::vector<ConstraintGroup> groups;
  int trees = 0;      // rigid trees (groups with a hinge)
  std::string error;  // empty: ok
};

// Builds T for the supports (NodeSpec::fixed, global axes, held at zero) and the rigid directions
// of `hinges` (linearize_hinges). Refused by the kernel's rule (ntn::for_each_rigid_cycle), as the
// model compiler refuses them: a rigid hinge that closes a cycle, or a tree that reaches the
// ground twice (two supported nodes, or a supported node and a hinge to the ground).
ConstraintMap build_constraints(const SpecView& spec, const std::vector<LinearHinge>& hinges);

}  // namespace ntn::modal
