// The UDP packet of the real-time loop (DESIGN §8): versioned, fixed layout, little-endian on the
// wire whatever the host, checksummed with XXH3-64. encode() and decode() work in caller buffers
// and never allocate.
//
//   offset  size  field
//        0     4  magic     "NTN1" (bytes 'N' 'T' 'N' '1'; u32 0x314E544E)
//        4     2  version   u16 = 1
//        6     1  kind      u8: 1 input, 2 output, 3 frame end (lock-step marker, count = 0)
//        7     1  reserved  u8, sent as 0, ignored on receipt (covered by the checksum)
//        8     4  sequence  u32, one per packet a sender produces (a resent copy keeps it)
//       12     8  frame     i64, frame index; frame time = frame x period
//       20     2  count     u16, number of values, <= kMaxChannels
//       22     2  flags     u16, see namespace flag (0 in input packets)
//       24  8*count values  f64, IEEE-754 bits as a little-endian u64 (NaN payloads kept)
//   24+8*count  8 checksum  u64 = XXH3_64bits(all preceding bytes), seed 0
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace ntn::hil {

inline constexpr std::uint32_t kPacketMagic = 0x314E544EU;  // "NTN1" read as a little-endian u32
inline constexpr std::uint16_t kPacketVersion = 1;
inline constexpr int kMaxChannels = 64;
inline constexpr std::size_t kHeaderBytes = 24;
inline constexpr std::size_t kChecksumBytes = 8;

// Bytes of a packet with `count` values.
constexpr std::size_t packet_size(int count) {
  return kHeaderBytes + 8 * static_cast<std::size_t>(count) + kChecksumBytes;
}
inline constexpr std::size_t kMinPacketBytes = packet_size(0);             // 32
inline constexpr std::size_t kMaxPacketBytes = packet_size(kMaxChannels);  // 544
// Receive into a buffer one byte longer than any valid packet: a longer datagram is then cut to
// a length no packet has, and decode() reports kLength instead of reading a valid-looking prefix.
inline constexpr std::size_t kReceiveBufferBytes = kMaxPacketBytes + 1;

enum class PacketKind : std::uint8_t {
  kInput = 1,     // sender -> loop: the input channels of one frame
  kOutput = 2,    // loop -> sender: the output channels of one frame, with flags
  kFrameEnd = 3,  // sender -> loop, lock-step mode only: "everything for `frame` has been sent"
};

// Bits of the flags field. Bits 0-10 and 15 are set by the input gate (what happened to the
// inputs of that frame); bit 11 by the sender schedule (schedule.hpp); bits 12-14 by the loop. An
// output packet carries the OR of both for its frame.
namespace flag {
inline constexpr std::uint16_t kHeld = 1U << 0;        // at least one channel held its last good
inline constexpr std::uint16_t kMissing = 1U << 1;     // no valid packet for the frame: all held
inline constexpr std::uint16_t kNonFinite = 1U << 2;   // a NaN/Inf value was replaced (held)
inline constexpr std::uint16_t kOutOfRange = 1U << 3;  // a value outside [min, max] was held
inline constexpr std::uint16_t kCorrupt = 1U << 4;     // a datagram failed to decode
inline constexpr std::uint16_t kWrongCount = 1U << 5;  // a packet had the wrong channel count
inline constexpr std::uint16_t kDuplicate = 1U << 6;  // a packet seen before (or a 2nd for a frame)
inline constexpr std::uint16_t kLate = 1U << 7;       // a packet for an already processed frame
inline constexpr std::uint16_t kEarly = 1U << 8;      // a packet for a later frame was buffered
inline constexpr std::uint16_t kReordered = 1U << 9;  // a packet older than the newest seen
inline constexpr std::uint16_t kTooEarly = 1U << 10;  // a packet beyond the jitter buffer: dropped
inline constexpr std::uint16_t kResync = 1U
                                         << 11;  // schedule: deadlines re-anchored (schedule.hpp)
inline constexpr std::uint16_t kBadFrame = 1U << 15;  // a packet for a frame outside the run or
                                                      // the plausibility window: dropped
inline constexpr std::uint16_t kGateMask = 0x87FF;    // bits the gate owns (0-10, 15)
inline constexpr std::uint16_t kAlarm = 1U << 12;     // loop: an output limit alarm is active
inline constexpr std::uint16_t kOverrun = 1U << 13;   // loop: the frame missed its deadline
inline constexpr std::uint16_t kDiverged = 1U << 14;  // loop: diverged, outputs held
}  // namespace flag

struct Packet {
  PacketKind kind = PacketKind::kInput;
  std::uint16_t flags = 0;
  std::uint32_t sequence = 0;
  std::int64_t frame = 0;
  std::uint16_t count = 0;  // values in use
  std::array<double, kMaxChannels> values{};

  std::span<const double> channels() const { return {values.data(), count}; }
};

enum class DecodeError : std::uint8_t {
  kOk = 0,
  kShort,     // fewer than kMinPacketBytes
  kMagic,     // not "NTN1"
  kVersion,   // version != kPacketVersion
  kKind,      // kind not 1, 2 or 3, or not the kind asked for
  kCount,     // count > kMaxChannels, or a frame-end marker with values
  kLength,    // datagram length != packet_size(count)
  kChecksum,  // XXH3 of the bytes does not match
};
inline constexpr int kDecodeErrorKinds = 8;
const char* to_string(DecodeError e);

// Writes a packet into `out`; returns the bytes written (packet_size(values.size())), or 0 if
// `out` is too small or there are more than kMaxChannels values. Never allocates.
std::size_t encode(PacketKind kind, std::uint32_t sequence, std::int64_t frame, std::uint16_t flags,
                   std::span<const double> values, std::span<std::byte> out);
std::size_t encode(const Packet& packet, std::span<std::byte> out);

// Reads a datagram. Checks, in order: length >= kMinPacketBytes, magic, version, kind, count,
// exact length, checksum. `out` is written only on kOk. Values are copied bit for bit.
DecodeError decode(std::span<const std::byte> bytes, Packet& out);
// Same, and a valid packet of another kind is kKind.
DecodeError decode(std::span<const std::byte> bytes, Packet& out, PacketKind expected);

// XXH3_64bits (seed 0) of `bytes`: the checksum function of the format.
std::uint64_t checksum(std::span<const std::byte> bytes);

}  // namespace ntn::hil
