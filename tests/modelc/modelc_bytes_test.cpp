// model_bytes(S) is the memory the kernel's three structs take for sizes known at run time:
// it must equal sizeof(Model<S>) + sizeof(State<S>) + sizeof(Scratch<S>) exactly, padding and
// zero-size arrays included. Truth: the compiler's own sizeof.
#include <gtest/gtest.h>

#include "ntn/model.hpp"
#include "ntn/modelc/model_bytes.hpp"
#include "ntn/state.hpp"

namespace modelc_bytes_test {

template <ntn::Sizes S>
void expect_exact() {
  const auto f = ntn::modelc::memory_footprint(S);
  EXPECT_EQ(f.model, sizeof(ntn::Model<S>));
  EXPECT_EQ(f.state, sizeof(ntn::State<S>));
  EXPECT_EQ(f.scratch, sizeof(ntn::Scratch<S>));
  EXPECT_EQ(ntn::modelc::model_bytes(S),
            sizeof(ntn::Model<S>) + sizeof(ntn::State<S>) + sizeof(ntn::Scratch<S>));
}

TEST(ModelBytes, EqualsSizeofExactly) {
  // Sizes: nodes, elements, time functions, time points, loads, inputs, outputs.
  expect_exact<ntn::Sizes{2, 1, 0, 0, 0, 0, 0}>();    // every optional array empty
  expect_exact<ntn::Sizes{21, 20, 0, 0, 1, 0, 3}>();  // cantilever
  expect_exact<ntn::Sizes{3, 2, 1, 1, 1, 1, 1}>();    // odd counts: padding
  expect_exact<ntn::Sizes{5, 4, 3, 7, 3, 2, 5}>();
  expect_exact<ntn::Sizes{7, 9, 2, 3, 0, 3, 0}>();
  expect_exact<ntn::Sizes{10001, 10000, 0, 0, 0, 0, 0}>();  // 10 000 elements
}

TEST(ModelBytes, EqualsSizeofExactlyWithHinges) {
  // ... then hinges, curves, curve points.
  expect_exact<ntn::Sizes{108, 104, 0, 0, 0, 1, 9, 12, 0, 0}>();  // frame3d, pinned beams
  expect_exact<ntn::Sizes{3, 2, 0, 0, 0, 0, 0, 1, 0, 0}>();       // one hinge
  expect_exact<ntn::Sizes{9, 7, 1, 2, 1, 1, 5, 5, 1, 4}>();       // hinged_beam-like
  expect_exact<ntn::Sizes{5, 4, 0, 0, 0, 0, 1, 3, 2, 7}>();       // odd counts: padding
  expect_exact<ntn::Sizes{7, 3, 0, 0, 0, 0, 0, 0, 1, 2}>();       // curves without hinges
  expect_exact<ntn::Sizes{1001, 1000, 0, 0, 0, 0, 0, 500, 0, 0}>();
}

// The marginal cost of more elements, nodes or hinges, as ntn-model prints it. The Model is
// aligned to 64 bytes (the mass table's entries), so the steps below are ones that keep its end
// padding: 16 element blocks (64 elements: 16 blocks of 48 bytes, 16 rotations and 16 stiffness
// entries), 64 nodes (16 mass-table entries), 16 hinges.
TEST(ModelBytes, PerElementNodeAndHinge) {
  constexpr ntn::Sizes a{8, 8, 0, 0, 0, 0, 0}, e{8, 72, 0, 0, 0, 0, 0};
  EXPECT_EQ(ntn::modelc::model_bytes(e) - ntn::modelc::model_bytes(a),
            64 * ntn::modelc::memory_footprint(a).per_element);
  EXPECT_EQ(
      ntn::modelc::memory_footprint(a).per_element,
      (sizeof(ntn::BeamBlock) + sizeof(ntn::BeamRotations) + sizeof(ntn::BeamStiffnessBlock)) /
              ntn::kBeamLanes +
          sizeof(std::int32_t));
  // 64 more nodes keep the 1-byte `fixed` array a multiple of 8: no new padding.
  constexpr ntn::Sizes n{72, 8, 0, 0, 0, 0, 0};
  EXPECT_EQ(ntn::modelc::model_bytes(n) - ntn::modelc::model_bytes(a),
            64 * ntn::modelc::memory_footprint(a).per_node);
  // 16 more hinges keep the 4-byte per-hinge arrays (hinge -> edge, the spring, branch,
  // projection, tree-stop and slip lists) and the 20-byte tree slots multiples of 8.
  constexpr ntn::Sizes h2{8, 8, 0, 0, 0, 0, 0, 2, 0, 0}, h4{8, 8, 0, 0, 0, 0, 0, 18, 0, 0};
  const auto f = ntn::modelc::memory_footprint(h2);
  EXPECT_EQ(ntn::modelc::model_bytes(h4) - ntn::modelc::model_bytes(h2), 16 * f.per_hinge);
  EXPECT_EQ(f.per_hinge, sizeof(ntn::HingeData) + sizeof(ntn::ForestEdge) +
                             sizeof(ntn::ForestEdgeMatrices) + sizeof(ntn::ForestRoot) +
                             6 * sizeof(std::int32_t) + sizeof(ntn::ForestTree) +
                             sizeof(std::int64_t) + 6 * sizeof(double) +
                             6 * sizeof(double));  // Scratch's stop_force, dashpot_force
  // 64 more nodes in a model with hinges: the per-node arrays plus the hinge ones.
  constexpr ntn::Sizes hn{72, 8, 0, 0, 0, 0, 0, 2, 0, 0};
  EXPECT_EQ(ntn::modelc::model_bytes(hn) - ntn::modelc::model_bytes(h2),
            64 * (f.per_node + f.per_node_with_hinges));
}

}  // namespace modelc_bytes_test
