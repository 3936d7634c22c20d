// Stages add_hinges, add_supports, add_point_masses: hinges in their order (explicit [[hinges]],
// then member-end releases, then supports with axes), each with the places of its key and
// directions for later checks; explicit hinges checked for their nodes, frame and eccentricity
// (coincident nodes unless eccentric; none with ntn_paper); supports (one per node; with axes a
// hinge to the ground); point masses added up on their node.
#include "compile.hpp"

#include <algorithm>
#include <cmath>

#include "messages.hpp"
#include "ntn/beam.hpp"
#include "roll.hpp"

namespace ntn::modelc::compile {
namespace {

// A hinge's directions from the file's behaviours: a curve reference resolves to its index.
bool set_dirs(Compilation& comp, HingeSpec& hs, const Behaviours& dirs) {
  auto ref = [&comp](const std::map<std::string, int>& index, const IdAt& id,
                     const std::string& what) { return comp.ref(index, id, what); };
  bool ok = true;
  for (std::size_t k = 0; k < kDofsPerNode; ++k) {
    const BehaviourIn& b = dirs[k];
    hs.behaviour[k] = b.kind;
    if (b.kind == HingeBehaviour::kLinear) hs.stiffness[k] = b.k, hs.dashpot[k] = b.c;
    if (b.kind == HingeBehaviour::kPlastic) {  // its law gets a history slot of its own
      hs.stiffness[k] = b.k, hs.dashpot[k] = b.c;
      hs.hysteresis[k] = static_cast<int>(comp.d.hystereses.size());
      comp.d.hystereses.push_back(b.law);
    }
    if (b.kind == HingeBehaviour::kRigidPlastic) {  // a history slot: its slip, its work
      if (comp.d.settings.hinge_method == HingeMethod::kNtnPaper) {
        comp.L.error(b.at,
                     "a rigid_plastic direction needs hinge_method = \"ntn_exact\" (exact "
                     "stick and slip) or \"penalty\" (an elasto-plastic penalty spring): "
                     "the seed's algorithm (\"ntn_paper\") gives no constraint force to "
                     "test against the yield");
        ok = false;
        continue;
      }
      if (b.law.failure != 0 && comp.d.settings.hinge_method == HingeMethod::kPenalty) {
        comp.L.error(b.at,
                     "a failure direction needs hinge_method = \"ntn_exact\": under "
                     "\"penalty\" only a constant limit (rigid_plastic = F) is offered");
        ok = false;
        continue;
      }
      if (b.law.normal >= 0) {  // friction: the normal is another, non-slip direction
        const auto n = static_cast<std::size_t>(b.law.normal);
        if (n == k || dirs[n].kind == HingeBehaviour::kRigidPlastic) {
          comp.L.error(
              b.normal_at,
              std::string("the normal of a friction direction must be another direction ") +
                  "of the hinge that does not slide itself (rigid, a spring or a curve)" +
                  (n == k ? ": it is this direction" : ": it slides") +
                  (b.normal_at.line == b.at.line && b.normal_at.column == b.at.column
                       ? " (the default normal is ux: give normal = \"..\")"
                       : ""));
          ok = false;
          continue;
        }
        if (comp.d.settings.hinge_method == HingeMethod::kPenalty) {
          comp.L.error(b.at,
                       "a friction direction needs hinge_method = \"ntn_exact\": under "
                       "\"penalty\" only a constant limit (rigid_plastic = F) is offered");
          ok = false;
          continue;
        }
      }
      hs.hysteresis[k] = static_cast<int>(comp.d.hystereses.size());
      comp.d.hystereses.push_back(b.law);
    }
    if (b.kind == HingeBehaviour::kCurve) {
      hs.curve[k] = ref(comp.ids.curves, *b.curve, "curve");
      ok = ok && hs.curve[k] >= 0;
    }
  }
  return ok;
}

// Adds a hinge with the places of its key and directions; a release or support with axes
// whose name is also an explicit hinge's id is an error.
void add_hinge(Compilation& comp, const HingeSpec& hs, const HingeInfo& info, const Where& at,
               const Behaviours* dirs) {
  DiagnosticSink& L = comp.L;
  const SourceModel& p = comp.p;
  ModelDescription& d = comp.d;
  if (info.origin != HingeOrigin::kExplicit) {
    const auto [it, inserted] =
        comp.ids.hinges.emplace(info.name, static_cast<int>(d.hinges.size()));
    if (!inserted && it->second < static_cast<int>(p.hinges.size())) {
      L.error(p.hinges[static_cast<std::size_t>(it->second)].id.at,
              "hinge id '" + info.name + "' is also the name of the " +
                  (info.origin == HingeOrigin::kRelease   ? "member-end release"
                   : info.origin == HingeOrigin::kSupport ? "support with axes"
                                                          : "point mass on an offset") +
                  " at " + at.key + ": choose another id");
    }
  }
  std::array<Where, kDofsPerNode> w;
  for (std::size_t k = 0; k < kDofsPerNode; ++k)
    w[k] = dirs != nullptr ? (*dirs)[k].at : at;
  d.hinges.push_back(hs);
  d.hinge_info.push_back(info);
  comp.hinge_at.push_back(at);
  comp.dir_at.push_back(w);
}

}  // namespace

void add_hinges(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const SourceModel& p = comp.p;
  ModelDescription& d = comp.d;
  Settings& s = comp.d.settings;
  auto node_ref = [&comp](long long id, const Where& at) { return comp.node_ref(id, at); };
  auto ref = [&comp](const std::map<std::string, int>& index, const IdAt& id,
                     const std::string& what) { return comp.ref(index, id, what); };
  for (const HingeIn& h : p.hinges) {
    HingeSpec hs;
    bool ok = true;
    hs.node1 = node_ref(h.node1, h.nodes_at);
    hs.node2 = h.node2 ? node_ref(*h.node2, h.nodes_at) : kGround;
    ok = hs.node1 >= 0 && (hs.node2 >= 0 || !h.node2);
    if (ok && hs.node1 == hs.node2) {
      L.error(h.nodes_at,
              "a hinge joins two different nodes; both are node " + std::to_string(h.node1));
      ok = false;
    }
    if (h.frame == FrameKind::kAxes) {
      hs.frame = h.axes;
    } else if (h.frame == FrameKind::kMember) {
      if (ref(comp.ids.members, h.frame_member, "member") < 0) {
        ok = false;
      } else {
        // Geometry errors leave a member without elements (already reported).
        const auto it = std::find_if(d.members.begin(), d.members.end(), [&](const MemberInfo& mi) {
          return mi.name == h.frame_member.id;
        });
        if (it == d.members.end()) {
          ok = false;
        } else {
          const ElementSpec& el = d.elements[static_cast<std::size_t>(it->first_element)];
          hs.frame = beam_geometry(d.nodes[static_cast<std::size_t>(el.node_i)],
                                   d.nodes[static_cast<std::size_t>(el.node_j)], el)
                         .rotation;
          // axes = { member, roll }: the member's y and z rows turned about its x (roll.hpp).
          std::array<double, 3> y{hs.frame[3], hs.frame[4], hs.frame[5]};
          std::array<double, 3> z{hs.frame[6], hs.frame[7], hs.frame[8]};
          roll_about_x(h.frame_roll, y, z);
          for (std::size_t i = 0; i < 3; ++i)
            hs.frame[3 + i] = y[i], hs.frame[6 + i] = z[i];
        }
      }
    }
    if (ok && hs.node2 == kGround && h.eccentric) {
      L.error(h.eccentric_at,
              "a hinge to the ground cannot be eccentric (the ground has no position): leave out "
              "eccentric");
      ok = false;
    } else if (ok && hs.node2 != kGround) {
      const NodeSpec& n1 = d.nodes[static_cast<std::size_t>(hs.node1)];
      const NodeSpec& n2 = d.nodes[static_cast<std::size_t>(hs.node2)];
      const std::array<double, 3> e{n2.x - n1.x, n2.y - n1.y, n2.z - n1.z};
      const double dist = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
      if (!h.eccentric && dist > kCoincident) {
        L.error(h.nodes_at, "nodes " + std::to_string(h.node1) + " and " +
                                std::to_string(*h.node2) + " do not coincide (they are " +
                                num(dist) +
                                " m apart): set eccentric = true for an eccentric hinge (e = x2 - "
                                "x1), or give the nodes the same position");
        ok = false;
      } else if (h.eccentric) {
        hs.eccentricity = e;
        if (dist > 0 && s.hinge_method == HingeMethod::kNtnPaper) {
          L.error(h.eccentric_at, "an eccentric hinge (e = (" + num(e[0]) + ", " + num(e[1]) +
                                      ", " + num(e[2]) +
                                      ") m) needs hinge_method = \"ntn_exact\" or \"penalty\": "
                                      "the seed's algorithm (\"ntn_paper\", S 17-37) has no "
                                      "eccentricity");
          ok = false;
        }
      }
    }
    ok = set_dirs(comp, hs, h.dirs) && ok;
    if (!ok) continue;
    add_hinge(comp, hs, {h.id.id, HingeOrigin::kExplicit, -1, 0}, h.nodes_at, &h.dirs);
  }
  for (PendingHinge& ph : comp.releases) {
    if (!set_dirs(comp, ph.spec, *ph.dirs)) continue;
    MemberInfo& mi = d.members[static_cast<std::size_t>(ph.info.member)];
    (ph.info.end == 0 ? mi.start_hinge : mi.end_hinge) = static_cast<int>(d.hinges.size());
    add_hinge(comp, ph.spec, ph.info, ph.at, ph.dirs);
  }
}

void add_supports(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const SourceModel& p = comp.p;
  ModelDescription& d = comp.d;
  std::map<int, int> support_of;  // node -> support index
  for (std::size_t i = 0; i < p.supports.size(); ++i) {
    const Support& sp = p.supports[i];
    const int n = comp.node_of(sp.node, sp.at);
    if (n < 0) continue;
    const auto [it, inserted] = support_of.emplace(n, static_cast<int>(i));
    if (!inserted) {
      L.error(sp.at, "node " + sp.node.text() + " already has a support (line " +
                         std::to_string(p.supports[static_cast<std::size_t>(it->second)].at.line) +
                         ")");
      continue;
    }
    if (sp.axes) {
      // A support with its own frame is a hinge to the ground: rigid in the fixed local
      // directions, free in the others (DESIGN §7.1); the node's own support bits stay 0.
      HingeSpec hs;
      hs.node1 = n;
      hs.node2 = kGround;
      hs.frame = *sp.axes;
      for (std::size_t k = 0; k < kDofsPerNode; ++k) {
        hs.behaviour[k] = ((sp.fixed >> k) & 1U) ? HingeBehaviour::kRigid : HingeBehaviour::kFree;
      }
      add_hinge(comp, hs, {"support." + sp.node.text(), HingeOrigin::kSupport, -1, 0}, sp.axes_at,
                nullptr);
      continue;
    }
    d.nodes[static_cast<std::size_t>(n)].fixed = sp.fixed;
  }
}

// Point masses add up on their node. One with an offset is its own node at the mass centre
// (node + offset) carrying the mass and inertia, joined to the node by a hinge rigid in all six
// directions with that eccentricity: the kernel's exact eccentric rigid hinge (DESIGN §7.1) is
// the rigid offset; under "penalty" it is six penalty springs; "ntn_paper" has no eccentricity.
void add_point_masses(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const SourceModel& p = comp.p;
  ModelDescription& d = comp.d;
  std::map<int, int> offsets_on;  // node -> point masses on offsets so far (for their names)
  for (const PointMass& pm : p.point_masses) {
    const int n = comp.node_of(pm.node, pm.at);
    if (n < 0) continue;
    if (pm.offset) {
      const std::array<double, 3>& e = *pm.offset;
      if (d.settings.hinge_method == HingeMethod::kNtnPaper) {
        L.error(pm.offset_at,
                "a point mass on an offset is an eccentric rigid hinge, which needs "
                "hinge_method = \"ntn_exact\" or \"penalty\": the seed's algorithm "
                "(\"ntn_paper\", S 17-37) has no eccentricity");
        continue;
      }
      const NodeSpec& at = d.nodes[static_cast<std::size_t>(n)];
      NodeSpec c;
      c.x = at.x + e[0], c.y = at.y + e[1], c.z = at.z + e[2];
      c.added = {pm.mass, pm.mass, pm.mass, pm.inertia[0], pm.inertia[1], pm.inertia[2]};
      const int centre = static_cast<int>(d.nodes.size());
      d.nodes.push_back(c);
      d.node_ids.push_back(kGeneratedNode);
      HingeSpec hs;  // rigid in all six, global axes
      hs.node1 = n;
      hs.node2 = centre;
      hs.eccentricity = e;  // e = x2 - x1
      // Under "penalty" a rigid direction is a spring, and a spring needs mass on both sides: a
      // rotation without inertia is left free (a massless, unloaded DOF of the mass centre,
      // reported as a mechanism). The translations follow the node's rotation all the same:
      // their rows, T (u2 - u1 - phi1 x e), hold phi1 only.
      for (std::size_t k = 0; k < 3; ++k) {
        if (d.settings.hinge_method == HingeMethod::kPenalty && pm.inertia[k] == 0)
          hs.behaviour[3 + k] = HingeBehaviour::kFree;
      }
      const int k = ++offsets_on[n];
      add_hinge(comp, hs,
                {"point mass at " + std::string(pm.node.point ? "" : "node ") + pm.node.text() +
                     " (offset" + (k > 1 ? " " + std::to_string(k) : std::string()) + ")",
                 HingeOrigin::kPointMass, -1, 0},
                pm.offset_at, nullptr);
      continue;
    }
    auto& added = d.nodes[static_cast<std::size_t>(n)].added;
    for (std::size_t k = 0; k < 3; ++k) {
      added[k] += pm.mass;
      added[3 + k] += pm.inertia[k];
    }
  }
}

}  // namespace ntn::modelc::compile
