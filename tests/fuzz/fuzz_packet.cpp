// libFuzzer entry point of the packet target (see fuzz_bodies.hpp).
#include <cstddef>
#include <cstdint>

#include "fuzz_bodies.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ntn_fuzz::packet(data, size);
  return 0;
}
