// Stages check_nodes_have_mass (a node no hinge touches needs mass in its free DOFs; a node
// connected to nothing at the place of another is most likely a typo for it) and
// check_effective_mass (with the hinge constraints, hinge_checks.cpp: a spring on a massless
// DOF is an error, a DOF without mass and stiffness a mechanism, reported as a note).
#include "compile.hpp"

#include <cmath>
#include <unordered_map>

#include "messages.hpp"
#include "ntn/modelc/hinge_checks.hpp"

namespace ntn::modelc::compile {

void check_nodes_have_mass(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const SourceModel& p = comp.p;
  const ModelDescription& d = comp.d;
  const std::vector<double>& mass = comp.mass;
  std::vector<bool> hinged(d.nodes.size(), false), connected(d.nodes.size(), false);
  for (const HingeSpec& h : d.hinges) {
    hinged[static_cast<std::size_t>(h.node1)] = true;
    if (h.node2 != kGround) hinged[static_cast<std::size_t>(h.node2)] = true;
  }
  for (const ElementSpec& e : d.elements)
    connected[static_cast<std::size_t>(e.node_i)] = connected[static_cast<std::size_t>(e.node_j)] =
        true;
  for (std::size_t i = 0; i < d.nodes.size(); ++i)
    connected[i] = connected[i] || hinged[i];
  // A given node that no member or hinge connects, at the same place (to kCoincident) as
  // another node: most likely a typo for that node. Cells of kCoincident hold the nodes; the
  // 27 cells around one hold every node within kCoincident of it.
  struct CellHash {
    std::size_t operator()(const std::array<double, 3>& c) const {
      std::size_t h = 0;
      for (double v : c)
        h = h * 1000003U ^ std::hash<double>{}(v);
      return h;
    }
  };
  std::unordered_map<std::array<double, 3>, std::vector<int>, CellHash> cells;
  auto cell_of = [](const NodeSpec& n) {
    return std::array<double, 3>{std::floor(n.x / kCoincident), std::floor(n.y / kCoincident),
                                 std::floor(n.z / kCoincident)};
  };
  bool any_loose = false;
  for (std::size_t i = 0; i < p.nodes.size(); ++i)
    any_loose = any_loose || !connected[i];
  if (any_loose) {
    for (std::size_t i = 0; i < d.nodes.size(); ++i)
      cells[cell_of(d.nodes[i])].push_back(static_cast<int>(i));
  }
  auto twin_of = [&](std::size_t i) -> int {  // the first other node within kCoincident, or -1
    const NodeSpec& n = d.nodes[i];
    const auto c = cell_of(n);
    int best = -1;
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == cells.end()) continue;
          for (int j : it->second) {
            if (j == static_cast<int>(i)) continue;
            const NodeSpec& o = d.nodes[static_cast<std::size_t>(j)];
            const double ex = o.x - n.x, ey = o.y - n.y, ez = o.z - n.z;
            if (std::sqrt(ex * ex + ey * ey + ez * ez) <= kCoincident && (best < 0 || j < best))
              best = j;
          }
        }
      }
    }
    return best;
  };
  // A node no hinge touches gets its mass from elements and point masses only; generated
  // nodes always have elements.
  for (std::size_t i = 0; i < p.nodes.size(); ++i) {
    const int twin = connected[i] ? -1 : twin_of(i);
    const std::string same_place =
        twin < 0 ? ""
                 : " It is connected to no member or hinge, at the same place as " +
                       d.describe_node(twin) + " (within 1e-9 m): did you mean that node?";
    if (hinged[i]) continue;
    std::string missing;
    for (int k = 0; k < kDofsPerNode; ++k) {
      const bool held = ((d.nodes[i].fixed >> k) & 1U) != 0;
      if (!held && !(mass[i * kDofsPerNode + static_cast<std::size_t>(k)] > 0)) {
        missing +=
            (missing.empty() ? "" : ", ") + std::string(kDofNames[static_cast<std::size_t>(k)]);
      }
    }
    if (!missing.empty()) {
      L.error(p.nodes[i].at, "node " + std::to_string(p.nodes[i].id) +
                                 " has no mass in its free DOFs " + missing +
                                 ": connect it to a member, give it a point mass (with inertia "
                                 "for rotations) or support those DOFs." +
                                 same_place);
    } else if (twin >= 0) {
      L.note(p.nodes[i].at, "node " + std::to_string(p.nodes[i].id) +
                                " moves on its own (its point mass or support only)." + same_place);
    }
  }
}

// Effective mass with the hinge constraints (config/README.md, "Mass and mechanisms").
void check_effective_mass(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  ModelDescription& d = comp.d;
  const std::vector<double>& mass = comp.mass;
  auto node_at = [&comp](int n) { return comp.node_at(n); };
  auto dof_list = [](std::uint8_t bits) {
    std::string out;
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      if (((bits >> k) & 1U) == 0) continue;
      out += (out.empty() ? "" : ", ") + std::string(kDofNames[k]);
    }
    return out;
  };
  const MassCheck mc = hinge_mass_check(d.view(), mass);
  for (const MassProblem& mp : mc.springs) {
    std::string msg = d.describe_node(mp.node) + " has no effective mass in " + dof_list(mp.dofs) +
                      " (global axes), but a hinge spring, dashpot or curve acts there: an "
                      "explicit step cannot integrate a massless spring (its frequency is "
                      "infinite). Give the node a point mass (with inertia for rotations), or make "
                      "those hinge directions rigid or free";
    if (mp.penalty) {
      msg +=
          ". With hinge_method = \"penalty\" a rigid direction is a stiff spring: penalty "
          "needs mass on both nodes; give the joint a point mass or use ntn_exact";
    }
    L.error(node_at(mp.node), msg);
  }
  if (L.failed()) return;
  d.mechanisms = mc.mechanisms;
  for (const Mechanism& m : d.mechanisms) {
    L.note(node_at(m.node), d.describe_node(m.node) +
                                " has no effective mass and no stiffness in " + dof_list(m.dofs) +
                                " (global axes): a mechanism (DESIGN §7.1); the kernel holds "
                                "these DOFs at zero");
  }
}

}  // namespace ntn::modelc::compile
