#include "ntn/modelc/hinge_checks.hpp"

#include <Eigen/Core>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "ntn/constraint_forest.hpp"
#include "ntn/hinge.hpp"

namespace ntn::modelc {
namespace {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      parent[static_cast<std::size_t>(x)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      x = parent[static_cast<std::size_t>(x)];
    }
    return x;
  }
  void join(int a, int b) { parent[static_cast<std::size_t>(find(a))] = find(b); }
};

bool any_rigid(const HingeSpec& h) {
  return std::any_of(h.behaviour.begin(), h.behaviour.end(),
                     [](HingeBehaviour b) { return b == HingeBehaviour::kRigid; });
}

// Orthonormal basis of the null space of A (columns), by SVD; rank with a relative threshold.
// Entries of B are direction cosines (1) and lever arms (m), so 1e-9 of the largest singular
// value (at least 1) separates rounding from a real constraint.
Eigen::MatrixXd null_space(const Eigen::MatrixXd& A, Eigen::MatrixXd* range_rows = nullptr) {
  const Eigen::Index n = A.cols();
  if (A.rows() == 0) {
    if (range_rows != nullptr) *range_rows = Eigen::MatrixXd(n, 0);
    return Eigen::MatrixXd::Identity(n, n);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  const double tol = 1e-9 * std::max(1.0, s.size() > 0 ? s(0) : 0.0);
  Eigen::Index rank = 0;
  while (rank < s.size() && s(rank) > tol)
    ++rank;
  if (range_rows != nullptr) *range_rows = svd.matrixV().leftCols(rank);
  return svd.matrixV().rightCols(n - rank);
}

}  // namespace

std::vector<RigidCycle> rigid_cycles(const SpecView& spec) {
  // The kernel's rule (ntn::for_each_rigid_cycle), with the declared behaviour as "rigid": a
  // cycle is refused whatever the hinge method.
  const std::size_t n = spec.nodes.size();
  std::vector<std::int32_t> set(n), up(n + 1), mark(n + 1), path(n + 1);
  std::vector<RigidCycle> out;
  (void)for_each_rigid_cycle(
      spec.hinges, spec.nodes,
      [&](int h) { return any_rigid(spec.hinges[static_cast<std::size_t>(h)]); },
      RigidCycleWork{set, up, mark, path},
      [&out](int h, std::span<const std::int32_t> nodes) {
        out.push_back({h, std::vector<int>(nodes.begin(), nodes.end())});
        return true;
      });
  return out;
}

MassCheck hinge_mass_check(const SpecView& spec, std::span<const double> mass) {
  MassCheck out;
  const int n = static_cast<int>(spec.nodes.size());
  const bool penalty = spec.settings.hinge_method == HingeMethod::kPenalty;
  // DOFs of zero lumped mass that no support holds: the only ones a zero-energy motion moves.
  auto massless = [&](int node, int d) {
    const auto j = static_cast<std::size_t>(kDofsPerNode * node + d);
    return ((spec.nodes[static_cast<std::size_t>(node)].fixed >> d) & 1U) == 0 && !(mass[j] > 0);
  };
  std::vector<bool> has_massless(static_cast<std::size_t>(n), false);
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < kDofsPerNode; ++d)
      if (massless(i, d)) has_massless[static_cast<std::size_t>(i)] = true;
  }
  // Groups of such nodes joined by hinges are checked together; others are zero in the motion.
  UnionFind uf(static_cast<std::size_t>(n));
  std::vector<std::vector<int>> hinges_of(static_cast<std::size_t>(n));
  for (std::size_t hi = 0; hi < spec.hinges.size(); ++hi) {
    const HingeSpec& h = spec.hinges[hi];
    hinges_of[static_cast<std::size_t>(h.node1)].push_back(static_cast<int>(hi));
    if (h.node2 != kGround) {
      hinges_of[static_cast<std::size_t>(h.node2)].push_back(static_cast<int>(hi));
      if (has_massless[static_cast<std::size_t>(h.node1)] &&
          has_massless[static_cast<std::size_t>(h.node2)])
        uf.join(h.node1, h.node2);
    }
  }
  std::map<int, std::vector<int>> groups;
  for (int i = 0; i < n; ++i) {
    if (has_massless[static_cast<std::size_t>(i)]) groups[uf.find(i)].push_back(i);
  }

  std::map<int, std::uint8_t> mech_bits, spring_bits;
  std::map<int, bool> spring_penalty;
  for (const auto& [root, members] : groups) {
    (void)root;
    // Columns: the massless DOFs of the group.
    std::map<int, Eigen::Index> col;  // global DOF -> column
    std::vector<int> dof_of;
    for (int node : members) {
      for (int d = 0; d < kDofsPerNode; ++d) {
        if (!massless(node, d)) continue;
        col[kDofsPerNode * node + d] = static_cast<Eigen::Index>(dof_of.size());
        dof_of.push_back(kDofsPerNode * node + d);
      }
    }
    const auto cols = static_cast<Eigen::Index>(dof_of.size());
    std::vector<Eigen::VectorXd> constraint_rows, spring_rows;
    std::vector<bool> spring_is_penalty;
    std::vector<int> seen;
    for (int node : members) {
      for (int hi : hinges_of[static_cast<std::size_t>(node)]) {
        if (std::find(seen.begin(), seen.end(), hi) != seen.end()) continue;
        seen.push_back(hi);
        const HingeSpec& h = spec.hinges[static_cast<std::size_t>(hi)];
        for (std::size_t k = 0; k < kDofsPerNode; ++k) {
          double b1[kDofsPerNode], b2[kDofsPerNode];  // the kernel's row k of B
          hinge_direction(h.frame, h.eccentricity, k, b1, b2);
          Eigen::VectorXd r = Eigen::VectorXd::Zero(cols);
          bool any = false;
          for (int c = 0; c < kDofsPerNode; ++c) {
            const auto add = [&](int nd, double v) {
              const auto it = col.find(kDofsPerNode * nd + c);
              if (it != col.end() && v != 0.0) r(it->second) += v, any = true;
            };
            add(h.node1, b1[c]);
            if (h.node2 != kGround) add(h.node2, b2[c]);
          }
          if (!any) continue;
          switch (h.behaviour[k]) {
            case HingeBehaviour::kRigid:
            case HingeBehaviour::kRigidPlastic:  // rigid below its yield
              if (penalty) {
                spring_rows.push_back(r), spring_is_penalty.push_back(true);
              } else {
                constraint_rows.push_back(r);
              }
              break;
            case HingeBehaviour::kFree:
              break;
            case HingeBehaviour::kLinear:
              if (h.stiffness[k] > 0 || h.dashpot[k] > 0)
                spring_rows.push_back(r), spring_is_penalty.push_back(false);
              break;
            case HingeBehaviour::kCurve:
            case HingeBehaviour::kPlastic:
              spring_rows.push_back(r), spring_is_penalty.push_back(false);
              break;
          }
        }
      }
    }
    auto stack = [cols](const std::vector<Eigen::VectorXd>& rows) {
      Eigen::MatrixXd A(static_cast<Eigen::Index>(rows.size()), cols);
      for (std::size_t i = 0; i < rows.size(); ++i)
        A.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
      return A;
    };
    // Zero-energy motions the rigid directions allow, then which of them a spring resists.
    const Eigen::MatrixXd V = null_space(stack(constraint_rows));
    if (V.cols() == 0) continue;
    const Eigen::MatrixXd S = stack(spring_rows);
    Eigen::MatrixXd range;
    const Eigen::MatrixXd free_motion = V * null_space(S * V, &range);
    const Eigen::MatrixXd resisted = V * range;
    // A DOF takes part in a subspace when its row of the orthonormal basis is not zero.
    constexpr double kPart = 1e-9;
    for (Eigen::Index c = 0; c < cols; ++c) {
      const int dof = dof_of[static_cast<std::size_t>(c)];
      const auto bit = static_cast<std::uint8_t>(1U << (dof % kDofsPerNode));
      if (resisted.cols() > 0 && resisted.row(c).squaredNorm() > kPart) {
        spring_bits[dof / kDofsPerNode] |= bit;
      } else if (free_motion.cols() > 0 && free_motion.row(c).squaredNorm() > kPart) {
        mech_bits[dof / kDofsPerNode] |= bit;
      }
    }
    if (resisted.cols() > 0) {
      for (std::size_t i = 0; i < spring_rows.size(); ++i) {
        if (!spring_is_penalty[i]) continue;
        if ((spring_rows[i].transpose() * resisted).norm() > 1e-9) {
          for (int node : members)
            spring_penalty[node] = true;
        }
      }
    }
  }
  for (const auto& [node, bits] : mech_bits)
    out.mechanisms.push_back({node, bits});
  for (const auto& [node, bits] : spring_bits) {
    const auto it = spring_penalty.find(node);
    out.springs.push_back({node, bits, it != spring_penalty.end() && it->second});
  }
  return out;
}

}  // namespace ntn::modelc
