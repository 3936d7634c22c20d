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
#include "ntn/hinge.hpp"
#include "roll.hpp"

namespace ntn::modelc::compile {
namespace {

// A fixed_if whose control is its own direction becomes a stop: a curve with one rigid branch at
// d = 0 (add_stop_curve).
Behaviours with_stops(const Behaviours& given) {
  Behaviours dirs = given;
  for (std::size_t k = 0; k < kDofsPerNode; ++k) {
    BehaviourIn& b = dirs[k];
    if (b.law.fixed_if != 0 && b.law.normal == static_cast<int>(k)) {
      b.kind = HingeBehaviour::kCurve;
      b.stop = b.law.fixed_if;
      b.law = {};
    }
  }
  return dirs;
}

// Direction n is a friction direction: rigid_plastic with a normal, not fixed_if.
bool is_friction(const Behaviours& dirs, std::size_t n) {
  return dirs[n].kind == HingeBehaviour::kRigidPlastic && dirs[n].law.normal >= 0 &&
         dirs[n].law.fixed_if == 0;
}

// Why direction c cannot be the circle of friction direction k; empty when it can.
std::string circle_refusal(const Behaviours& given, const Behaviours& dirs, std::size_t k,
                           std::size_t c) {
  const HysteresisSpec& a = dirs[k].law;
  if (c == k) return "it is this direction";
  if (c == static_cast<std::size_t>(a.normal)) return "it is the normal";
  if (c / 3 != k / 3)
    return k < 3 ? "it is a rotation and this a translation"
                 : "it is a translation and this a rotation";
  if (!is_friction(dirs, c)) return "it is not a friction direction";
  if (dirs[c].law.normal != a.normal || dirs[c].law.mu != a.mu ||
      dirs[c].law.cohesion != a.cohesion)
    return "its friction, cohesion or normal differ from this direction's";
  if (given[c].law.circle >= 0 && given[c].law.circle != static_cast<int>(k))
    return "its own circle names another direction";
  return {};
}

// The friction circle: the partner a friction direction with the same law; both get the pair.
// False, and the error, for a circle that names no such partner.
bool pair_friction_circles(Compilation& comp, const Behaviours& given, Behaviours& dirs) {
  for (std::size_t k = 0; k < kDofsPerNode; ++k) {
    if (given[k].law.circle < 0 || !is_friction(dirs, k)) continue;
    const auto c = static_cast<std::size_t>(given[k].law.circle);
    const std::string why = circle_refusal(given, dirs, k, c);
    if (!why.empty()) {
      comp.L.error(given[k].circle_at,
                   "the circle of a friction direction must be another friction direction of the "
                   "hinge with the same friction, cohesion and normal (the two share one limit on "
                   "their resultant): " +
                       why);
      return false;
    }
    dirs[c].law.circle = static_cast<int>(k);
  }
  return true;
}

// Direction n is a stop (a rigid branch, by the kernel's rule): its force is the stops'
// clamp's, known only after the slip stage.
bool is_stop(const Compilation& comp, const Behaviours& dirs, std::size_t n) {
  if (dirs[n].stop != 0) return true;
  if (dirs[n].kind != HingeBehaviour::kCurve) return false;
  const auto it = comp.ids.curves.find(dirs[n].curve->id);
  if (it == comp.ids.curves.end()) return false;
  const CurveBranches b =
      curve_branches(comp.d.curve_points, comp.d.curves[static_cast<std::size_t>(it->second)],
                     branch_slope_limit(comp.d.settings, n));
  return b.valid && (b.lower > -1e300 || b.upper < 1e300);
}

// The normal of friction direction k, or the control of fixed_if direction k: another,
// non-slip direction that carries the force; false, and the error, when it is not.
bool check_normal(Compilation& comp, const Behaviours& dirs, std::size_t k) {
  const BehaviourIn& b = dirs[k];
  const auto n = static_cast<std::size_t>(b.law.normal);
  const char* role = b.law.fixed_if != 0 ? "the control of a fixed_if direction"
                                         : "the normal of a friction direction";
  // A free normal carries no force: the limit would be the cohesion alone (friction) or
  // the direction never held (fixed_if). A translation's friction takes a force as its
  // normal, not a moment (mu x N m is not a force).
  const bool free_normal = dirs[n].kind == HingeBehaviour::kFree;
  const bool moment_normal = b.law.fixed_if == 0 && k < 3 && n >= 3;
  if (free_normal || moment_normal) {
    comp.L.error(b.normal_at,
                 std::string(role) + " is " + std::string(kDofNames[n]) +
                     (!free_normal          ? ", a rotation: a translation's friction limit mu "
                                              "N needs a force N, not a moment"
                      : b.law.fixed_if != 0 ? ", a free direction: it carries no force, so "
                                              "the direction would never be held"
                                            : ", a free direction: it carries no force, so "
                                              "the limit would be the cohesion alone") +
                     " (give normal = / control = a direction that carries the force)");
    return false;
  }
  if (n == k || dirs[n].kind == HingeBehaviour::kRigidPlastic || is_stop(comp, dirs, n)) {
    const bool by_default = b.normal_at.line == b.at.line && b.normal_at.column == b.at.column;
    comp.L.error(b.normal_at,
                 std::string(role) +
                     " must be another direction of the hinge that does not slide itself and is "
                     "not a stop (rigid, a spring or a curve without rigid branches)" +
                     (n == k                                          ? ": it is this direction"
                      : dirs[n].kind == HingeBehaviour::kRigidPlastic ? ": it slides"
                                                                      : ": it is a stop, whose "
                                                                        "force comes after the "
                                                                        "slip stage") +
                     (by_default ? " (the default normal is ux: give normal = \"..\")" : ""));
    return false;
  }
  return true;
}

// Rigid_plastic direction k under the model's hinge method: one that gives a constraint force to
// test against the limit and, for friction and fixed_if, a limit the method offers; false, and
// the error, when it does not fit.
bool check_rigid_plastic(Compilation& comp, const Behaviours& dirs, std::size_t k) {
  const BehaviourIn& b = dirs[k];
  const HingeMethod method = comp.d.settings.hinge_method;
  const bool brittle = law_breaks(b.law.rule);
  const char* what = brittle               ? "a failure direction"
                     : b.law.fixed_if != 0 ? "a fixed_if direction with a control"
                     : b.law.normal >= 0   ? "a friction direction"
                                           : "a rigid_plastic direction";
  if (method == HingeMethod::kNtnPaper) {
    comp.L.error(b.at, std::string(what) +
                           " needs hinge_method = \"ntn_exact\" (exact stick and slip)" +
                           (b.law.normal < 0 ? " or \"penalty\" (an elasto-plastic "
                                               "penalty spring)"
                                             : "") +
                           ": the seed's algorithm (\"ntn_paper\") gives no constraint force "
                           "to test against the limit" +
                           (brittle ? " (a spring that breaks works with every method: "
                                      "{ linear = k, failure = F })"
                                    : ""));
    return false;
  }
  if (b.law.normal < 0) return true;
  // friction, fixed_if: the normal is another, non-slip direction
  if (!check_normal(comp, dirs, k)) return false;
  if (method == HingeMethod::kPenalty) {
    comp.L.error(b.at, std::string(what) +
                           " needs hinge_method = \"ntn_exact\": under \"penalty\" only "
                           "a constant limit (rigid_plastic = F, failure = F) is offered");
    return false;
  }
  return true;
}

// Direction k's curve for a fixed_if on its own force (`stop`, -1: rigid against d < 0): a rigid
// branch of slope 1e300 (at least any limit stiffness) on one side of d = 0, no force on the
// other.
void add_stop_curve(ModelDescription& d, HingeSpec& hs, std::size_t k, int stop) {
  const double side = static_cast<double>(stop);
  hs.curve[k] = static_cast<int>(d.curves.size());
  d.curves.push_back({static_cast<int>(d.curve_points.size()), 3});
  d.curve_points.push_back({-1.0, side < 0 ? -1e300 : 0.0});
  d.curve_points.push_back({0.0, 0.0});
  d.curve_points.push_back({1.0, side < 0 ? 0.0 : 1e300});
  d.curve_ids.push_back("fixed_if");
}

// Direction k of the hinge from its behaviour: its stiffness and dashpot, a history slot for a
// law, its curve; false (reported) when it does not fit.
bool set_dir(Compilation& comp, HingeSpec& hs, const Behaviours& dirs, std::size_t k) {
  const BehaviourIn& b = dirs[k];
  hs.behaviour[k] = b.kind;
  if (b.kind == HingeBehaviour::kLinear) hs.stiffness[k] = b.k, hs.dashpot[k] = b.c;
  if (b.kind == HingeBehaviour::kPlastic) {  // its law gets a history slot of its own
    hs.stiffness[k] = b.k, hs.dashpot[k] = b.c;
    hs.hysteresis[k] = static_cast<int>(comp.d.hystereses.size());
    comp.d.hystereses.push_back(b.law);
  }
  if (b.kind == HingeBehaviour::kRigidPlastic) {  // a history slot: its slip, its work
    if (!check_rigid_plastic(comp, dirs, k)) return false;
    hs.stiffness[k] = b.k;  // its hardening with the slip, if any
    hs.hysteresis[k] = static_cast<int>(comp.d.hystereses.size());
    comp.d.hystereses.push_back(b.law);
  }
  if (b.kind == HingeBehaviour::kCurve && b.stop != 0) {  // fixed_if on its own force
    add_stop_curve(comp.d, hs, k, b.stop);
  } else if (b.kind == HingeBehaviour::kCurve) {
    hs.curve[k] = comp.ref(comp.ids.curves, *b.curve, "curve");
    return hs.curve[k] >= 0;
  }
  return true;
}

// A hinge's directions from the file's behaviours: a curve reference resolves to its index; a
// fixed_if on its own force becomes a stop (a curve with one rigid branch at d = 0).
bool set_dirs(Compilation& comp, HingeSpec& hs, const Behaviours& given) {
  Behaviours dirs = with_stops(given);
  if (!pair_friction_circles(comp, given, dirs)) return false;
  bool ok = true;
  for (std::size_t k = 0; k < kDofsPerNode; ++k)
    ok = set_dir(comp, hs, dirs, k) && ok;
  return ok;
}

// Adds a hinge with the places of its key and directions, and its name (the one place that
// gives a name an index in d.hinges: Ids::hinges); a release or support with axes whose name is
// also an explicit hinge's id is an error.
void add_hinge(Compilation& comp, const HingeSpec& hs, const HingeInfo& info, const Where& at,
               const Behaviours* dirs) {
  DiagnosticSink& L = comp.L;
  const SourceModel& p = comp.p;
  ModelDescription& d = comp.d;
  comp.ids.hinges.emplace(info.name, static_cast<int>(d.hinges.size()));  // a duplicate: the first
  if (info.origin != HingeOrigin::kExplicit) {
    const auto it = comp.ids.hinge_ids.find(info.name);
    if (it != comp.ids.hinge_ids.end()) {
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
    if (!ok) {
      comp.refuse_hinge(h.id.id);
      continue;
    }
    add_hinge(comp, hs, {h.id.id, HingeOrigin::kExplicit, -1, 0}, h.nodes_at, &h.dirs);
  }
  for (PendingHinge& ph : comp.releases) {
    if (!set_dirs(comp, ph.spec, *ph.dirs)) {
      comp.refuse_hinge(ph.info.name);
      continue;
    }
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
    const std::string name = "support." + sp.node.text();  // with axes: a hinge of this name
    const int n = comp.node_of(sp.node, sp.at);
    if (n < 0) {
      if (sp.axes) comp.refuse_hinge(name);
      continue;
    }
    const auto [it, inserted] = support_of.emplace(n, static_cast<int>(i));
    if (!inserted) {
      L.error(sp.at, "node " + sp.node.text() + " already has a support (line " +
                         std::to_string(p.supports[static_cast<std::size_t>(it->second)].at.line) +
                         ")");
      if (sp.axes) comp.refuse_hinge(name);
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
      add_hinge(comp, hs, {name, HingeOrigin::kSupport, -1, 0}, sp.axes_at, nullptr);
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
      const int nth = ++offsets_on[n];
      const std::string name = "point mass at " + std::string(pm.node.point ? "" : "node ") +
                               pm.node.text() + " (offset" +
                               (nth > 1 ? " " + std::to_string(nth) : std::string()) + ")";
      if (d.settings.hinge_method == HingeMethod::kNtnPaper) {
        L.error(pm.offset_at,
                "a point mass on an offset is an eccentric rigid hinge, which needs "
                "hinge_method = \"ntn_exact\" or \"penalty\": the seed's algorithm "
                "(\"ntn_paper\", S 17-37) has no eccentricity");
        comp.refuse_hinge(name);
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
      add_hinge(comp, hs, {name, HingeOrigin::kPointMass, -1, 0}, pm.offset_at, nullptr);
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
