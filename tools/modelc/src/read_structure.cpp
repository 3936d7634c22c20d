// The reader's tables of the structure: materials, sections, nodes, members, supports, point
// masses, curves and hinges (read_tables.hpp).
#include "read_tables.hpp"

#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "read_hinge_parts.hpp"
#include "roll.hpp"

namespace ntn::modelc::compile {
namespace {

constexpr long long kMaxDivisions = 1000000;

std::string roll_message(double deg) {
  return "must be within [-" + num(kMaxRollDegrees) + ", " + num(kMaxRollDegrees) +
         "] degrees, one turn either way (got " + num(deg) + ")";
}

}  // namespace

// One [[materials]] table: E, rho, and G or nu (G = E / (2 (1 + nu))).
void read_material(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p) {
  Table t(L, tt, path, {"id", "E", "G", "nu", "rho"});
  t.check_unknown();
  Material m;
  auto id = read_id(L, t, "id");
  auto E = t.positive("E", Need::kRequired);
  auto rho = t.positive("rho", Need::kRequired);
  std::optional<double> G;
  if (!t.conflict("G", "nu")) {
    if (t.has("nu")) {
      if (auto nu = t.number("nu", Need::kRequired)) {
        if (!(*nu > -1.0 && *nu < 0.5)) {
          L.error(t.where("nu"),
                  "must be greater than -1 and less than 0.5 (got " + num(*nu) + ")");
        } else if (E) {
          G = *E / (2.0 * (1.0 + *nu));  // isotropic elasticity
        }
      }
    } else {
      G = t.positive("G", Need::kRequired);
    }
  }
  if (!id || !E || !rho || !G) return;
  m.id = *id, m.E = *E, m.G = *G, m.rho = *rho;
  m.E_at = t.where("E"), m.rho_at = t.where("rho");
  m.G_at = t.where(t.has("nu") ? "E" : "G");  // G = E / (2 (1 + nu)) follows E
  p.materials.push_back(m);
}

// One [[sections]] table: A, Iy, Iz, J, and the shear model with its coefficients.
void read_section(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p) {
  Table t(L, tt, path, {"id", "A", "Iy", "Iz", "J", "shear", "kappa_y", "kappa_z"});
  t.check_unknown();
  Section s;
  auto id = read_id(L, t, "id");
  auto A = t.positive("A", Need::kRequired);
  auto Iy = t.positive("Iy", Need::kRequired);
  auto Iz = t.positive("Iz", Need::kRequired);
  auto J = t.positive("J", Need::kRequired);
  auto shear = t.choice("shear", Need::kOptional, {"euler_bernoulli", "timoshenko"});
  double ky = 5.0 / 6.0, kz = 5.0 / 6.0;  // shear coefficient of a rectangle
  bool ok = id && A && Iy && Iz && J && (shear || !t.has("shear"));
  if (shear.value_or(0) == 1) {
    auto y = t.positive("kappa_y", Need::kOptional);
    auto z = t.positive("kappa_z", Need::kOptional);
    if (y) ky = *y;
    if (z) kz = *z;
    ok = ok && (y || !t.has("kappa_y")) && (z || !t.has("kappa_z"));
  } else {
    for (std::string_view k : {"kappa_y", "kappa_z"}) {
      if (t.has(k)) {
        L.error(t.where(k), "only applies with shear = \"timoshenko\"");
        ok = false;
      }
    }
  }
  if (!ok) return;
  s.id = *id, s.A = *A, s.Iy = *Iy, s.Iz = *Iz, s.J = *J;
  s.A_at = t.where("A"), s.Iy_at = t.where("Iy"), s.Iz_at = t.where("Iz"), s.J_at = t.where("J");
  s.shear_at = t.where("shear");
  if (shear.value_or(0) == 1) s.shear_y = ky * *A, s.shear_z = kz * *A;
  p.sections.push_back(s);
}

// One [[nodes]] table: id and xyz.
void read_node(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p) {
  Table t(L, tt, path, {"id", "xyz"});
  t.check_unknown();
  auto id = t.integer("id", Need::kRequired, 0, kMaxNodeId);
  auto xyz = t.numbers("xyz", Need::kRequired, 3);
  if (!id || !xyz) return;
  p.nodes.push_back({*id, t.where("id"), (*xyz)[0], (*xyz)[1], (*xyz)[2]});
}

// One [[members]] table: nodes, material, section, divisions, orientation or roll, end
// releases.
void read_member(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p) {
  Table t(L, tt, path,
          {"id", "nodes", "material", "section", "divisions", "orientation", "roll",
           "release_start", "release_end", "geometry"});
  t.check_unknown();
  Member m;
  for (std::size_t e = 0; e < 2; ++e) {
    const std::string_view k = e == 0 ? "release_start" : "release_end";
    if (const toml::node* r = t.get(k, Need::kOptional)) {
      if (auto release = read_release(L, *r, t.key(k)))
        m.release[e] = std::make_shared<const Release>(std::move(*release));
    }
  }
  auto id = read_id(L, t, "id");
  auto nodes = t.node_ids("nodes", Need::kRequired, 2);
  auto mat = read_id(L, t, "material");
  auto sec = read_id(L, t, "section");
  auto div = t.integer("divisions", Need::kOptional, 1, kMaxDivisions);
  auto geometry = t.choice("geometry", Need::kOptional, kGeometries);
  if (geometry) m.geometry = kGeometryOf[*geometry];
  bool ok =
      id && nodes && mat && sec && (div || !t.has("divisions")) && (geometry || !t.has("geometry"));
  if (!t.conflict("orientation", "roll")) {
    if (t.has("orientation")) {
      auto o = t.numbers("orientation", Need::kRequired, 3);
      if (o) {
        m.orientation = std::array<double, 3>{(*o)[0], (*o)[1], (*o)[2]};
      } else {
        ok = false;
      }
      m.orientation_at = t.where("orientation");
    } else if (t.has("roll")) {
      auto r = t.number("roll", Need::kRequired);
      if (r && !roll_in_range(*r)) {
        L.error(t.where("roll"), roll_message(*r));
        r.reset();
      }
      if (r) {
        m.roll_deg = *r;
      } else {
        ok = false;
      }
    }
  } else {
    ok = false;
  }
  if (!ok) return;
  m.id = *id, m.nodes = *nodes, m.nodes_at = t.where("nodes"), m.material = *mat;
  m.section = *sec, m.divisions = static_cast<int>(div.value_or(1));
  p.members.push_back(m);
}

// One [[leaning_columns]] table: a column segment that carries gravity into P-Delta without
// bending stiffness (a member of Geometry::kLeaning, one element: it has no bending to mesh).
void read_leaning_column(Reader& L, const toml::table& tt, const std::string& path,
                         SourceModel& p) {
  Table t(L, tt, path, {"id", "nodes", "material", "A"});
  t.check_unknown();
  auto id = read_id(L, t, "id");
  auto nodes = t.node_ids("nodes", Need::kRequired, 2);
  auto mat = read_id(L, t, "material");
  auto area = t.positive("A", Need::kRequired);
  if (!id || !nodes || !mat || !area) return;
  Member m;
  m.id = *id, m.nodes = *nodes, m.nodes_at = t.where("nodes"), m.material = *mat;
  m.geometry = Geometry::kLeaning;
  m.leaning_area = *area;
  p.members.push_back(m);
}

// One [[supports]] table: the node, the held DOFs (fix) and their axes.
void read_support(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p) {
  Table t(L, tt, path, {"node", "fix", "axes"});
  t.check_unknown();
  auto node = read_node_ref(L, t, "node", Need::kRequired);
  std::optional<std::array<double, 9>> axes;
  if (const toml::node* ax = t.get("axes", Need::kOptional)) {
    axes = read_axes(L, *ax, t.key("axes"));
    if (!axes) return;
  }
  const toml::node* fix = t.get("fix", Need::kRequired);
  std::optional<std::uint8_t> bits;
  if (fix != nullptr) {
    const std::string msg =
        "must be \"all\", \"pinned\" or an array of DOF names (" + quoted_list(kDofNames) + ")";
    if (const auto* s = fix->as_string()) {
      if (s->get() == "all") {
        bits = 0x3F;
      } else if (s->get() == "pinned") {
        bits = 0x07;  // translations held, rotations free
      } else {
        L.error(fix->source(), t.key("fix"), msg + ", got \"" + s->get() + "\"");
      }
    } else if (const auto* a = fix->as_array(); a != nullptr && !a->empty()) {
      std::uint8_t b = 0;
      bool ok = true;
      for (std::size_t i = 0; i < a->size(); ++i) {
        auto d = L.choice((*a)[i], t.key("fix") + "[" + std::to_string(i) + "]", kDofNames);
        if (d) {
          b = static_cast<std::uint8_t>(b | (1U << *d));
        } else {
          ok = false;
        }
      }
      if (ok) bits = b;
    } else {
      L.error(fix->source(), t.key("fix"),
              msg + ", got " + (fix->is_array() ? "an empty array" : type_name(*fix)));
    }
  }
  if (!node || !bits) return;
  p.supports.push_back({*node, t.where("node"), *bits, axes, t.where("axes")});
}

// One [[point_masses]] table: node, mass, inertia and offset.
void read_point_mass(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p) {
  Table t(L, tt, path, {"node", "mass", "inertia", "offset"});
  t.check_unknown();
  auto node = read_node_ref(L, t, "node", Need::kRequired);
  auto mass = t.non_negative("mass", Need::kRequired);
  auto inertia = t.numbers("inertia", Need::kOptional, 3, true);
  auto offset = t.numbers("offset", Need::kOptional, 3);
  if (!node || !mass || (!inertia && t.has("inertia")) || (!offset && t.has("offset"))) return;
  PointMass pm{*node, t.where("node"), *mass, {}, std::nullopt, t.where("offset")};
  if (inertia) pm.inertia = {(*inertia)[0], (*inertia)[1], (*inertia)[2]};
  if (offset) pm.offset = std::array<double, 3>{(*offset)[0], (*offset)[1], (*offset)[2]};
  p.point_masses.push_back(pm);
}

// One [[curves]] table: id and at least two [d, force] points.
void read_curve(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p) {
  Table t(L, tt, path, {"id", "points"});
  t.check_unknown();
  auto id = read_id(L, t, "id");
  const auto points = read_points(L, t, 2, "at least 2 [d, force] points", "d", "", "deformations");
  if (!id || !points) return;
  Curve c;
  for (const auto& [d, force] : *points)
    c.points.push_back({d, force});
  c.id = *id;
  c.points_at = t.where("points");
  p.curves.push_back(c);
}

// One [[hinges]] table: the nodes (node 2 may be "ground"), the frame or axes, eccentric, and
// the behaviour of each direction.
void read_hinge(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p) {
  Table t(L, tt, path,
          {"id", "nodes", "frame", "axes", "eccentric", "ux", "uy", "uz", "rx", "ry", "rz"});
  t.check_unknown();
  HingeIn h;
  auto id = read_id(L, t, "id");
  bool ok = id.has_value();
  if (const toml::node* nn = t.get("nodes", Need::kRequired)) {
    const std::string nkey = t.key("nodes");
    h.nodes_at = t.where("nodes");
    const auto* a = nn->as_array();
    if (a == nullptr || a->size() != 2) {
      L.error(nn->source(), nkey,
              "expected [node 1, node 2] (node 2 may be \"ground\"), got " +
                  (a ? std::to_string(a->size()) + (a->size() == 1 ? " value" : " values")
                     : type_name(*nn)));
      ok = false;
    } else {
      auto n1 = L.integer((*a)[0], nkey + "[0]", 0, kMaxNodeId);
      if (n1) h.node1 = *n1;
      ok = ok && n1;
      const toml::node& second = (*a)[1];
      if (const auto* s = second.as_string()) {
        if (s->get() != "ground") {
          L.error(second.source(), nkey + "[1]",
                  "must be a node id or \"ground\" (got \"" + s->get() + "\")");
          ok = false;
        }
      } else {
        auto n2 = L.integer(second, nkey + "[1]", 0, kMaxNodeId);
        if (n2) h.node2 = *n2;
        ok = ok && n2;
      }
    }
  } else {
    ok = false;
  }
  if (t.conflict("frame", "axes")) {
    ok = false;
  } else if (const toml::node* f = t.get("frame", Need::kOptional)) {
    const std::string fkey = t.key("frame");
    const std::string what = "must be \"global\" or { member = \"id\" } (or give axes)";
    if (const auto* s = f->as_string()) {
      if (s->get() != "global") {
        L.error(f->source(), fkey, what + ", got \"" + s->get() + "\"");
        ok = false;
      }
    } else if (const auto* ft = f->as_table()) {
      Table fr(L, *ft, fkey, {"member"});
      fr.check_unknown();
      auto m = read_id(L, fr, "member");
      if (m) {
        h.frame = FrameKind::kMember;
        h.frame_member = *m;
      }
      ok = ok && m;
    } else {
      L.error(f->source(), fkey, what + ", got " + type_name(*f));
      ok = false;
    }
  } else if (const toml::node* ax = t.get("axes", Need::kOptional)) {
    if (const auto* at = ax->as_table()) {
      // axes = { member = "id", roll = degrees }: the member's local axes turned by roll.
      const std::string akey = t.key("axes");
      Table fr(L, *at, akey, {"member", "roll"});
      fr.check_unknown();
      auto m = read_id(L, fr, "member");
      const toml::node* r = fr.get("roll", Need::kRequired,
                                   " (degrees about the member's local x; without a roll, "
                                   "give frame = { member = \"id\" })");
      auto roll = r != nullptr ? L.number(*r, fr.key("roll")) : std::nullopt;
      if (roll && !roll_in_range(*roll)) {
        L.error(fr.where("roll"), roll_message(*roll));
        roll.reset();
      }
      if (m && roll) {
        h.frame = FrameKind::kMember;
        h.frame_member = *m;
        h.frame_roll = *roll;
      }
      ok = ok && m && roll;
    } else if (!ax->is_array()) {
      L.error(ax->source(), t.key("axes"),
              "must be rows [[x], [y], [z]] or { member = \"id\", roll = degrees }, got " +
                  type_name(*ax));
      ok = false;
    } else {
      auto R = read_axes(L, *ax, t.key("axes"));
      if (R) {
        h.frame = FrameKind::kAxes;
        h.axes = *R;
      }
      ok = ok && R;
    }
  }
  if (auto e = t.boolean("eccentric", Need::kOptional)) h.eccentric = *e;
  h.eccentric_at = t.where("eccentric");
  for (std::size_t d = 0; d < kDofNames.size(); ++d) {
    h.dirs[d].at = t.where("nodes");
    const toml::node* v = t.get(kDofNames[d], Need::kOptional);
    if (v == nullptr) continue;
    auto b = read_behaviour(L, *v, t.key(kDofNames[d]));
    if (b) {
      h.dirs[d] = *b;
    } else {
      ok = false;
    }
  }
  if (!ok) return;
  h.id = *id;
  p.hinges.push_back(h);
}

}  // namespace ntn::modelc::compile
