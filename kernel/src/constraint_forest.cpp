// build_forest (constraint_forest.hpp, DESIGN §7.1): the forest's constant matrices, built once
// at init with Eigen's fixed-size 6x6 algebra. Compiled once here, so that the step's headers do
// not carry Eigen into every program that includes them.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cstdint>
#include <span>

#include "ntn/constraint_forest.hpp"
#include "ntn/forest_matrices.hpp"

namespace ntn {

namespace detail {
namespace {

// Inverse on the DOFs in `keep` (bit mask), zero elsewhere. False if that block is not SPD.
bool masked_inverse(const M6& m, std::uint8_t keep, M6& out) {
  int idx[6], n = 0;
  for (int i = 0; i < 6; ++i) {
    if ((keep >> i) & 1U) idx[n++] = i;
  }
  out.setZero();
  if (n == 0) return true;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6> sub(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j)
      sub(i, j) = m(idx[i], idx[j]);
  }
  const Eigen::LLT<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>> llt(sub);
  if (llt.info() != Eigen::Success) return false;
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6> inv =
      llt.solve(Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>::Identity(n, n));
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j)
      out(idx[i], idx[j]) = inv(i, j);
  }
  return true;
}

}  // namespace
}  // namespace detail

ForestBuild build_forest(std::span<const HingeData> hinges, std::span<const NodeSpec> nodes,
                         std::span<const double> mass, std::span<std::int32_t> node_tree,
                         std::span<ForestEdge> edges, std::span<ForestEdgeMatrices> mats,
                         std::span<ForestRoot> roots, std::span<ForestWork> work,
                         std::span<std::uint8_t> held) {
  using detail::M6;
  ForestBuild out = forest_topology(hinges, nodes, mass, node_tree, edges, roots, work);
  for (auto& h : held)
    h = 0;
  if (!out.status.ok()) return out;
  const int written = out.edges;

  // 3. Matrices, leaves first: each child's effective mass is its own plus what its children
  // hand up (DESIGN §7.1).
  for (int k = written - 1; k >= 0; --k) {
    ForestEdge& e = edges[static_cast<std::size_t>(k)];
    ForestEdgeMatrices& mx = mats[static_cast<std::size_t>(k)];
    const HingeData& h = hinges[static_cast<std::size_t>(e.hinge)];
    M6 mc = detail::own_mass(mass, e.child);
    for (int j = k + 1; j < written; ++j) {
      if (edges[static_cast<std::size_t>(j)].parent == e.child)
        mc += detail::to_m6(work[static_cast<std::size_t>(j)].mass_up);
    }
    // d_L = T [u2 - u1 - phi1 x e; phi2 - phi1] (DESIGN §7): the lever arm e turns with node 1.
    // So the link X(e) sits on node 1's side: on the child when it is node 1 (q = T X(e) a_c,
    // tied to T a_p), on the parent when the child is node 2 (q = T a_c, tied to T X(e) a_p).
    const M6 t6 = detail::frame6(h);
    const M6 x = e.sign > 0 ? detail::link(h.eccentricity, 1.0) : M6::Identity();
    const M6 tp = t6 * (e.sign > 0 ? M6::Identity() : detail::link(h.eccentricity, 1.0));
    const M6 y = t6 * x;
    M6 xinv = M6::Identity();
    xinv.topRightCorner<3, 3>() = -x.topRightCorner<3, 3>();
    const M6 yinv = xinv * t6.transpose();
    const M6 mq = yinv.transpose() * mc * yinv;

    std::uint8_t rigid_mask = h.rigid, free_mask = 0;
    for (int d = 0; d < 6; ++d) {
      if ((rigid_mask >> d) & 1U) continue;
      if (mq(d, d) > 0) {
        free_mask |= static_cast<std::uint8_t>(1U << d);
      } else {
        ++out.held_dofs;  // a free direction without mass: a mechanism, held (q_d = 0)
      }
    }
    M6 g = M6::Zero();
    for (int d = 0; d < 6; ++d)
      g(d, d) = (rigid_mask >> d) & 1U ? 1.0 : 0.0;
    M6 ainv;
    if (!detail::masked_inverse(mq, free_mask, ainv)) {
      out.status = {InitError::kMechanism, e.hinge};
      return out;
    }
    const M6 id = M6::Identity();
    const M6 s = g * (mq - mq * ainv * mq) * g;
    work[static_cast<std::size_t>(k)].mass_up = detail::to_mat6(tp.transpose() * s * tp);
    mx.up = detail::to_mat6(tp.transpose() * g * (id - mq * ainv) * yinv.transpose());
    mx.down_a = detail::to_mat6(yinv * (id - ainv * mq) * g * tp);
    mx.down_r = detail::to_mat6(yinv * ainv * yinv.transpose());
    mx.proj_p = detail::to_mat6(yinv * g * tp);
    mx.proj_c = detail::to_mat6(yinv * g * y);
    mx.force_a = detail::to_mat6(g * mq * y);
    mx.force_r = detail::to_mat6(g * yinv.transpose());
    if (e.parent == kGround) mx.down_a = Mat6{}, mx.proj_p = Mat6{};
    // Aligned: the matrices the step uses are diagonal, and up = down_a = proj_p = proj_c (a
    // ground edge uses only proj_c and down_r).
    Diag6 up_d, down_a_d, proj_p_d;
    e.aligned = detail::diagonal_of(mx.proj_c, e.rigid_d) &&
                detail::diagonal_of(mx.down_r, e.down_r_d) &&
                (e.parent == kGround ||
                 (detail::diagonal_of(mx.up, up_d) && detail::diagonal_of(mx.down_a, down_a_d) &&
                  detail::diagonal_of(mx.proj_p, proj_p_d) && detail::same(up_d, e.rigid_d) &&
                  detail::same(down_a_d, e.rigid_d) && detail::same(proj_p_d, e.rigid_d)));
  }

  // 4. Roots: inverse effective mass on the DOFs that are neither supported nor massless.
  for (int r = 0; r < out.roots; ++r) {
    ForestRoot& root = roots[static_cast<std::size_t>(r)];
    M6 m = detail::own_mass(mass, root.node);
    for (int j = 0; j < written; ++j) {
      if (edges[static_cast<std::size_t>(j)].parent == root.node)
        m += detail::to_m6(work[static_cast<std::size_t>(j)].mass_up);
    }
    std::uint8_t keep = 0;
    const std::uint8_t fixed = nodes[static_cast<std::size_t>(root.node)].fixed;
    for (int d = 0; d < 6; ++d) {
      if ((fixed >> d) & 1U) continue;
      if (m(d, d) > 0) {
        keep |= static_cast<std::uint8_t>(1U << d);
      } else {
        held[static_cast<std::size_t>(root.node)] |= static_cast<std::uint8_t>(1U << d);
        ++out.held_dofs;
      }
    }
    M6 inv;
    if (!detail::masked_inverse(m, keep, inv)) {
      out.status = {InitError::kMechanism, root.node};
      return out;
    }
    root.inv_mass = detail::to_mat6(inv);
    root.diagonal = detail::diagonal_of(root.inv_mass, root.inv_mass_d);
  }
  return out;
}

}  // namespace ntn
