// ntn_test::init_model: ntn::init() with a workspace of its own. InitWorkspace<S> (the divided
// mass and the forest build's per-hinge placements) is large for large models; tests may use the
// heap, so it lives there for the call. A test that counts allocations around init() (the kernel
// never allocates) passes its own static workspace to ntn::init(spec, model, work) instead.
#pragma once

#include <memory>

#include "ntn/init.hpp"
#include "ntn/model.hpp"
#include "ntn/state.hpp"

namespace ntn_test {

// A model's spec and its Model, State and Scratch together (the tests keep one in static
// storage: a large model's do not fit the stack).
template <ntn::Sizes S>
struct Sim {
  ntn::ModelSpec<S> spec;
  ntn::Model<S> model;
  ntn::State<S> state;
  ntn::Scratch<S> scratch;
};

template <ntn::Sizes S>
[[nodiscard]] ntn::InitStatus init_model(const ntn::ModelSpec<S>& spec, ntn::Model<S>& model) {
  const auto work = std::make_unique<ntn::InitWorkspace<S>>();
  return ntn::init(spec, model, *work);
}

}  // namespace ntn_test
