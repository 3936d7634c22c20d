// Models with `plastic` hinge directions (HingeBehaviour::kPlastic) shared by the
// validation and the kernel tests. No heap, no exceptions.
//
// The oscillator: a point mass m on a `plastic` hinge to the ground, along global x. The kernel
// needs at least one element, so node 0 (the mass, every DOF but ux held) is tied to the clamped
// node 1, 1 m further along x, by a very soft, very light element: its axial stiffness
// E A / L = kSdofElementK (1e-6 of k, a spring in parallel with the hinge) and its mass
// rho A L = 1e-3 kg (half of it, 1e-6 m, at node 0). The hinge's frame is x reversed (a right-
// handed turn of 180 degrees about z) so that its deformation d = +u_x of the mass: a positive
// load stretches it in the hinge's positive sense (yield_pos).
#pragma once

#include <array>
#include <cstddef>

#include "ntn/model_spec.hpp"
#include "support/builders.hpp"
#include "support/hinges.hpp"

namespace ntn_test {

inline constexpr double kSdofK = 1e6;      // N/m, the hinge's elastic stiffness
inline constexpr double kSdofMass = 1e3;   // kg at node 0 (ux)
inline constexpr double kSdofYield = 1e4;  // N: u_y = 1 cm
inline constexpr Material kSdofMaterial{1e4, 1e4 / 2.6, 10.0};  // E A / L = 1 N/m, rho A L = 1 g
inline constexpr Section kSdofSection = rectangle(0.01, 0.01);  // A = 1e-4 m^2
inline constexpr double kSdofElementK = 1e4 * 1e-4 / 1.0;       // N/m, E A / L of the element
inline constexpr Mat3 kReversedX{-1, 0, 0, 0, -1, 0, 0, 0, 1};  // hinge frame: d = +u_x

// Sizes of the oscillator with room for `extra` (loads, inputs, outputs, ...).
constexpr ntn::Sizes sdof_sizes(ntn::Sizes extra) {
  extra.nodes = 2;
  extra.elements = 1;
  extra.hinges = 1;
  extra.hystereses = 1;
  return extra;
}

// The oscillator: hinge 0 (node 0 to the ground) plastic in its ux with law `law` in slot 0,
// every other direction free (the node's supports hold them). No loads, outputs or dt.
template <ntn::Sizes S>
void plastic_oscillator(ntn::ModelSpec<S>& s, const ntn::HysteresisSpec& law) {
  s = {};
  s.nodes[0] = {};
  s.nodes[0].fixed = static_cast<std::uint8_t>(kFixedAll & ~(1U << ntn::kUx));
  s.nodes[0].added = {kSdofMass, kSdofMass, kSdofMass, 0, 0, 0};
  s.nodes[1] = {};
  s.nodes[1].x = 1.0;
  s.nodes[1].fixed = kFixedAll;
  s.elements[0] = element(0, 1, kSdofMaterial, kSdofSection, {0, 0, 1});
  s.hinges[0] = hinge(0, ntn::kGround, kReversedX, released(0x3f));
  s.hinges[0].behaviour[ntn::kUx] = ntn::HingeBehaviour::kPlastic;
  s.hinges[0].stiffness[ntn::kUx] = kSdofK;
  s.hinges[0].hysteresis[ntn::kUx] = 0;
  s.hystereses[0] = law;
}

// Output channel of hinge 0, direction ux: kHingeForce, kHingeDisplacement, kHingePlastic, ...
inline ntn::OutputSpec hinge_channel(ntn::OutputKind kind, int hinge = 0, int direction = 0) {
  ntn::OutputSpec o;
  o.kind = kind;
  o.hinge = hinge;
  o.dof = direction;
  return o;
}

// A cantilever of 4 steel elements (2 m along x, 0.08 x 0.12 section), clamped at node 0, cut at
// node 2: node 5 (at node 2) starts the outer half, joined to node 2 by hinge 0 (node 1 = 5,
// node 2 = 2, the member's frame), rigid in translations and torsion and `behaviour` about the
// bending axes y and z with the rotational stiffness `k` (plastic: slots 0 (ry), 1 (rz)).
inline constexpr ntn::Sizes kHingedCantilever{.nodes = 6, .elements = 4, .hinges = 1};
constexpr ntn::Sizes hinged_cantilever_sizes(ntn::Sizes extra) {
  extra.nodes = kHingedCantilever.nodes;
  extra.elements = kHingedCantilever.elements;
  extra.hinges = 1;
  extra.hystereses = 2;
  return extra;
}

template <ntn::Sizes S>
void hinged_cantilever(ntn::ModelSpec<S>& s, ntn::HingeBehaviour behaviour, double k) {
  s = {};
  split_beam(s, 2.0, kSteel, rectangle(0.08, 0.12), 2, 5, kFixedAll, 0);
  s.hinges[0] = hinge(5, 2, kIdentity3);
  int slot = 0;
  for (const int d : {ntn::kRy, ntn::kRz}) {
    const auto k_ = static_cast<std::size_t>(d);
    s.hinges[0].behaviour[k_] = behaviour;
    s.hinges[0].stiffness[k_] = k;
    s.hinges[0].hysteresis[k_] = behaviour == ntn::HingeBehaviour::kPlastic ? slot++ : 0;
  }
}

}  // namespace ntn_test
