// The constraint forest alone (constraint_forest.hpp, DESIGN §7.1), against a dense reference.
// For forces R on nodes joined by rigid hinge directions C a = 0 (the rows of B of each rigid
// direction, hinge_direction, and a unit row per supported DOF), the constrained accelerations
// are those of the KKT system M a - C^T lambda = R, C a = 0, i.e. with the dense Schur complement
// S = C M^-1 C^T:
//     a = M^-1 (R - C^T S^-1 C M^-1 R).
// The forest's upward pass (forest_up), roots and downward pass (forest_down, in place, as the
// step calls them; and tree by tree, forest_tree_accelerations) must give the same a on a star, a
// chain and two trees each grounded once (one by a hinge to the ground, one by a supported root),
// with rotated and eccentric hinges (the general 6x6 path) and aligned centric ones (the diagonal
// path) mixed. And the cycle rule refuses the same tree grounded twice, naming the hinge that
// closes the cycle and the cycle's nodes.
//
// Tolerance: |a_forest - a_dense| <= 1e-10 max |a_dense|. Both are direct solves of the same
// linear system of at most 42 unknowns in double; the masses lie within a factor 10 of each other
// and the lever arms are of order 1 m, so the systems are well conditioned (below 1e4) and the
// two agree to about 1e-12 in practice; 1e-10 leaves room for the rounding of the dense LU. A
// wrong matrix (a lever arm on the wrong node, a missing rigid row, a wrong sign, a child's mass
// not handed to its parent) changes a at order 1.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "ntn/constraint_forest.hpp"
#include "ntn/hinge.hpp"
#include "ntn/hinge_methods.hpp"
#include "support/hinges.hpp"

namespace forest_test {

using ntn_test::Behaviour;

struct Forest {
  std::vector<ntn::NodeSpec> nodes;
  std::vector<ntn::HingeData> hinges;
  std::vector<double> mass;  // 6 per node
};

// A node at the origin (the forest needs only its support bits) with a mass that varies by node
// and direction (1..10 kg, kg m^2), so that no two directions are alike.
void add_node(Forest& f, std::uint8_t fixed = 0) {
  ntn::NodeSpec n;
  n.fixed = fixed;
  f.nodes.push_back(n);
  const double k = static_cast<double>(f.nodes.size());
  for (int d = 0; d < 6; ++d)
    f.mass.push_back(1.0 + static_cast<double>((3 * static_cast<int>(k) + 5 * d) % 10));
}

void add_hinge(Forest& f, const ntn::HingeSpec& spec) {
  ntn::Settings s;  // ntn_exact: rigid directions are NTN-coupled
  ntn::HingeData h;
  const std::array<ntn::CurveSpec, 0> no_curves{};
  const std::array<ntn::CurvePoint, 0> no_points{};
  ASSERT_TRUE(ntn::make_hinge_data(spec, s, f.nodes.size(), no_curves, no_points, h));
  f.hinges.push_back(h);
}

// Deterministic forces of order 1..10, all DOFs.
Eigen::VectorXd forces(std::size_t dofs) {
  Eigen::VectorXd r(static_cast<Eigen::Index>(dofs));
  for (Eigen::Index j = 0; j < r.size(); ++j)
    r(j) = static_cast<double>((7 * j + 3) % 19) - 9.0 + 0.25 * static_cast<double>(j % 4);
  return r;
}

// The dense reference: a = M^-1 (R - C^T S^-1 C M^-1 R), S = C M^-1 C^T.
Eigen::VectorXd dense_accelerations(const Forest& f, const Eigen::VectorXd& r) {
  const auto n = static_cast<Eigen::Index>(f.mass.size());
  std::vector<Eigen::VectorXd> rows;
  for (const ntn::HingeData& h : f.hinges) {
    for (std::size_t k = 0; k < 6; ++k) {
      if (!((h.rigid >> k) & 1U)) continue;
      double b1[6], b2[6];
      ntn::hinge_direction(h, k, b1, b2);
      Eigen::VectorXd c = Eigen::VectorXd::Zero(n);
      for (int d = 0; d < 6; ++d) {
        c(6 * h.node1 + d) += b1[d];
        if (h.node2 != ntn::kGround) c(6 * h.node2 + d) += b2[d];
      }
      rows.push_back(c);
    }
  }
  for (std::size_t i = 0; i < f.nodes.size(); ++i) {
    for (int d = 0; d < 6; ++d) {
      if (!((f.nodes[i].fixed >> d) & 1U)) continue;
      Eigen::VectorXd c = Eigen::VectorXd::Zero(n);
      c(static_cast<Eigen::Index>(6 * i) + d) = 1.0;
      rows.push_back(c);
    }
  }
  Eigen::MatrixXd C(static_cast<Eigen::Index>(rows.size()), n);
  for (std::size_t i = 0; i < rows.size(); ++i)
    C.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
  Eigen::VectorXd minv(n);
  for (Eigen::Index j = 0; j < n; ++j)
    minv(j) = 1.0 / f.mass[static_cast<std::size_t>(j)];
  const Eigen::MatrixXd cm = C * minv.asDiagonal();
  const Eigen::MatrixXd S = cm * C.transpose();
  const Eigen::VectorXd lambda = S.fullPivLu().solve(cm * r);
  return minv.asDiagonal() * (r - C.transpose() * lambda);
}

struct Built {
  ntn::ForestBuild fb;
  std::vector<std::int32_t> node_tree;
  std::vector<ntn::ForestEdge> edges;
  std::vector<ntn::ForestEdgeMatrices> mats;
  std::vector<ntn::ForestRoot> roots;
  std::vector<ntn::ForestTree> trees;
  int num_trees = 0;
};

Built build(const Forest& f) {
  Built b;
  const std::size_t nh = f.hinges.size();
  b.node_tree.resize(f.nodes.size());
  b.edges.resize(nh), b.mats.resize(nh), b.roots.resize(nh), b.trees.resize(nh);
  std::vector<ntn::ForestWork> work(nh);
  std::vector<std::uint8_t> held(f.nodes.size());
  b.fb = ntn::build_forest(f.hinges, f.nodes, f.mass, b.node_tree, b.edges, b.mats, b.roots, work,
                           held);
  b.num_trees = ntn::forest_trees(
      std::span<const ntn::ForestEdge>(b.edges.data(), static_cast<std::size_t>(b.fb.edges)),
      b.node_tree, b.trees);
  return b;
}

// Every node lies in a tree here: the forest gives every acceleration.
void expect_matches_dense(const Forest& f, int want_edges, int want_roots) {
  const Built b = build(f);
  ASSERT_TRUE(b.fb.status.ok()) << ntn::to_string(b.fb.status.error) << " at " << b.fb.status.where;
  ASSERT_EQ(b.fb.edges, want_edges);
  ASSERT_EQ(b.fb.roots, want_roots);
  ASSERT_EQ(b.fb.held_dofs, 0);
  int aligned = 0;
  for (int k = 0; k < b.fb.edges; ++k)
    aligned += b.edges[static_cast<std::size_t>(k)].aligned ? 1 : 0;
  // Both paths of the passes are exercised: diagonal (aligned) edges and general ones.
  EXPECT_GT(aligned, 0);
  EXPECT_LT(aligned, b.fb.edges);
  for (std::size_t i = 0; i < f.nodes.size(); ++i)
    ASSERT_GE(b.node_tree[i], 0) << "node " << i;

  const Eigen::VectorXd r = forces(f.mass.size());
  const Eigen::VectorXd want = dense_accelerations(f, r);
  const double tol = 1e-10 * want.cwiseAbs().maxCoeff();
  ASSERT_GT(want.cwiseAbs().maxCoeff(), 0.1);

  // As the step calls them: the upward pass over all edges, then the roots and the downward
  // pass, in place.
  std::vector<double> a(r.data(), r.data() + r.size());
  ntn::forest_up(b.edges, b.mats, b.fb.edges, a.data());
  ntn::forest_down(b.roots, b.fb.roots, b.edges, b.mats, b.fb.edges, a.data(), a.data());
  for (Eigen::Index j = 0; j < want.size(); ++j)
    EXPECT_NEAR(a[static_cast<std::size_t>(j)], want(j), tol) << "DOF " << j;

  // Tree by tree (the momentum clamp's solve): the same numbers.
  std::vector<double> rt(r.data(), r.data() + r.size()), at(a.size(), 0.0);
  for (int t = 0; t < b.num_trees; ++t)
    ntn::forest_tree_accelerations(b.trees[static_cast<std::size_t>(t)], b.roots, b.edges, b.mats,
                                   rt.data(), at.data());
  for (Eigen::Index j = 0; j < want.size(); ++j)
    EXPECT_NEAR(at[static_cast<std::size_t>(j)], want(j), tol) << "DOF " << j << " (by tree)";
}

const ntn_test::Mat3 kTurned = ntn_test::rotate_frame(
    ntn_test::kIdentity3, ntn_test::rotation({1, 2, 3}, 40 * ntn_test::kDegree));
const ntn_test::Mat3 kTurned2 = ntn_test::rotate_frame(
    ntn_test::kIdentity3, ntn_test::rotation({-2, 1, 1}, 25 * ntn_test::kDegree));

// A star: node 0 joined to four others, as node 2 of two hinges and node 1 of two (both signs),
// pins about different axes, turned and eccentric frames and an aligned centric one. No support:
// the root is node 0 (the most rigid hinges) and its full 6x6 effective mass is inverted.
TEST(Forest, StarMatchesTheDenseSchurComplement) {
  Forest f;
  for (int i = 0; i < 5; ++i)
    add_node(f);
  add_hinge(f, ntn_test::hinge(1, 0, ntn_test::kIdentity3, ntn_test::released(1U << ntn::kRy)));
  add_hinge(f,
            ntn_test::hinge(2, 0, kTurned, ntn_test::released(1U << ntn::kRz), {0.4, -0.3, 0.2}));
  add_hinge(f,
            ntn_test::hinge(0, 3, kTurned2, ntn_test::released((1U << ntn::kRx) | (1U << ntn::kUz)),
                            {-0.5, 0.1, 0.7}));
  add_hinge(f, ntn_test::hinge(0, 4, ntn_test::kIdentity3, ntn_test::kAllRigid, {0.0, 0.6, 0.0}));
  expect_matches_dense(f, 4, 1);
}

// A chain of six nodes, its first supported in translations: the root is the supported node and
// the rotations it leaves free are coordinates; the edges alternate signs and frames, so each
// child's effective mass collects a chain of Schur complements.
TEST(Forest, ChainMatchesTheDenseSchurComplement) {
  Forest f;
  add_node(f, 0x07);
  for (int i = 1; i < 6; ++i)
    add_node(f);
  add_hinge(f, ntn_test::hinge(1, 0, kTurned, ntn_test::released(1U << ntn::kRy), {0.3, 0.0, 0.1}));
  add_hinge(f, ntn_test::hinge(1, 2, ntn_test::kIdentity3, ntn_test::released(1U << ntn::kRz)));
  add_hinge(
      f, ntn_test::hinge(3, 2, kTurned2, ntn_test::released((1U << ntn::kRx) | (1U << ntn::kRz))));
  add_hinge(f, ntn_test::hinge(4, 3, ntn_test::kIdentity3, ntn_test::released(1U << ntn::kUx),
                               {0.0, 0.0, -0.4}));
  add_hinge(f, ntn_test::hinge(4, 5, ntn_test::kIdentity3, ntn_test::released(1U << ntn::kRx)));
  expect_matches_dense(f, 5, 1);
}

// Two trees, each grounded once: nodes 0-1-2 hang from the ground by a turned hinge to the ground
// (an inclined support) at node 0; nodes 3-4-5 hang from the supported node 3 (clamped in ux, uy,
// rz only). Both tree roots reach the ground; the second tree has a root in Model's sense, the
// first does not.
TEST(Forest, TwoGroundedTreesMatchTheDenseSchurComplement) {
  Forest f;
  for (int i = 0; i < 3; ++i)
    add_node(f);
  add_node(f, (1U << ntn::kUx) | (1U << ntn::kUy) | (1U << ntn::kRz));
  add_node(f);
  add_node(f);
  add_hinge(f, ntn_test::hinge(0, ntn::kGround, kTurned, ntn_test::released(1U << ntn::kRy)));
  add_hinge(f,
            ntn_test::hinge(1, 0, kTurned2, ntn_test::released(1U << ntn::kRz), {0.2, 0.5, 0.0}));
  add_hinge(f, ntn_test::hinge(4, 3, ntn_test::kIdentity3, ntn_test::released(1U << ntn::kRy)));
  add_hinge(f, ntn_test::hinge(0, 2, ntn_test::kIdentity3, ntn_test::released(1U << ntn::kRx)));
  add_hinge(f,
            ntn_test::hinge(5, 4, kTurned, ntn_test::released(1U << ntn::kUy), {0.0, -0.3, 0.3}));
  expect_matches_dense(f, 5, 1);
}

// The same tree grounded twice (a hinge to the ground and a support; or two hinges to the
// ground) is a cycle through the ground: build_forest refuses it with the closing hinge, and the
// cycle rule reports the cycle's nodes, from the hinge's node 1 to its node 2.
TEST(Forest, ATreeGroundedTwiceIsACycle) {
  Forest f;
  add_node(f);
  add_node(f);
  add_node(f, 0x3f);
  add_hinge(f, ntn_test::hinge(0, ntn::kGround, kTurned, ntn_test::released(1U << ntn::kRy)));
  add_hinge(f, ntn_test::hinge(1, 0, ntn_test::kIdentity3, ntn_test::released(1U << ntn::kRz)));
  add_hinge(f, ntn_test::hinge(1, 2, ntn_test::kIdentity3, ntn_test::released(1U << ntn::kRz)));
  const Built b = build(f);
  EXPECT_EQ(b.fb.status.error, ntn::InitError::kRigidCycle);
  EXPECT_EQ(b.fb.status.where, 2);

  std::vector<std::int32_t> set(3), up(4), mark(4), path(4);
  std::vector<int> closing;
  std::vector<std::vector<std::int32_t>> cycles;
  const int found = ntn::for_each_rigid_cycle(
      std::span<const ntn::HingeData>(f.hinges), std::span<const ntn::NodeSpec>(f.nodes),
      [&](int h) { return f.hinges[static_cast<std::size_t>(h)].rigid != 0; },
      ntn::RigidCycleWork{set, up, mark, path},
      [&](int h, std::span<const std::int32_t> nodes) {
        closing.push_back(h);
        cycles.emplace_back(nodes.begin(), nodes.end());
        return true;
      });
  ASSERT_EQ(found, 1);
  EXPECT_EQ(closing[0], 2);
  // Node 1, up to node 0, to the ground, back down to the supported node 2.
  EXPECT_EQ(cycles[0], (std::vector<std::int32_t>{1, 0, ntn::kGround, 2}));

  // Without the support the tree is grounded once, and valid.
  f.nodes[2].fixed = 0;
  EXPECT_TRUE(build(f).fb.status.ok());
  // A second hinge to the ground instead: refused the same way.
  f.hinges[2].node2 = ntn::kGround;
  f.hinges[2].node1 = 1;
  const Built b2 = build(f);
  EXPECT_EQ(b2.fb.status.error, ntn::InitError::kRigidCycle);
  EXPECT_EQ(b2.fb.status.where, 2);
}

}  // namespace forest_test
