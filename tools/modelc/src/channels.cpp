// Stage add_channels: inputs (ground accelerations, nodal forces) and outputs (node
// quantities, element forces at a member end, storey drift, reactions, hinge forces and
// displacements) resolved to indices, with their names, units and alarms; a drift needs a
// positive storey height, a reaction a support that holds its DOF.
#include "compile.hpp"

#include <algorithm>

#include "messages.hpp"

namespace ntn::modelc::compile {

void add_channels(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const SourceModel& p = comp.p;
  ModelDescription& d = comp.d;
  auto node_ref = [&comp](long long id, const Where& at) { return comp.node_ref(id, at); };
  auto ref = [&comp](const std::map<std::string, int>& index, const IdAt& id,
                     const std::string& what) { return comp.ref(index, id, what); };
  for (const Input& in : p.inputs) {
    InputSpec is;
    is.kind = in.kind, is.dof = in.dof, is.scale = in.scale, is.min = in.min, is.max = in.max;
    is.factor = in.factor;
    if (in.kind == InputKind::kNodalForce) {
      is.node = node_ref(in.node, in.node_at);
      if (is.node < 0) continue;
    }
    d.inputs.push_back(is);
    d.input_names.push_back(in.name.id);
  }

  const char* const rot_units[3] = {"rad", "rad/s", "rad/s2"};
  const char* const trans_units[3] = {"m", "m/s", "m/s2"};
  for (const Output& o : p.outputs) {
    OutputSpec os;
    std::string units;
    os.dof = o.dof;
    switch (o.kind) {
      case OutKind::kNode: {
        os.kind = o.node_kind;
        os.node = comp.node_of(o.nodes[0], o.nodes_at);
        if (os.node < 0) continue;
        const std::size_t k = o.node_kind == OutputKind::kAbsoluteAcceleration
                                  ? 2
                                  : static_cast<std::size_t>(o.node_kind);
        units = o.dof < 3 ? trans_units[k] : rot_units[k];
        break;
      }
      case OutKind::kElementForce: {
        os.kind = OutputKind::kElementForce;
        const int m = ref(comp.ids.members, o.member, "member");
        if (m < 0) continue;
        // Geometry errors leave a member without elements; nothing to point at then.
        const auto it = std::find_if(d.members.begin(), d.members.end(),
                                     [&](const MemberInfo& mi) { return mi.name == o.member.id; });
        if (it == d.members.end()) continue;
        os.end = o.end;
        os.element = o.end == 0 ? it->first_element : it->first_element + it->element_count - 1;
        units = o.dof < 3 ? "N" : "N m";
        break;
      }
      case OutKind::kDrift: {
        os.kind = OutputKind::kDrift;
        os.node = comp.node_of(o.nodes[0], o.nodes_at);
        os.node2 = comp.node_of(o.nodes[1], o.nodes_at);
        if (os.node < 0 || os.node2 < 0) continue;
        const double z0 = d.nodes[static_cast<std::size_t>(os.node)].z;
        const double z1 = d.nodes[static_cast<std::size_t>(os.node2)].z;
        const double h = z1 - z0;
        if (h == 0.0) {
          L.error(o.nodes_at, "drift height is zero: nodes " + o.nodes[0].text() + " and " +
                                  o.nodes[1].text() + " are both at z = " + num(z0) + " m");
          continue;
        }
        if (h < 0.0) {
          L.error(o.nodes_at, "the upper node " + o.nodes[1].text() + " (z = " + num(z1) +
                                  " m) is below the lower node " + o.nodes[0].text() +
                                  " (z = " + num(z0) + " m)");
          continue;
        }
        os.scale = 1.0 / h;  // drift ratio = relative displacement / storey height
        units = "-";
        break;
      }
      case OutKind::kHinge: {
        os.kind = o.node_kind;
        os.hinge = comp.hinge_of(o.hinge);
        if (os.hinge < 0) continue;  // unknown (reported here) or refused (reported there)
        const bool history = o.node_kind == OutputKind::kHingePlastic ||
                             o.node_kind == OutputKind::kHingeDissipated ||
                             o.node_kind == OutputKind::kHingeLevel;
        const HingeBehaviour hb =
            d.hinges[static_cast<std::size_t>(os.hinge)].behaviour[static_cast<std::size_t>(o.dof)];
        if (o.node_kind == OutputKind::kHingeSlipState && hb != HingeBehaviour::kRigidPlastic) {
          L.error(o.dof_at, "direction " + std::string(kDofNames[static_cast<std::size_t>(o.dof)]) +
                                " of " + d.describe_hinge(os.hinge) +
                                " does not stick or slip: a hinge_slip_state channel needs a "
                                "rigid_plastic, friction, fixed_if or failure direction");
          continue;
        }
        if (history && hb != HingeBehaviour::kPlastic && hb != HingeBehaviour::kRigidPlastic) {
          L.error(o.dof_at, "direction " + std::string(kDofNames[static_cast<std::size_t>(o.dof)]) +
                                " of " + d.describe_hinge(os.hinge) +
                                " is not plastic: it has no plastic deformation or dissipated "
                                "energy (give it { plastic = k, yield = F })");
          continue;
        }
        if (o.node_kind == OutputKind::kHingeForce) {
          units = o.dof < 3 ? "N" : "N m";
        } else if (o.node_kind == OutputKind::kHingeDissipated) {
          units = "J";
        } else if (o.node_kind == OutputKind::kHingeLevel ||
                   o.node_kind == OutputKind::kHingeSlipState) {
          units = "-";
        } else if (o.node_kind == OutputKind::kHingeVelocity) {
          units = o.dof < 3 ? "m/s" : "rad/s";
        } else {
          units = o.dof < 3 ? "m" : "rad";
        }
        break;
      }
      case OutKind::kReaction: {
        os.kind = OutputKind::kReaction;
        // A reaction is what the ground applies: through a support that holds the DOF, or
        // through a hinge to the ground (its forces in global axes, integrator.hpp).
        const bool held =
            std::any_of(d.nodes.begin(), d.nodes.end(),
                        [&](const NodeSpec& n) { return ((n.fixed >> o.dof) & 1U) != 0; }) ||
            std::any_of(d.hinges.begin(), d.hinges.end(),
                        [](const HingeSpec& h) { return h.node2 == kGround; });
        if (!held) {
          L.error(o.dof_at, "no support holds DOF " +
                                std::string(kDofNames[static_cast<std::size_t>(o.dof)]) +
                                " and no hinge joins the ground, so this reaction is always zero");
          continue;
        }
        units = o.dof < 3 ? "N" : "N m";
        break;
      }
    }
    d.outputs.push_back(os);
    d.output_names.push_back(o.name.id);
    d.output_units.push_back(units);
    d.output_alarms.push_back({o.alarm, o.alarm_hysteresis});
  }
}

}  // namespace ntn::modelc::compile
