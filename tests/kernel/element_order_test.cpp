// The model's element order (element_order.hpp): init() places the elements by
// the rule (window of the higher node, AxisMap, nodes), each in one lane; Model::beam(e) is still
// element e of the file; and the order does not depend on the file's: a model whose elements come
// in another order (outputs and member loads renumbered with them) is the same model, byte for
// byte, and runs to the same bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <random>
#include <vector>

#include "../bench/frame_models.hpp"
#include "ntn/element_order.hpp"
#include "ntn/integrator.hpp"
#include "support/frames.hpp"
#include "support/init_model.hpp"

namespace element_order_test {

// The spec with its elements in order perm (new element k is old element perm[k]), the element
// indices of its outputs and member loads renumbered to match.
template <ntn::Sizes S>
void reorder(ntn::ModelSpec<S>& spec, const std::vector<int>& perm) {
  const auto old = spec.elements;
  std::vector<int> new_index(perm.size());
  for (std::size_t k = 0; k < perm.size(); ++k) {
    spec.elements[k] = old[static_cast<std::size_t>(perm[k])];
    new_index[static_cast<std::size_t>(perm[k])] = static_cast<int>(k);
  }
  for (ntn::OutputSpec& o : spec.outputs) {
    if (o.kind == ntn::OutputKind::kElementForce)
      o.element = new_index[static_cast<std::size_t>(o.element)];
  }
  for (ntn::ElementLoadSpec& l : spec.element_loads)
    l.element = new_index[static_cast<std::size_t>(l.element)];
}

std::vector<int> shuffled(std::size_t n, std::uint64_t seed) {
  std::vector<int> perm(n);
  std::iota(perm.begin(), perm.end(), 0);
  std::mt19937_64 rng(seed);
  std::shuffle(perm.begin(), perm.end(), rng);
  return perm;
}

// The OpenSees frame_scaling grid of 1 064 elements (the step-speed benchmark's frame).
constexpr ntn::bench::Grid kGrid{.nx = 6, .ny = 6, .storeys = 8, .col_div = 1, .beam_div = 1};
constexpr ntn::Sizes kGridSizes = ntn::bench::sizes_of(kGrid);

TEST(ElementOrder, EveryElementHasOnePlaceInTheRulesOrder) {
  static ntn_test::Sim<kGridSizes> sim;
  ntn::bench::build_frame<kGrid>(sim.spec);
  ASSERT_TRUE(ntn_test::init_model(sim.spec, sim.model).ok());
  const std::size_t n = kGridSizes.elements;
  std::vector<int> at(n, -1);  // place -> file element
  for (std::size_t e = 0; e < n; ++e) {
    const auto k = static_cast<std::size_t>(sim.model.element_slot[e]);
    ASSERT_LT(k, n);
    ASSERT_EQ(at[k], -1) << "two elements in place " << k;
    at[k] = static_cast<int>(e);
    // beam(e) is element e of the file, wherever it sits.
    const ntn::BeamData b = sim.model.beam(e);
    ASSERT_EQ(b.node_i, sim.spec.elements[e].node_i);
    ASSERT_EQ(b.node_j, sim.spec.elements[e].node_j);
  }
  // Consecutive places follow the rule as kernel/include/ntn/element_order.hpp states it.
  std::size_t moved = 0, uniform = 0;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const ntn::BeamData a = sim.model.beam(static_cast<std::size_t>(at[k]));
    const ntn::BeamData b = sim.model.beam(static_cast<std::size_t>(at[k + 1]));
    const int ha = std::max(a.node_i, a.node_j), hb = std::max(b.node_i, b.node_j);
    const auto key_a =
        std::make_tuple(ha / ntn::kOrderWindow, a.axes, ha, std::min(a.node_i, a.node_j), at[k]);
    const auto key_b = std::make_tuple(hb / ntn::kOrderWindow, b.axes, hb,
                                       std::min(b.node_i, b.node_j), at[k + 1]);
    EXPECT_LT(key_a, key_b) << "places " << k << ", " << k + 1;
    moved += at[k] != static_cast<int>(k) ? 1 : 0;
  }
  // The blocks: nearly all of one orientation (the point of the rule's second key).
  for (const ntn::BeamBlock& blk : sim.model.beams) {
    bool same = true;
    for (const ntn::AxisMap m : blk.axes)
      same = same && m == blk.axes[0];
    uniform += same ? 1 : 0;
  }
  EXPECT_GT(moved, 0U) << "the grid's file order is not the rule's: the test means something";
  EXPECT_GE(uniform, sim.model.beams.size() * 9 / 10);
}

// The grid with its elements shuffled is the same model, byte for byte: the same element blocks and
// rotations in the same places (the rule's keys are the elements' own) and the same lumped masses
// (summed at each node in the model's order), so the same sums and bits, where the file's order
// alone made it run 2.2-3.2x slower (tests/bench/README).
TEST(ElementOrder, TheFilesOrderDoesNotChangeTheModel) {
  static ntn_test::Sim<kGridSizes> a, b;
  ntn::bench::build_frame<kGrid>(a.spec);
  b.spec = a.spec;
  reorder(b.spec, shuffled(kGridSizes.elements, 5));
  ASSERT_TRUE(ntn_test::init_model(a.spec, a.model).ok());
  ASSERT_TRUE(ntn_test::init_model(b.spec, b.model).ok());
  EXPECT_EQ(std::memcmp(a.model.beams.data(), b.model.beams.data(), sizeof(a.model.beams)), 0);
  EXPECT_EQ(
      std::memcmp(a.model.rotations.data(), b.model.rotations.data(), sizeof(a.model.rotations)),
      0);
  EXPECT_EQ(
      std::memcmp(a.model.stiffness.data(), b.model.stiffness.data(), sizeof(a.model.stiffness)),
      0);
  EXPECT_EQ(a.model.num_stiffness, b.model.num_stiffness);
  EXPECT_EQ(std::memcmp(a.model.mass.data(), b.model.mass.data(), sizeof(a.model.mass)), 0);
  ntn::initial_state(a.model, a.state), ntn::initial_state(b.model, b.state);
  std::array<double, kGridSizes.inputs> in{};
  (void)ntn::start(a.model, a.state, a.scratch, in);
  (void)ntn::start(b.model, b.state, b.scratch, in);
  for (long n = 0; n < 300; ++n) {
    in[0] = ntn_test::input_sample(0, n), in[1] = ntn_test::input_sample(1, n);
    (void)ntn::step(a.model, a.state, a.scratch, in);
    (void)ntn::step(b.model, b.state, b.scratch, in);
    ASSERT_EQ(std::memcmp(a.state.u.data(), b.state.u.data(), sizeof(a.state.u)), 0) << n;
    ASSERT_EQ(std::memcmp(a.state.v.data(), b.state.v.data(), sizeof(a.state.v)), 0) << n;
  }
}

// The feature frame (every channel kind, an element-force channel among them) with its elements
// in several other orders: the same channels, bit for bit, step after step; so the element-force
// channel reads the element the file names.
TEST(ElementOrder, ChannelsNameTheFilesElements) {
  constexpr auto S = ntn_test::kFeatureSizes;
  static ntn_test::Sim<S> a, b;
  ASSERT_TRUE(ntn_test::feature_frame(a.spec));
  ASSERT_TRUE(ntn_test::init_model(a.spec, a.model).ok());
  for (const std::uint64_t seed : {1U, 2U, 3U}) {
    b.spec = a.spec;
    const std::vector<int> perm = shuffled(S.elements, seed);
    reorder(b.spec, perm);
    ASSERT_NE(b.spec.outputs[3].element, a.spec.outputs[3].element)
        << "seed " << seed << " must move the element-force channel's element";
    ASSERT_TRUE(ntn_test::init_model(b.spec, b.model).ok());
    ntn::initial_state(a.model, a.state), ntn::initial_state(b.model, b.state);
    std::array<double, S.inputs> in{};
    (void)ntn::start(a.model, a.state, a.scratch, in);
    (void)ntn::start(b.model, b.state, b.scratch, in);
    for (long n = 0; n < 2000; ++n) {
      for (std::size_t c = 0; c < S.inputs; ++c)
        in[c] = ntn_test::input_sample(static_cast<int>(c), n);
      (void)ntn::step(a.model, a.state, a.scratch, in);
      (void)ntn::step(b.model, b.state, b.scratch, in);
      ASSERT_EQ(std::memcmp(a.scratch.outputs.data(), b.scratch.outputs.data(),
                            sizeof(a.scratch.outputs)),
                0)
          << "seed " << seed << ", step " << n;
    }
  }
}

}  // namespace element_order_test
