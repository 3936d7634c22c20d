// The output hash that ntn-run-<model> and ntn-hil-<model> print ("output hash" on screen,
// "output_hash" in the JSON summary): XXH3-64 over every kernel step's outputs, as bytes in step
// order (Scratch::outputs after each step()), then the final state's u and v. Two runs that
// print the same hash took the same steps to the same bits (up to XXH3 collisions), the sign of
// zero included; the El Centro reference of ntn-run-frame3d, 6e2293debe9ca748, is this hash.
#pragma once

#include <cstddef>
#include <cstdint>

#include "ntn/state.hpp"

namespace ntn::hil {

class OutputHash {
 public:
  OutputHash();  // allocates XXH3's state (once, before a run)
  OutputHash(const OutputHash&) = delete;
  OutputHash& operator=(const OutputHash&) = delete;
  ~OutputHash();
  bool ok() const { return state_ != nullptr; }

  void add(const void* data, std::size_t bytes);
  // One kernel step's outputs (a sink's after_step, loop.hpp).
  template <Sizes S>
  void add_step(const Scratch<S>& scratch) {
    add(scratch.outputs.data(), scratch.outputs.size() * sizeof(double));
  }
  // The final state, then the digest (call once, at the end of the run).
  template <Sizes S>
  std::uint64_t finish(const State<S>& state) {
    add(state.u.data(), state.u.size() * sizeof(double));
    add(state.v.data(), state.v.size() * sizeof(double));
    return digest();
  }
  std::uint64_t digest() const;

 private:
  void* state_ = nullptr;  // XXH3_state_t (xxhash.h stays out of this header)
};

}  // namespace ntn::hil
