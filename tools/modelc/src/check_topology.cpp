// Stage check_rigid_cycles: a hinge whose rigid directions close a cycle (the topology is
// hinge_checks.cpp's rigid_cycles); the message names the hinge and the cycle's nodes.
#include "compile.hpp"

#include "ntn/modelc/hinge_checks.hpp"

namespace ntn::modelc::compile {

void check_rigid_cycles(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const ModelDescription& d = comp.d;
  auto node_name = [&](int n) { return n == kGround ? std::string("ground") : d.describe_node(n); };
  for (const RigidCycle& c : rigid_cycles(d.view())) {
    std::string path;
    for (int n : c.nodes)
      path += node_name(n) + " - ";
    path += node_name(c.nodes.front());
    L.error(comp.hinge_at[static_cast<std::size_t>(c.hinge)],
            d.describe_hinge(c.hinge) + " closes a cycle of rigid connections: " + path +
                ". A node can hang from one chain of rigid hinge directions only, and a "
                "supported node counts as joined to the ground: make a direction of one of "
                "these hinges free or a spring, or leave one out");
  }
}

}  // namespace ntn::modelc::compile
