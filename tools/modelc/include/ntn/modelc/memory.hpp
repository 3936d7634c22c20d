// The memory a model needs, said before it is allocated: what the process may still use
// (available_memory) against an estimate of each stage. The estimates are upper bounds from
// measured costs (config/README.md, "Limits of a model file"): the TOML tree per value, the
// compile stages per node, member and element, the run-time storage exactly.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace ntn::modelc {

// The TOML parser's tree, per value, key or table the text holds (NestingScan::values): the
// dearest measured pattern is 184 bytes (`a1 = 0` lines: a key, a value and a map node).
inline constexpr std::uint64_t kParseBytesPerValue = 200;
// The compile stages (SourceModel, the mesh, ModelDescription), measured at 100 000 members of
// one element each (1 080 bytes per node, member and element together) and at 10^6 elements
// in 1 000 members (390 bytes per element with its mesh node).
inline constexpr std::uint64_t kCompileBytesPerNode = 400;
inline constexpr std::uint64_t kCompileBytesPerMember = 1000;
inline constexpr std::uint64_t kCompileBytesPerElement = 450;

struct AvailableMemory {
  std::uint64_t bytes = UINT64_MAX;
  std::string what;  // "MemAvailable (/proc/meminfo)", "the cgroup's memory.max", "ulimit -v"
};

// The least of: the system's available memory (/proc/meminfo MemAvailable), the room left under
// this process's cgroup limit (memory.max - memory.current) and under its address-space and
// data limits (RLIMIT_AS, RLIMIT_DATA less what is mapped). UINT64_MAX when none is known.
AvailableMemory available_memory();

// "8.7 GB", "512 MB", "96 kB": three significant digits, decimal units.
std::string format_bytes(std::uint64_t bytes);

// The message refusing a stage that needs `needed` bytes ("reading the file", "compiling the
// model"; `counts`: what it is made of) when that is more than available_memory(); nullopt
// when it fits.
std::optional<std::string> memory_refusal(const std::string& stage, std::uint64_t needed,
                                          const std::string& counts);

}  // namespace ntn::modelc
