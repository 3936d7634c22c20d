// Writes the packet fuzzer's seed corpus (corpus/packet/): valid datagrams of every kind made by
// ntn::hil::encode, and a few broken on purpose. Run once by hand:
//   make_packet_seeds tests/fuzz/corpus/packet
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <fstream>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "ntn/hil/packet.hpp"

namespace {

void write(const std::string& dir, const std::string& name, std::span<const std::byte> bytes) {
  std::ofstream out(dir + "/" + name, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_packet_seeds DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  using ntn::hil::PacketKind;
  std::array<std::byte, ntn::hil::kMaxPacketBytes> buf{};

  const std::array<double, 3> three{0.25, -0.5, 1e-3};
  auto n = ntn::hil::encode(PacketKind::kInput, 7, 0, 0, three, buf);
  write(dir, "input_3ch_frame0", {buf.data(), n});
  n = ntn::hil::encode(PacketKind::kInput, 8, 3, 0, three, buf);
  write(dir, "input_3ch_frame3", {buf.data(), n});
  const std::array<double, 3> bad{std::numeric_limits<double>::quiet_NaN(), 5.0,
                                  -std::numeric_limits<double>::infinity()};
  n = ntn::hil::encode(PacketKind::kInput, 9, 0, 0, bad, buf);
  write(dir, "input_3ch_nan_range", {buf.data(), n});
  const std::array<double, 1> one{0.1};
  n = ntn::hil::encode(PacketKind::kInput, 10, 0, 0, one, buf);
  write(dir, "input_1ch_wrong_count", {buf.data(), n});
  n = ntn::hil::encode(PacketKind::kFrameEnd, 11, 0, 0, {}, buf);
  write(dir, "frame_end", {buf.data(), n});
  std::vector<double> many(ntn::hil::kMaxChannels);
  for (std::size_t i = 0; i < many.size(); ++i)
    many[i] = std::sin(static_cast<double>(i));
  n = ntn::hil::encode(PacketKind::kOutput, 12, 1000, ntn::hil::flag::kHeld | ntn::hil::flag::kLate,
                       many, buf);
  write(dir, "output_64ch", {buf.data(), n});

  // Broken: a checksum off by one bit, and a datagram cut short.
  n = ntn::hil::encode(PacketKind::kInput, 13, 1, 0, three, buf);
  buf[n - 1] ^= std::byte{1};
  write(dir, "input_bad_checksum", {buf.data(), n});
  write(dir, "input_truncated", {buf.data(), n - 9});
  return 0;
}
