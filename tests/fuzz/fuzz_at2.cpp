// libFuzzer entry point of the at2 target (see fuzz_bodies.hpp).
#include <cstddef>
#include <cstdint>

#include "fuzz_bodies.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ntn_fuzz::at2(data, size);
  return 0;
}
