#include "ntn/modal/constraints.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cstdio>
#include <numeric>
#include <string>
#include <utility>

#include "ntn/hinge.hpp"
#include "ntn/hinge_methods.hpp"

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
  // Spring segments: [s0, s1] (rigid end segments excluded).
  int s0 = 0, s1 = cs.count - 2;
  while (s0 < s1 && p[s0 + 1].d <= b.lower)
    ++s0;
  while (s1 > s0 && p[s1].d >= b.upper)
    --s1;
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

// The 6x6 frame T = diag(T_R, T_R) and link X(e) = [I E; 0 I] with E phi = phi x e.
Mat6 frame6(const HingeSpec& h) {
  Mat6 t = Mat6::Zero();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c)
      t(r, c) = t(r + 3, c + 3) = h.frame[static_cast<std::size_t>(3 * r + c)];
  }
  return t;
}

Mat6 link(const std::array<double, 3>& e, double sign) {
  Mat6 x = Mat6::Identity();
  const double ex = sign * e[0], ey = sign * e[1], ez = sign * e[2];
  x(0, 4) = ez, x(0, 5) = -ey;
  x(1, 3) = -ez, x(1, 5) = ex;
  x(2, 3) = ey, x(2, 4) = -ex;
  return x;
}

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

// A node's motion as a combination of coordinates: x = sum over (column, v) of v q_column.
using Rows = std::vector<std::pair<int, Vec6>>;

}  // namespace

HingeLinearization linearize_hinges(const SpecView& spec, bool penalty_as_springs) {
  HingeLinearization out;
  out.hinges.resize(spec.hinges.size());
  Settings settings = spec.settings;
  if (!penalty_as_springs) settings.hinge_method = HingeMethod::kNtnExact;
  bool dashpots = false;
  for (std::size_t h = 0; h < spec.hinges.size(); ++h) {
    const HingeSpec& hs = spec.hinges[h];
    HingeData check;
    if (!make_hinge_data(hs, settings, static_cast<int>(spec.nodes.size()), spec.curves,
                         spec.curve_points, check)) {
      out.error = hinge_name(h) +
                  " is not valid (nodes, frame, eccentricity of a ground hinge, curve, negative "
                  "stiffness" +
                  (penalty_as_springs ? ", or no penalty stiffness)" : ")");
      return out;
    }
    LinearHinge& lh = out.hinges[h];
    for (std::size_t k = 0; k < 6; ++k) {
      switch (hs.behaviour[k]) {
        case HingeBehaviour::kRigid:
          if (penalty_as_springs) {
            lh.stiffness[k] =
                k < 3 ? settings.penalty_stiffness : settings.penalty_rotational_stiffness;
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
          const double lim = k < 3 ? settings.limit_stiffness : settings.limit_rotational_stiffness;
          linearize_curve(spec, h, k, lim > 0 ? lim : 1e300, lh, out.notes);
          break;
        }
      }
    }
  }
  if (dashpots) out.notes.push_back("hinge dashpots left out: the modes are undamped");
  return out;
}

ConstraintMap build_constraints(const SpecView& spec, const std::vector<LinearHinge>& hinges) {
  ConstraintMap out;
  const int n = static_cast<int>(spec.nodes.size());
  const int ground = n;
  auto vertex = [ground](int node) { return node == kGround ? ground : node; };

  // Rigid hinges per node; supported nodes joined to the ground first (model compiler's rule).
  std::vector<std::vector<int>> rigid_of(static_cast<std::size_t>(n));
  for (std::size_t h = 0; h < spec.hinges.size(); ++h) {
    if (hinges[h].rigid == 0) continue;
    rigid_of[static_cast<std::size_t>(spec.hinges[h].node1)].push_back(static_cast<int>(h));
    if (spec.hinges[h].node2 != kGround)
      rigid_of[static_cast<std::size_t>(spec.hinges[h].node2)].push_back(static_cast<int>(h));
  }
  UnionFind uf(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i < n; ++i) {
    if (spec.nodes[static_cast<std::size_t>(i)].fixed != 0 &&
        !rigid_of[static_cast<std::size_t>(i)].empty())
      uf.join(i, ground);
  }
  for (std::size_t h = 0; h < spec.hinges.size(); ++h) {
    if (hinges[h].rigid == 0) continue;
    const int a = vertex(spec.hinges[h].node1), b = vertex(spec.hinges[h].node2);
    if (uf.find(a) == uf.find(b)) {
      out.error =
          hinge_name(h) + " (node " + std::to_string(spec.hinges[h].node1) + " to " +
          (spec.hinges[h].node2 == kGround ? std::string("the ground")
                                           : "node " + std::to_string(spec.hinges[h].node2)) +
          ") closes a cycle of rigid connections (through the ground when supports or "
          "ground hinges are involved)";
      return out;
    }
    uf.join(a, b);
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

  // Child c of parent p (or the ground) through hinge h: x_c = Y^-1 (G G^T Y_p x_p + H s).
  auto place_child = [&](int h, int child, int parent) {
    const HingeSpec& hs = spec.hinges[static_cast<std::size_t>(h)];
    const LinearHinge& lh = hinges[static_cast<std::size_t>(h)];
    const Mat6 t6 = frame6(hs);
    Mat6 yinv, yp;  // Y^-1 and Y_p
    if (child == hs.node1) {
      yinv = link(hs.eccentricity, -1.0) * t6.transpose();
      yp = t6;
    } else {
      yinv = t6.transpose();
      yp = t6 * link(hs.eccentricity, 1.0);
    }
    Mat6 g = Mat6::Zero();
    for (int k = 0; k < 6; ++k)
      g(k, k) = ((lh.rigid >> k) & 1U) ? 1.0 : 0.0;
    const Mat6 a = yinv * g * yp;
    Rows& rc = rows[static_cast<std::size_t>(child)];
    if (parent != kGround) {
      for (const auto& [col, v] : rows[static_cast<std::size_t>(parent)])
        rc.emplace_back(col, a * v);
    }
    for (int k = 0; k < 6; ++k) {
      if ((lh.rigid >> k) & 1U) continue;
      rc.emplace_back(new_column(), yinv.col(k));
    }
    placed[static_cast<std::size_t>(child)] = 1;
  };

  for (int start = 0; start < n; ++start) {
    if (placed[static_cast<std::size_t>(start)]) continue;
    ConstraintGroup g;
    g.first_column = columns;
    if (rigid_of[static_cast<std::size_t>(start)].empty()) {
      g.nodes = {start};
      place_root(start);
    } else {
      // The tree of `start`: its nodes and hinges, by breadth-first search over rigid hinges.
      std::vector<int> tree{start};
      std::vector<char> seen(static_cast<std::size_t>(n), 0);
      seen[static_cast<std::size_t>(start)] = 1;
      int ground_hinge = -1;
      for (std::size_t i = 0; i < tree.size(); ++i) {
        for (int h : rigid_of[static_cast<std::size_t>(tree[i])]) {
          const HingeSpec& hs = spec.hinges[static_cast<std::size_t>(h)];
          if (hs.node2 == kGround) ground_hinge = h;
          for (int m : {hs.node1, hs.node2}) {
            if (m == kGround || seen[static_cast<std::size_t>(m)]) continue;
            seen[static_cast<std::size_t>(m)] = 1;
            tree.push_back(m);
          }
        }
      }
      // Root: the ground, else the supported node, else the most rigid hinges (lowest index).
      int root = kGround;
      if (ground_hinge < 0) {
        std::size_t best = 0;
        root = -2;
        for (int m : tree) {
          const std::size_t deg = rigid_of[static_cast<std::size_t>(m)].size();
          if (spec.nodes[static_cast<std::size_t>(m)].fixed != 0) {
            root = m;
            break;
          }
          if (root == -2 || deg > best || (deg == best && m < root)) root = m, best = deg;
        }
      }
      g.root = root;
      std::vector<int> order;  // parents before children
      if (root == kGround) {
        const HingeSpec& hs = spec.hinges[static_cast<std::size_t>(ground_hinge)];
        place_child(ground_hinge, hs.node1, kGround);
        order.push_back(hs.node1);
      } else {
        place_root(root);
        order.push_back(root);
      }
      for (std::size_t i = 0; i < order.size(); ++i) {
        const int p = order[i];
        for (int h : rigid_of[static_cast<std::size_t>(p)]) {
          const HingeSpec& hs = spec.hinges[static_cast<std::size_t>(h)];
          const int c = hs.node1 == p ? hs.node2 : hs.node1;
          if (c == kGround || placed[static_cast<std::size_t>(c)]) continue;
          place_child(h, c, p);
          order.push_back(c);
        }
      }
      std::sort(tree.begin(), tree.end());
      g.nodes = std::move(tree);
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
