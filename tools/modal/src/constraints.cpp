#include "ntn/modal/constraints.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>

#include "ntn/constraint_forest.hpp"
#include "ntn/forest_matrices.hpp"
#include "ntn/hinge.hpp"
#include "ntn/hinge_methods.hpp"
#include "ntn/modal/assembly.hpp"
#include "ntn/model.hpp"

namespace ntn::modal {
namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

const char* const kDirection[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};

std::string hinge_name(std::size_t h) {
  return "hinge " + std::to_string(h);
}

std::string fmt(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

// Curve direction k of hinge h, linearized at d = 0 (see linearize_hinges).
void linearize_curve(const SpecView& spec, std::size_t h, std::size_t k, double k_lim,
                     LinearHinge& out, std::vector<std::string>& notes) {
  const HingeSpec& hs = spec.hinges[h];
  const CurveSpec& cs = spec.curves[static_cast<std::size_t>(hs.curve[k])];
  const CurveBranches b = curve_branches(spec.curve_points, cs, k_lim);
  const std::string where = hinge_name(h) + " " + kDirection[k];
  if (0.0 < b.lower || 0.0 > b.upper) {
    out.rigid |= static_cast<std::uint8_t>(1U << k);
    notes.push_back(where + ": curve with the origin on a rigid branch: tied");
    return;
  }
  const CurvePoint* p = spec.curve_points.data() + cs.first;
  // Spring segments: [s0, s1], the kernel's split (rigid end segments excluded).
  const int s0 = b.first, s1 = b.last;
  auto slope = [p](int s) { return (p[s + 1].force - p[s].force) / (p[s + 1].d - p[s].d); };
  int s = s0;
  while (s < s1 && p[s + 1].d < 0.0)
    ++s;
  double k0 = slope(s);
  if (0.0 == b.lower || 0.0 == b.upper) {
    notes.push_back(where +
                    ": curve whose rigid branch starts at the origin: the spring side's "
                    "slope " +
                    fmt(k0) + " is used (the motion is one-sided; no single linear frequency)");
  } else if (s < s1 && p[s + 1].d == 0.0 && slope(s + 1) != k0) {
    k0 = 0.5 * (k0 + slope(s + 1));
    notes.push_back(where + ": curve with a breakpoint at the origin: the mean " + fmt(k0) +
                    " of the two adjacent slopes is used");
  }
  out.stiffness[k] = k0 > 0 ? k0 : 0.0;
  if (k0 < 0) notes.push_back(where + ": negative slope at the origin, taken as free");
}

// A node's motion as a combination of coordinates: x = sum over (column, v) of v q_column.
using Rows = std::vector<std::pair<int, Vec6>>;

}  // namespace

HingeLinearization linearize_hinges(const SpecView& spec, bool penalty_as_springs) {
  HingeLinearization out;
  out.hinges.resize(spec.hinges.size());
  Settings settings = spec.settings;
  if (!penalty_as_springs) settings.hinge_method = HingeMethod::kNtnExact;
  bool dashpots = false, plastic = false, rigid_plastic = false;
  for (std::size_t h = 0; h < spec.hinges.size(); ++h) {
    const HingeSpec& hs = spec.hinges[h];
    HingeData check;
    if (!make_hinge_data(hs, settings, spec.nodes.size(), spec.curves, spec.curve_points, check)) {
      out.error = hinge_name(h) +
                  " is not valid (nodes, frame, eccentricity of a ground hinge, curve, negative "
                  "stiffness" +
                  (penalty_as_springs ? ", or no penalty stiffness)" : ")");
      return out;
    }
    LinearHinge& lh = out.hinges[h];
    for (std::size_t k = 0; k < 6; ++k) {
      rigid_plastic = rigid_plastic || hs.behaviour[k] == HingeBehaviour::kRigidPlastic;
      switch (hs.behaviour[k]) {
        case HingeBehaviour::kRigid:
        case HingeBehaviour::kRigidPlastic:  // below its yield: rigid (a penalty spring)
          if (penalty_as_springs) {
            lh.stiffness[k] = ntn::penalty_stiffness(settings, k);
          } else {
            lh.rigid |= static_cast<std::uint8_t>(1U << k);
          }
          break;
        case HingeBehaviour::kFree:
          break;
        case HingeBehaviour::kLinear:
          lh.stiffness[k] = hs.stiffness[k];
          if (hs.dashpot[k] > 0) dashpots = true;
          break;
        case HingeBehaviour::kCurve: {
          linearize_curve(spec, h, k, ntn::branch_slope_limit(settings, k), lh, out.notes);
          break;
        }
        case HingeBehaviour::kPlastic:  // below yield: its elastic stiffness
          lh.stiffness[k] = hs.stiffness[k];
          if (hs.dashpot[k] > 0) dashpots = true;
          plastic = true;
          break;
      }
    }
  }
  if (dashpots) out.notes.push_back("hinge dashpots left out: the modes are undamped");
  if (rigid_plastic) {
    out.notes.push_back("rigid-plastic hinge directions rigid (the modes below their yield)");
  }
  if (plastic) {
    out.notes.push_back(
        "plastic hinge directions at their elastic stiffness (the modes below yield)");
  }
  return out;
}

ConstraintMap build_constraints(const SpecView& spec, const std::vector<LinearHinge>& hinges) {
  ConstraintMap out;
  const int n = static_cast<int>(spec.nodes.size());

  // The kernel's forest (ntn::forest_topology, DESIGN §7.1) on the linearized hinges: the same
  // cycle rule, the same trees, roots and edge order as ntn_exact's step.
  std::vector<HingeData> data(spec.hinges.size());
  for (std::size_t h = 0; h < spec.hinges.size(); ++h) {
    const HingeSpec& hs = spec.hinges[h];
    HingeData& hd = data[h];
    hd.node1 = hs.node1, hd.node2 = hs.node2;
    hd.frame = hs.frame, hd.eccentricity = hs.eccentricity;
    hd.rigid = hinges[h].rigid;
  }
  const std::vector<double> mass = lumped_mass(spec);
  std::vector<std::int32_t> node_tree(static_cast<std::size_t>(n));
  std::vector<ForestEdge> edges(data.size());
  std::vector<ForestRoot> roots(data.size());
  std::vector<ntn::ForestWork> work(data.size());
  const ForestBuild fb = forest_topology(data, spec.nodes, mass, node_tree, edges, roots, work);
  if (fb.status.error == InitError::kRigidCycle) {
    const auto h = static_cast<std::size_t>(fb.status.where);
    out.error = hinge_name(h) + " (node " + std::to_string(spec.hinges[h].node1) + " to " +
                (spec.hinges[h].node2 == kGround ? std::string("the ground")
                                                 : "node " + std::to_string(spec.hinges[h].node2)) +
                ") closes a cycle of rigid connections (through the ground when supports or "
                "ground hinges are involved)";
    return out;
  }

  std::vector<Rows> rows(static_cast<std::size_t>(n));
  std::vector<char> placed(static_cast<std::size_t>(n), 0);
  int columns = 0;
  auto new_column = [&columns]() { return columns++; };

  // A root's unsupported DOFs are coordinates.
  auto place_root = [&](int node) {
    const std::uint8_t fixed = spec.nodes[static_cast<std::size_t>(node)].fixed;
    for (int d = 0; d < 6; ++d) {
      if ((fixed >> d) & 1U) continue;
      rows[static_cast<std::size_t>(node)].emplace_back(new_column(), Vec6::Unit(d));
    }
    placed[static_cast<std::size_t>(node)] = 1;
  };

  // The child of edge e (its parent a node or the ground): x_c = Y^-1 (G G^T Y_p x_p + H s), with
  // the kernel's frame T and link X(e) (the lever arm turns with node 1).
  auto place_child = [&](const ForestEdge& e) {
    const HingeData& hd = data[static_cast<std::size_t>(e.hinge)];
    const Mat6 t6 = ntn::detail::frame6(hd);
    Mat6 yinv, yp;     // Y^-1 and Y_p
    if (e.sign > 0) {  // the child is node 1
      yinv = ntn::detail::link(hd.eccentricity, -1.0) * t6.transpose();
      yp = t6;
    } else {
      yinv = t6.transpose();
      yp = t6 * ntn::detail::link(hd.eccentricity, 1.0);
    }
    Mat6 g = Mat6::Zero();
    for (int k = 0; k < 6; ++k)
      g(k, k) = ((hd.rigid >> k) & 1U) ? 1.0 : 0.0;
    const Mat6 a = yinv * g * yp;
    Rows& rc = rows[static_cast<std::size_t>(e.child)];
    if (e.parent != kGround) {
      for (const auto& [col, v] : rows[static_cast<std::size_t>(e.parent)])
        rc.emplace_back(col, a * v);
    }
    for (int k = 0; k < 6; ++k) {
      if ((hd.rigid >> k) & 1U) continue;
      rc.emplace_back(new_column(), yinv.col(k));
    }
    placed[static_cast<std::size_t>(e.child)] = 1;
  };

  for (int start = 0; start < n; ++start) {
    if (placed[static_cast<std::size_t>(start)]) continue;
    ConstraintGroup g;
    g.first_column = columns;
    const std::int32_t t = node_tree[static_cast<std::size_t>(start)];
    if (t < 0) {
      g.nodes = {start};
      place_root(start);
    } else {
      // The tree's edges are contiguous, parents first; its root is its first edge's parent.
      std::size_t first = 0;
      while (node_tree[static_cast<std::size_t>(edges[first].child)] != t)
        ++first;
      g.root = edges[first].parent;
      if (g.root != kGround) place_root(g.root);
      for (std::size_t k = first; k < static_cast<std::size_t>(fb.edges) &&
                                  node_tree[static_cast<std::size_t>(edges[k].child)] == t;
           ++k)
        place_child(edges[k]);
      for (int m = 0; m < n; ++m) {
        if (node_tree[static_cast<std::size_t>(m)] == t) g.nodes.push_back(m);
      }
      ++out.trees;
    }
    g.columns = columns - g.first_column;
    out.groups.push_back(std::move(g));
  }

  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) {
    for (const auto& [col, v] : rows[static_cast<std::size_t>(i)]) {
      for (int d = 0; d < 6; ++d) {
        if (v(d) != 0.0) entries.emplace_back(6 * i + d, col, v(d));
      }
    }
  }
  out.T.resize(6 * n, columns);
  out.T.setFromTriplets(entries.begin(), entries.end());
  return out;
}

}  // namespace ntn::modal
