// The step's energy books over the DOFs (DESIGN §5): the sums of the central difference scheme's
// discrete work-energy identity that need every DOF, computed in the step's own DOF pass (a model
// without hinges, dof_pass.hpp) or in one pass after the constraint stages (a model with hinges),
// when Model::books is on. With Delta_n = (u_{n+1} - u_{n-1}) / 2 = dt (v_{n-1/2} + v_{n+1/2}) / 2
// and the damping velocity v_d (v_{n-1/2}, the lagged damping of S 3-4):
//   external  Delta . P_n
//   internal  Delta . F_n              (elements, hinge springs and dashpots)
//   damping   Delta . alpha M v_d
//   kinetic   1/2 v_{n+1/2}^T M v_{n+1/2}
// The hinge stages' own works (a spring direction's law, the slips, the stops) are per hinge: the
// energy books of a run (hil/energy.hpp) add them.
//
// The order of the sums is fixed whatever does them (the scalar path, the SIMD path of any width,
// any team): within a book group of kBookNodes nodes DOF j goes to partial j % 8 in DOF order,
// the 8 partials are added by one tree into the group's sum (Scratch::group_books), and the
// groups' sums are added in group order (books_total). A team's workers take whole groups.
#pragma once

#include <array>
#include <cstddef>

namespace ntn {

// The step's sums over the DOFs, J (the header's list). Scratch::books: written by the step when
// Model::books is on, read by the caller.
struct StepBooks {
  double external = 0;
  double internal = 0;
  double damping = 0;
  double kinetic = 0;  // at v_{n+1/2}
};

inline constexpr std::size_t kBookAccounts = 4;  // StepBooks' fields, in their order
inline constexpr std::size_t kBookLanes = 8;     // partials per account within a group
inline constexpr std::size_t kBookNodes = 16;    // nodes per book group (the last may have fewer)

constexpr std::size_t book_groups(std::size_t nodes) {
  return (nodes + kBookNodes - 1) / kBookNodes;
}

// One group's sums: external, internal, damping, 2 x kinetic (m v v: the 1/2 is applied once, in
// books_total).
using GroupBooks = std::array<double, kBookAccounts>;

// The partials of the group being summed, by account and lane.
struct BookPartials {
  double p[kBookAccounts][kBookLanes] = {};
};

namespace detail {

// DOF j's terms into the partials: delta = dt/2 (v_{n-1/2} + v_{n+1/2}), c = alpha m v_d (the
// damping force), v = v_{n+1/2}.
inline void book_dof(BookPartials& b, std::size_t j, double half_dt, double v0, double v, double p,
                     double f, double c, double m) {
  const std::size_t l = j % kBookLanes;
  const double delta = half_dt * (v0 + v);
  b.p[0][l] += delta * p;
  b.p[1][l] += delta * f;
  b.p[2][l] += delta * c;
  b.p[3][l] += (m * v) * v;
}

// The tree that adds a group's 8 partials: ((p0 + p4) + (p2 + p6)) + ((p1 + p5) + (p3 + p7)), the
// order in which a vector of 8, 4, 2 or 1 lanes folds its halves.
inline double fold_partials(const double* p) {
  const double q0 = p[0] + p[4], q1 = p[1] + p[5], q2 = p[2] + p[6], q3 = p[3] + p[7];
  return (q0 + q2) + (q1 + q3);
}

// The group's sums into `out`, the partials cleared for the next group.
inline void flush_group(BookPartials& b, double* out) {
  for (std::size_t a = 0; a < kBookAccounts; ++a) {
    out[a] = fold_partials(b.p[a]);
    for (double& x : b.p[a])
      x = 0.0;
  }
}

}  // namespace detail

// The step's sums from the groups' (in group order: 4 chains, group g into chain g % 4, added as
// (c0 + c2) + (c1 + c3)).
inline StepBooks books_total(const GroupBooks* groups, std::size_t count) {
  double c[4][kBookAccounts] = {};
  for (std::size_t g = 0; g < count; ++g) {
    for (std::size_t a = 0; a < kBookAccounts; ++a)
      c[g % 4][a] += groups[g][a];
  }
  double s[kBookAccounts];
  for (std::size_t a = 0; a < kBookAccounts; ++a)
    s[a] = (c[0][a] + c[2][a]) + (c[1][a] + c[3][a]);
  return {s[0], s[1], s[2], 0.5 * s[3]};
}

}  // namespace ntn
