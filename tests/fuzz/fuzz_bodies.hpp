// The bodies of the fuzz targets, one function per target. Each takes any bytes and must return
// normally: an error or a result, never a crash, a sanitizer report or an unbounded allocation.
// The libFuzzer entry points (fuzz_<target>.cpp) call them, and so does fuzz_replay_test, which
// runs every seed and every regression input through them in the ordinary test build.
#pragma once

#include <cstddef>
#include <cstdint>

namespace ntn_fuzz {

void modelc(const std::uint8_t* data, std::size_t size);  // TOML text -> load_model_from_string
void at2(const std::uint8_t* data, std::size_t size);     // bytes -> io::read_at2_text
void csv(const std::uint8_t* data, std::size_t size);     // bytes -> io::read_csv_text
void packet(const std::uint8_t* data, std::size_t size);  // datagram -> hil::decode, InputGate

}  // namespace ntn_fuzz
