#include "ntn/modelc/memory.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace ntn::modelc {
namespace {

// A "Key:   123 kB" line of a /proc file, in bytes.
std::optional<std::uint64_t> proc_kb(const char* path, const std::string& key) {
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    if (line.compare(0, key.size() + 1, key + ":") != 0) continue;
    std::istringstream s(line.substr(key.size() + 1));
    std::uint64_t kb = 0;
    if (s >> kb) return kb * 1024;
  }
  return std::nullopt;
}

std::optional<std::uint64_t> file_number(const std::string& path) {
  std::ifstream in(path);
  std::uint64_t v = 0;
  if (in >> v) return v;
  return std::nullopt;  // missing, or "max"
}

}  // namespace

AvailableMemory available_memory() {
  AvailableMemory a;
  const auto take = [&](std::uint64_t bytes, const char* what) {
    if (bytes < a.bytes) a.bytes = bytes, a.what = what;
  };
  if (const auto m = proc_kb("/proc/meminfo", "MemAvailable"))
    take(*m, "MemAvailable in /proc/meminfo");
  // cgroup v2: "0::/path" in /proc/self/cgroup.
  std::ifstream cg("/proc/self/cgroup");
  for (std::string line; std::getline(cg, line);) {
    if (line.compare(0, 3, "0::") != 0) continue;
    const std::string dir = "/sys/fs/cgroup" + line.substr(3);
    const auto max = file_number(dir + "/memory.max");
    const auto current = file_number(dir + "/memory.current");
    if (max && current) take(*max > *current ? *max - *current : 0, "the cgroup's memory.max");
  }
  const auto room = [&](int resource, std::optional<std::uint64_t> used, const char* what) {
    rlimit r{};
    if (getrlimit(resource, &r) != 0 || r.rlim_cur == RLIM_INFINITY) return;
    const std::uint64_t limit = r.rlim_cur, in_use = used.value_or(0);
    take(limit > in_use ? limit - in_use : 0, what);
  };
  room(RLIMIT_AS, proc_kb("/proc/self/status", "VmSize"), "the address-space limit (ulimit -v)");
  room(RLIMIT_DATA, proc_kb("/proc/self/status", "VmData"), "the data limit (ulimit -d)");
  return a;
}

std::string format_bytes(std::uint64_t bytes) {
  const double b = static_cast<double>(bytes);
  char s[32];
  if (b >= 1e9) {
    std::snprintf(s, sizeof s, "%.3g GB", b / 1e9);
  } else if (b >= 1e6) {
    std::snprintf(s, sizeof s, "%.3g MB", b / 1e6);
  } else {
    std::snprintf(s, sizeof s, "%.3g kB", b / 1e3);
  }
  return s;
}

std::optional<std::string> memory_refusal(const std::string& stage, std::uint64_t needed,
                                          const std::string& counts) {
  const AvailableMemory a = available_memory();
  if (needed <= a.bytes) return std::nullopt;
  return stage + " needs about " + format_bytes(needed) + " of memory (" + counts + "), and " +
         format_bytes(a.bytes) + " is available (" + a.what +
         "): refused before allocating it; a smaller model, or a machine or limit with more "
         "memory";
}

}  // namespace ntn::modelc
