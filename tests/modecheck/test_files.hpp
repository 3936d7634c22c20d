// Helpers of the modal check's tests: running ntn-check-modes as a subprocess (exit code and
// everything it printed). The temporary directory and whole-file read and write come from
// tests/support/temp_files.hpp.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

#include "support/temp_files.hpp"

namespace ntn_test {

struct ProgramResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

// Runs `command` through the shell with stderr merged into stdout.
inline ProgramResult run_program(const std::string& command) {
  ProgramResult r;
  std::FILE* p = ::popen((command + " 2>&1").c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), p) != nullptr)
    r.output += buf.data();
  const int status = ::pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline std::string quoted(const std::string& s) {
  return "'" + s + "'";
}

}  // namespace ntn_test
