// A small RAII UDP socket on the loopback interface: bound to 127.0.0.1:port, non-blocking,
// sending only to 127.0.0.1. Failures are return values carrying errno; nothing throws and
// nothing allocates after open().
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace ntn::hil {

// Outcome of a socket call: errno (0 = success) and the name of the system call that failed.
struct SocketStatus {
  int error = 0;
  const char* call = "";

  bool ok() const { return error == 0; }
  // "bind: Address already in use" (allocates: not for the hot path).
  std::string message() const;
};

enum class ReceiveStatus : std::uint8_t {
  kOk,          // one datagram in the buffer
  kTruncated,   // a datagram longer than the buffer: its first buffer.size() bytes are there
  kWouldBlock,  // nothing queued
  kError,       // see Received::error
};

struct Received {
  ReceiveStatus status = ReceiveStatus::kWouldBlock;
  std::size_t size = 0;         // bytes written into the buffer
  std::uint16_t from_port = 0;  // sender's port (its address is always 127.0.0.1)
  int error = 0;                // errno when status == kError

  bool has_datagram() const {
    return status == ReceiveStatus::kOk || status == ReceiveStatus::kTruncated;
  }
};

enum class WaitStatus : std::uint8_t { kReadable, kTimeout, kError };

class UdpSocket {
 public:
  UdpSocket() = default;
  ~UdpSocket();
  UdpSocket(UdpSocket&& other) noexcept;
  UdpSocket& operator=(UdpSocket&& other) noexcept;
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;

  // Binds a new non-blocking socket to 127.0.0.1:port (0 = a free port the kernel picks; port()
  // then reports it). Closes any socket this object held first.
  SocketStatus open(std::uint16_t port = 0);
  void close();
  bool is_open() const { return fd_ >= 0; }
  std::uint16_t port() const { return port_; }  // the bound port, 0 when closed
  int fd() const { return fd_; }

  // Sends one datagram to 127.0.0.1:port. Non-blocking: a full send buffer is EAGAIN.
  SocketStatus send_to(std::uint16_t port, std::span<const std::byte> datagram);
  // Takes one queued datagram, or reports kWouldBlock at once.
  Received receive(std::span<std::byte> buffer);
  // Waits (poll) until a datagram is queued or `timeout` passes; a zero timeout only looks.
  WaitStatus wait_readable(std::chrono::nanoseconds timeout);

 private:
  int fd_ = -1;
  std::uint16_t port_ = 0;
};

}  // namespace ntn::hil
