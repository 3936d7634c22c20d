// Run-time storage (storage.hpp): Model, State, Scratch, InitWorkspace and, for the multi-core
// step, TeamWork at sizes known only when the model is loaded, their arrays bound to one block
// that the caller allocates once, before init(). The kernel only lays the block out and binds:
// it allocates nothing. Each array starts on its own cache line; the members and their lengths
// are footprint.hpp's lists, the one source of what each struct holds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>

#include "ntn/footprint.hpp"
#include "ntn/model.hpp"
#include "ntn/state.hpp"
#include "ntn/team.hpp"

namespace ntn {

// Everything one run of a model needs, in run-time storage.
struct RunTimeParts {
  Model<kRunTime> model;
  State<kRunTime> state;
  Scratch<kRunTime> scratch;
  InitWorkspace<kRunTime> init_work;
  TeamWork<kRunTime> team_work;  // the multi-core step's: bound only when asked for
  State<kRunTime> checkpoint;    // a second state (the loop's last good frame): likewise
};

// What runtime_bind() binds besides the model, its state, scratch and init workspace.
struct RunTimeOptions {
  bool team = false;        // TeamWork, for step() with a team (team.hpp)
  bool checkpoint = false;  // a second State
};

namespace detail {

inline constexpr std::size_t kArrayAlign = 64;  // a cache line: no array shares one

// A member list's visitor that gives each array of *object its part of the block (or, with no
// block, only counts the bytes).
template <class C>
class BindArrays {
 public:
  BindArrays(C* object, std::byte* block, std::size_t offset)
      : object_(object), block_(block), offset_(offset) {}
  template <class T>
  void operator()(Slice<T> C::*member, std::size_t n) {
    static_assert(alignof(T) <= kArrayAlign);
    offset_ = (offset_ + kArrayAlign - 1) / kArrayAlign * kArrayAlign;
    if (block_ != nullptr) {
      T* p = reinterpret_cast<T*>(block_ + offset_);
      std::uninitialized_value_construct_n(p, n);  // as std::array's {}: zeros, or T's defaults
      (object_->*member).bind(p, n);
    }
    offset_ += n * sizeof(T);
  }
  template <class T>
  void operator()(T C::*member) {
    if constexpr (std::is_same_v<T, ClampWork<kRunTime>>) {
      BindArrays<ClampWork<kRunTime>> inner(block_ ? &(object_->*member) : nullptr, block_,
                                            offset_);
      clamp_work_members(sizes_, inner);
      offset_ = inner.offset();
    }
  }
  void set_sizes(const Sizes& s) { sizes_ = s; }
  std::size_t offset() const { return offset_; }

 private:
  C* object_;
  std::byte* block_;
  std::size_t offset_;
  Sizes sizes_{};
};

template <class C, class List>
std::size_t bind_arrays(C* object, const Sizes& s, std::byte* block, std::size_t offset,
                        List list) {
  BindArrays<C> v(object, block, offset);
  v.set_sizes(s);
  list(s, v);
  if (object != nullptr && block != nullptr) object->sizes = s;
  return v.offset();
}

inline std::size_t bind_all(RunTimeParts* parts, const Sizes& s, const RunTimeOptions& o,
                            std::byte* block) {
  std::size_t at = 0;
  at = bind_arrays(parts ? &parts->model : nullptr, s, block, at,
                   [](const Sizes& z, auto& v) { model_members(z, v); });
  at = bind_arrays(parts ? &parts->state : nullptr, s, block, at,
                   [](const Sizes& z, auto& v) { state_members(z, v); });
  at = bind_arrays(parts ? &parts->scratch : nullptr, s, block, at,
                   [](const Sizes& z, auto& v) { scratch_members(z, v); });
  at = bind_arrays(parts ? &parts->init_work : nullptr, s, block, at,
                   [](const Sizes& z, auto& v) { init_workspace_members(z, v); });
  if (o.team) {
    at = bind_arrays(parts ? &parts->team_work : nullptr, s, block, at,
                     [](const Sizes& z, auto& v) { team_work_members(z, v); });
  }
  if (o.checkpoint) {
    at = bind_arrays(parts ? &parts->checkpoint : nullptr, s, block, at,
                     [](const Sizes& z, auto& v) { state_members(z, v); });
  }
  return at;
}

}  // namespace detail

// Alignment and bytes of the block that runtime_bind() takes for sizes s.
inline constexpr std::size_t kRunTimeBlockAlign = detail::kArrayAlign;
inline std::size_t runtime_block_bytes(const Sizes& s, const RunTimeOptions& o = {}) {
  return detail::bind_all(nullptr, s, o, nullptr);
}

// Binds every array of `parts` to its part of `block` (aligned to kRunTimeBlockAlign, at least
// runtime_block_bytes(s, o) long) and sets each struct's sizes; the arrays start as a compiled
// model's do (zeros, or the element's defaults). False, binding nothing, when the block is too
// small or misaligned. The parts are then ready for init(); a second binding is another model's.
[[nodiscard]] inline bool runtime_bind(RunTimeParts& parts, const Sizes& s, const RunTimeOptions& o,
                                       std::span<std::byte> block) {
  if (s.runtime) return false;  // the model's own sizes, not the storage's tag
  if (block.size() < runtime_block_bytes(s, o)) return false;
  if (reinterpret_cast<std::uintptr_t>(block.data()) % kRunTimeBlockAlign != 0) return false;
  detail::bind_all(&parts, s, o, block.data());
  return true;
}

// A State of its own (a checkpoint): its bytes, and its binding to a block of them.
inline std::size_t runtime_state_bytes(const Sizes& s) {
  return detail::bind_arrays(static_cast<State<kRunTime>*>(nullptr), s, nullptr, 0,
                             [](const Sizes& z, auto& v) { state_members(z, v); });
}
[[nodiscard]] inline bool runtime_bind_state(State<kRunTime>& state, const Sizes& s,
                                             std::span<std::byte> block) {
  if (s.runtime || block.size() < runtime_state_bytes(s)) return false;
  if (reinterpret_cast<std::uintptr_t>(block.data()) % kRunTimeBlockAlign != 0) return false;
  detail::bind_arrays(&state, s, block.data(), 0,
                      [](const Sizes& z, auto& v) { state_members(z, v); });
  return true;
}

}  // namespace ntn
