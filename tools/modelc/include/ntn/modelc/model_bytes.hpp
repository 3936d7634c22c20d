// Memory of Model<S> + State<S> + Scratch<S> for sizes known only at run time, from the sizes
// and alignments of the kernel's per-item types laid out as the compiler lays out those structs.
#pragma once

#include <cstddef>

#include "ntn/model_spec.hpp"

namespace ntn::modelc {

struct MemoryFootprint {
  std::size_t model = 0;        // sizeof(Model<S>)
  std::size_t state = 0;        // sizeof(State<S>)
  std::size_t scratch = 0;      // sizeof(Scratch<S>)
  std::size_t total = 0;        // the three together
  std::size_t per_element = 0;  // bytes per element (BeamData's fields, in blocks of kBeamLanes)
  std::size_t per_node = 0;     // marginal bytes of one more node (8 DOF arrays + fixed + list)
  std::size_t per_hinge = 0;    // marginal bytes of one more hinge (HingeData + forest slots)
  std::size_t per_node_with_hinges = 0;  // extra per node in a model with hinges
  std::size_t per_curve_point = 0;       // marginal bytes of one more curve point
};

MemoryFootprint memory_footprint(const Sizes& s);

// sizeof(Model<S>) + sizeof(State<S>) + sizeof(Scratch<S>), exactly (tested against sizeof).
std::size_t model_bytes(const Sizes& s);

}  // namespace ntn::modelc
