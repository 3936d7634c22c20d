// The model's element order: the order in which both element passes take the
// elements (element_pass.hpp: block by block, lane by lane), and so the order in which every node
// sums its elements' end forces. init() applies the rule below once; the model compiler reports it
// (ntn-model's report); the scalar reference and the SIMD path both follow it, so they agree by
// construction. A model file's own element order is kept for everything the user names an element
// by (outputs, member loads, messages): Model::beam(e) is element e of the file wherever it sits.
//
// The rule: elements sorted by
//   1. the window of their higher node, kOrderWindow nodes to a window: the elements at a window's
//      nodes come together, so the pass reads and adds to a few kilobytes of u and F at a time
//      (the u and F of 128 nodes are 12 KiB, well inside any L1 cache) whatever the file's order;
//   2. their AxisMap (beam.hpp): elements of one orientation come together, so that blocks of
//      kBeamLanes share one map and the SIMD pass picks their components by register names
//      instead of computing a mixed block both ways;
//   3. the higher node, the lower node, and the file's index (a total order: the same order on
//      every build).
// The higher node, not the lower: a member meshed into several elements usually has its interior
// nodes numbered after the joints, and by their higher node its elements stay together. The
// lumped masses sum the element ends at each node in the same order (assemble_lumped_mass), so a
// file that lists the same elements in another order is the same model, to the bit.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "ntn/beam.hpp"

namespace ntn {

inline constexpr std::int32_t kOrderWindow = 128;  // nodes

// An element as the rule sees it.
struct OrderElement {
  std::int32_t node_i = 0, node_j = 0;
  AxisMap axes = kGeneralAxes;
};

// order[k] = the file index of the element the passes take k-th (order has elements.size()
// entries). No heap: std::sort sorts in place.
inline void element_order(std::span<const OrderElement> elements, std::span<std::int32_t> order) {
  for (std::size_t k = 0; k < elements.size(); ++k)
    order[k] = static_cast<std::int32_t>(k);
  auto before = [&](std::int32_t a, std::int32_t b) {
    const OrderElement& x = elements[static_cast<std::size_t>(a)];
    const OrderElement& y = elements[static_cast<std::size_t>(b)];
    const std::int32_t xh = std::max(x.node_i, x.node_j), yh = std::max(y.node_i, y.node_j);
    if (xh / kOrderWindow != yh / kOrderWindow) return xh / kOrderWindow < yh / kOrderWindow;
    if (x.axes != y.axes) return x.axes < y.axes;
    if (xh != yh) return xh < yh;
    const std::int32_t xl = std::min(x.node_i, x.node_j), yl = std::min(y.node_i, y.node_j);
    if (xl != yl) return xl < yl;
    return a < b;
  };
  std::sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(elements.size()), before);
}

}  // namespace ntn
