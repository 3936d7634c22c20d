// One kernel, two storages (DESIGN §2): the sizes of a model, and the arrays its structs hold.
//
// Compiled storage: Sizes known at compile time (the model compiler's header), every array a
// std::array inside the struct: Model<S>, State<S> ... are plain objects, static on the embedded
// target. Run-time storage: Sizes `kRunTime`, every array a Slice, a view into one block the
// caller allocated once before init() (storage_bind.hpp lays it out); the sizes are a member
// that the binding sets. The kernel's code reads sizes as `m.sizes.x` and arrays through
// Array<T, S, N>: the same source lines compute both, and for compiled storage `m.sizes` is a
// static constexpr member, so they compile to what they did with std::array alone.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>
#include <type_traits>

namespace ntn {

// The sizes of a model. A structural type, so it is a template parameter: compile-time sizes, or
// kRunTime for run-time storage.
struct Sizes {
  std::size_t nodes = 0;
  std::size_t elements = 0;
  std::size_t time_functions = 0;
  std::size_t time_points = 0;  // all time-function points, concatenated
  std::size_t loads = 0;
  std::size_t inputs = 0;
  std::size_t outputs = 0;
  std::size_t hinges = 0;  // NTN hinges, member-end releases and supports with a frame (DESIGN §7)
  std::size_t curves = 0;  // force-deformation curves of `curve` hinge directions
  std::size_t curve_points = 0;   // all curve points, concatenated
  std::size_t element_loads = 0;  // distributed loads on elements (the member loads' parts)
  std::size_t hystereses = 0;     // hysteretic hinge directions (kPlastic), each with its history
  std::size_t geometric = 0;      // p_delta and leaning elements (geometry.hpp)
  std::size_t corotational = 0;   // corotational elements (corotational.hpp)
  // True only in kRunTime: the counts above are zero, the model's own are in its `sizes`.
  bool runtime = false;

  friend constexpr bool operator==(const Sizes&, const Sizes&) = default;
};

// Run-time storage: the sizes come from the loaded model (Model<kRunTime>::sizes).
inline constexpr Sizes kRunTime{.runtime = true};

// A view of `size()` elements of the run-time storage's block, with the value semantics of the
// std::array it stands for: assignment copies elements (never rebinds), constness is deep, and it
// cannot be copy-constructed (a copied State would share its arrays: copy one into a bound one).
// bind() is the one way to point it at memory (storage_bind.hpp).
template <class T>
class Slice {
 public:
  using value_type = std::remove_cv_t<T>;
  using size_type = std::size_t;
  using iterator = T*;
  using const_iterator = const T*;

  Slice() = default;
  Slice(const Slice&) = delete;
  ~Slice() = default;
  // Element by element, as std::array's assignment: both views hold size() elements (the binding
  // sized them from the same Sizes); only the common part is copied otherwise.
  Slice& operator=(const Slice& other) {
    if (this != &other) assign(other);
    return *this;
  }
  template <class Range>
  Slice& operator=(const Range& other) {
    assign(other);
    return *this;
  }

  void bind(T* data, std::size_t size) {
    data_ = data;
    size_ = size;
  }

  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  T* begin() { return data_; }
  T* end() { return data_ + size_; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }
  void fill(const T& x) { std::fill(data_, data_ + size_, x); }

 private:
  template <class Range>
  void assign(const Range& other) {
    const std::size_t n = std::min<std::size_t>(size_, std::size(other));
    std::copy(std::data(other), std::data(other) + n, data_);
  }

  T* data_ = nullptr;
  std::size_t size_ = 0;
};

// An array of N elements of T in storage S: a std::array, or a Slice of the block.
template <class T, Sizes S, std::size_t N>
using Array = std::conditional_t<S.runtime, Slice<T>, std::array<T, N>>;

// The sizes of a struct in storage S, as the member `sizes`: static constexpr for compiled
// storage (every `m.sizes.x` a constant), a value the binding sets for run-time storage.
template <Sizes S, bool = S.runtime>
struct SizesOf {
  static constexpr Sizes sizes = S;
};
template <Sizes S>
struct SizesOf<S, true> {
  Sizes sizes{};
};

// The part of a size that the kernel's if-constexpr guards may skip: compiled storage knows at
// compile time that a model has no hinges (no hinge code is instantiated), run-time storage
// decides at run time.
template <Sizes S>
inline constexpr bool kMayHaveHinges = S.runtime || S.hinges > 0;
template <Sizes S>
inline constexpr bool kMayHaveHystereses = S.runtime || (S.hinges > 0 && S.hystereses > 0);
// A model whose hinges may turn with their nodes (corotational geometry, HingeData::turns).
template <Sizes S>
inline constexpr bool kMayTurnHinges = S.runtime || (S.hinges > 0 && S.corotational > 0);

// What a step takes its inputs as: the std::array of the model's channels (compiled storage), a
// span of them (run-time storage; one of another length holds every channel).
template <Sizes S>
using StepInputs =
    std::conditional_t<S.runtime, std::span<const double>, const std::array<double, S.inputs>&>;

}  // namespace ntn
