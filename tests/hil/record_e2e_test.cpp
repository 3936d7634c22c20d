// ntn-hil-frame3d's record, replay and stop end to end: SIGTERM ends a run
// after the frame in progress with the CSV, the log and the JSON complete (exit 4), also while
// the loop waits for a sender; a log cut mid-frame replays its complete frames and says where it
// ends (exit 4); a changed output bit, trailing bytes, altered header fields, a renumbered frame,
// a changed diverged flag and a log with no frames are refused or reported as differing. Virtual
// clock; no result depends on the machine's speed: the signal is sent once the run is seen
// running (its log has grown), and the limits on waits are generous bounds, not measurements.
#include <gtest/gtest.h>
#include <signal.h>
#include <xxhash.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "ntn/hil/packet.hpp"
#include "ntn/hil/recorder.hpp"
#include "subprocess.hpp"

namespace {

using namespace std::chrono_literals;
using ntn_test::Child;
using ntn_test::read_file;
using ntn_test::TempDir;
using ntn_test::write_file;

const std::string kElCentro = std::string(NTN_RECORDS_DIR) + "/elCentro.AT2";
constexpr std::size_t kHeader = ntn::hil::kLogHeaderBytes;
constexpr std::size_t kFrame = ntn::hil::log_frame_bytes(1, 9);  // frame3d: 1 input, 9 outputs

struct Ran {
  int code;
  std::string output;  // stdout and stderr
};

Ran run(const TempDir& dir, const std::vector<std::string>& args, const std::string& name) {
  std::vector<std::string> argv{NTN_HIL};
  argv.insert(argv.end(), args.begin(), args.end());
  Child child(argv, dir / name);
  const int code = child.wait(120s);
  return {code, read_file(dir / name)};
}

// The integer after `prefix` in `text`, or -1.
long long number_after(const std::string& text, const std::string& prefix) {
  const std::size_t at = text.find(prefix);
  if (at == std::string::npos) return -1;
  return std::stoll(text.substr(at + prefix.size()));
}

std::size_t lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

void reseal(std::string& bytes, std::size_t at, std::size_t size) {
  const std::uint64_t h = XXH3_64bits(bytes.data() + at, size - 8);
  std::memcpy(bytes.data() + at + size - 8, &h, 8);
}

long long rss_kib(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stoll(line.substr(6));
  return -1;
}

// Regression: a run of --duration 1e6 (10^9 frames; it aborted with bad_alloc, its CSV
// buffer reserved for the whole run) runs with bounded memory and, on SIGTERM, stops after the
// frame in progress with every file complete: the CSV has one row per frame the summary counts,
// the JSON says how it stopped, the log replays bit-identical over those frames.
TEST(RecordE2e, SigtermStopsTheRunWithEveryFileWritten) {
  const TempDir dir("record_sigterm");
  Child child({NTN_HIL, "run", "--clock", "virtual", "--input", "ag_x=" + kElCentro, "--duration",
               "1e6", "--out", dir / "run.csv", "--record", dir / "run.ntnlog", "--summary-json",
               dir / "run.json"},
              dir / "run.txt");
  ASSERT_TRUE(child.started());
  // Running: the log has been flushed twice (1 MiB buffer), ~20 000 frames.
  const auto give_up = std::chrono::steady_clock::now() + 60s;
  const auto log_size = [&] {
    std::error_code ec;
    const auto n = std::filesystem::file_size(dir / "run.ntnlog", ec);
    return ec ? std::uintmax_t{0} : n;  // not there yet: 0
  };
  while (log_size() < (2u << 20) && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(10ms);
  ASSERT_GE(log_size(), 2u << 20) << read_file(dir / "run.txt");
  // Memory is bounded: the CSV and the log stream to their files, 64 MiB of timing are reserved
  // (not all touched). Before, 10^9 frames reserved 8 GB of per-frame hashes and 264 GB of CSV.
  // The bound, 512 MiB, leaves room for a sanitizer build's own memory.
  const long long rss = rss_kib(child.pid());
  EXPECT_GT(rss, 0);
  EXPECT_LT(rss, 512 * 1024) << "VmRSS " << rss << " KiB";
  ASSERT_EQ(kill(child.pid(), SIGTERM), 0);
  const int code = child.wait(60s);
  const std::string out = read_file(dir / "run.txt");
  ASSERT_EQ(code, 4) << out;
  const long long n = number_after(out, "stopped by SIGTERM after ");
  ASSERT_GT(n, 10000) << out;
  EXPECT_NE(out.find("STOPPED by SIGTERM after " + std::to_string(n) + " of 1000000000 frames"),
            std::string::npos)
      << out;
  // The CSV: a header and one row per frame, the last one frame n - 1's.
  const std::string csv = read_file(dir / "run.csv");
  EXPECT_EQ(lines(csv), static_cast<std::size_t>(n) + 1);
  const std::size_t last = csv.rfind('\n', csv.size() - 2) + 1;
  char t[32];
  std::snprintf(t, sizeof t, "%.9g,", static_cast<double>(n - 1) * 1e-3);
  EXPECT_EQ(csv.compare(last, std::strlen(t), t), 0) << csv.substr(last);
  // The JSON, complete, says so.
  const std::string json = read_file(dir / "run.json");
  EXPECT_NE(json.find("\"frames\": " + std::to_string(n) + ","), std::string::npos) << json;
  EXPECT_NE(json.find("\"stopped_by\": \"SIGTERM\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"output_hash\""), std::string::npos) << json;
  // The log: complete (end record), n frames, bit-identical.
  EXPECT_EQ(std::filesystem::file_size(dir / "run.ntnlog"),
            kHeader + static_cast<std::size_t>(n) * kFrame + ntn::hil::kLogEndBytes);
  const Ran replay = run(dir, {"replay", dir / "run.ntnlog"}, "replay.txt");
  EXPECT_EQ(replay.code, 0) << replay.output;
  EXPECT_NE(replay.output.find("bit-identical over " + std::to_string(n) + " frames"),
            std::string::npos)
      << replay.output;
}

// SIGTERM while the loop waits for a sender's first packet (real clock, --listen): it does not
// wait out --wait-first; frame 0 completes (every input missing, held), the files are written.
TEST(RecordE2e, SigtermWhileWaitingForTheSender) {
  const TempDir dir("record_sigterm_listen");
  const std::vector<std::uint16_t> ports = ntn_test::free_ports(1);
  ASSERT_EQ(ports.size(), 1U);
  Child child(
      {NTN_HIL, "run", "--clock", "real", "--listen", std::to_string(ports[0]), "--wait-first",
       "600", "--frames", "1000", "--record", dir / "run.ntnlog", "--out", dir / "run.csv"},
      dir / "run.txt");
  ASSERT_TRUE(ntn_test::wait_port_bound(ports[0], 30s)) << read_file(dir / "run.txt");
  ASSERT_EQ(kill(child.pid(), SIGTERM), 0);
  const int code = child.wait(30s);  // the wait is cut in slices of 0.1 s
  const std::string out = read_file(dir / "run.txt");
  ASSERT_EQ(code, 4) << out;
  EXPECT_NE(out.find("stopped by SIGTERM after 1 frames"), std::string::npos) << out;
  EXPECT_EQ(out.find("no input packet within"), std::string::npos) << out;  // it did not wait
  EXPECT_EQ(lines(read_file(dir / "run.csv")), 2U);
  const Ran replay = run(dir, {"replay", dir / "run.ntnlog"}, "replay.txt");
  EXPECT_EQ(replay.code, 0) << replay.output;
  EXPECT_NE(replay.output.find("bit-identical over 1 frames"), std::string::npos) << replay.output;
}

class ReplayChecks : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir("record_replay_checks");
    const Ran r = run(*dir_,
                      {"run", "--clock", "virtual", "--input", "ag_x=" + kElCentro, "--frames",
                       "2000", "--record", *dir_ / "run.ntnlog", "--out", *dir_ / "run.csv", "-q"},
                      "run.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    log_ = read_file(*dir_ / "run.ntnlog");
    ASSERT_EQ(log_.size(), kHeader + 2000 * kFrame + ntn::hil::kLogEndBytes);
    const std::string csv = read_file(*dir_ / "run.csv");
    std::istringstream head(csv.substr(0, csv.find('\n')));
    for (std::string cell; std::getline(head, cell, ',');)
      columns_.push_back(cell.substr(0, cell.find('[')));
  }
  static void TearDownTestSuite() { delete dir_; }
  // Replays `bytes` written as a log.
  static Ran replay(const std::string& bytes) {
    write_file(*dir_ / "x.ntnlog", bytes);
    return run(*dir_, {"replay", *dir_ / "x.ntnlog"}, "replay_" + std::to_string(++n_) + ".txt");
  }
  static std::size_t frame_at(std::size_t k) { return kHeader + k * kFrame; }
  static inline TempDir* dir_ = nullptr;
  static inline std::string log_;
  static inline std::vector<std::string> columns_;  // time, outputs..., flags
  static inline int n_ = 0;
};

TEST_F(ReplayChecks, TheUntouchedLogIsBitIdentical) {
  const Ran r = replay(log_);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("replay: bit-identical over 2000 frames"), std::string::npos) << r.output;
}

// A log cut mid-frame (a killed run) replays every complete frame (it refused all
// of them) and says where it ends; a log cut at a frame boundary lacks its end record: the same.
TEST_F(ReplayChecks, ACutLogReplaysItsCompleteFrames) {
  Ran r = replay(log_.substr(0, frame_at(1234) + kFrame / 2));
  EXPECT_EQ(r.code, 4) << r.output;
  EXPECT_NE(r.output.find("bit-identical over 1234 frames (0..1233); the log is incomplete"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("log ends inside frame 1234 (truncated): replayed frames 0..1233"),
            std::string::npos)
      << r.output;
  r = replay(log_.substr(0, frame_at(1500)));
  EXPECT_EQ(r.code, 4) << r.output;
  EXPECT_NE(r.output.find("log ends after 1500 frames without its end record"), std::string::npos)
      << r.output;
}

// Regression: a log with no frames segfaulted.
TEST_F(ReplayChecks, ALogWithNoFramesIsAnError) {
  for (const std::size_t n : {kHeader, kHeader + kFrame - 1}) {
    const Ran r = replay(log_.substr(0, n));
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("the log holds no complete frame: nothing to replay"),
              std::string::npos)
        << r.output;
  }
}

// A flipped bit in a recorded output is found: by the record's checksum, and, the
// checksum forged to match, by comparing the output with the replayed one (frame and channel).
TEST_F(ReplayChecks, AFlippedOutputBitIsFound) {
  const std::size_t k = 700, c = 3;
  std::string x = log_;
  const std::size_t at = frame_at(k) + 16 + 8 * (1 + c);
  x[at] = static_cast<char>(x[at] ^ 1);
  Ran r = replay(x);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("frame 700: checksum"), std::string::npos) << r.output;
  reseal(x, frame_at(k), kFrame);
  r = replay(x);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(
      r.output.find("DIFFERS at frame 700 (t = 0.700000 s), channel " + columns_[1 + c] + ":"),
      std::string::npos)
      << r.output;
}

TEST_F(ReplayChecks, TrailingBytesAreRefused) {
  const Ran r = replay(log_ + "xyz");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("3 bytes after the end record"), std::string::npos) << r.output;
}

// Header fields (checksum forged to match) are compared with the model: period, dt, substeps,
// the model's name; unresealed, the header's checksum refuses them first.
TEST_F(ReplayChecks, AlteredHeaderFieldsAreRefused) {
  struct Edit {
    std::size_t offset;
    std::string bytes;
    std::string message;
  };
  const double period = 2e-3, dt = 1e-5;
  const std::uint32_t substeps = 7;
  std::string p(8, '\0'), d(8, '\0'), s(4, '\0');
  std::memcpy(p.data(), &period, 8);
  std::memcpy(d.data(), &dt, 8);
  std::memcpy(s.data(), &substeps, 4);
  for (const Edit& e : {Edit{28, p, "period 0.002"}, Edit{36, d, "dt 1.0000000000000001e-05"},
                        Edit{20, s, "7 substeps per frame"}, Edit{44, "other", "model 'other"}}) {
    std::string x = log_;
    x.replace(e.offset, e.bytes.size(), e.bytes);
    Ran r = replay(x);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("header checksum"), std::string::npos) << r.output;
    reseal(x, 0, kHeader);
    r = replay(x);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("was recorded with another model or step: " + e.message),
              std::string::npos)
        << r.output;
  }
}

// Frame numbers must be 0, 1, 2, ...; the diverged flag is replayed and compared.
TEST_F(ReplayChecks, FrameFieldsAreChecked) {
  std::string x = log_;
  const std::int64_t six = 6;
  std::memcpy(x.data() + frame_at(5), &six, 8);
  reseal(x, frame_at(5), kFrame);
  Ran r = replay(x);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("frame 5 is numbered 6"), std::string::npos) << r.output;

  x = log_;
  std::uint32_t flags = 0;
  std::memcpy(&flags, x.data() + frame_at(10) + 12, 4);
  flags |= ntn::hil::flag::kDiverged;
  std::memcpy(x.data() + frame_at(10) + 12, &flags, 4);
  reseal(x, frame_at(10), kFrame);
  r = replay(x);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("DIFFERS at frame 10 (t = 0.010000 s): the log's output flags"),
            std::string::npos)
      << r.output;
}

}  // namespace
