// A small 3D frame for tests that need every kind of element orientation: a one-bay, one-storey
// portal, four columns (along z, reference x) and four beams around the top (along x and y,
// reference z), each member meshed into `divisions` elements, the column bases clamped.
#pragma once

#include <cstddef>
#include <cstdint>

#include "ntn/model_spec.hpp"
#include "ntn/time_step.hpp"
#include "support/builders.hpp"

namespace ntn_test {

constexpr ntn::Sizes portal_frame_sizes(int divisions, ntn::Sizes extra = {}) {
  extra.nodes = static_cast<std::size_t>(8 + 8 * (divisions - 1));
  extra.elements = static_cast<std::size_t>(8 * divisions);
  return extra;
}

// Nodes 0-3 are the column bases, 4-7 the tops (same order); returns complete().
template <ntn::Sizes S>
bool portal_frame(ntn::ModelSpec<S>& spec, int divisions, double bay = 4.0, double height = 3.0) {
  constexpr Section kColumn = rectangle(0.2, 0.2);
  constexpr Section kBeam = rectangle(0.15, 0.3);
  FrameBuilder<S> f(spec);
  const Vec3 corners[4] = {{0, 0, 0}, {bay, 0, 0}, {bay, bay, 0}, {0, bay, 0}};
  int base[4], top[4];
  for (int i = 0; i < 4; ++i)
    base[i] = f.add_node(corners[i], kFixedAll);
  for (int i = 0; i < 4; ++i)
    top[i] = f.add_node({corners[i][0], corners[i][1], height});
  for (int i = 0; i < 4; ++i)
    f.add_member(base[i], top[i], divisions, kSteel, kColumn, {1, 0, 0});
  for (int i = 0; i < 4; ++i) {
    f.add_member(top[i], top[(i + 1) % 4], divisions, kSteel, kBeam, {0, 0, 1});
  }
  return f.complete();
}

}  // namespace ntn_test

namespace ntn_test {

// The portal frame with every load and channel kind the kernel has: a ramped lateral load and a
// constant moment, gravity, damping, three inputs (ground acceleration in x and y in g, a force
// at a top corner) and one output of each kind. For determinism, input-holding, allocation and
// no-exceptions tests.
inline constexpr int kFeatureDivisions = 4;
inline constexpr ntn::Sizes kFeatureSizes = portal_frame_sizes(
    kFeatureDivisions,
    {.time_functions = 1, .time_points = 3, .loads = 2, .inputs = 3, .outputs = 6});

template <ntn::Sizes S>
bool feature_frame(ntn::ModelSpec<S>& spec, double dt_factor = 0.9) {
  static_assert(S.inputs == kFeatureSizes.inputs && S.outputs == kFeatureSizes.outputs &&
                S.loads == kFeatureSizes.loads && S.time_points == kFeatureSizes.time_points);
  spec = {};
  if (!portal_frame(spec, kFeatureDivisions)) return false;
  spec.nodes[6].added = {800, 800, 800, 0, 0, 0};
  spec.time_points = {{{0, 0}, {0.05, 1}, {0.2, 0.3}}};
  spec.time_functions[0] = {0, 3};
  spec.loads[0] = {4, ntn::kUx, 2e4, 0};
  spec.loads[1] = {5, ntn::kRz, 3e3, ntn::kConstant};
  spec.inputs[0] = {ntn::InputKind::kGroundAcceleration, 0, 0, 9.80665, -5, 5};
  spec.inputs[1] = {ntn::InputKind::kGroundAcceleration, 0, 1, 9.80665, -5, 5};
  spec.inputs[2] = {ntn::InputKind::kNodalForce, 7, ntn::kUy, 1e3, -100, 100};
  using K = ntn::OutputKind;
  spec.outputs[0] = {K::kDisplacement, 6, 0, 0, 0, ntn::kUx, 1.0};
  spec.outputs[1] = {K::kVelocity, 6, 0, 0, 0, ntn::kUy, 1.0};
  spec.outputs[2] = {K::kAcceleration, 5, 0, 0, 0, ntn::kUx, 1.0};
  spec.outputs[3] = {K::kElementForce, 0, 0, 3, 1, 4, 1.0};
  spec.outputs[4] = {K::kDrift, 0, 6, 0, 0, ntn::kUx, 1.0 / 3.0};
  spec.outputs[5] = {K::kReaction, 0, 0, 0, 0, ntn::kUx, 1.0};
  spec.settings.gravity = {0, 0, -9.81};
  spec.settings.alpha = 0.5;
  spec.settings.dt = dt_factor * ntn::stable_time_step(ntn::view(spec)).dt_stable;
  return true;
}

// A deterministic input sample in [-0.5, 0.5) for channel c at step n (splitmix64 of both):
// the same on every build, no libm.
inline double input_sample(int c, long n) {
  std::uint64_t z =
      (static_cast<std::uint64_t>(n) << 8) + static_cast<std::uint64_t>(c) + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53 - 0.5;
}

}  // namespace ntn_test
