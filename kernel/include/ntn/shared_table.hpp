// The rule by which equal entries of a model's tables share one slot (the element blocks'
// stiffness, element_pass.hpp; the node groups' masses, dof_pass.hpp): an entry is compared, byte
// for byte (so -0.0 and +0.0 differ), with the last kShareWindow distinct entries, newest first,
// and takes the first equal one, else is appended. The window bounds init's work (entries x
// kShareWindow comparisons) whatever the model; a table that finds no equal keeps every entry,
// which changes where a reader finds its values, never the values.
#pragma once

#include <cstddef>
#include <cstring>

namespace ntn {

inline constexpr std::size_t kShareWindow = 64;

// `x` into table[0, distinct): the index of the entry it shares, or `distinct` after appending it
// (distinct is then one more).
template <class T>
std::size_t share_entry(T* table, std::size_t& distinct, const T& x) {
  for (std::size_t k = distinct; k-- > 0 && distinct - k <= kShareWindow;) {
    if (std::memcmp(&table[k], &x, sizeof x) == 0) return k;
  }
  table[distinct] = x;
  return distinct++;
}

}  // namespace ntn
