// The loopback UDP socket (hil_sim/include/ntn/hil/udp.hpp).
#include "ntn/hil/udp.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <string>
#include <utility>

#include "ntn/hil/packet.hpp"

namespace udp_test {

using namespace ntn::hil;
using namespace std::chrono_literals;

std::span<const std::byte> as_bytes(const char* s, std::size_t n) {
  return {reinterpret_cast<const std::byte*>(s), n};
}

TEST(Udp, EphemeralPortsExchangeDatagrams) {
  UdpSocket a, b;
  ASSERT_TRUE(a.open().ok());
  ASSERT_TRUE(b.open(0).ok());
  EXPECT_NE(a.port(), 0);
  EXPECT_NE(a.port(), b.port());
  std::array<std::byte, 64> buf{};
  EXPECT_EQ(b.receive(buf).status, ReceiveStatus::kWouldBlock);  // non-blocking, nothing queued
  ASSERT_TRUE(a.send_to(b.port(), as_bytes("hello", 5)).ok());
  ASSERT_EQ(b.wait_readable(1s), WaitStatus::kReadable);
  const Received r = b.receive(buf);
  ASSERT_EQ(r.status, ReceiveStatus::kOk);
  EXPECT_EQ(r.size, 5u);
  EXPECT_EQ(r.from_port, a.port());
  EXPECT_EQ(std::memcmp(buf.data(), "hello", 5), 0);
  EXPECT_EQ(b.receive(buf).status, ReceiveStatus::kWouldBlock);
}

TEST(Udp, WaitTimesOut) {
  UdpSocket a;
  ASSERT_TRUE(a.open().ok());
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(a.wait_readable(20ms), WaitStatus::kTimeout);
  EXPECT_GE(std::chrono::steady_clock::now() - t0, 19ms);
  EXPECT_EQ(a.wait_readable(0ns), WaitStatus::kTimeout);
}

// A datagram longer than the buffer is reported truncated; with a buffer of
// kReceiveBufferBytes that cut length is one no packet has.
TEST(Udp, TruncationIsReported) {
  UdpSocket a, b;
  ASSERT_TRUE(a.open().ok() && b.open().ok());
  std::array<std::byte, kMaxPacketBytes + 100> big{};
  ASSERT_TRUE(a.send_to(b.port(), big).ok());
  ASSERT_EQ(b.wait_readable(1s), WaitStatus::kReadable);
  std::array<std::byte, kReceiveBufferBytes> buf{};
  const Received r = b.receive(buf);
  EXPECT_EQ(r.status, ReceiveStatus::kTruncated);
  EXPECT_TRUE(r.has_datagram());
  EXPECT_EQ(r.size, kReceiveBufferBytes);
  Packet p;
  EXPECT_NE(decode(std::span(buf).first(r.size), p), DecodeError::kOk);
}

TEST(Udp, ErrorsCarryErrnoAndTheCall) {
  UdpSocket a, b;
  ASSERT_TRUE(a.open().ok());
  const SocketStatus st = b.open(a.port());  // taken
  EXPECT_FALSE(st.ok());
  EXPECT_EQ(st.error, EADDRINUSE);
  EXPECT_EQ(std::string(st.call), "bind");
  EXPECT_NE(st.message().find("bind: "), std::string::npos);
  EXPECT_FALSE(b.is_open());
  EXPECT_EQ(b.send_to(a.port(), as_bytes("x", 1)).error, EBADF);
  std::array<std::byte, 8> buf{};
  EXPECT_EQ(b.receive(buf).status, ReceiveStatus::kError);
  EXPECT_EQ(b.wait_readable(1ms), WaitStatus::kError);
}

TEST(Udp, MoveTransfersTheSocket) {
  UdpSocket a;
  ASSERT_TRUE(a.open().ok());
  const std::uint16_t port = a.port();
  UdpSocket b = std::move(a);
  EXPECT_FALSE(a.is_open());  // NOLINT(bugprone-use-after-move): moved-from state is specified
  EXPECT_EQ(b.port(), port);
  UdpSocket c;
  ASSERT_TRUE(c.open().ok());
  c = std::move(b);
  EXPECT_EQ(c.port(), port);
  c.close();
  EXPECT_FALSE(c.is_open());
  // The port is free again.
  UdpSocket d;
  EXPECT_TRUE(d.open(port).ok());
}

}  // namespace udp_test
