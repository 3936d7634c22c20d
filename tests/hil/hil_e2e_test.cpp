// ntn-hil-frame3d fed by ntn-feeder over loopback UDP, both as subprocesses, as a controller or
// DAQ would run them (hil_sim/README.md): in lock-step with every fault kind injected (counts,
// flags, no NaN out, the outputs equal a run on exactly the held inputs, replay), and in real
// time (deadlines follow the sender; counts consistent).
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "ntn/hil/faults.hpp"
#include "ntn/hil/packet.hpp"
#include "ntn/hil/udp.hpp"
#include "ntn/modelc/load_model.hpp"
#include "record.hpp"
#include "subprocess.hpp"

namespace {

using namespace std::chrono_literals;
using namespace ntn::hil;
using ntn_test::Child;
using ntn_test::read_file;
using ntn_test::TempDir;

constexpr double kPeriod = 1.0 / 1000.0;  // s: frame3d's frame and the feeder's default rate

const std::string kElCentro = std::string(NTN_RECORDS_DIR) + "/elCentro.AT2";
const std::string kFrame3d = std::string(NTN_CONFIG_DIR) + "/frame3d.toml";

// The number after "key": in a JSON text, looked up after "section": when one is given (the
// summaries are flat enough for this; a missing key is NaN, which fails every comparison).
double json_number(const std::string& text, const std::string& key,
                   const std::string& section = {}) {
  std::size_t from = 0;
  if (!section.empty()) {
    from = text.find("\"" + section + "\":");
    if (from == std::string::npos) return std::nan("");
  }
  const std::string k = "\"" + key + "\":";
  const std::size_t at = text.find(k, from);
  if (at == std::string::npos) return std::nan("");
  return std::strtod(text.c_str() + at + k.size(), nullptr);
}

// "output hash 0123456789abcdef" from the loop's screen summary.
std::string output_hash(const std::string& out) {
  const std::string key = "output hash ";
  const std::size_t at = out.find(key);
  return at == std::string::npos ? "" : out.substr(at + key.size(), 16);
}

// A CSV of outputs (time, channels..., flags), as ntn-hil and ntn-feeder write it.
struct Csv {
  std::vector<std::vector<double>> values;  // per row: the channels
  std::vector<unsigned> flags;              // per row
  std::string error;
};

Csv read_csv(const std::string& path) {
  Csv c;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) c.error = "empty " + path;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ','))
      row.push_back(std::strtod(cell.c_str(), nullptr));  // strtod reads "nan" and "inf" too
    if (row.size() < 3) {
      c.error = "short row: " + line;
      return c;
    }
    c.flags.push_back(static_cast<unsigned>(row.back()));
    c.values.emplace_back(row.begin() + 1, row.end() - 1);
  }
  return c;
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

std::vector<std::string> hil_run(std::uint16_t listen, std::uint16_t reply, std::int64_t frames) {
  return {NTN_HIL,    "run",
          "--listen", std::to_string(listen),
          "--reply",  std::to_string(reply),
          "--frames", std::to_string(frames)};
}

std::vector<std::string> feeder(std::uint16_t port, std::uint16_t own, std::int64_t frames) {
  return {NTN_FEEDER, "--port",  std::to_string(port), "--listen-port",       std::to_string(own),
          "--record", kElCentro, "--frames",           std::to_string(frames)};
}

// Starts ntn-hil on two free ports with `hil_args`, waits until it listens, then runs the feeder
// with `feeder_args` and waits for both (`timeout` each). Their screens go to hil.txt and
// feeder.txt in `dir`, their JSON summaries to hil.json and feeder.json.
struct PairRun {
  int hil_rc = -1, feeder_rc = -1;
  std::string hil_json, feeder_json, hil_text, feeder_text;
};

PairRun run_pair(const TempDir& dir, std::int64_t frames, const std::vector<std::string>& hil_args,
                 const std::vector<std::string>& feeder_args, std::chrono::seconds timeout) {
  PairRun r;
  const auto ports = ntn_test::free_ports(2);
  if (ports.size() != 2U) {
    ADD_FAILURE() << "no two free UDP ports";
    return r;
  }
  std::vector<std::string> h = hil_run(ports[0], ports[1], frames);
  h.insert(h.end(), hil_args.begin(), hil_args.end());
  h.insert(h.end(), {"--summary-json", dir / "hil.json"});
  Child hil(h, dir / "hil.txt");
  if (!hil.started() || !ntn_test::wait_port_bound(ports[0], 10s)) {
    ADD_FAILURE() << "ntn-hil did not start: " << read_file(dir / "hil.txt");
    return r;
  }
  std::vector<std::string> f = feeder(ports[0], ports[1], frames);
  f.insert(f.end(), feeder_args.begin(), feeder_args.end());
  f.insert(f.end(), {"--summary-json", dir / "feeder.json"});
  Child feed(f, dir / "feeder.txt");
  if (feed.started()) r.feeder_rc = feed.wait(timeout);
  r.hil_rc = hil.wait(timeout);
  r.hil_json = read_file(dir / "hil.json");
  r.feeder_json = read_file(dir / "feeder.json");
  r.hil_text = read_file(dir / "hil.txt");
  r.feeder_text = read_file(dir / "feeder.txt");
  std::printf("%s%s", r.hil_text.c_str(), r.feeder_text.c_str());
  return r;
}

// Real time, 3000 frames at 1 kHz: the loop's deadlines follow the feeder's stream (frame k due
// half a period after packet k is expected), so packets do not come after their frame ran.
// Before the loop took its deadlines from the first packet, ~90 % of them were late here.
// Both run under SCHED_FIFO (--fifo; a warning and normal priority where that is not permitted).
// How many frames miss their packet depends on the machine (a stall of the loop or the feeder
// beyond the jitter buffer's 8 frames costs that many frames; this shared 2-core VM shows
// wake-up stalls of 3-19 ms under load, and `cyclictest` at 1 kHz the same), so that figure is
// reported, not asserted (no default test passes or fails with the machine's load).
// Asserted is what holds whatever the machine does: every frame ran and is accounted for as
// accepted or missing, each late packet's frame is among the missing, nothing is corrupt, and
// the outputs equal a virtual-clock run on the inputs the gate accepted (the log replays bit for
// bit).
TEST(HilE2E, RealTimeDeadlinesFollowTheSender) {
  constexpr std::int64_t kFrames = 3000;
  const TempDir dir("hil_e2e_rt_aligned");
  const PairRun pair =
      run_pair(dir, kFrames, {"--clock", "real", "--fifo", "--record", dir / "run.ntnlog"},
               {"--fifo", "70"}, 30s);
  EXPECT_EQ(pair.feeder_rc, 0) << pair.feeder_text;
  ASSERT_EQ(pair.hil_rc, 0) << pair.hil_text;
  const std::string& js = pair.hil_json;
  const std::string& fs = pair.feeder_json;

  EXPECT_EQ(json_number(js, "frames"), kFrames);
  EXPECT_EQ(json_number(js, "first_packet_frame"), 0);
  const double missing = json_number(js, "missing", "inputs");
  std::printf(
      "real time, 3000 frames: %g missing, %g late, %g overruns, latency p50 %g us, "
      "max %g us\n",
      missing, json_number(js, "late", "inputs"), json_number(js, "overruns"),
      json_number(js, "p50", "latency_us"), json_number(js, "max", "latency_us"));
  EXPECT_LE(json_number(js, "late", "inputs"), missing);  // each late packet's frame was missing
  EXPECT_EQ(json_number(js, "accepted", "inputs") + missing, kFrames);
  EXPECT_EQ(json_number(js, "corrupt", "inputs"), 0);
  // UDP on loopback may drop an output when the feeder stalls longer than its socket buffer
  // holds; none is ever invented.
  EXPECT_LE(json_number(fs, "outputs_received"), kFrames) << fs;

  Child replay({NTN_HIL, "replay", dir / "run.ntnlog"}, dir / "replay.txt");
  EXPECT_EQ(replay.wait(60s), 0);
  EXPECT_NE(read_file(dir / "replay.txt").find("bit-identical over 3000 frames"), std::string::npos)
      << read_file(dir / "replay.txt");
}

FaultPlan plan_of(const std::string& faults, std::int64_t frames) {
  std::vector<FaultAt> list;
  FaultPlan plan;
  EXPECT_EQ(parse_fault_list(faults, list), "");
  EXPECT_EQ(make_fault_plan(frames, list, {}, 1, plan), "");
  return plan;
}

// What the gate must hand the kernel for each frame: the feeder's sample (the record at
// k / rate, as ntn-feeder computes it) where the frame's packet arrived with a good value,
// else the last good value (0 before the first).
std::vector<double> held_inputs(const FaultPlan& plan, std::int64_t frames) {
  const ntn::io::Record r = *ntn::io::read_record(kElCentro).record;
  std::vector<double> v;
  double last = 0;
  for (std::int64_t k = 0; k < frames; ++k) {
    const FaultKind f = plan[k];
    const bool held = f == FaultKind::kNan || f == FaultKind::kInf || f == FaultKind::kRange ||
                      f == FaultKind::kLate || f == FaultKind::kLost || f == FaultKind::kCorrupt;
    if (!held) last = r.at(static_cast<double>(k) * kPeriod);
    v.push_back(last);
  }
  return v;
}

// The gate's flags each frame must carry (hil_sim/README.md, "Fault kinds").
std::vector<unsigned> gate_flags(const FaultPlan& plan, std::int64_t frames) {
  std::vector<unsigned> f(static_cast<std::size_t>(frames), 0);
  for (std::int64_t k = 0; k < frames; ++k) {
    unsigned& x = f[static_cast<std::size_t>(k)];
    switch (plan[k]) {
      case FaultKind::kNan:
      case FaultKind::kInf:
        x |= flag::kNonFinite | flag::kHeld;
        break;
      case FaultKind::kRange:
        x |= flag::kOutOfRange | flag::kHeld;
        break;
      case FaultKind::kLate:  // missing in its frame; dropped as late in the next one
        x |= flag::kMissing | flag::kHeld;
        f[static_cast<std::size_t>(k + 1)] |= flag::kLate;
        break;
      case FaultKind::kLost:
        x |= flag::kMissing | flag::kHeld;
        break;
      case FaultKind::kDuplicate:
        x |= flag::kDuplicate;
        break;
      case FaultKind::kReorder:  // k+1's packet buffered, then k's below the highest sequence
        x |= flag::kEarly | flag::kReordered;
        break;
      case FaultKind::kCorrupt:
        x |= flag::kCorrupt | flag::kMissing | flag::kHeld;
        break;
      case FaultKind::kNone:
        break;
    }
  }
  return f;
}

// The held values as a CSV record that ntn-hil's file input reads back bit for bit at every
// frame time. Record::at interpolates linearly at x = t / dt, and t = k period divided by a dt
// of one period can round just below k, which would mix in the previous value. So each value is
// written twice at a spacing dt = (period / 2)(1 - 1e-9): x = 2k (1 + 1e-9) then always falls in
// [2k, 2k + 1), where both ends hold the same value and the interpolation returns it exactly.
void write_held_csv(const std::string& path, const std::vector<double>& v) {
  const double dt = kPeriod / 2 * (1 - 1e-9);
  std::ofstream out(path);
  out << "time,ag_x\n";
  char row[80];
  for (std::size_t i = 0; i < 2 * v.size(); ++i) {
    std::snprintf(row, sizeof row, "%.17g,%.17g\n", static_cast<double>(i) * dt, v[i / 2]);
    out << row;
  }
}

// Lock-step (deterministic): every fault kind, a burst of 50 NaN frames, against the loop's own
// summary, output CSV and hash. All comparisons are exact: in lock-step nothing depends on timing.
TEST(HilE2E, LockStepEveryFaultKind) {
  constexpr std::int64_t kFrames = 4000;
  std::string faults =
      "nan@1200,inf@1300,inf@1301,range@1400,late@1500,lost@1600,duplicate@1700,reorder@1800,"
      "corrupt@1900,late@2100,lost@2101,corrupt@2102,reorder@2103,range@2200,duplicate@2201";
  for (int k = 2500; k < 2550; ++k)  // 50 consecutive frames of NaN, in the strong motion
    faults += ",nan@" + std::to_string(k);
  const FaultPlan plan = plan_of(faults, kFrames);
  const TempDir dir("hil_e2e_lockstep");
  const PairRun pair =
      run_pair(dir, kFrames,
               {"--clock", "virtual", "--out", dir / "hil.csv", "--record", dir / "run.ntnlog"},
               {"--virtual", "--fault", faults, "--out", dir / "feeder.csv"}, 60s);
  ASSERT_EQ(pair.feeder_rc, 0) << pair.feeder_text;
  ASSERT_EQ(pair.hil_rc, 0) << pair.hil_text;
  const std::string& hil_out = pair.hil_text;
  const std::string& js = pair.hil_json;
  const std::string& fs = pair.feeder_json;

  // The feeder injected the plan the library makes from the same list.
  const auto injected = [&](FaultKind k) { return json_number(fs, to_string(k), "faults"); };
  for (FaultKind k : kAllFaults)
    EXPECT_EQ(injected(k), static_cast<double>(plan.count(k))) << to_string(k);
  EXPECT_EQ(injected(FaultKind::kNan), 51);

  // The loop counted each kind as the feeder injected it.
  const auto counted = [&](const char* key) { return json_number(js, key, "inputs"); };
  const double not_arrived =
      injected(FaultKind::kLate) + injected(FaultKind::kLost) + injected(FaultKind::kCorrupt);
  EXPECT_EQ(counted("nonfinite"), injected(FaultKind::kNan) + injected(FaultKind::kInf));
  EXPECT_EQ(counted("out_of_range"), injected(FaultKind::kRange));
  EXPECT_EQ(counted("late"), injected(FaultKind::kLate));
  EXPECT_EQ(counted("lost"), injected(FaultKind::kLost) + injected(FaultKind::kCorrupt));
  EXPECT_EQ(counted("missing"), not_arrived);
  EXPECT_EQ(counted("duplicate"), injected(FaultKind::kDuplicate));
  EXPECT_EQ(counted("reordered"), injected(FaultKind::kReorder));
  EXPECT_EQ(counted("early"), injected(FaultKind::kReorder));
  EXPECT_EQ(counted("corrupt"), injected(FaultKind::kCorrupt));
  EXPECT_EQ(counted("wrong_count"), 0);
  EXPECT_EQ(counted("too_early"), 0);
  EXPECT_EQ(counted("accepted"), kFrames - not_arrived);
  EXPECT_EQ(json_number(js, "frames"), kFrames);
  EXPECT_EQ(json_number(fs, "outputs_received"), kFrames);

  // Not a NaN or Inf in the loop's CSV nor in what the feeder received; the two agree bit for
  // bit; every frame carries exactly the gate flags its fault implies.
  const Csv loop_csv = read_csv(dir / "hil.csv");
  const Csv fed_csv = read_csv(dir / "feeder.csv");
  ASSERT_EQ(loop_csv.error, "");
  ASSERT_EQ(fed_csv.error, "");
  ASSERT_EQ(loop_csv.values.size(), static_cast<std::size_t>(kFrames));
  ASSERT_EQ(fed_csv.values.size(), static_cast<std::size_t>(kFrames));
  const std::vector<unsigned> want = gate_flags(plan, kFrames);
  int nonfinite = 0, flagged = 0;
  for (std::size_t k = 0; k < loop_csv.values.size(); ++k) {
    ASSERT_EQ(loop_csv.values[k].size(), fed_csv.values[k].size());
    for (std::size_t c = 0; c < loop_csv.values[k].size(); ++c) {
      nonfinite += std::isfinite(loop_csv.values[k][c]) ? 0 : 1;
      nonfinite += std::isfinite(fed_csv.values[k][c]) ? 0 : 1;
      EXPECT_TRUE(same_bits(loop_csv.values[k][c], fed_csv.values[k][c])) << "frame " << k;
    }
    EXPECT_EQ(loop_csv.flags[k], fed_csv.flags[k]) << "frame " << k;
    EXPECT_EQ(loop_csv.flags[k] & flag::kGateMask, want[k]) << "frame " << k;
    flagged += want[k] != 0 ? 1 : 0;
  }
  EXPECT_EQ(nonfinite, 0);
  EXPECT_GT(flagged, 60);  // the checks above covered the faulted frames, not only clean ones

  // The faults changed nothing but the values held: a run on the virtual clock from a file of
  // exactly the held values gives the same output hash, and one from the clean record does not
  // (the holds were visible in the response).
  const std::vector<double> held = held_inputs(plan, kFrames);
  write_held_csv(dir / "held.csv", held);
  const std::string with_faults = output_hash(hil_out);
  ASSERT_EQ(with_faults.size(), 16U) << hil_out;
  std::string file_hash[2];
  const std::string records[2] = {dir / "held.csv", kElCentro};
  for (int i = 0; i < 2; ++i) {
    Child run({NTN_HIL, "run", "--clock", "virtual", "--input", "ag_x=" + records[i], "--frames",
               std::to_string(kFrames), "-q"},
              dir / ("file" + std::to_string(i) + ".txt"));
    ASSERT_EQ(run.wait(60s), 0) << read_file(dir / ("file" + std::to_string(i) + ".txt"));
    file_hash[i] = output_hash(read_file(dir / ("file" + std::to_string(i) + ".txt")));
  }
  EXPECT_EQ(file_hash[0], with_faults);
  EXPECT_NE(file_hash[1], with_faults);

  // And the run's log replays bit for bit.
  Child replay({NTN_HIL, "replay", dir / "run.ntnlog"}, dir / "replay.txt");
  EXPECT_EQ(replay.wait(60s), 0);
  EXPECT_NE(read_file(dir / "replay.txt").find("bit-identical over 4000 frames"), std::string::npos)
      << read_file(dir / "replay.txt");
}

// Real time, 2000 frames at 1 kHz with a few faults whose counts do not depend on timing:
// the summary is written, its counts add up and agree with the feeder's, and the run replays
// bit for bit. How many frames miss their packet beyond the three injected ones depends on the
// machine's load: reported, not asserted (see RealTimeDeadlinesFollowTheSender).
TEST(HilE2E, RealTimeWithFaults) {
  constexpr std::int64_t kFrames = 2000;
  const std::string faults = "corrupt@300,duplicate@600,lost@700,nan@900,corrupt@1100";
  const TempDir dir("hil_e2e_rt_faults");
  const PairRun pair =
      run_pair(dir, kFrames, {"--clock", "real", "--fifo", "--record", dir / "run.ntnlog"},
               {"--fifo", "70", "--fault", faults}, 30s);
  EXPECT_EQ(pair.feeder_rc, 0) << pair.feeder_text;
  ASSERT_EQ(pair.hil_rc, 0) << pair.hil_text;
  const std::string& js = pair.hil_json;
  const std::string& fs = pair.feeder_json;
  ASSERT_FALSE(js.empty());

  const auto counted = [&](const char* key) { return json_number(js, key, "inputs"); };
  EXPECT_EQ(json_number(js, "frames"), kFrames);
  EXPECT_EQ(json_number(js, "first_packet_frame"), 0);
  EXPECT_EQ(json_number(fs, "corrupt", "faults"), 2);
  EXPECT_EQ(json_number(fs, "duplicate", "faults"), 1);
  EXPECT_EQ(json_number(fs, "lost", "faults"), 1);
  EXPECT_EQ(counted("corrupt"), 2);
  EXPECT_EQ(counted("duplicate"), 1);
  EXPECT_GE(counted("lost"), 3);  // frames 300, 700 and 1100 never arrive
  EXPECT_LE(counted("nonfinite"), 1);
  EXPECT_EQ(counted("accepted") + counted("missing"), kFrames);
  std::printf("real time with faults, 2000 frames: %g missing (3 injected), %g overruns\n",
              counted("missing"), json_number(js, "overruns"));
  // The frames the feeder saw flagged are the loop's counts, exactly when every output came back
  // (a stalled feeder may lose some on loopback UDP: then at most the loop's counts).
  const double received = json_number(fs, "outputs_received");
  EXPECT_LE(received, kFrames) << fs;
  const auto flagged = [&](const char* key) {
    const double n = json_number(fs, key, "output_flag_frames");
    return std::isnan(n) ? 0.0 : n;
  };
  if (received == kFrames) {
    EXPECT_EQ(flagged("missing"), counted("missing"));
    EXPECT_EQ(flagged("overrun"), json_number(js, "overruns"));
  } else {
    EXPECT_LE(flagged("missing"), counted("missing"));
    EXPECT_LE(flagged("overrun"), json_number(js, "overruns"));
  }
  EXPECT_GE(json_number(js, "max", "latency_us"), json_number(js, "p50", "latency_us"));
  EXPECT_GT(json_number(js, "p50", "compute_fraction"), 0);

  // What the loop accepted in real time replays bit for bit on the virtual clock.
  Child replay({NTN_HIL, "replay", dir / "run.ntnlog"}, dir / "replay.txt");
  EXPECT_EQ(replay.wait(60s), 0);
  EXPECT_NE(read_file(dir / "replay.txt").find("bit-identical over 2000 frames"), std::string::npos)
      << read_file(dir / "replay.txt");
}

// An alarm's state frame by frame from the channel's values (the rule of config/README.md:
// on when |value| > limit, off again when |value| < limit - hysteresis).
struct AlarmTrace {
  std::vector<bool> on;
  int raised = 0, cleared = 0;
  int held_by_hysteresis = 0;  // frames on with |value| <= limit: on only because of hysteresis
};

AlarmTrace alarm_trace(const Csv& csv, std::size_t channel, double limit, double hysteresis) {
  AlarmTrace t;
  bool on = false;
  for (const auto& row : csv.values) {
    const double v = std::abs(row[channel]);
    if (!on && v > limit) {
      on = true, ++t.raised;
    } else if (on && v < limit - hysteresis) {
      on = false, ++t.cleared;
    }
    if (on && v <= limit) ++t.held_by_hysteresis;
    t.on.push_back(on);
  }
  return t;
}

// The "raised" count of a channel in the loop's JSON summary (-1 if it has no alarm there).
double json_raised(const std::string& js, const std::string& channel) {
  const std::size_t at = js.find("{\"channel\": \"" + channel + "\"");
  return at == std::string::npos ? -1 : json_number(js.substr(at), "raised");
}

// Runs the loop on El Centro (virtual clock, file input) with extra arguments; the CSV and JSON.
struct FileRun {
  int exit = -1;
  Csv csv;
  std::string json, screen;
};

FileRun run_el_centro(const TempDir& dir, const std::string& tag,
                      const std::vector<std::string>& extra) {
  std::vector<std::string> a{NTN_HIL,          "run",
                             "--clock",        "virtual",
                             "--input",        "ag_x=" + kElCentro,
                             "--frames",       "8000",
                             "--out",          dir / (tag + ".csv"),
                             "--summary-json", dir / (tag + ".json")};
  a.insert(a.end(), extra.begin(), extra.end());
  Child c(a, dir / (tag + ".txt"));
  FileRun r;
  r.exit = c.wait(60s);
  r.screen = read_file(dir / (tag + ".txt"));
  if (r.exit == 0)
    r.csv = read_csv(dir / (tag + ".csv")), r.json = read_file(dir / (tag + ".json"));
  return r;
}

// The model file's alarms are on by default: every frame's alarm flag is the OR of the alarms
// computed from the CSV's own values with the file's limits and hysteresis, an alarm goes on
// and off again under El Centro, and some frames stay on only because of the hysteresis.
// --alarm NAME=off and --alarm NAME=LIMIT:H replace a channel's alarm; bad values exit 2.
TEST(HilE2E, ModelAlarmTriggersAndClearsWithHysteresis) {
  const auto model = ntn::modelc::load_model(kFrame3d);
  ASSERT_TRUE(model.ok()) << ntn::modelc::format_all(model.errors);
  const auto& alarms = model.model->output_alarms;
  const auto& names = model.model->output_names;
  const TempDir dir("hil_e2e_alarm");

  const FileRun def = run_el_centro(dir, "default", {});
  ASSERT_EQ(def.exit, 0) << def.screen;
  ASSERT_EQ(def.csv.error, "");
  ASSERT_EQ(def.csv.values.size(), 8000U);
  std::vector<bool> any(def.csv.values.size(), false);
  int channels = 0, raised = 0, cleared = 0, held = 0;
  for (std::size_t c = 0; c < alarms.size(); ++c) {
    if (alarms[c].limit <= 0) {
      EXPECT_EQ(json_raised(def.json, names[c]), -1) << names[c];
      continue;
    }
    ++channels;
    const AlarmTrace t = alarm_trace(def.csv, c, alarms[c].limit, alarms[c].hysteresis);
    EXPECT_EQ(json_raised(def.json, names[c]), t.raised) << names[c];
    raised += t.raised, cleared += t.cleared, held += t.held_by_hysteresis;
    for (std::size_t k = 0; k < t.on.size(); ++k)
      any[k] = any[k] || t.on[k];
  }
  EXPECT_GT(channels, 0);  // frame3d.toml has alarms
  EXPECT_GT(raised, 1);    // on more than once: it went on, off, and on again
  EXPECT_GT(cleared, 0);
  EXPECT_GT(held, 0);  // the hysteresis changed the state of some frames
  for (std::size_t k = 0; k < any.size(); ++k)
    ASSERT_EQ((def.csv.flags[k] & flag::kAlarm) != 0, any[k]) << "frame " << k;

  // Every model alarm off: no frame flagged.
  std::vector<std::string> off;
  for (std::size_t c = 0; c < alarms.size(); ++c) {
    if (alarms[c].limit > 0) off.insert(off.end(), {"--alarm", names[c] + "=off"});
  }
  const FileRun none = run_el_centro(dir, "off", off);
  ASSERT_EQ(none.exit, 0) << none.screen;
  for (unsigned f : none.csv.flags)
    ASSERT_EQ(f & flag::kAlarm, 0U);

  // One channel's alarm replaced (a limit of 3/4 of its peak, hysteresis a tenth of that):
  // its raised count follows the new values; the outputs do not change.
  std::size_t ch = 0;
  while (ch < alarms.size() && !(alarms[ch].limit > 0))
    ++ch;
  ASSERT_LT(ch, alarms.size());
  double peak = 0;
  for (const auto& row : def.csv.values)
    peak = std::max(peak, std::abs(row[ch]));
  const double limit = 0.75 * peak, hysteresis = 0.075 * peak;
  char spec[96];
  std::snprintf(spec, sizeof spec, "%s=%.17g:%.17g", names[ch].c_str(), limit, hysteresis);
  const FileRun other = run_el_centro(dir, "override", {"--alarm", spec});
  ASSERT_EQ(other.exit, 0) << other.screen;
  const AlarmTrace t = alarm_trace(other.csv, ch, limit, hysteresis);
  EXPECT_GT(t.raised, 0);
  EXPECT_EQ(json_raised(other.json, names[ch]), t.raised);
  EXPECT_EQ(output_hash(other.screen), output_hash(def.screen));

  for (const std::string& bad : {names[ch] + "=-1", names[ch] + "=0.01:0.02", names[ch] + "=x",
                                 names[ch] + "=0.01:-1", std::string("no_such_output=1")}) {
    Child c({NTN_HIL, "run", "--clock", "virtual", "--input", "ag_x=" + kElCentro, "--frames", "10",
             "--alarm", bad},
            dir / "bad.txt");
    EXPECT_EQ(c.wait(30s), 2) << bad;
  }
}

}  // namespace

namespace {

// A far-off frame number and the --listen 0 message. `--listen 0` binds a port the OS chooses: the
// loop prints it (startup line, summary, JSON), so a sender can be pointed at it. One valid packet
// for frame 18 445 744 073 710 hung the loop (its arrival fixed the deadlines: frame 0 due in ~11
// days); now it is out of the run, counted, and never fixes the deadlines: the loop waits its
// --wait-first (0.5 s) for a plausible packet, runs its 50 frames on its own clock and ends.
// Nothing here depends on timing: the packet is queued before the loop reads its socket, and
// whenever it is read it is counted the same.
TEST(HilE2E, ListenZeroPrintsThePortAndAHugeFrameNeverFixesTheDeadlines) {
  const TempDir dir("hil_e2e_huge_frame");
  Child hil({NTN_HIL, "run", "--listen", "0", "--frames", "50", "--wait-first", "0.5",
             "--summary-json", dir / "hil.json"},
            dir / "hil.txt");
  ASSERT_TRUE(hil.started());
  const std::string key = "listening on 127.0.0.1:";
  long port = -1;
  const auto give_up = std::chrono::steady_clock::now() + 10s;
  while (port < 0 && std::chrono::steady_clock::now() < give_up) {
    const std::string text = read_file(dir / "hil.txt");
    if (const std::size_t at = text.find(key); at != std::string::npos)
      port = std::strtol(text.c_str() + at + key.size(), nullptr, 10);
    else
      std::this_thread::sleep_for(5ms);
  }
  ASSERT_GT(port, 0) << read_file(dir / "hil.txt");
  ASSERT_LT(port, 65536);
  ASSERT_TRUE(ntn_test::udp_port_bound(static_cast<std::uint16_t>(port)));
  UdpSocket sender;
  ASSERT_TRUE(sender.open().ok());
  std::array<std::byte, kMaxPacketBytes> buf{};
  const double value[1] = {0.01};  // frame3d has one input, ag_x
  const std::size_t n = encode(PacketKind::kInput, 1, 18'445'744'073'710, 0, value, buf);
  ASSERT_TRUE(sender.send_to(static_cast<std::uint16_t>(port), std::span(buf).first(n)).ok());
  const int rc = hil.wait(30s);  // a hang is -2
  const std::string text = read_file(dir / "hil.txt");
  const std::string json = read_file(dir / "hil.json");
  std::printf("%s", text.c_str());
  EXPECT_EQ(rc, 0);
  EXPECT_NE(text.find("UDP on 127.0.0.1:" + std::to_string(port)), std::string::npos);
  EXPECT_EQ(json_number(json, "listen_port"), static_cast<double>(port));
  EXPECT_EQ(json_number(json, "out_of_run", "inputs"), 1.0);
  EXPECT_EQ(json_number(json, "accepted", "inputs"), 0.0);
  EXPECT_EQ(json_number(json, "missing", "inputs"), 50.0);
  EXPECT_EQ(json_number(json, "frames"), 50.0);
  EXPECT_EQ(json_number(json, "first_packet_frame"), -1.0);
}

}  // namespace
