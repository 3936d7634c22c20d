// Packet encoding and decoding (see packet.hpp for the layout). Byte order is spelled out with
// shifts, so the wire format is little-endian on any host.
#include "ntn/hil/packet.hpp"

#include <xxhash.h>

#include <bit>

namespace ntn::hil {
namespace {

template <typename U>
void put(std::byte* p, U v) {
  for (std::size_t i = 0; i < sizeof(U); ++i) {
    p[i] = static_cast<std::byte>(static_cast<std::uint64_t>(v) >> (8 * i));
  }
}

template <typename U>
U get(const std::byte* p) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < sizeof(U); ++i) {
    v |= static_cast<std::uint64_t>(std::to_integer<std::uint8_t>(p[i])) << (8 * i);
  }
  return static_cast<U>(v);
}

}  // namespace

const char* to_string(DecodeError e) {
  switch (e) {
    case DecodeError::kOk:
      return "ok";
    case DecodeError::kShort:
      return "shorter than a packet header";
    case DecodeError::kMagic:
      return "bad magic";
    case DecodeError::kVersion:
      return "unsupported version";
    case DecodeError::kKind:
      return "wrong packet kind";
    case DecodeError::kCount:
      return "bad channel count";
    case DecodeError::kLength:
      return "length does not match the channel count";
    case DecodeError::kChecksum:
      return "checksum mismatch";
  }
  return "unknown";
}

std::uint64_t checksum(std::span<const std::byte> bytes) {
  return XXH3_64bits(bytes.data(), bytes.size());
}

std::size_t encode(PacketKind kind, std::uint32_t sequence, std::int64_t frame, std::uint16_t flags,
                   std::span<const double> values, std::span<std::byte> out) {
  if (values.size() > static_cast<std::size_t>(kMaxChannels)) return 0;
  const std::size_t size = packet_size(static_cast<int>(values.size()));
  if (out.size() < size) return 0;
  std::byte* p = out.data();
  put<std::uint32_t>(p + 0, kPacketMagic);
  put<std::uint16_t>(p + 4, kPacketVersion);
  put<std::uint8_t>(p + 6, static_cast<std::uint8_t>(kind));
  put<std::uint8_t>(p + 7, 0);
  put<std::uint32_t>(p + 8, sequence);
  put<std::uint64_t>(p + 12, static_cast<std::uint64_t>(frame));
  put<std::uint16_t>(p + 20, static_cast<std::uint16_t>(values.size()));
  put<std::uint16_t>(p + 22, flags);
  for (std::size_t i = 0; i < values.size(); ++i) {
    put<std::uint64_t>(p + kHeaderBytes + 8 * i, std::bit_cast<std::uint64_t>(values[i]));
  }
  const std::size_t body = size - kChecksumBytes;
  put<std::uint64_t>(p + body, checksum(out.first(body)));
  return size;
}

std::size_t encode(const Packet& packet, std::span<std::byte> out) {
  if (packet.count > kMaxChannels) return 0;
  return encode(packet.kind, packet.sequence, packet.frame, packet.flags, packet.channels(), out);
}

DecodeError decode(std::span<const std::byte> bytes, Packet& out) {
  if (bytes.size() < kMinPacketBytes) return DecodeError::kShort;
  const std::byte* p = bytes.data();
  if (get<std::uint32_t>(p + 0) != kPacketMagic) return DecodeError::kMagic;
  if (get<std::uint16_t>(p + 4) != kPacketVersion) return DecodeError::kVersion;
  const auto kind = get<std::uint8_t>(p + 6);
  if (kind < 1 || kind > 3) return DecodeError::kKind;
  const auto count = get<std::uint16_t>(p + 20);
  if (count > kMaxChannels) return DecodeError::kCount;
  if (kind == static_cast<std::uint8_t>(PacketKind::kFrameEnd) && count != 0) {
    return DecodeError::kCount;
  }
  const std::size_t size = packet_size(count);
  if (bytes.size() != size) return DecodeError::kLength;
  const std::size_t body = size - kChecksumBytes;
  if (get<std::uint64_t>(p + body) != checksum(bytes.first(body))) return DecodeError::kChecksum;

  out.kind = static_cast<PacketKind>(kind);
  out.sequence = get<std::uint32_t>(p + 8);
  out.frame = static_cast<std::int64_t>(get<std::uint64_t>(p + 12));
  out.count = count;
  out.flags = get<std::uint16_t>(p + 22);
  for (std::size_t i = 0; i < count; ++i) {
    out.values[i] = std::bit_cast<double>(get<std::uint64_t>(p + kHeaderBytes + 8 * i));
  }
  return DecodeError::kOk;
}

DecodeError decode(std::span<const std::byte> bytes, Packet& out, PacketKind expected) {
  Packet p;
  const DecodeError e = decode(bytes, p);
  if (e != DecodeError::kOk) return e;
  if (p.kind != expected) return DecodeError::kKind;
  out = p;
  return DecodeError::kOk;
}

}  // namespace ntn::hil
