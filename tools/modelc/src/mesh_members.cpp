// Stage mesh_members: the user's nodes in file order, then each member: its material and
// section, its orientation vector (given, or the default reference turned by `roll`), the
// kernel's geometry check (zero length, orientation parallel to the axis), `divisions` equal
// elements with the interior nodes between, a node at each member point (collect_member_points:
// an end or division point within kSamePoint of the length is reused, any other point splits
// its element there), and for a member-end release a node at that end and a pending hinge in
// the member's local axes (added by add_hinges).
#include "compile.hpp"

#include <algorithm>
#include <cmath>

#include "messages.hpp"
#include "ntn/beam.hpp"
#include "roll.hpp"

namespace ntn::modelc::compile {
namespace {

// The orientation vector of member m's elements (DESIGN §3): given, or the default reference
// turned by `roll`; (dx, dy, dz) and len: the member's axis and length.
void set_orientation(const Member& m, double dx, double dy, double dz, double len, ElementSpec& e) {
  if (m.orientation) {
    e.ref_x = (*m.orientation)[0], e.ref_y = (*m.orientation)[1], e.ref_z = (*m.orientation)[2];
  } else if (len > 0) {
    const double ex[3] = {dx / len, dy / len, dz / len};
    // Vertical members (axis within 1e-3 rad of global Z) take global X as the reference,
    // all others global Z.
    const bool vertical = std::sqrt(ex[0] * ex[0] + ex[1] * ex[1]) < 1e-3;
    const double r0[3] = {vertical ? 1.0 : 0.0, 0.0, vertical ? 0.0 : 1.0};
    const double along = r0[0] * ex[0] + r0[1] * ex[1] + r0[2] * ex[2];
    double ez[3] = {r0[0] - along * ex[0], r0[1] - along * ex[1], r0[2] - along * ex[2]};
    const double zn = std::sqrt(ez[0] * ez[0] + ez[1] * ez[1] + ez[2] * ez[2]);
    for (double& c : ez)
      c /= zn;
    std::array<double, 3> y = {ez[1] * ex[2] - ez[2] * ex[1], ez[2] * ex[0] - ez[0] * ex[2],
                               ez[0] * ex[1] - ez[1] * ex[0]};  // y = z x x
    std::array<double, 3> z = {ez[0], ez[1], ez[2]};
    roll_about_x(m.roll_deg, y, z);  // the reference: local z turned by `roll`
    e.ref_x = z[0];
    e.ref_y = z[1];
    e.ref_z = z[2];
  }
}

}  // namespace

void mesh_members(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const SourceModel& p = comp.p;
  ModelDescription& d = comp.d;
  auto node_ref = [&comp](long long id, const Where& at) { return comp.node_ref(id, at); };
  auto ref = [&comp](const std::map<std::string, int>& index, const IdAt& id,
                     const std::string& what) { return comp.ref(index, id, what); };
  const auto& materials = comp.ids.materials;
  const auto& sections = comp.ids.sections;
  std::vector<PendingHinge>& releases = comp.releases;

  // User nodes first, in file order; generated nodes follow, member by member.
  for (const UserNode& n : p.nodes) {
    NodeSpec ns;
    ns.x = n.x, ns.y = n.y, ns.z = n.z;
    d.nodes.push_back(ns);
    d.node_ids.push_back(static_cast<int>(n.id));
  }

  // Members are optional (point masses on hinges are a model: an SDOF); with neither there is
  // no mass anywhere. A node without mass in a free DOF is named by check_nodes_have_mass.
  if (p.members.empty() && p.point_masses.empty()) {
    L.error_at_start("members",
                     "the model has no members and no point masses, so it has no mass and nothing "
                     "to integrate");
  }

  comp.member_index.assign(p.members.size(), -1);
  comp.member_nodes.assign(p.members.size(), {});
  // The member points of each member, as sorted fractions of its length.
  std::vector<std::vector<double>> point_ts(p.members.size());
  for (const auto& [mp, pa] : comp.points) {
    (void)mp;
    point_ts[static_cast<std::size_t>(pa.member)].push_back(pa.t);
  }
  for (auto& ts : point_ts)
    std::sort(ts.begin(), ts.end());
  // Whether sorted `ts` holds a value within kSamePoint of t.
  const auto near = [](const std::vector<double>& ts, double t) {
    const auto it = std::lower_bound(ts.begin(), ts.end(), t - kSamePoint);
    return it != ts.end() && *it <= t + kSamePoint;
  };
  for (std::size_t mi = 0; mi < p.members.size(); ++mi) {
    const Member& m = p.members[mi];
    const int a = node_ref(m.nodes[0], m.nodes_at);
    const int b = node_ref(m.nodes[1], m.nodes_at);
    const int mat = ref(materials, m.material, "material");
    const int sec = ref(sections, m.section, "section");
    if (a < 0 || b < 0 || mat < 0 || sec < 0) continue;
    const Material& ma = p.materials[static_cast<std::size_t>(mat)];
    const Section& se = p.sections[static_cast<std::size_t>(sec)];
    const NodeSpec na = d.nodes[static_cast<std::size_t>(a)];
    const NodeSpec nb = d.nodes[static_cast<std::size_t>(b)];

    ElementSpec e;
    e.E = ma.E, e.G = ma.G, e.rho = ma.rho;
    e.A = se.A, e.Iy = se.Iy, e.Iz = se.Iz, e.J = se.J;
    e.shear_area_y = se.shear_y, e.shear_area_z = se.shear_z;
    e.member = static_cast<int>(mi);

    // Orientation vector (DESIGN §3): given, or the default reference turned by `roll`.
    const double dx = nb.x - na.x, dy = nb.y - na.y, dz = nb.z - na.z;
    const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
    set_orientation(m, dx, dy, dz, len, e);

    // Whole-member geometry with the kernel's own check.
    e.node_i = a, e.node_j = b;
    const BeamGeometry g = beam_geometry(na, nb, e);
    if (g.check == ElementCheck::kZeroLength) {
      L.error(m.nodes_at, "member " + m.id.id + " has zero length: nodes " +
                              std::to_string(m.nodes[0]) + " and " + std::to_string(m.nodes[1]) +
                              " are both at (" + num(na.x) + ", " + num(na.y) + ", " + num(na.z) +
                              ")");
      continue;
    }
    if (g.check == ElementCheck::kOrientationParallel) {
      L.error(m.orientation_at, "orientation (" + num(e.ref_x) + ", " + num(e.ref_y) + ", " +
                                    num(e.ref_z) + ") is parallel to the axis of member " +
                                    m.id.id);
      continue;
    }

    // Interior points: the division points k / N, and the member points that are none of them
    // (nor an end), ascending; split[k]: point k is a member point's.
    std::vector<double> cuts;
    std::vector<bool> split;
    for (int k = 1; k < m.divisions; ++k) {
      cuts.push_back(static_cast<double>(k) / static_cast<double>(m.divisions));
      split.push_back(false);
    }
    for (const double t : point_ts[mi]) {
      if (t <= kSamePoint || t >= 1 - kSamePoint || near(cuts, t)) continue;
      const auto pos = std::lower_bound(cuts.begin(), cuts.end(), t);
      split.insert(split.begin() + (pos - cuts.begin()), true);
      cuts.insert(pos, t);
    }
    const int elements = static_cast<int>(cuts.size()) + 1;

    // Mesh: interior nodes at x_a + t (x_b - x_a) for each interior point t.
    MemberInfo info;
    info.name = m.id.id;
    info.material = ma.id.id;
    info.section = se.id.id;
    info.first_element = static_cast<int>(d.elements.size());
    info.element_count = elements;
    info.start_node = a;
    info.end_node = b;
    info.first_interior_node = static_cast<int>(d.nodes.size());
    info.interior_node_count = elements - 1;
    const int member = static_cast<int>(d.members.size());
    auto& along = comp.member_nodes[mi];
    along.emplace_back(0.0, a);
    int prev = a;
    for (int k = 1; k <= elements; ++k) {
      int next = b;
      if (k < elements) {
        const double t = cuts[static_cast<std::size_t>(k - 1)];
        NodeSpec n;
        n.x = na.x + t * dx, n.y = na.y + t * dy, n.z = na.z + t * dz;
        next = static_cast<int>(d.nodes.size());
        d.nodes.push_back(n);
        d.node_ids.push_back(kGeneratedNode);
        along.emplace_back(t, next);
      }
      ElementSpec el = e;
      el.node_i = prev, el.node_j = next;
      d.elements.push_back(el);
      d.element_member.push_back(static_cast<int>(mi));
      prev = next;
    }
    along.emplace_back(1.0, b);
    // The member points made or reused on this member, for reports.
    for (std::size_t k = 0; k < along.size() && !point_ts[mi].empty(); ++k) {
      const auto& [t, n] = along[k];
      if (!near(point_ts[mi], t)) continue;
      const bool was_split = k > 0 && k + 1 < along.size() && split[k - 1];
      d.member_points.push_back({member, t, n, was_split});
    }
    // Member-end releases: a node at the end, coincident with the joint, takes the end element;
    // a hinge in the member's local axes (the end element's rotation) joins it to the joint.
    for (int end = 0; end < 2; ++end) {
      if (!m.release[end]) continue;
      const int joint = end == 0 ? a : b;
      const int el_index =
          end == 0 ? info.first_element : info.first_element + info.element_count - 1;
      NodeSpec rn;
      rn.x = d.nodes[static_cast<std::size_t>(joint)].x;
      rn.y = d.nodes[static_cast<std::size_t>(joint)].y;
      rn.z = d.nodes[static_cast<std::size_t>(joint)].z;
      const int rnode = static_cast<int>(d.nodes.size());
      d.nodes.push_back(rn);
      d.node_ids.push_back(kGeneratedNode);
      ElementSpec& el = d.elements[static_cast<std::size_t>(el_index)];
      (end == 0 ? el.node_i : el.node_j) = rnode;
      PendingHinge ph;
      ph.spec.node1 = rnode;
      ph.spec.node2 = joint;
      ph.spec.frame = beam_geometry(d.nodes[static_cast<std::size_t>(el.node_i)],
                                    d.nodes[static_cast<std::size_t>(el.node_j)], el)
                          .rotation;
      ph.info = {m.id.id + (end == 0 ? ".start" : ".end"), HingeOrigin::kRelease,
                 static_cast<int>(d.members.size()), end};
      ph.dirs = &m.release[end]->dirs;
      ph.at = m.release[end]->at;
      releases.push_back(ph);
      (end == 0 ? info.start_release_node : info.end_release_node) = rnode;
    }
    comp.member_index[mi] = member;
    d.members.push_back(info);
  }
}

}  // namespace ntn::modelc::compile
