// The log of the frame loop (hil_sim/include/ntn/hil/recorder.hpp, format 2): what the Recorder
// writes is read back exactly; a log cut at any byte gives every complete frame and says where it
// ends (never a clean end); any changed bit, trailing bytes, a skipped frame number, inconsistent
// flags and a version-1 or unknown version are refused; a write error is reported by close(). No
// timing, no tolerance: bytes and bits are compared.
#include <gtest/gtest.h>
#include <xxhash.h>

#include <cstring>
#include <string>
#include <vector>

#include "ntn/hil/packet.hpp"
#include "ntn/hil/recorder.hpp"
#include "support/temp_files.hpp"

namespace log_format_test {

using ntn::hil::LogFrame;
using ntn::hil::LogRead;
using ntn::hil::LogReader;
using ntn::hil::Recorder;
using ntn_test::read_file;
using ntn_test::TempDir;
using ntn_test::write_file;

constexpr std::uint32_t kIn = 1, kOut = 2;
constexpr std::size_t kFrameBytes = ntn::hil::log_frame_bytes(kIn, kOut);  // 48

ntn::hil::LogHeader header() {
  ntn::hil::LogHeader h;
  h.inputs = kIn, h.outputs = kOut, h.substeps = 4, h.interpolate = 0;
  h.period = 1e-3, h.dt = 0.25e-3, h.model = "test_model";
  return h;
}

double in_value(std::int64_t k) {
  return 0.5 * static_cast<double>(k) - 1.0;
}
double out_value(std::int64_t k, int c) {
  return static_cast<double>(k * 10 + c) / 3.0;
}

// A log of `frames` frames; frame 1 carries the gate's held bit and an alarm, frame 2 the sender
// schedule's resync bit (input side, schedule.hpp).
std::string write_log(const std::string& path, int frames) {
  Recorder r;
  EXPECT_TRUE(r.open(path, header())) << r.error();
  for (int k = 0; k < frames; ++k) {
    const double in[kIn] = {in_value(k)};
    const double out[kOut] = {out_value(k, 0), out_value(k, 1)};
    const std::uint32_t f = k == 1 ? ntn::hil::flag::kHeld : k == 2 ? ntn::hil::flag::kResync : 0U;
    r.write_frame(k, f, f | (k == 1 ? ntn::hil::flag::kAlarm : 0U), in, out);
  }
  EXPECT_TRUE(r.close()) << r.error();
  return read_file(path);
}

struct ReadAll {
  LogRead last = LogRead::kError;
  std::int64_t frames = 0;
  std::string error;
  std::vector<LogFrame> got;
};

ReadAll read_all(const std::string& path) {
  ReadAll r;
  LogReader reader;
  if (!reader.open(path)) {
    r.error = reader.error();
    return r;
  }
  LogFrame f;
  while ((r.last = reader.next(f)) == LogRead::kFrame)
    r.got.push_back(f);
  r.frames = reader.frames();
  r.error = reader.error();
  return r;
}

// Sets the XXH3 at the end of the record [at, at + size) to that of its bytes (a consistent
// forgery: only the semantic checks can refuse it).
void reseal(std::string& bytes, std::size_t at, std::size_t size) {
  const std::uint64_t h = XXH3_64bits(bytes.data() + at, size - 8);
  std::memcpy(bytes.data() + at + size - 8, &h, 8);
}

TEST(LogFormat, RoundTripIsExact) {
  const TempDir dir("record_roundtrip");
  const std::string bytes = write_log(dir / "a.log", 5);
  EXPECT_EQ(bytes.size(), ntn::hil::kLogHeaderBytes + 5 * kFrameBytes + ntn::hil::kLogEndBytes);
  const ReadAll r = read_all(dir / "a.log");
  ASSERT_EQ(r.last, LogRead::kEnd) << r.error;
  ASSERT_EQ(r.got.size(), 5U);
  for (int k = 0; k < 5; ++k) {
    const LogFrame& f = r.got[static_cast<std::size_t>(k)];
    EXPECT_EQ(f.frame, k);
    EXPECT_EQ(f.inputs[0], in_value(k));
    EXPECT_EQ(f.outputs[0], out_value(k, 0));
    EXPECT_EQ(f.outputs[1], out_value(k, 1));
  }
  EXPECT_EQ(r.got[1].input_flags, ntn::hil::flag::kHeld);
  EXPECT_EQ(r.got[1].output_flags, ntn::hil::flag::kHeld | ntn::hil::flag::kAlarm);
  EXPECT_EQ(r.got[2].input_flags, ntn::hil::flag::kResync);
  EXPECT_EQ(r.got[2].output_flags, ntn::hil::flag::kResync);
  LogReader reader;
  ASSERT_TRUE(reader.open(dir / "a.log"));
  EXPECT_EQ(reader.header().model, "test_model");
  EXPECT_EQ(reader.header().substeps, 4U);
  EXPECT_EQ(reader.header().period, 1e-3);
  EXPECT_EQ(reader.header().dt, 0.25e-3);
}

// A log cut at any byte after its header (a killed run) gives exactly its complete
// frames and reports truncation, naming the frame it ends in; it is never a clean end.
TEST(LogFormat, CutAtEveryByteGivesTheCompleteFrames) {
  const TempDir dir("record_cut");
  const std::string bytes = write_log(dir / "a.log", 4);
  const std::size_t h = ntn::hil::kLogHeaderBytes;
  for (std::size_t n = h; n < bytes.size(); ++n) {
    write_file(dir / "cut.log", bytes.substr(0, n));
    const ReadAll r = read_all(dir / "cut.log");
    const auto complete =
        static_cast<std::int64_t>(std::min<std::size_t>((n - h) / kFrameBytes, 4));
    ASSERT_EQ(r.last, LogRead::kTruncated) << "cut at " << n << ": " << r.error;
    EXPECT_EQ(r.frames, complete) << "cut at " << n;
    const bool inside_frame = n - h < 4 * kFrameBytes && (n - h) % kFrameBytes != 0;
    if (inside_frame) {
      const std::string want =
          "log ends inside frame " + std::to_string(complete) + " (truncated): " +
          (complete == 0 ? std::string("no complete frame")
                         : "replayed frames 0.." + std::to_string(complete - 1));
      EXPECT_NE(r.error.find(want), std::string::npos) << r.error;
    }
  }
  // A cut inside the header is an error of the header.
  write_file(dir / "cut.log", bytes.substr(0, h - 1));
  LogReader reader;
  EXPECT_FALSE(reader.open(dir / "cut.log"));
  EXPECT_NE(reader.error().find("truncated header"), std::string::npos) << reader.error();
}

// Every single bit of the log changed in turn is refused (header, frames, end
// record), or, where the change makes the log shorter in meaning (a frame number turned into
// the end marker), still never read as the same complete log.
TEST(LogFormat, EveryFlippedBitIsRefused) {
  const TempDir dir("record_flip");
  const std::string bytes = write_log(dir / "a.log", 2);
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    for (int b = 0; b < 8; ++b) {
      std::string x = bytes;
      x[i] = static_cast<char>(x[i] ^ (1 << b));
      write_file(dir / "x.log", x);
      const ReadAll r = read_all(dir / "x.log");
      EXPECT_NE(r.last, LogRead::kEnd) << "byte " << i << " bit " << b << " passed";
    }
  }
}

TEST(LogFormat, TrailingBytesAfterTheEndAreRefused) {
  const TempDir dir("record_trailing");
  for (const std::string& tail :
       {std::string("xyz"), std::string(1, '\0'), std::string(200, 'Z')}) {
    write_file(dir / "t.log", write_log(dir / "a.log", 3) + tail);
    const ReadAll r = read_all(dir / "t.log");
    EXPECT_EQ(r.last, LogRead::kError);
    EXPECT_NE(r.error.find(std::to_string(tail.size()) + " bytes after the end record"),
              std::string::npos)
        << r.error;
  }
}

// Consistent forgeries (checksums recomputed): the semantic checks refuse them.
TEST(LogFormat, ResealedInconsistenciesAreRefused) {
  const TempDir dir("record_forged");
  const std::string bytes = write_log(dir / "a.log", 3);
  const std::size_t h = ntn::hil::kLogHeaderBytes;
  auto expect_error = [&](std::string x, const std::string& what) {
    write_file(dir / "x.log", x);
    const ReadAll r = read_all(dir / "x.log");
    EXPECT_EQ(r.last, LogRead::kError) << what;
    EXPECT_NE(r.error.find(what), std::string::npos) << r.error;
  };
  {  // frame 1 numbered 2
    std::string x = bytes;
    const std::int64_t two = 2;
    std::memcpy(x.data() + h + kFrameBytes, &two, 8);
    reseal(x, h + kFrameBytes, kFrameBytes);
    expect_error(x, "frame 1 is numbered 2");
  }
  {  // frame 1 removed: the end record's count and the numbering disagree
    std::string x = bytes.substr(0, h + kFrameBytes) + bytes.substr(h + 2 * kFrameBytes);
    expect_error(x, "frame 1 is numbered 2");
  }
  {  // frame 2 removed (the last): the end record says 3
    std::string x = bytes.substr(0, h + 2 * kFrameBytes) + bytes.substr(h + 3 * kFrameBytes);
    expect_error(x, "the end record says 3 frames, the log holds 2");
  }
  {  // an output flag that is not its input flags plus the loop's bits
    std::string x = bytes;
    const std::uint32_t flags = ntn::hil::flag::kMissing;
    std::memcpy(x.data() + h + 12, &flags, 4);
    reseal(x, h, kFrameBytes);
    expect_error(x, "frame 0: output flags");
  }
  {  // an input flag the gate does not set
    std::string x = bytes;
    const std::uint32_t flags = ntn::hil::flag::kDiverged;
    std::memcpy(x.data() + h + 8, &flags, 4);
    std::memcpy(x.data() + h + 12, &flags, 4);
    reseal(x, h, kFrameBytes);
    expect_error(x, "frame 0: input flags");
  }
}

TEST(LogFormat, VersionsAreCheckedByNumber) {
  const TempDir dir("record_version");
  const std::string bytes = write_log(dir / "a.log", 2);
  for (std::uint32_t v : {1U, 3U, 0U}) {
    std::string x = bytes;
    std::memcpy(x.data() + 8, &v, 4);
    reseal(x, 0, ntn::hil::kLogHeaderBytes);
    write_file(dir / "v.log", x);
    LogReader reader;
    EXPECT_FALSE(reader.open(dir / "v.log"));
    const std::string want = v == 1 ? "version 1 (no checksums, no end record) is no longer read"
                                    : "unknown log format version " + std::to_string(v);
    EXPECT_NE(reader.error().find(want), std::string::npos) << reader.error();
  }
  // A header changed and resealed is read (the replay compares it with the model); changed and
  // not resealed, it is refused.
  std::string x = bytes;
  const double period = 2e-3;
  std::memcpy(x.data() + 28, &period, 8);
  write_file(dir / "p.log", x);
  LogReader reader;
  EXPECT_FALSE(reader.open(dir / "p.log"));
  EXPECT_NE(reader.error().find("header checksum"), std::string::npos) << reader.error();
  reseal(x, 0, ntn::hil::kLogHeaderBytes);
  write_file(dir / "p.log", x);
  LogReader resealed;
  ASSERT_TRUE(resealed.open(dir / "p.log")) << resealed.error();
  EXPECT_EQ(resealed.header().period, 2e-3);
}

// A write error (the log's part) is not lost. /dev/full takes the open and fails
// every write.
TEST(LogFormat, WriteErrorIsReportedByClose) {
  Recorder r;
  ASSERT_TRUE(r.open("/dev/full", header()));
  const double in[kIn] = {1};
  const double out[kOut] = {2, 3};
  for (int k = 0; k < 3; ++k)
    r.write_frame(k, 0, 0, in, out);
  EXPECT_FALSE(r.close());
  EXPECT_NE(r.error().find("No space left on device"), std::string::npos) << r.error();
  EXPECT_NE(r.error().find("--record"), std::string::npos) << r.error();
}

}  // namespace log_format_test
