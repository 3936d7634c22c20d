#include "ntn/hil/recorder.hpp"

#include "ntn/hil/packet.hpp"

#include <xxhash.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>

namespace ntn::hil {

namespace {

static_assert(std::endian::native == std::endian::little,
              "the log is written in the host's byte order, which must be little-endian");

constexpr std::array<char, 8> kMagic = {'N', 'T', 'N', 'L', 'O', 'G', '1', '\0'};
constexpr std::int64_t kEndMarker = -1;

std::uint64_t checksum(const std::byte* data, std::size_t n) {
  return XXH3_64bits(data, n);
}

// Appends the bytes of a value at `at` and advances it.
template <class T>
void put(std::byte*& at, const T& v) {
  std::memcpy(at, &v, sizeof v);
  at += sizeof v;
}

template <class T>
T get(const std::byte*& at) {
  T v;
  std::memcpy(&v, at, sizeof v);
  at += sizeof v;
  return v;
}

// Reads up to n bytes; the count read.
std::size_t read_some(std::FILE* f, std::byte* out, std::size_t n) {
  return std::fread(out, 1, n, f);
}

std::string hex(std::uint64_t v) {
  char text[24];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
  return text;
}

}  // namespace

// ---- Recorder ----

Recorder::~Recorder() {
  (void)close();
}

bool Recorder::open(const std::string& path, const LogHeader& header) {
  path_ = path;
  frames_ = 0;
  write_errno_ = 0;
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) {
    error_ = "cannot write " + path + ": " + std::strerror(errno);
    return false;
  }
  buffer_.resize(1 << 20);  // one allocation, before the run
  std::setvbuf(file_, buffer_.data(), _IOFBF, buffer_.size());
  record_.resize(std::max(kLogHeaderBytes, log_frame_bytes(header.inputs, header.outputs)));
  std::byte* at = record_.data();
  std::memcpy(at, kMagic.data(), kMagic.size());
  at += kMagic.size();
  put(at, kLogVersion);
  put(at, header.inputs);
  put(at, header.outputs);
  put(at, header.substeps);
  put(at, header.interpolate);
  put(at, header.period);
  put(at, header.dt);
  std::array<char, 64> name{};
  std::memcpy(name.data(), header.model.data(), std::min<std::size_t>(63, header.model.size()));
  std::memcpy(at, name.data(), name.size());
  at += name.size();
  put(at, checksum(record_.data(), static_cast<std::size_t>(at - record_.data())));
  if (std::fwrite(record_.data(), 1, kLogHeaderBytes, file_) != kLogHeaderBytes)
    write_errno_ = errno != 0 ? errno : EIO;
  flush();  // the header on disk before the first frame
  record_.resize(log_frame_bytes(header.inputs, header.outputs));
  return true;
}

void Recorder::write_frame(std::int64_t frame, std::uint32_t input_flags,
                           std::uint32_t output_flags, std::span<const double> inputs,
                           std::span<const double> outputs) {
  if (file_ == nullptr) return;
  if (log_frame_bytes(inputs.size(), outputs.size()) != record_.size()) return;  // not this log's
  std::byte* at = record_.data();
  put(at, frame);
  put(at, input_flags);
  put(at, output_flags);
  std::memcpy(at, inputs.data(), inputs.size_bytes());
  at += inputs.size_bytes();
  std::memcpy(at, outputs.data(), outputs.size_bytes());
  at += outputs.size_bytes();
  put(at, checksum(record_.data(), static_cast<std::size_t>(at - record_.data())));
  if (std::fwrite(record_.data(), 1, record_.size(), file_) != record_.size()) {
    if (write_errno_ == 0) write_errno_ = errno != 0 ? errno : EIO;
    return;
  }
  ++frames_;
}

void Recorder::flush() {
  if (file_ == nullptr || write_errno_ != 0) return;
  errno = 0;
  if (std::fflush(file_) != 0) write_errno_ = errno != 0 ? errno : EIO;
}

bool Recorder::close() {
  if (file_ == nullptr) return write_errno_ == 0;
  std::array<std::byte, kLogEndBytes> end{};
  std::byte* at = end.data();
  put(at, kEndMarker);
  put(at, static_cast<std::uint64_t>(frames_));
  put(at, checksum(end.data(), 16));
  if (std::fwrite(end.data(), 1, end.size(), file_) != end.size() && write_errno_ == 0)
    write_errno_ = errno != 0 ? errno : EIO;
  if (std::fflush(file_) != 0 && write_errno_ == 0) write_errno_ = errno != 0 ? errno : EIO;
  if (std::ferror(file_) != 0 && write_errno_ == 0) write_errno_ = EIO;
  if (std::fclose(file_) != 0 && write_errno_ == 0) write_errno_ = errno != 0 ? errno : EIO;
  file_ = nullptr;
  if (write_errno_ != 0) {
    error_ = "--record: write error in " + path_ + ": " + std::strerror(write_errno_) +
             " (the log is incomplete)";
    return false;
  }
  return true;
}

// ---- LogReader ----

LogReader::~LogReader() {
  if (file_ != nullptr) std::fclose(file_);
}

LogRead LogReader::fail(const std::string& what) {
  error_ = path_ + ": byte " + std::to_string(offset_) + ": " + what;
  return LogRead::kError;
}

bool LogReader::open(const std::string& path) {
  path_ = path;
  file_ = std::fopen(path.c_str(), "rb");
  if (file_ == nullptr) {
    error_ = "cannot open " + path + ": " + std::strerror(errno);
    return false;
  }
  std::array<std::byte, kLogHeaderBytes> h{};
  const std::size_t got = read_some(file_, h.data(), h.size());
  if (std::ferror(file_) != 0) {
    error_ = "cannot read " + path + ": " + std::strerror(errno);
    return false;
  }
  const auto refuse = [&](const std::string& what) {
    error_ = path + ": " + what;
    return false;
  };
  if (got == 0)
    return refuse("the log is empty (0 bytes): the run that wrote it ended before its header");
  if (got < kMagic.size() || std::memcmp(h.data(), kMagic.data(), kMagic.size()) != 0)
    return refuse("not an ntn-rt log (no NTNLOG1 magic at its start)");
  const std::byte* at = h.data() + kMagic.size();
  if (got < kMagic.size() + 4)
    return refuse("truncated header (" + std::to_string(got) + " bytes)");
  const auto version = get<std::uint32_t>(at);
  if (version == 1) {
    return refuse(
        "log format version 1 (no checksums, no end record) is no longer read; this program "
        "reads version 2: record the run again");
  }
  if (version != kLogVersion) {
    return refuse("unknown log format version " + std::to_string(version) +
                  "; this program reads version " + std::to_string(kLogVersion));
  }
  if (got < kLogHeaderBytes) {
    return refuse("truncated header (" + std::to_string(got) + " of " +
                  std::to_string(kLogHeaderBytes) + " bytes)");
  }
  LogHeader& hd = header_;
  hd.inputs = get<std::uint32_t>(at);
  hd.outputs = get<std::uint32_t>(at);
  hd.substeps = get<std::uint32_t>(at);
  hd.interpolate = get<std::uint32_t>(at);
  hd.period = get<double>(at);
  hd.dt = get<double>(at);
  std::array<char, 64> name{};
  std::memcpy(name.data(), at, name.size());
  at += name.size();
  const auto stored = get<std::uint64_t>(at);
  const std::uint64_t computed = checksum(h.data(), kLogHeaderBytes - 8);
  if (stored != computed) {
    return refuse("header checksum " + hex(stored) + " != " + hex(computed) +
                  " of its bytes: the header is corrupt");
  }
  // A header with a good checksum was written by a Recorder; these guard against one that was
  // written by a broken program all the same.
  if (hd.inputs > kLogMaxChannels || hd.outputs > kLogMaxChannels)
    return refuse("implausible channel counts (" + std::to_string(hd.inputs) + " inputs, " +
                  std::to_string(hd.outputs) + " outputs)");
  if (hd.substeps < 1) return refuse("substeps is 0");
  if (hd.interpolate > 1) return refuse("interpolate is " + std::to_string(hd.interpolate));
  if (!std::isfinite(hd.period) || !(hd.period > 0) || !std::isfinite(hd.dt) || !(hd.dt > 0))
    return refuse("period and dt must be finite and > 0");
  if (std::find(name.begin(), name.end(), '\0') == name.end())
    return refuse("the model name is not NUL-terminated");
  hd.model = name.data();
  offset_ = static_cast<long>(kLogHeaderBytes);
  record_.resize(log_frame_bytes(hd.inputs, hd.outputs));
  return true;
}

LogRead LogReader::next(LogFrame& frame) {
  if (file_ == nullptr) {
    error_ = "the log is not open";
    return LogRead::kError;
  }
  const std::size_t n = record_.size();
  const std::size_t got = read_some(file_, record_.data(), n);
  if (std::ferror(file_) != 0) return fail(std::string("read error: ") + std::strerror(errno));
  const std::string k = std::to_string(frames_);
  const std::string done = frames_ == 0 ? std::string("no complete frame")
                                        : "replayed frames 0.." + std::to_string(frames_ - 1);
  if (got == 0) {
    error_ = path_ + ": log ends after " + std::to_string(frames_) +
             " frames without its end record (the run did not close it: killed?): " + done;
    return LogRead::kTruncated;
  }
  const std::byte* at = record_.data();
  std::int64_t index = 0;
  if (got >= 8) index = get<std::int64_t>(at);
  if (got >= 8 && index == kEndMarker) {
    if (got < kLogEndBytes) {
      error_ = path_ + ": log ends inside its end record after frame " +
               std::to_string(frames_ - 1) + " (truncated): " + done;
      return LogRead::kTruncated;
    }
    const auto count = get<std::uint64_t>(at);
    const auto stored = get<std::uint64_t>(at);
    if (stored != checksum(record_.data(), 16))
      return fail("the end record's checksum does not match: the record is corrupt");
    if (count != static_cast<std::uint64_t>(frames_)) {
      return fail("the end record says " + std::to_string(count) + " frames, the log holds " +
                  std::to_string(frames_));
    }
    const std::size_t trailing = got - kLogEndBytes;
    std::size_t more = 0;
    std::array<std::byte, 256> rest{};
    while (std::size_t r = read_some(file_, rest.data(), rest.size()))
      more += r;
    if (trailing + more > 0) {
      offset_ += static_cast<long>(kLogEndBytes);
      return fail(std::to_string(trailing + more) +
                  " bytes after the end record: not a log this program wrote");
    }
    return LogRead::kEnd;
  }
  if (got < n) {
    error_ = path_ + ": log ends inside frame " + k + " (truncated): " + done + " (" +
             std::to_string(got) + " of the frame's " + std::to_string(n) + " bytes are there)";
    return LogRead::kTruncated;
  }
  const auto stored = [&] {
    std::uint64_t v;
    std::memcpy(&v, record_.data() + n - 8, 8);
    return v;
  }();
  if (const std::uint64_t computed = checksum(record_.data(), n - 8); stored != computed) {
    return fail("frame " + k + ": checksum " + hex(stored) + " != " + hex(computed) +
                " of its bytes: the record is corrupt");
  }
  if (index != frames_)
    return fail("frame " + k + " is numbered " + std::to_string(index) +
                " (frames must be 0, 1, 2, ...)");
  const auto input_flags = get<std::uint32_t>(at);
  const auto output_flags = get<std::uint32_t>(at);
  // The loop records the source's bits (the gate's, and the sender schedule's resync bit) as
  // the input flags and adds its own (alarm, overrun, diverged) to them for the output flags.
  constexpr std::uint32_t kInputBits = flag::kGateMask | flag::kResync;
  constexpr std::uint32_t kLoopBits = flag::kAlarm | flag::kOverrun | flag::kDiverged;
  if ((input_flags & ~kInputBits) != 0)
    return fail("frame " + k + ": input flags 0x" + hex(input_flags).substr(12) +
                " have bits the input side does not set");
  if ((output_flags & ~(kInputBits | kLoopBits)) != 0 || (output_flags & kInputBits) != input_flags)
    return fail("frame " + k + ": output flags 0x" + hex(output_flags).substr(12) +
                " do not extend its input flags 0x" + hex(input_flags).substr(12));
  frame.frame = index;
  frame.input_flags = input_flags;
  frame.output_flags = output_flags;
  frame.inputs.resize(header_.inputs);
  frame.outputs.resize(header_.outputs);
  std::memcpy(frame.inputs.data(), at, 8 * frame.inputs.size());
  at += 8 * frame.inputs.size();
  std::memcpy(frame.outputs.data(), at, 8 * frame.outputs.size());
  ++frames_;
  offset_ += static_cast<long>(n);
  return LogRead::kFrame;
}

}  // namespace ntn::hil
