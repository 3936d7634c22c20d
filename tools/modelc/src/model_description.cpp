#include "ntn/modelc/model_description.hpp"

#include <string>

#include "messages.hpp"

namespace ntn::modelc {

Sizes ModelDescription::sizes() const {
  return sizes_of(view());
}

SpecView ModelDescription::view() const {
  return {nodes,  elements, time_points,  time_functions, loads,      inputs,  outputs,
          hinges, curves,   curve_points, element_loads,  hystereses, settings};
}

std::string ModelDescription::describe_element(int element) const {
  if (element < 0 || element >= static_cast<int>(elements.size())) return "no element";
  const MemberInfo& m =
      members[static_cast<std::size_t>(element_member[static_cast<std::size_t>(element)])];
  return "member " + m.name + ", element " + std::to_string(element - m.first_element + 1) +
         " of " + std::to_string(m.element_count) + " (model element " + std::to_string(element) +
         ")";
}

std::string ModelDescription::describe_node(int node) const {
  if (node < 0 || node >= static_cast<int>(nodes.size())) return "no node";
  const int id = node_ids[static_cast<std::size_t>(node)];
  if (id != kGeneratedNode) return "node " + std::to_string(id);
  for (const MemberInfo& m : members) {
    if (node >= m.first_interior_node && node < m.first_interior_node + m.interior_node_count) {
      return "interior node " + std::to_string(node - m.first_interior_node + 1) + " of member " +
             m.name + " (model node " + std::to_string(node) + ")";
    }
    if (node == m.start_release_node || node == m.end_release_node) {
      return std::string(node == m.start_release_node ? "start" : "end") + " of member " + m.name +
             " (released, model node " + std::to_string(node) + ")";
    }
  }
  for (std::size_t h = 0; h < hinge_info.size(); ++h) {
    if (hinge_info[h].origin == HingeOrigin::kPointMass && hinges[h].node2 == node)
      return "the mass centre of the " + hinge_info[h].name + " (model node " +
             std::to_string(node) + ")";
  }
  return "model node " + std::to_string(node);
}

std::string ModelDescription::describe_stable_step(const StableStepReport& r) const {
  if (r.governing_hinge >= 0 && r.hinge_direction >= 0 && r.hinge_direction < kDofsPerNode) {
    return describe_hinge(r.governing_hinge) + ", direction " +
           std::string(compile::kDofNames[static_cast<std::size_t>(r.hinge_direction)]) +
           " (the spring with the largest share of the governing node's bound)";
  }
  if (r.governing_element >= 0) return describe_element(r.governing_element);
  // The kernel's alpha of the bound (stable_step_alpha): 0 with damping_velocity = "central".
  const double alpha = stable_step_alpha(settings);
  return alpha > 0 ? "the damping alpha = " + compile::num(alpha) +
                         " 1/s alone (2 / alpha: no element and no hinge spring bounds it)"
                   : std::string("nothing (no element, hinge spring or damping bounds it)");
}

std::string ModelDescription::describe_hinge(int hinge) const {
  if (hinge < 0 || hinge >= static_cast<int>(hinge_info.size())) return "no hinge";
  const HingeInfo& h = hinge_info[static_cast<std::size_t>(hinge)];
  switch (h.origin) {
    case HingeOrigin::kRelease:
      return "member-end release " + h.name;
    case HingeOrigin::kSupport:
      return "support with axes " + h.name;
    case HingeOrigin::kPointMass:
      return "the rigid offset of the " + h.name;
    case HingeOrigin::kExplicit:
      break;
  }
  return "hinge " + h.name;
}

int ModelDescription::hinge_count(HingeOrigin origin) const {
  int n = 0;
  for (const HingeInfo& h : hinge_info)
    n += h.origin == origin ? 1 : 0;
  return n;
}

}  // namespace ntn::modelc
