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
#include "ntn/hinge_methods.hpp"
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

// Whether sorted `ts` holds a value within kSamePoint of t.
bool near(const std::vector<double>& ts, double t) {
  const auto it = std::lower_bound(ts.begin(), ts.end(), t - kSamePoint);
  return it != ts.end() && *it <= t + kSamePoint;
}

// One member's end nodes, their positions and its axis (b - a) and length.
struct MemberAxis {
  int a = -1, b = -1;
  NodeSpec na, nb;
  double dx = 0, dy = 0, dz = 0;
  double len = 0;
};

// The interior points of a member, ascending; split[k]: point k is a member point's.
struct InteriorPoints {
  std::vector<double> cuts;
  std::vector<bool> split;
};

// User nodes first, in file order; generated nodes follow, member by member.
void add_user_nodes(Compilation& comp) {
  for (const UserNode& n : comp.p.nodes) {
    NodeSpec ns;
    ns.x = n.x, ns.y = n.y, ns.z = n.z;
    comp.d.nodes.push_back(ns);
    comp.d.node_ids.push_back(static_cast<int>(n.id));
  }
}

// Members are optional (point masses on hinges are a model: an SDOF); with neither there is
// no mass anywhere. A node without mass in a free DOF is named by check_nodes_have_mass.
void check_model_has_mass(Compilation& comp) {
  if (comp.p.members.empty() && comp.p.point_masses.empty()) {
    comp.L.error_at_start("members",
                          "the model has no members and no point masses, so it has no mass and "
                          "nothing to integrate");
  }
}

// The member points of each member, as sorted fractions of its length.
std::vector<std::vector<double>> member_point_fractions(const Compilation& comp) {
  std::vector<std::vector<double>> point_ts(comp.p.members.size());
  for (const auto& [mp, pa] : comp.points) {
    (void)mp;
    point_ts[static_cast<std::size_t>(pa.member)].push_back(pa.t);
  }
  for (auto& ts : point_ts)
    std::sort(ts.begin(), ts.end());
  return point_ts;
}

// The element of member mi before meshing: its material's and section's properties.
ElementSpec member_element(const Material& ma, const Section& se, std::size_t mi) {
  ElementSpec e;
  e.E = ma.E, e.G = ma.G, e.rho = ma.rho;
  e.A = se.A, e.Iy = se.Iy, e.Iz = se.Iz, e.J = se.J;
  e.shear_area_y = se.shear_y, e.shear_area_z = se.shear_z;
  e.member = static_cast<int>(mi);
  return e;
}

// Whole-member geometry with the kernel's own check: false, and the error, for a zero length or
// an orientation parallel to the axis.
bool check_member_geometry(DiagnosticSink& L, const Member& m, const MemberAxis& ax,
                           const ElementSpec& e) {
  const BeamGeometry g = beam_geometry(ax.na, ax.nb, e);
  if (g.check == ElementCheck::kZeroLength) {
    L.error(m.nodes_at, "member " + m.id.id + " has zero length: nodes " +
                            std::to_string(m.nodes[0]) + " and " + std::to_string(m.nodes[1]) +
                            " are both at (" + num(ax.na.x) + ", " + num(ax.na.y) + ", " +
                            num(ax.na.z) + ")");
    return false;
  }
  if (g.check == ElementCheck::kOrientationParallel) {
    L.error(m.orientation_at, "orientation (" + num(e.ref_x) + ", " + num(e.ref_y) + ", " +
                                  num(e.ref_z) + ") is parallel to the axis of member " + m.id.id);
    return false;
  }
  return true;
}

// Interior points: the division points k / N, and the member points `ts` that are none of them
// (nor an end).
InteriorPoints interior_points(int divisions, const std::vector<double>& ts) {
  InteriorPoints in;
  for (int k = 1; k < divisions; ++k) {
    in.cuts.push_back(static_cast<double>(k) / static_cast<double>(divisions));
    in.split.push_back(false);
  }
  for (const double t : ts) {
    if (t <= kSamePoint || t >= 1 - kSamePoint || near(in.cuts, t)) continue;
    const auto pos = std::lower_bound(in.cuts.begin(), in.cuts.end(), t);
    in.split.insert(in.split.begin() + (pos - in.cuts.begin()), true);
    in.cuts.insert(pos, t);
  }
  return in;
}

// Mesh: interior nodes at x_a + t (x_b - x_a) for each interior point t and the elements between
// them (copies of e); the member's nodes as (t, node) along it, into `along`.
void add_elements(ModelDescription& d, std::size_t mi, const ElementSpec& e, const MemberAxis& ax,
                  const std::vector<double>& cuts, std::vector<std::pair<double, int>>& along) {
  const int elements = static_cast<int>(cuts.size()) + 1;
  along.emplace_back(0.0, ax.a);
  int prev = ax.a;
  for (int k = 1; k <= elements; ++k) {
    int next = ax.b;
    if (k < elements) {
      const double t = cuts[static_cast<std::size_t>(k - 1)];
      NodeSpec n;
      n.x = ax.na.x + t * ax.dx, n.y = ax.na.y + t * ax.dy, n.z = ax.na.z + t * ax.dz;
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
  along.emplace_back(1.0, ax.b);
}

// The member points made or reused on member `member` (its nodes `along`), for reports.
void add_member_points(ModelDescription& d, int member,
                       const std::vector<std::pair<double, int>>& along,
                       const std::vector<double>& ts, const std::vector<bool>& split) {
  for (std::size_t k = 0; k < along.size() && !ts.empty(); ++k) {
    const auto& [t, n] = along[k];
    if (!near(ts, t)) continue;
    const bool was_split = k > 0 && k + 1 < along.size() && split[k - 1];
    d.member_points.push_back({member, t, n, was_split});
  }
}

// Member-end releases: a node at the end, coincident with the joint, takes the end element;
// a hinge in the member's local axes (the end element's rotation) joins it to the joint.
void add_end_releases(Compilation& comp, const Member& m, int a, int b, MemberInfo& info) {
  ModelDescription& d = comp.d;
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
    comp.releases.push_back(ph);
    (end == 0 ? info.start_release_node : info.end_release_node) = rnode;
  }
}

// Member mi, whose member points are at the sorted fractions `ts`: its elements and interior
// nodes, its member points and its end releases; nothing more when a reference or its geometry
// is wrong (reported).
void mesh_member(Compilation& comp, std::size_t mi, const std::vector<double>& ts) {
  const SourceModel& p = comp.p;
  ModelDescription& d = comp.d;
  const Member& m = p.members[mi];
  MemberAxis ax;
  ax.a = comp.node_ref(m.nodes[0], m.nodes_at);
  ax.b = comp.node_ref(m.nodes[1], m.nodes_at);
  const int mat = comp.ref(comp.ids.materials, m.material, "material");
  const int sec = m.leaning_area ? 0 : comp.ref(comp.ids.sections, m.section, "section");
  if (ax.a < 0 || ax.b < 0 || mat < 0 || sec < 0) return;
  const Material& ma = p.materials[static_cast<std::size_t>(mat)];
  const Section se =
      m.leaning_area ? leaning_section(m) : p.sections[static_cast<std::size_t>(sec)];
  ax.na = d.nodes[static_cast<std::size_t>(ax.a)];
  ax.nb = d.nodes[static_cast<std::size_t>(ax.b)];
  ax.dx = ax.nb.x - ax.na.x, ax.dy = ax.nb.y - ax.na.y, ax.dz = ax.nb.z - ax.na.z;
  ax.len = std::sqrt(ax.dx * ax.dx + ax.dy * ax.dy + ax.dz * ax.dz);

  ElementSpec e = member_element(ma, se, mi);
  e.geometry = m.geometry.value_or(p.model.geometry);
  set_orientation(m, ax.dx, ax.dy, ax.dz, ax.len, e);
  e.node_i = ax.a, e.node_j = ax.b;
  if (!check_member_geometry(comp.L, m, ax, e)) return;

  const InteriorPoints in = interior_points(m.divisions, ts);
  const int elements = static_cast<int>(in.cuts.size()) + 1;
  MemberInfo info;
  info.name = m.id.id;
  info.material = ma.id.id;
  info.section = se.id.id;
  info.first_element = static_cast<int>(d.elements.size());
  info.element_count = elements;
  info.start_node = ax.a;
  info.end_node = ax.b;
  info.first_interior_node = static_cast<int>(d.nodes.size());
  info.interior_node_count = elements - 1;
  const int member = static_cast<int>(d.members.size());
  auto& along = comp.member_nodes[mi];
  add_elements(d, mi, e, ax, in.cuts, along);
  add_member_points(d, member, along, ts, in.split);
  add_end_releases(comp, m, ax.a, ax.b, info);
  comp.member_index[mi] = member;
  d.members.push_back(info);
}

}  // namespace

void mesh_members(Compilation& comp) {
  add_user_nodes(comp);
  check_model_has_mass(comp);
  comp.member_index.assign(comp.p.members.size(), -1);
  comp.member_nodes.assign(comp.p.members.size(), {});
  const std::vector<std::vector<double>> point_ts = member_point_fractions(comp);
  for (std::size_t mi = 0; mi < comp.p.members.size(); ++mi)
    mesh_member(comp, mi, point_ts[mi]);
}

// A node that only leaning columns reach has rotations that nothing resists or drives (a leaning
// column has no bending or torsion stiffness): they are held, as a support would hold them,
// unless a hinge joins the node in a rotation (a rigid, spring or yielding rotational direction:
// the hinge then gives them their stiffness, and the user their support).
void hold_leaning_rotations(Compilation& comp) {
  ModelDescription& d = comp.d;
  std::vector<int> leaning(d.nodes.size(), 0), other(d.nodes.size(), 0);
  for (const ElementSpec& e : d.elements) {
    auto& count = e.geometry == Geometry::kLeaning ? leaning : other;
    ++count[static_cast<std::size_t>(e.node_i)], ++count[static_cast<std::size_t>(e.node_j)];
  }
  for (const HingeSpec& h : d.hinges) {
    bool rotates = false;
    for (std::size_t k = 3; k < kDofsPerNode; ++k)
      rotates = rotates || h.behaviour[k] != HingeBehaviour::kFree;
    if (!rotates) continue;
    ++other[static_cast<std::size_t>(h.node1)];
    if (h.node2 != kGround) ++other[static_cast<std::size_t>(h.node2)];
  }
  for (std::size_t n = 0; n < d.nodes.size(); ++n) {
    if (leaning[n] > 0 && other[n] == 0) d.nodes[n].fixed |= 0x38;  // rx, ry, rz
  }
}

namespace {

// "node 12", or "a node inside a member" for a node the meshing made.
std::string node_text(const ModelDescription& d, int n) {
  const int id = d.node_ids[static_cast<std::size_t>(n)];
  return id == kGeneratedNode ? "a node inside a member" : "node " + std::to_string(id);
}

}  // namespace

// A hinge that turns with its nodes (the kernel's corotational_hinge_node) may hold only what
// turns with them (turning_hinge_check): the reason, and what the user can do instead.
void check_corotational_hinges(Compilation& comp) {
  ModelDescription& d = comp.d;
  static const char* const kDirection[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  for (std::size_t i = 0; i < d.hinges.size(); ++i) {
    const int n = corotational_hinge_node(d.hinges[i], d.elements);
    if (n < 0) continue;
    HingeData h;
    if (!make_hinge_data(d.hinges[i], d.settings, d.nodes.size(), d.curves, d.curve_points, h))
      continue;  // a bad hinge: its own checks say why
    const TurnCheck c = turning_hinge_check(h, d.settings);
    if (c.ok()) continue;
    const std::string dir = kDirection[static_cast<std::size_t>(c.direction)];
    std::string why;
    switch (c.why) {
      case TurnRefusal::kPartCoupled:
        why = "its coupled directions cover part of a block (" + dir +
              " is not coupled), and ntn_exact's rows of such a block are built once in the "
              "reference axes; couple all three of the block or none (springs turn), or use "
              "hinge_method = \"penalty\"";
        break;
      case TurnRefusal::kEccentricCoupled:
        why =
            "its translations are coupled across an offset, whose lever arm turns; join the "
            "nodes at one point, or give the translations springs";
        break;
      case TurnRefusal::kPaperCoupled:
        why = "ntn_paper's hinge-frame masses are built once in the reference axes (" + dir +
              " is coupled); use hinge_method = \"ntn_exact\" or \"penalty\"";
        break;
      case TurnRefusal::kStop:
        why = dir +
              "'s curve has a rigid branch (a stop), whose direction is built once in the "
              "reference axes; give the curve a finite slope there";
        break;
      case TurnRefusal::kSlip:
        why = dir +
              " is rigid-plastic, held by the slip stage in the reference axes; give it a "
              "plastic spring (plastic = k) instead";
        break;
      case TurnRefusal::kCentralDashpot:
        why = dir +
              "'s dashpot acts at v_n through directions built once in the reference "
              "axes; set damping_velocity = \"lagged\"";
        break;
      case TurnRefusal::kNone:
        break;
    }
    comp.L.error(comp.hinge_at[i], "hinge '" + d.hinge_info[i].name + "' joins " + node_text(d, n) +
                                       " of a member with geometry = \"corotational\", so its "
                                       "axes turn with its nodes, but " +
                                       why);
  }
}

}  // namespace ntn::modelc::compile
