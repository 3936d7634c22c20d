// Helpers for the tests that run ntn-feeder and ntn-hil-<model> as subprocesses: a child process
// with its output in a file (killed if the test ends first), a wait with a time limit, free
// loopback ports, and a wait until a process has bound its UDP port. The temporary directory and
// read_file come from tests/support/temp_files.hpp.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "ntn/hil/udp.hpp"
#include "support/temp_files.hpp"

extern char** environ;

namespace ntn_test {

// A child process with stdout and stderr appended to one file; killed (SIGKILL) and reaped if
// the test ends before it does.
class Child {
 public:
  Child(const std::vector<std::string>& args, const std::string& output_path) {
    std::vector<char*> argv;
    for (const std::string& a : args)
      argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, output_path.c_str(), O_WRONLY | O_CREAT | O_APPEND,
                                     0644);
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
    ok_ = posix_spawn(&pid_, argv[0], &fa, nullptr, argv.data(), environ) == 0;
    posix_spawn_file_actions_destroy(&fa);
  }
  ~Child() {
    if (ok_ && !reaped_) {
      kill(pid_, SIGKILL);
      int status = 0;
      waitpid(pid_, &status, 0);
    }
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  bool started() const { return ok_; }
  pid_t pid() const { return pid_; }

  // Exit code; -1 if it died of a signal; -2 if it was still running after `limit` (it is
  // then killed).
  int wait(std::chrono::milliseconds limit = std::chrono::minutes(2)) {
    if (!ok_ || reaped_) return -1;
    const auto give_up = std::chrono::steady_clock::now() + limit;
    int status = 0;
    for (;;) {
      const pid_t r = waitpid(pid_, &status, WNOHANG);
      if (r == pid_) break;
      if (r < 0) return -1;
      if (std::chrono::steady_clock::now() > give_up) {
        kill(pid_, SIGKILL);
        waitpid(pid_, &status, 0);
        reaped_ = true;
        return -2;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    reaped_ = true;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

 private:
  pid_t pid_ = -1;
  bool ok_ = false;
  bool reaped_ = false;
};

// `n` distinct loopback UDP ports that were free a moment ago: bound together (so the kernel
// hands out different ones), then released for the subprocesses to bind.
inline std::vector<std::uint16_t> free_ports(int n) {
  std::vector<ntn::hil::UdpSocket> sockets(static_cast<std::size_t>(n));
  std::vector<std::uint16_t> ports;
  for (auto& s : sockets) {
    if (!s.open().ok()) return {};
    ports.push_back(s.port());
  }
  return ports;
}

// True once some process has a UDP socket bound to 127.0.0.1:port, read from /proc/net/udp
// (binding a probe socket would race with the process being waited for).
inline bool udp_port_bound(std::uint16_t port) {
  std::ifstream in("/proc/net/udp");
  char want[32];
  std::snprintf(want, sizeof want, "0100007F:%04X", static_cast<unsigned>(port));
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string slot, local;
    fields >> slot >> local;
    if (local == want) return true;
  }
  return false;
}

inline bool wait_port_bound(std::uint16_t port, std::chrono::milliseconds limit) {
  const auto give_up = std::chrono::steady_clock::now() + limit;
  while (!udp_port_bound(port)) {
    if (std::chrono::steady_clock::now() > give_up) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

}  // namespace ntn_test
