// ntn-feeder end to end over loopback UDP: the test plays the loop (an InputGate fed from a
// socket, output packets sent back) and the feeder runs as a subprocess with faults injected.
// In lock-step mode every count must equal the injected one, and every value the gate passed
// must be the feeder's record sample or the held last good value, bit for bit.
#include <time.h>

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "ntn/hil/faults.hpp"
#include "ntn/hil/gate.hpp"
#include "ntn/hil/packet.hpp"
#include "ntn/hil/udp.hpp"
#include "record.hpp"
#include "subprocess.hpp"

namespace feeder_test {

using namespace ntn::hil;
using namespace std::chrono_literals;
using ntn_test::Child;
using ntn_test::read_file;
using ntn_test::TempDir;

constexpr int kChannels = 2;
constexpr double kRate = 1000.0;  // Hz, the feeder's default
const std::string kElCentro = std::string(NTN_RECORDS_DIR) + "/elCentro.AT2";
const std::string kArleta = std::string(NTN_RECORDS_DIR) + "/ARL360.AT2";

// The feeder's "faults nan=1 inf=0 ..." line, as a map.
std::map<std::string, std::uint64_t> fault_line(const std::string& out) {
  std::map<std::string, std::uint64_t> m;
  const auto at = out.find("\nfaults ");
  const auto start =
      at == std::string::npos ? (out.rfind("faults ", 0) == 0 ? 0 : out.size()) : at + 1;
  std::istringstream line(out.substr(start, out.find('\n', start) - start));
  std::string word;
  line >> word;  // "faults"
  while (line >> word) {
    const auto eq = word.find('=');
    if (eq != std::string::npos) m[word.substr(0, eq)] = std::stoull(word.substr(eq + 1));
  }
  return m;
}

InputGate make_gate() {
  InputGate g(kChannels);
  for (int c = 0; c < kChannels; ++c)
    EXPECT_TRUE(g.set_range(c, -3.0, 3.0));  // g, as the frame3d model's ground inputs
  return g;
}

// What the loop side saw.
struct LoopRun {
  std::vector<std::array<double, kChannels>> values;
  std::vector<std::uint16_t> flags;
  std::string error;
};

void reply(UdpSocket& s, std::uint16_t port, std::int64_t k, std::uint16_t flags,
           const std::array<double, kChannels>& v) {
  std::array<std::byte, kMaxPacketBytes> out{};
  const std::size_t n =
      encode(PacketKind::kOutput, static_cast<std::uint32_t>(k), k, flags, v, out);
  EXPECT_TRUE(s.send_to(port, std::span(out).first(n)).ok());
}

// Lock-step loop: frame k ends when the feeder's frame-end marker for k arrives.
LoopRun lockstep_loop(UdpSocket& s, InputGate& g, std::int64_t frames) {
  LoopRun run;
  std::array<std::byte, kReceiveBufferBytes> buf{};
  std::uint16_t feeder_port = 0;
  for (std::int64_t k = 0; k < frames; ++k) {
    g.begin_frame(k);
    bool done = false;
    while (!done) {
      if (s.wait_readable(10s) != WaitStatus::kReadable) {
        run.error = "no frame-end marker for frame " + std::to_string(k);
        return run;
      }
      for (Received r; !done && (r = s.receive(buf)).has_datagram();) {
        feeder_port = r.from_port;
        const OfferResult o = g.offer(std::span(buf).first(r.size));
        done = o.status == OfferStatus::kFrameEnd && o.frame >= k;
      }
    }
    std::array<double, kChannels> v{};
    std::uint16_t flags = 0;
    g.end_frame(v, flags);
    run.values.push_back(v);
    run.flags.push_back(flags);
    reply(s, feeder_port, k, flags, v);
  }
  return run;
}

// The values the gate must have passed: the feeder's samples (record interpolated at k / rate),
// with a channel held at its last good value when the plan's fault hides it.
void expect_held_values(const LoopRun& run, const FaultPlan& plan) {
  const ntn::io::Record r0 = *ntn::io::read_record(kElCentro).record;
  const ntn::io::Record r1 = *ntn::io::read_record(kArleta).record;
  const double period = 1.0 / kRate;
  std::array<double, kChannels> last{};
  int checked_holds = 0;
  for (std::size_t k = 0; k < run.values.size(); ++k) {
    const double t = static_cast<double>(k) * period;
    const std::array<double, kChannels> sample{r0.at(t), r1.at(t)};
    const FaultKind f = plan[static_cast<std::int64_t>(k)];
    const bool all_held =
        f == FaultKind::kLost || f == FaultKind::kLate || f == FaultKind::kCorrupt;
    for (std::size_t c = 0; c < kChannels; ++c) {
      const bool value_fault =
          (f == FaultKind::kNan || f == FaultKind::kInf || f == FaultKind::kRange) &&
          c == k % kChannels;
      if (all_held || value_fault) {
        if (sample[c] != last[c]) ++checked_holds;  // a hold that is visible in the data
      } else {
        last[c] = sample[c];
      }
    }
    ASSERT_EQ(run.values[k], last) << "frame " << k << " fault " << to_string(f);
  }
  // The holds were tested against data that had moved on, not against a constant signal.
  EXPECT_GT(checked_holds, 0);
}

// Rows of the feeder's output CSV equal what the loop sent (%.17g round-trips doubles).
void expect_csv_matches(const std::string& path, const LoopRun& run) {
  std::ifstream in(path);
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line, "time[s],y0,y1,flags");
  std::size_t rows = 0;
  while (std::getline(in, line)) {
    double t = 0, y0 = 0, y1 = 0;
    unsigned flags = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%u", &t, &y0, &y1, &flags), 4) << line;
    ASSERT_LT(rows, run.values.size());
    EXPECT_NEAR(t, static_cast<double>(rows) / kRate, 1e-9);
    EXPECT_EQ(y0, run.values[rows][0]) << "row " << rows;
    EXPECT_EQ(y1, run.values[rows][1]) << "row " << rows;
    EXPECT_EQ(flags, run.flags[rows]) << "row " << rows;
    ++rows;
  }
  EXPECT_EQ(rows, run.values.size());
}

// The gate's counters against the injected faults (see faults.hpp for each kind's effect).
void expect_counts(const GateCounters& n, const FaultPlan& plan, std::int64_t frames) {
  const auto c = [&plan](FaultKind k) { return plan.count(k); };
  const std::uint64_t not_arrived =
      c(FaultKind::kLate) + c(FaultKind::kLost) + c(FaultKind::kCorrupt);
  EXPECT_EQ(n.nonfinite, c(FaultKind::kNan) + c(FaultKind::kInf));
  EXPECT_EQ(n.out_of_range, c(FaultKind::kRange));
  EXPECT_EQ(n.late, c(FaultKind::kLate));
  EXPECT_EQ(n.late_for_missing, c(FaultKind::kLate));
  EXPECT_EQ(n.missing, not_arrived);
  EXPECT_EQ(n.lost(), c(FaultKind::kLost) + c(FaultKind::kCorrupt));
  EXPECT_EQ(n.duplicate, c(FaultKind::kDuplicate));
  EXPECT_EQ(n.reordered, c(FaultKind::kReorder));
  EXPECT_EQ(n.early, c(FaultKind::kReorder));
  EXPECT_EQ(n.corrupt, c(FaultKind::kCorrupt));
  EXPECT_EQ(n.wrong_count, 0u);
  EXPECT_EQ(n.too_early, 0u);
  EXPECT_EQ(n.accepted, static_cast<std::uint64_t>(frames) - not_arrived);
  EXPECT_EQ(n.frame_ends, static_cast<std::uint64_t>(frames));
}

void expect_printed_counts(const std::string& out, const FaultPlan& plan) {
  const auto printed = fault_line(out);
  ASSERT_EQ(printed.size(), kAllFaults.size()) << out;
  for (FaultKind k : kAllFaults)
    EXPECT_EQ(printed.at(to_string(k)), plan.count(k)) << to_string(k);
}

std::vector<std::string> feeder_args(std::uint16_t port, std::int64_t frames) {
  return {NTN_FEEDER,
          "--port",
          std::to_string(port),
          "--input",
          "ag_x=" + kElCentro,
          "--input",
          "ag_y=" + kArleta,
          "--frames",
          std::to_string(frames)};
}

// Each kind once, at frames where the signal moves, in lock-step.
TEST(Feeder, LockStepEachFaultKindCountedExactly) {
  constexpr std::int64_t kFrames = 600;
  const TempDir dir("feeder_test_each");
  UdpSocket s;
  ASSERT_TRUE(s.open().ok());
  const std::string faults =
      "nan@200,nan@211,inf@220,inf@231,range@240,late@250,lost@260,duplicate@270,reorder@280,"
      "corrupt@290,late@300,late@301,lost@302,reorder@303,corrupt@305,duplicate@306";
  std::vector<std::string> args = feeder_args(s.port(), kFrames);
  for (const char* a : {"--virtual", "--fault"})
    args.emplace_back(a);
  args.push_back(faults);
  args.insert(args.end(), {"--out", dir / "out.csv"});
  Child feeder(args, dir / "stdout.txt");
  ASSERT_TRUE(feeder.started());

  InputGate gate = make_gate();
  const LoopRun run = lockstep_loop(s, gate, kFrames);
  ASSERT_EQ(run.error, "");
  ASSERT_EQ(feeder.wait(), 0) << read_file(dir / "stdout.txt");

  std::vector<FaultAt> list;
  ASSERT_EQ(parse_fault_list(faults, list), "");
  FaultPlan plan;
  ASSERT_EQ(make_fault_plan(kFrames, list, {}, 1, plan), "");
  const std::string out = read_file(dir / "stdout.txt");
  expect_printed_counts(out, plan);
  expect_counts(gate.counters(), plan, kFrames);
  expect_held_values(run, plan);
  expect_csv_matches(dir / "out.csv", run);
  // Flags of the faulted frames.
  EXPECT_EQ(run.flags[200], flag::kNonFinite | flag::kHeld);
  EXPECT_EQ(run.flags[240], flag::kOutOfRange | flag::kHeld);
  EXPECT_EQ(run.flags[250], flag::kMissing | flag::kHeld);
  EXPECT_EQ(run.flags[251], flag::kLate);
  EXPECT_EQ(run.flags[270], flag::kDuplicate);
  EXPECT_EQ(run.flags[280], flag::kEarly | flag::kReordered);
  EXPECT_EQ(run.flags[290], flag::kCorrupt | flag::kMissing | flag::kHeld);
  std::printf("%s", out.c_str());
}

// Random faults of every kind at 1 % each over 3000 frames: the feeder's printed counts are the
// plan the library makes from the same seed, and the gate counts each exactly.
TEST(Feeder, LockStepRandomFaultsCountedExactly) {
  constexpr std::int64_t kFrames = 3000;
  constexpr std::uint64_t kSeed = 2024;
  const TempDir dir("feeder_test_random");
  UdpSocket s;
  ASSERT_TRUE(s.open().ok());
  std::vector<std::string> args = feeder_args(s.port(), kFrames);
  args.insert(args.end(), {"--virtual", "--seed", std::to_string(kSeed)});
  std::vector<FaultRate> rates;
  for (FaultKind k : kAllFaults) {
    args.insert(args.end(), {"--fault-rate", std::string(to_string(k)) + "=0.01"});
    rates.push_back({k, 0.01});
  }
  Child feeder(args, dir / "stdout.txt");
  ASSERT_TRUE(feeder.started());
  InputGate gate = make_gate();
  const LoopRun run = lockstep_loop(s, gate, kFrames);
  ASSERT_EQ(run.error, "");
  ASSERT_EQ(feeder.wait(), 0);

  FaultPlan plan;
  ASSERT_EQ(make_fault_plan(kFrames, {}, rates, kSeed, plan), "");
  for (FaultKind k : kAllFaults)
    ASSERT_GT(plan.count(k), 5u) << to_string(k);  // each kind really exercised
  const std::string out = read_file(dir / "stdout.txt");
  expect_printed_counts(out, plan);
  expect_counts(gate.counters(), plan, kFrames);
  expect_held_values(run, plan);
  std::printf("%s", out.c_str());
}

void sleep_until(std::chrono::steady_clock::time_point t) {
  // steady_clock is CLOCK_MONOTONIC on Linux/glibc.
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch());
  const timespec ts{static_cast<time_t>(ns.count() / 1'000'000'000),
                    static_cast<long>(ns.count() % 1'000'000'000)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

// Real time at 1 kHz for 1.5 s. Which packets are on time depends on this machine's scheduling,
// so only what does not depend on timing is asserted exactly: corrupt and duplicate counts,
// lost frames, the frame accounting, an output back for every frame, and the pace.
TEST(Feeder, RealTimeOneKilohertz) {
  constexpr std::int64_t kFrames = 1500;
  const TempDir dir("feeder_test_realtime");
  UdpSocket s;
  ASSERT_TRUE(s.open().ok());
  std::vector<std::string> args = feeder_args(s.port(), kFrames);
  args.insert(args.end(), {"--fault", "corrupt@300,duplicate@600,lost@700,nan@900,corrupt@1100",
                           "--out", dir / "out.csv", "--linger", "5000"});
  const auto start = std::chrono::steady_clock::now();
  Child feeder(args, dir / "stdout.txt");
  ASSERT_TRUE(feeder.started());

  InputGate gate = make_gate();
  std::array<std::byte, kReceiveBufferBytes> buf{};
  ASSERT_EQ(s.wait_readable(10s), WaitStatus::kReadable);
  // Frame 0's packet has just arrived: the loop's frame k runs half a period after the feeder's
  // deadline k.
  const auto t0 = std::chrono::steady_clock::now() + 500us;
  std::uint16_t feeder_port = 0;
  for (std::int64_t k = 0; k < kFrames; ++k) {
    sleep_until(t0 + k * 1ms);
    gate.begin_frame(k);
    for (Received r; (r = s.receive(buf)).has_datagram();) {
      feeder_port = r.from_port;
      gate.offer(std::span(buf).first(r.size));
    }
    std::array<double, kChannels> v{};
    std::uint16_t flags = 0;
    gate.end_frame(v, flags);
    ASSERT_TRUE(std::isfinite(v[0]) && std::isfinite(v[1]));
    reply(s, feeder_port, k, flags, v);
  }
  ASSERT_EQ(feeder.wait(), 0);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string out = read_file(dir / "stdout.txt");
  std::printf("%s", out.c_str());

  const GateCounters& n = gate.counters();
  EXPECT_EQ(n.corrupt, 2u);
  EXPECT_EQ(n.duplicate, 1u);
  EXPECT_GE(n.lost(), 3u);  // lost@700 and the two corrupt frames never arrive
  EXPECT_LE(n.nonfinite, 1u);
  EXPECT_EQ(n.accepted + n.missing, static_cast<std::uint64_t>(kFrames));
  EXPECT_GE(wall, 1.45);  // paced by deadlines, not as fast as possible
  const auto printed = fault_line(out);
  EXPECT_EQ(printed.at("corrupt"), 2u);
  EXPECT_EQ(printed.at("duplicate"), 1u);
  // Every output came back to the feeder.
  EXPECT_NE(out.find("outputs     1500 of 1500 frames received"), std::string::npos) << out;
  std::printf("gate: accepted %llu, missing %llu, late %llu, early %llu, lost %llu\n",
              static_cast<unsigned long long>(n.accepted),
              static_cast<unsigned long long>(n.missing), static_cast<unsigned long long>(n.late),
              static_cast<unsigned long long>(n.early), static_cast<unsigned long long>(n.lost()));
}

TEST(Feeder, BadArgumentsExitTwo) {
  const TempDir dir("feeder_test_args");
  const std::vector<std::vector<std::string>> bad{
      {NTN_FEEDER, "--port", "9", "--record", "/nonexistent.AT2"},
      {NTN_FEEDER, "--port", "9", "--record", kElCentro, "--fault", "bogus@1"},
      {NTN_FEEDER, "--port", "9", "--record", kElCentro, "--frames", "10", "--fault", "late@9"},
      {NTN_FEEDER, "--port", "9", "--record", kElCentro, "--fault-rate", "nan=2"},
      {NTN_FEEDER, "--port", "9"},
  };
  for (const auto& a : bad) {
    Child c(a, dir / "stdout.txt");
    ASSERT_TRUE(c.started());
    EXPECT_EQ(c.wait(), 2) << a.back();
  }
}

}  // namespace feeder_test
