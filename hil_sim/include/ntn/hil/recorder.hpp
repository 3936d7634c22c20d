// Record and replay (DESIGN §8): a binary log of every frame's accepted inputs and its outputs,
// so a run can be re-run on the virtual clock and compared bit for bit.
//
// Layout, format version 2 (little-endian, as the host on every platform we build for; checked
// at compile time). Every record ends with the XXH3_64bits (seed 0) of its own bytes before it:
//   header  "NTNLOG1\0" | u32 version = 2 | u32 inputs | u32 outputs | u32 substeps |
//           u32 interpolate | f64 period s | f64 dt s | char[64] model name (NUL-terminated) |
//           u64 checksum                                                     (kLogHeaderBytes)
//   frame   i64 frame | u32 input flags | u32 output flags | f64 inputs[inputs] |
//           f64 outputs[outputs] | u64 checksum                 (log_frame_bytes(inputs, outputs))
//   end     i64 -1 | u64 frames written | u64 checksum                       (kLogEndBytes)
// Frames are numbered 0, 1, 2, ... in order. The end record is written when the log is closed
// (a finished run, or one stopped by SIGINT / SIGTERM); a log without it was cut (the process
// was killed, or the disk filled): its complete frames can still be replayed (LogReader says
// where it ends). Version 1 (no checksums, no end record) is refused.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

namespace ntn::hil {

inline constexpr std::uint32_t kLogVersion = 2;
inline constexpr std::size_t kLogHeaderBytes = 8 + 5 * 4 + 2 * 8 + 64 + 8;  // 116
inline constexpr std::size_t kLogEndBytes = 24;
inline constexpr std::uint32_t kLogMaxChannels = 4096;  // refused above, as implausible
constexpr std::size_t log_frame_bytes(std::size_t inputs, std::size_t outputs) {
  return 16 + 8 * (inputs + outputs) + 8;
}

struct LogHeader {
  std::uint32_t inputs = 0;
  std::uint32_t outputs = 0;
  std::uint32_t substeps = 0;
  std::uint32_t interpolate = 0;
  double period = 0;  // s
  double dt = 0;      // s
  std::string model;  // at most 63 bytes are stored
};

struct LogFrame {
  std::int64_t frame = 0;
  std::uint32_t input_flags = 0;
  std::uint32_t output_flags = 0;
  std::vector<double> inputs;
  std::vector<double> outputs;
};

// Writes a log. open() allocates the FILE buffer (1 MiB) and the frame buffer; write_frame()
// does not allocate. A write error (disk full) is kept and reported by close().
class Recorder {
 public:
  Recorder() = default;
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;
  ~Recorder();
  bool open(const std::string& path, const LogHeader& header);  // false: see error()
  void write_frame(std::int64_t frame, std::uint32_t input_flags, std::uint32_t output_flags,
                   std::span<const double> inputs, std::span<const double> outputs);
  // Hands the buffered frames to the file (open() does so with the header): a run killed later
  // leaves every frame before the last flush, which replays as a cut log.
  void flush();
  bool close();  // writes the end record and flushes; false on a write error (see error())
  std::int64_t frames() const { return frames_; }
  const std::string& error() const { return error_; }

 private:
  std::FILE* file_ = nullptr;
  std::vector<char> buffer_;
  std::vector<std::byte> record_;
  std::string path_, error_;
  std::int64_t frames_ = 0;
  int write_errno_ = 0;
};

// Reads a log record by record, checking everything it stores: the magic, the version, every
// record's checksum, the channel counts, period, dt, substeps and interpolate for plausibility,
// the frame numbers (0, 1, 2, ...), the end record's frame count, and that nothing follows it.
enum class LogRead {
  kFrame,      // a complete, checked frame
  kEnd,        // the end record: the log is complete
  kTruncated,  // the file ends without an end record (inside a frame, or at a record boundary)
  kError,      // a corrupt or inconsistent record: error()
};

class LogReader {
 public:
  LogReader() = default;
  LogReader(const LogReader&) = delete;
  LogReader& operator=(const LogReader&) = delete;
  ~LogReader();
  bool open(const std::string& path);  // reads and checks the header; false: see error()
  const LogHeader& header() const { return header_; }
  // The next record. kFrame fills `frame` (its vectors are resized once, then reused).
  // kTruncated and kError describe themselves in error() ("log ends inside frame N ...").
  LogRead next(LogFrame& frame);
  std::int64_t frames() const { return frames_; }  // complete frames read so far
  const std::string& error() const { return error_; }

 private:
  LogRead fail(const std::string& what);
  std::FILE* file_ = nullptr;
  LogHeader header_;
  std::vector<std::byte> record_;
  std::string path_, error_;
  std::int64_t frames_ = 0;
  long offset_ = 0;
};

}  // namespace ntn::hil
