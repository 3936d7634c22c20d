// Record and replay (DESIGN §8): a binary log of every frame's accepted inputs and its outputs
// with their hash, so a run can be re-run on the virtual clock and compared bit for bit.
//
// Layout (little-endian, as the host on every platform we build for; checked at open):
//   header  "NTNLOG1\0" | u32 version = 1 | u32 inputs | u32 outputs | u32 substeps |
//           u32 interpolate | f64 period s | f64 dt s | char[64] model name
//   frame   i64 frame | u32 input flags | u32 output flags | f64 inputs[inputs] |
//           f64 outputs[outputs] | u64 XXH3 of the outputs' bytes
#pragma once

#include <cstdint>
#include <cstdio>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace ntn::hil {

struct LogHeader {
  std::uint32_t inputs = 0;
  std::uint32_t outputs = 0;
  std::uint32_t substeps = 0;
  std::uint32_t interpolate = 0;
  double period = 0;  // s
  double dt = 0;      // s
  std::string model;
};

struct LogFrame {
  std::int64_t frame = 0;
  std::uint32_t input_flags = 0;
  std::uint32_t output_flags = 0;
  std::vector<double> inputs;
  std::vector<double> outputs;
  std::uint64_t hash = 0;
};

std::uint64_t hash_outputs(std::span<const double> outputs);

// Writes a log. The FILE buffer is set up by open(); write_frame() does not allocate.
class Recorder {
 public:
  Recorder() = default;
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;
  ~Recorder();
  bool open(const std::string& path, const LogHeader& header);  // false: see error()
  void write_frame(std::int64_t frame, std::uint32_t input_flags, std::uint32_t output_flags,
                   std::span<const double> inputs, std::span<const double> outputs);
  bool close();  // flushes; false on a write error
  const std::string& error() const { return error_; }

 private:
  std::FILE* file_ = nullptr;
  std::vector<char> buffer_;
  std::string error_;
};

struct Log {
  LogHeader header;
  std::vector<LogFrame> frames;
};

// Reads a whole log; an error names the byte offset of the problem.
std::optional<Log> read_log(const std::string& path, std::string& error);

}  // namespace ntn::hil
