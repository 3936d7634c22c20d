// The packet format (hil_sim/include/ntn/hil/packet.hpp): bytes on the wire fixed by the spec,
// bit-exact values, every decode error.
#include "ntn/hil/packet.hpp"

#include <gtest/gtest.h>
#include <xxhash.h>

#include <bit>
#include <cstdint>
#include <limits>
#include <vector>

namespace packet_test {

using namespace ntn::hil;

std::vector<std::byte> bytes(std::initializer_list<int> list) {
  std::vector<std::byte> out;
  for (int b : list)
    out.push_back(static_cast<std::byte>(b));
  return out;
}

std::vector<std::byte> encoded(PacketKind kind, std::uint32_t seq, std::int64_t frame,
                               std::uint16_t flags, std::vector<double> values) {
  std::vector<std::byte> buf(kMaxPacketBytes);
  const std::size_t n = encode(kind, seq, frame, flags, values, buf);
  buf.resize(n);
  return buf;
}

// Rewrites the checksum after a deliberate change to the body, so that the check under test
// (not the checksum) is what fails.
void reseal(std::vector<std::byte>& b) {
  const std::size_t body = b.size() - kChecksumBytes;
  const std::uint64_t h = XXH3_64bits(b.data(), body);
  for (std::size_t i = 0; i < 8; ++i)
    b[body + i] = static_cast<std::byte>(h >> (8 * i));
}

// The xxHash library computes what its specification says: XXH3_64bits of no bytes (seed 0) is
// 0x2D06800538D394C2 (xxHash's published sanity-check value).
TEST(Packet, Xxh3KnownAnswer) {
  EXPECT_EQ(XXH3_64bits(nullptr, 0), 0x2D06800538D394C2ULL);
}

// A known packet written out byte by byte from the layout in the spec: little-endian fields on
// any host. The checksum is XXH3 of the 40 hand-written bytes, stored little-endian.
TEST(Packet, GoldenBytes) {
  std::vector<std::byte> expect = bytes({
      0x4E, 0x54, 0x4E, 0x31,                          // magic "NTN1"
      0x01, 0x00,                                      // version 1
      0x01,                                            // kind input
      0x00,                                            // reserved
      0x04, 0x03, 0x02, 0x01,                          // sequence 0x01020304
      0x88, 0x77, 0x66, 0x55, 0x44, 0x33, 0x22, 0x11,  // frame 0x1122334455667788
      0x02, 0x00,                                      // count 2
      0x0B, 0x0A,                                      // flags 0x0A0B
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xF0, 0x3F,  // 1.0  = 0x3FF0000000000000
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x04, 0xC0,  // -2.5 = 0xC004000000000000
  });
  ASSERT_EQ(expect.size(), 40u);
  const std::uint64_t h = XXH3_64bits(expect.data(), expect.size());
  for (int i = 0; i < 8; ++i)
    expect.push_back(static_cast<std::byte>(h >> (8 * i)));

  const auto got =
      encoded(PacketKind::kInput, 0x01020304U, 0x1122334455667788LL, 0x0A0B, {1.0, -2.5});
  EXPECT_EQ(got, expect);
  EXPECT_EQ(got.size(), packet_size(2));

  Packet p;
  ASSERT_EQ(decode(expect, p), DecodeError::kOk);
  EXPECT_EQ(p.kind, PacketKind::kInput);
  EXPECT_EQ(p.sequence, 0x01020304U);
  EXPECT_EQ(p.frame, 0x1122334455667788LL);
  EXPECT_EQ(p.flags, 0x0A0B);
  ASSERT_EQ(p.count, 2);
  EXPECT_EQ(p.values[0], 1.0);
  EXPECT_EQ(p.values[1], -2.5);
}

// A negative frame is two's complement, little-endian; an output packet with no values is just
// header and checksum.
TEST(Packet, GoldenNegativeFrameEmptyOutput) {
  const auto got = encoded(PacketKind::kOutput, 7, -2, 0x8001, {});
  const auto expect_head =
      bytes({0x4E, 0x54, 0x4E, 0x31, 0x01, 0x00, 0x02, 0x00, 0x07, 0x00, 0x00, 0x00,
             0xFE, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x00, 0x00, 0x01, 0x80});
  ASSERT_EQ(got.size(), kMinPacketBytes);
  EXPECT_TRUE(std::equal(expect_head.begin(), expect_head.end(), got.begin()));
}

// Round trip of every kind of double bit pattern, NaN payloads and signs included: decode gives
// the sender's bits, not merely an equal value.
TEST(Packet, RoundTripIsBitExact) {
  const std::vector<std::uint64_t> bits = {
      0x7FF8000000000123ULL,  // quiet NaN with a payload
      0xFFF8DEADBEEF0001ULL,  // negative quiet NaN with a payload
      0x7FF0000000000001ULL,  // signalling NaN
      0x7FF0000000000000ULL,  // +Inf
      0xFFF0000000000000ULL,  // -Inf
      0x8000000000000000ULL,  // -0.0
      0x0000000000000001ULL,  // smallest subnormal
      0x7FEFFFFFFFFFFFFFULL,  // DBL_MAX
      0x3FB999999999999AULL,  // 0.1
  };
  std::vector<double> values;
  for (std::uint64_t b : bits)
    values.push_back(std::bit_cast<double>(b));
  for (PacketKind kind : {PacketKind::kInput, PacketKind::kOutput}) {
    const auto b =
        encoded(kind, 0xFFFFFFFFU, std::numeric_limits<std::int64_t>::min(), 0xFFFF, values);
    Packet p;
    ASSERT_EQ(decode(b, p), DecodeError::kOk);
    EXPECT_EQ(p.kind, kind);
    EXPECT_EQ(p.sequence, 0xFFFFFFFFU);
    EXPECT_EQ(p.frame, std::numeric_limits<std::int64_t>::min());
    EXPECT_EQ(p.flags, 0xFFFF);
    ASSERT_EQ(p.count, bits.size());
    for (std::size_t i = 0; i < bits.size(); ++i)
      EXPECT_EQ(std::bit_cast<std::uint64_t>(p.values[i]), bits[i]) << "value " << i;
  }
}

TEST(Packet, RoundTripAtMaxChannels) {
  std::vector<double> v(kMaxChannels);
  for (int i = 0; i < kMaxChannels; ++i)
    v[static_cast<std::size_t>(i)] = 1.0 / (i + 1);
  const auto b = encoded(PacketKind::kInput, 1, 2, 0, v);
  ASSERT_EQ(b.size(), kMaxPacketBytes);
  Packet p;
  ASSERT_EQ(decode(b, p, PacketKind::kInput), DecodeError::kOk);
  EXPECT_TRUE(std::equal(v.begin(), v.end(), p.channels().begin(), p.channels().end()));
}

TEST(Packet, EncodeRefusesSmallBufferAndTooManyValues) {
  std::vector<std::byte> buf(packet_size(3) - 1);
  const double v[3] = {1, 2, 3};
  EXPECT_EQ(encode(PacketKind::kInput, 0, 0, 0, v, buf), 0u);
  buf.resize(packet_size(3));
  EXPECT_EQ(encode(PacketKind::kInput, 0, 0, 0, v, buf), packet_size(3));
  std::vector<double> many(kMaxChannels + 1, 0.0);
  std::vector<std::byte> big(packet_size(kMaxChannels + 1));
  EXPECT_EQ(encode(PacketKind::kInput, 0, 0, 0, many, big), 0u);
}

TEST(Packet, DecodeErrors) {
  Packet p;
  const auto good = encoded(PacketKind::kInput, 5, 6, 0, {1.5, 2.5, 3.5});
  ASSERT_EQ(decode(good, p), DecodeError::kOk);

  // kShort: nothing, and one byte less than the smallest packet.
  EXPECT_EQ(decode({}, p), DecodeError::kShort);
  EXPECT_EQ(decode(std::span(good).first(kMinPacketBytes - 1), p), DecodeError::kShort);

  auto b = good;
  b[3] = std::byte{'2'};  // "NTN2"
  reseal(b);
  EXPECT_EQ(decode(b, p), DecodeError::kMagic);

  b = good;
  b[4] = std::byte{2};  // version 2, checksum valid
  reseal(b);
  EXPECT_EQ(decode(b, p), DecodeError::kVersion);

  for (int kind : {0, 4, 255}) {
    b = good;
    b[6] = static_cast<std::byte>(kind);
    reseal(b);
    EXPECT_EQ(decode(b, p), DecodeError::kKind) << "kind " << kind;
  }
  EXPECT_EQ(decode(good, p, PacketKind::kOutput), DecodeError::kKind);  // valid, other kind

  // kCount: 65 channels (the datagram long enough for them), and a frame-end with a value.
  std::vector<double> many(kMaxChannels, 0.0);
  b = encoded(PacketKind::kInput, 0, 0, 0, many);
  b.insert(b.end() - kChecksumBytes, 8, std::byte{0});
  b[20] = std::byte{kMaxChannels + 1};
  reseal(b);
  EXPECT_EQ(decode(b, p), DecodeError::kCount);
  b = encoded(PacketKind::kInput, 0, 0, 0, {0.0});
  b[6] = static_cast<std::byte>(PacketKind::kFrameEnd);
  reseal(b);
  EXPECT_EQ(decode(b, p), DecodeError::kCount);

  // kLength: one byte more, one byte less (both longer than a header).
  b = good;
  b.push_back(std::byte{0});
  EXPECT_EQ(decode(b, p), DecodeError::kLength);
  EXPECT_EQ(decode(std::span(good).first(good.size() - 1), p), DecodeError::kLength);

  // kChecksum: a value bit, and a checksum bit.
  b = good;
  b[kHeaderBytes + 3] ^= std::byte{0x10};
  EXPECT_EQ(decode(b, p), DecodeError::kChecksum);
  b = good;
  b.back() ^= std::byte{0x01};
  EXPECT_EQ(decode(b, p), DecodeError::kChecksum);

  // `out` is untouched by a failed decode.
  Packet q;
  q.sequence = 99;
  EXPECT_NE(decode(b, q), DecodeError::kOk);
  EXPECT_EQ(q.sequence, 99u);
}

// Any single flipped bit anywhere in a packet is caught by one of the checks.
TEST(Packet, EverySingleBitFlipIsRejected) {
  const auto good = encoded(PacketKind::kInput, 123, 456, 0, {0.25, -1e-3, 9.81});
  int rejected = 0, total = 0;
  for (std::size_t i = 0; i < good.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      auto b = good;
      b[i] ^= static_cast<std::byte>(1 << bit);
      Packet p;
      ++total;
      if (decode(b, p) != DecodeError::kOk) ++rejected;
    }
  }
  EXPECT_EQ(rejected, total);
  EXPECT_EQ(total, static_cast<int>(8 * packet_size(3)));
}

TEST(Packet, FrameEndMarker) {
  const auto b = encoded(PacketKind::kFrameEnd, 3, 41, 0, {});
  Packet p;
  ASSERT_EQ(decode(b, p), DecodeError::kOk);
  EXPECT_EQ(p.kind, PacketKind::kFrameEnd);
  EXPECT_EQ(p.frame, 41);
  EXPECT_EQ(p.count, 0);
}

}  // namespace packet_test
