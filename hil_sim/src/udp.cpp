#include "ntn/hil/udp.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <utility>

namespace ntn::hil {
namespace {

sockaddr_in loopback(std::uint16_t port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  return a;
}

}  // namespace

std::string SocketStatus::message() const {
  if (ok()) return "ok";
  return std::string(call) + ": " + std::strerror(error);
}

UdpSocket::~UdpSocket() {
  close();
}

UdpSocket::UdpSocket(UdpSocket&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), port_(std::exchange(other.port_, 0)) {}

UdpSocket& UdpSocket::operator=(UdpSocket&& other) noexcept {
  if (this != &other) {
    close();
    fd_ = std::exchange(other.fd_, -1);
    port_ = std::exchange(other.port_, 0);
  }
  return *this;
}

void UdpSocket::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  port_ = 0;
}

SocketStatus UdpSocket::open(std::uint16_t port) {
  close();
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) return {errno, "socket"};
  const sockaddr_in a = loopback(port);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
    const int e = errno;
    ::close(fd);
    return {e, "bind"};
  }
  sockaddr_in bound{};
  socklen_t len = sizeof bound;
  if (::getsockname(fd, reinterpret_cast<sockaddr*>(&bound), &len) != 0) {
    const int e = errno;
    ::close(fd);
    return {e, "getsockname"};
  }
  fd_ = fd;
  port_ = ntohs(bound.sin_port);
  return {};
}

SocketStatus UdpSocket::send_to(std::uint16_t port, std::span<const std::byte> datagram) {
  if (fd_ < 0) return {EBADF, "sendto"};
  const sockaddr_in a = loopback(port);
  const ssize_t n = ::sendto(fd_, datagram.data(), datagram.size(), 0,
                             reinterpret_cast<const sockaddr*>(&a), sizeof a);
  if (n < 0) return {errno, "sendto"};
  if (static_cast<std::size_t>(n) != datagram.size()) return {EMSGSIZE, "sendto"};
  return {};
}

Received UdpSocket::receive(std::span<std::byte> buffer) {
  Received r;
  if (fd_ < 0) {
    r.status = ReceiveStatus::kError;
    r.error = EBADF;
    return r;
  }
  sockaddr_in from{};
  socklen_t len = sizeof from;
  // MSG_TRUNC: the return value is the datagram's real length, so truncation is visible.
  const ssize_t n = ::recvfrom(fd_, buffer.data(), buffer.size(), MSG_TRUNC,
                               reinterpret_cast<sockaddr*>(&from), &len);
  if (n < 0) {
    if (errno == EAGAIN || errno == EWOULDBLOCK) {
      r.status = ReceiveStatus::kWouldBlock;
    } else {
      r.status = ReceiveStatus::kError;
      r.error = errno;
    }
    return r;
  }
  const auto real = static_cast<std::size_t>(n);
  r.size = real < buffer.size() ? real : buffer.size();
  r.status = real > buffer.size() ? ReceiveStatus::kTruncated : ReceiveStatus::kOk;
  r.from_port = ntohs(from.sin_port);
  return r;
}

WaitStatus UdpSocket::wait_readable(std::chrono::nanoseconds timeout) {
  if (fd_ < 0) return WaitStatus::kError;
  if (timeout.count() < 0) timeout = std::chrono::nanoseconds(0);
  pollfd p{fd_, POLLIN, 0};
  const timespec ts{static_cast<time_t>(timeout.count() / 1'000'000'000),
                    static_cast<long>(timeout.count() % 1'000'000'000)};
  for (;;) {
    const int n = ::ppoll(&p, 1, &ts, nullptr);
    if (n > 0) return (p.revents & POLLIN) ? WaitStatus::kReadable : WaitStatus::kError;
    if (n == 0) return WaitStatus::kTimeout;
    if (errno != EINTR) return WaitStatus::kError;
  }
}

}  // namespace ntn::hil
