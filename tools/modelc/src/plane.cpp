// Stage hold_out_of_plane ([model] plane = "xz" | "xy" | "yz"): the one rule that holds exactly
// the out-of-plane motion of every node (xz: uy, rx, rz; xy: uz, rx, ry; yz: ux, ry, rz), user
// and generated alike, within the kernel's rule for supports and rigid trees (DESIGN §7.1,
// ntn::for_each_rigid_cycle: a tree of rigid hinge directions may reach the ground once only, so
// a support bit on two nodes of one tree is refused):
//
//   1. A hinge with a rigid direction (an edge of a rigid tree) and a free or spring direction
//      must have an axis normal to the plane; its out-of-plane local directions (the translation
//      along that axis, the rotations about the other two) become rigid. A child then follows its
//      parent out of plane through the hinge, as a support would hold it: a planar motion gives
//      those directions no deformation, so nothing else changes. A hinge with no rigid direction
//      joins no tree and is left alone (both its nodes are held as nodes of their own).
//   2. Each rigid tree is held once: nothing more when a hinge to the ground (a support with axes,
//      its out-of-plane directions rigid by 1.) holds it; else the out-of-plane bits go on its
//      supported node if it has one, else on its lowest-index node (a user node before the
//      generated ones: the joint of a member-end release, the node of a point mass on an offset).
//      Every node in no tree takes the bits itself.
#include <numeric>

#include "compile.hpp"
#include "messages.hpp"

namespace ntn::modelc::compile {
namespace {

constexpr const char* kPlaneName[] = {"", "xz", "xy", "yz"};
constexpr int kNormal[] = {-1, 1, 2, 0};                     // axis normal to the plane
constexpr std::uint8_t kHeldBits[] = {0, 0x2A, 0x1C, 0x31};  // out-of-plane DOFs per plane
constexpr const char* kHeldNames[] = {"", "uy, rx, rz", "uz, rx, ry", "ux, ry, rz"};

bool any_rigid(const HingeSpec& h) {
  for (HingeBehaviour b : h.behaviour)
    if (b == HingeBehaviour::kRigid) return true;
  return false;
}

int find(std::vector<int>& up, int x) {
  while (up[static_cast<std::size_t>(x)] != x) {
    up[static_cast<std::size_t>(x)] = up[static_cast<std::size_t>(up[static_cast<std::size_t>(x)])];
    x = up[static_cast<std::size_t>(x)];
  }
  return x;
}

}  // namespace

void hold_out_of_plane(Compilation& comp) {
  const Plane plane = comp.p.model.plane;
  if (plane == Plane::kNone) return;
  DiagnosticSink& L = comp.L;
  ModelDescription& d = comp.d;
  const auto pi = static_cast<std::size_t>(plane);
  const auto normal = static_cast<std::size_t>(kNormal[pi]);
  const std::uint8_t bits = kHeldBits[pi];
  d.plane = kPlaneName[pi];

  // 1. Hinges in rigid trees: the out-of-plane local directions rigid.
  for (std::size_t h = 0; h < d.hinges.size(); ++h) {
    HingeSpec& hs = d.hinges[h];
    if (!any_rigid(hs)) continue;
    bool all_rigid = true;
    for (HingeBehaviour b : hs.behaviour)
      all_rigid = all_rigid && b == HingeBehaviour::kRigid;
    if (all_rigid) continue;
    int axis = -1;  // the frame row along the normal (rows are orthonormal to 1e-9)
    for (std::size_t r = 0; r < 3; ++r)
      if (std::abs(hs.frame[3 * r + normal]) >= 1.0 - 1e-9) axis = static_cast<int>(r);
    if (axis < 0) {
      L.error(comp.hinge_at[h],
              d.describe_hinge(static_cast<int>(h)) +
                  " has a free or spring direction but no axis normal to the plane of the model "
                  "(plane = \"" +
                  d.plane + "\", normal " + std::string(kDofNames[normal]).substr(1) +
                  "): in a planar model such a hinge's frame needs an axis along " +
                  std::string(kDofNames[normal]).substr(1) +
                  " so that its directions are in plane or out of plane");
      continue;
    }
    const auto a = static_cast<std::size_t>(axis);
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      const bool out_of_plane = k < 3 ? k == a : k - 3 != a;
      if (!out_of_plane || hs.behaviour[k] == HingeBehaviour::kRigid) continue;
      hs.behaviour[k] = HingeBehaviour::kRigid;
      hs.stiffness[k] = hs.dashpot[k] = 0;
      hs.curve[k] = 0;
      ++d.plane_rigid_directions;
    }
  }

  // 2. Each tree (and each node in none) held once.
  const int n = static_cast<int>(d.nodes.size());
  std::vector<int> up(d.nodes.size());
  std::iota(up.begin(), up.end(), 0);
  std::vector<bool> grounded(d.nodes.size(), false);  // by a rigid hinge to the ground
  for (const HingeSpec& hs : d.hinges) {
    if (!any_rigid(hs)) continue;
    if (hs.node2 == kGround) {
      grounded[static_cast<std::size_t>(hs.node1)] = true;
    } else {
      up[static_cast<std::size_t>(find(up, hs.node1))] = find(up, hs.node2);
    }
  }
  std::vector<int> holder(d.nodes.size(), -1);  // per tree root: the node that takes the bits
  std::vector<bool> tree_grounded(d.nodes.size(), false);
  for (int i = 0; i < n; ++i) {
    const auto r = static_cast<std::size_t>(find(up, i));
    if (grounded[static_cast<std::size_t>(i)]) tree_grounded[r] = true;
    const bool supported = d.nodes[static_cast<std::size_t>(i)].fixed != 0;
    if (holder[r] < 0 || (supported && d.nodes[static_cast<std::size_t>(holder[r])].fixed == 0)) {
      holder[r] = i;
    }
  }
  for (std::size_t r = 0; r < d.nodes.size(); ++r) {
    if (holder[r] < 0 || tree_grounded[r]) continue;
    std::uint8_t& fixed = d.nodes[static_cast<std::size_t>(holder[r])].fixed;
    for (int k = 0; k < kDofsPerNode; ++k)
      d.plane_held_dofs += ((bits >> k) & 1U) && !((fixed >> k) & 1U) ? 1 : 0;
    fixed = static_cast<std::uint8_t>(fixed | bits);
  }
  d.plane_held_names = kHeldNames[pi];
}

}  // namespace ntn::modelc::compile
