// Stage collect_member_points: every point inside a member that the file gives where a node id
// is accepted (supports, loads, point masses, node and drift outputs, [[initial.nodes]]), checked
// against its member (known, at_m within the length) and kept as a fraction of the length, so that
// mesh_members can put a node there. Members whose end nodes are unknown are left to
// mesh_members' errors.
#include <cmath>

#include "compile.hpp"
#include "messages.hpp"

namespace ntn::modelc::compile {
namespace {

void collect(Compilation& comp, const NodeRef& r) {
  if (!r.point) return;
  const MemberPoint& mp = *r.point;
  const int mi = comp.ref(comp.ids.members, mp.member, "member");
  if (mi < 0) return;
  const Member& m = comp.p.members[static_cast<std::size_t>(mi)];
  double t = mp.at;
  if (mp.in_metres) {
    const auto a = comp.ids.nodes.find(m.nodes[0]);
    const auto b = comp.ids.nodes.find(m.nodes[1]);
    if (a == comp.ids.nodes.end() || b == comp.ids.nodes.end()) return;
    const UserNode& na = comp.p.nodes[static_cast<std::size_t>(a->second)];
    const UserNode& nb = comp.p.nodes[static_cast<std::size_t>(b->second)];
    const double len = std::hypot(nb.x - na.x, nb.y - na.y, nb.z - na.z);
    if (!(len > 0)) return;  // zero length: mesh_members' error
    if (mp.at > len * (1 + kSamePoint)) {
      comp.L.error(mp.at_at, "must be between 0 and the length of member " + m.id.id +
                                 ", L = " + num(len) + " m (got " + num(mp.at) + " m)");
      return;
    }
    t = std::min(mp.at / len, 1.0);
  }
  comp.points[&mp] = {mi, t};
}

}  // namespace

void collect_member_points(Compilation& comp) {
  const SourceModel& p = comp.p;
  for (const Support& s : p.supports)
    collect(comp, s.node);
  for (const PointMass& pm : p.point_masses)
    collect(comp, pm.node);
  for (const Load& l : p.loads)
    collect(comp, l.node);
  for (const Output& o : p.outputs) {
    for (const NodeRef& r : o.nodes)
      collect(comp, r);
  }
  for (const InitialNode& in : p.initial.nodes)
    collect(comp, in.node);
}

}  // namespace ntn::modelc::compile
