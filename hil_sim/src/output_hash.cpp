#include "ntn/hil/output_hash.hpp"

#include <xxhash.h>

namespace ntn::hil {

OutputHash::OutputHash() {
  XXH3_state_t* s = XXH3_createState();
  if (s != nullptr && XXH3_64bits_reset(s) != XXH_OK) {
    XXH3_freeState(s);
    s = nullptr;
  }
  state_ = s;
}

OutputHash::~OutputHash() {
  XXH3_freeState(static_cast<XXH3_state_t*>(state_));
}

void OutputHash::add(const void* data, std::size_t bytes) {
  if (state_ != nullptr) (void)XXH3_64bits_update(static_cast<XXH3_state_t*>(state_), data, bytes);
}

std::uint64_t OutputHash::digest() const {
  return state_ != nullptr ? XXH3_64bits_digest(static_cast<const XXH3_state_t*>(state_)) : 0;
}

}  // namespace ntn::hil
