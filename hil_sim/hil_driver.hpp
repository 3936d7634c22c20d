// The real-time frame loop's program (DESIGN §8), for ntn-hil MODEL.toml (run-time storage) and
// the compiled ntn-hil-<model>: one template over the model's storage (hil_main.cpp,
// ntn_hil_main.cpp), so that both run the same lines on the same kernel code. Inputs from
// recorded files or from UDP on loopback through the input gate; outputs to CSV and back over
// UDP; real-time or virtual clock; a log for bit-exact replay; a summary on screen and as JSON.
// The record source, the CSV sink and the output hash are the loop library's, shared with
// ntn-run (tools/run): for the same --sampling, `run --clock virtual` and ntn-run give the same
// output hash and CSV.
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <map>
#include <optional>
#include <string_view>
#include "cli.hpp"
#include "ntn/hil/clock.hpp"
#include "ntn/hil/csv_sink.hpp"
#include "ntn/hil/gate.hpp"
#include "ntn/hil/loop.hpp"
#include "ntn/hil/output_hash.hpp"
#include "ntn/hil/packet.hpp"
#include "ntn/hil/record_source.hpp"
#include "ntn/hil/recorder.hpp"
#include "ntn/hil/sampling.hpp"
#include "ntn/hil/schedule.hpp"
#include "ntn/hil/udp.hpp"
#include "ntn/hil/worker_team.hpp"
#include "ntn/hil/yield_report.hpp"
#include "ntn/kernel.hpp"
#include "record.hpp"

#include "ntn/hil/model_info.hpp"
#include "ntn/hil/stop_signals.hpp"

namespace ntn::hil::program {

// SIGINT / SIGTERM (stop_signals.hpp): the loop ends after the frame it is in, and the program
// flushes the CSV, the log and the JSON and says so.
using ntn::hil::g_stop_signal;

// Runs are bounded so that nothing the run keeps grows without limit: at most kMaxFrames frames
// (11.6 days at 1 kHz; the CSV's time column, %.9g, resolves 1 ms frames up to 10^6 s), and the
// wake-up latency and compute time of the first kTimedFrames frames (64 MiB) for the summary's
// percentiles (overruns are counted over the whole run). The CSV and the log are streamed to
// their files through 1 MiB buffers; the output hash is computed as the run goes.
constexpr std::int64_t kMaxFrames = 1'000'000'000;
constexpr std::int64_t kTimedFrames = std::int64_t{1} << 22;

// Input packets on a loopback port, through the gate. In lock-step mode (virtual clock) frame k
// waits for the sender's frame-end marker for k, so the accepted inputs do not depend on timing.
// In real time frame 0 waits for the sender's first input packet (frame f0, arriving at t_a) and
// the loop's deadlines follow the sender's stream: frame k is due at t_a + (k - f0) period +
// period / 2, half a period after its packet is expected, so that arrival jitter below half a
// period makes no packet late (after its frame ran) or early (before the frame before it ran).
// The SenderSchedule (schedule.hpp) keeps that epoch: set by a plausible first packet only, and
// re-anchored (resync) when the stream misses the schedule (K of its last 2K packets dropped on
// one side with a consistent offset, README "The input schedule").
struct UdpSource {
  ntn::hil::UdpSocket* socket;
  ntn::hil::InputGate* gate;
  bool lock_step;
  std::int64_t period_ns = 1'000'000;
  std::int64_t first_wait_ns = 0;  // real time: how long frame 0 waits for the first packet
  std::array<std::byte, ntn::hil::kMaxPacketBytes + 64> buffer{};
  ntn::hil::SenderSchedule* schedule = nullptr;  // real time: the deadlines
  std::uint64_t timeouts = 0;
  std::int64_t first_frame = -1;  // frame of the packet the deadlines follow
  std::int64_t waited_ns = 0;     // time frame 0 waited for it
  std::int64_t epoch_ns() const { return schedule != nullptr ? schedule->epoch_ns() : -1; }
  void drain(std::int64_t k, bool& ended) {
    for (;;) {
      const ntn::hil::Received r = socket->receive(buffer);
      if (!r.has_datagram()) return;
      const auto res = gate->offer(std::span<const std::byte>(buffer.data(), r.size));
      if (schedule != nullptr) (void)schedule->observe(res, k, ntn::hil::monotonic_ns());
      if (res.status == ntn::hil::OfferStatus::kFrameEnd && res.frame >= k) ended = true;
    }
  }
  // The first input packet (decoded, with the model's channel count) seen arriving fixes the
  // deadlines; one beyond the jitter buffer too (the sender started long before the loop, which
  // then catches up). Packets already queued when frame 0 begins go through the gate, but their
  // arrival time is unknown, so the deadlines wait for the next packet to arrive.
  void wait_first_packet() {
    const std::int64_t start = ntn::hil::monotonic_ns();
    bool ended = false;
    drain(0, ended);
    for (std::int64_t left = first_wait_ns; left > 0 && g_stop_signal == 0;
         left = start + first_wait_ns - ntn::hil::monotonic_ns()) {
      // In slices of 0.1 s, so that SIGINT / SIGTERM (g_stop_signal) ends the wait soon.
      if (socket->wait_readable(std::chrono::nanoseconds(
              std::min<std::int64_t>(left, 100'000'000))) != ntn::hil::WaitStatus::kReadable)
        continue;
      const std::int64_t arrival = ntn::hil::monotonic_ns();
      for (;;) {
        const ntn::hil::Received r = socket->receive(buffer);
        if (!r.has_datagram()) break;
        const auto res = gate->offer(std::span<const std::byte>(buffer.data(), r.size));
        using ntn::hil::OfferStatus;
        // Only a packet whose frame is plausible (the gate checked the run and the window;
        // the schedule checks again, and the arithmetic) fixes the deadlines.
        if ((res.status == OfferStatus::kCurrent || res.status == OfferStatus::kBuffered ||
             res.status == OfferStatus::kTooEarly) &&
            schedule != nullptr && schedule->anchor(res.frame, arrival, 0)) {
          first_frame = res.frame;
          waited_ns = arrival - start;
          return;
        }
      }
    }
    waited_ns = ntn::hil::monotonic_ns() - start;
  }
  void frame_inputs(std::int64_t k, std::span<double> v, std::uint16_t& flags) {
    gate->begin_frame(k);
    if (k == 0 && !lock_step) wait_first_packet();
    bool ended = false;
    drain(k, ended);
    while (lock_step && !ended && g_stop_signal == 0) {
      if (socket->wait_readable(std::chrono::seconds(2)) != ntn::hil::WaitStatus::kReadable) {
        ++timeouts;  // the sender went away: the frame is missing, values held
        break;
      }
      drain(k, ended);
    }
    gate->end_frame(v, flags);
    if (schedule != nullptr) flags |= schedule->take_flags();
  }
};

// Inputs from a log, as they were accepted, read frame by frame (the log was checked whole
// before; a record that fails now, the file having changed, stops the replay).
struct ReplaySource {
  ntn::hil::LogReader* reader;
  volatile std::sig_atomic_t* stop;
  ntn::hil::LogFrame frame;
  std::string error;  // not empty: frame k could not be read, the loop stops after it
  void frame_inputs(std::int64_t, std::span<double> v, std::uint16_t& flags) {
    if (!error.empty() || reader->next(frame) != ntn::hil::LogRead::kFrame) {
      if (error.empty()) error = reader->error();
      std::fill(v.begin(), v.end(), 0.0);
      flags = 0;
      *stop = 1;
      return;
    }
    std::copy(frame.inputs.begin(), frame.inputs.end(), v.begin());
    flags = static_cast<std::uint16_t>(frame.input_flags);
  }
};

// Compares each replayed frame with the log: every output value bit for bit, and the diverged
// flag (the alarm bit depends on --alarm and the overrun bit on timing: neither is replayed).
struct ReplaySink {
  const ReplaySource* source;
  volatile std::sig_atomic_t* stop;
  std::int64_t differs = -1;  // first differing frame
  int channel = -1;           // its first differing channel, or -1: the diverged flag
  double recorded = 0, now = 0;
  std::uint16_t recorded_flags = 0, now_flags = 0;
  void frame_outputs(std::int64_t k, std::span<const double> v, std::uint16_t flags) {
    if (differs >= 0 || !source->error.empty()) return;
    const ntn::hil::LogFrame& f = source->frame;
    for (std::size_t c = 0; c < v.size(); ++c) {
      if (std::memcmp(&v[c], &f.outputs[c], sizeof(double)) != 0) {
        differs = k, channel = static_cast<int>(c), recorded = f.outputs[c], now = v[c];
        *stop = 1;
        return;
      }
    }
    if ((flags & ntn::hil::flag::kDiverged) != (f.output_flags & ntn::hil::flag::kDiverged)) {
      differs = k, recorded_flags = static_cast<std::uint16_t>(f.output_flags), now_flags = flags;
      *stop = 1;
    }
  }
};

// The caller's storage of the model: static objects (compiled) or bound to one block
// (ntn/runtime_storage.hpp); `buffers`: the loop's channels (run-time storage: made before init).
template <Sizes S>
struct HilStorage {
  Model<S>& model;
  InitWorkspace<S>& init_work;
  State<S>& state;
  Scratch<S>& scratch;
  State<S>& checkpoint;  // the end of the last good frame (the loop's safe state)
  TeamWork<S>& team_work;
  LoopBuffers<S>* buffers = nullptr;
};

// CSV rows (the library's CsvWriter, opened before the run); output packets back to the
// sender; the output hash (output_hash.hpp: every kernel step's outputs, then the final state).
template <Sizes S>
struct Sink {
  ntn::hil::CsvWriter* csv = nullptr;
  ntn::hil::UdpSocket* socket = nullptr;
  std::uint16_t reply_port = 0;
  std::uint32_t sequence = 0;
  double period = 1e-3;
  std::array<std::byte, ntn::hil::kMaxPacketBytes> packet{};
  ntn::hil::OutputHash* hash = nullptr;
  std::vector<double> peak;              // largest |value| per channel
  std::vector<std::int64_t> peak_frame;  // and its first frame
  // The CSV and the log are handed to their files every flush_every frames (about a second),
  // after the frame's output packet is sent: a run killed (SIGKILL, a power cut) loses at most
  // the last second.
  ntn::hil::Recorder* recorder = nullptr;
  std::int64_t flush_every = 0;
  void after_step(const ntn::State<S>&, const ntn::Scratch<S>& w) {
    if (hash != nullptr) hash->add_step(w);
  }
  void frame_outputs(std::int64_t k, std::span<const double> v, std::uint16_t flags) {
    for (std::size_t c = 0; c < peak.size(); ++c) {
      if (std::abs(v[c]) > peak[c]) peak[c] = std::abs(v[c]), peak_frame[c] = k;
    }
    if (csv != nullptr && csv->is_open()) csv->row(static_cast<double>(k) * period, v, flags);
    if (socket != nullptr && reply_port != 0) {
      const std::size_t n =
          ntn::hil::encode(ntn::hil::PacketKind::kOutput, sequence++, k, flags, v, packet);
      (void)socket->send_to(reply_port, std::span<const std::byte>(packet.data(), n));
    }
    if (flush_every > 0 && (k + 1) % flush_every == 0) {
      if (csv != nullptr && csv->is_open()) csv->flush();
      if (recorder != nullptr) recorder->flush();
    }
  }
};

// "NAME=LIMIT[:HYSTERESIS]" or "NAME=off" for one output channel, as the model file's alarm
// keys: 0 < LIMIT finite, 0 <= HYSTERESIS < LIMIT. "" on success, else what is wrong.
inline std::string parse_alarm(const ModelInfo& info, const std::string& arg,
                               std::vector<ntn::hil::Alarm>& alarms) {
  const auto eq = arg.find('=');
  const std::string name = arg.substr(0, eq);
  std::size_t c = 0;
  while (c < info.output_names.size() && info.output_names[c] != name)
    ++c;
  if (eq == std::string::npos) return "want OUTPUT=LIMIT[:HYSTERESIS] or OUTPUT=off";
  if (c == info.output_names.size()) return "the model has no output '" + name + "'";
  const std::string spec = arg.substr(eq + 1);
  if (spec == "off") {
    alarms[c] = {};
    return "";
  }
  const auto number = [](const std::string& text, double& out) {
    char* end = nullptr;
    out = std::strtod(text.c_str(), &end);
    return !text.empty() && end == text.c_str() + text.size() && std::isfinite(out);
  };
  const auto colon = spec.find(':');
  double limit = 0, hysteresis = 0;
  if (!number(spec.substr(0, colon), limit) || !(limit > 0))
    return "the limit must be a finite number > 0";
  if (colon != std::string::npos &&
      (!number(spec.substr(colon + 1), hysteresis) || hysteresis < 0 || !(hysteresis < limit)))
    return "the hysteresis must be a number >= 0 and below the limit";
  alarms[c] = {};
  alarms[c].enabled = true, alarms[c].limit = limit, alarms[c].hysteresis = hysteresis;
  return "";
}

inline double us(std::int64_t ns) {
  return static_cast<double>(ns) / 1e3;
}

inline bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// `replay LOG`: checks the whole log first (every record's checksum, the frame numbers, the end
// record; the header against this model), then re-runs its complete frames on the virtual clock
// and compares every output with the recorded one. Exit 0: bit-identical over a complete log;
// 1: a frame differs; 2: the log cannot be used; 4: the log is incomplete (no end record: the
// run was killed, or the disk filled) and its complete frames replay bit-identical.
template <Sizes S>
int replay_log(const ModelInfo& info, HilStorage<S> store, const std::string& path,
               ntn::hil::LoopConfig config) {
  const Sizes z = store.model.sizes;
  using ntn::hil::LogRead;
  ntn::hil::LogReader check;
  if (!check.open(path)) {
    std::fprintf(stderr, "error: %s\n", check.error().c_str());
    return 2;
  }
  const ntn::hil::LogHeader& h = check.header();
  const std::string name(info.name);
  char why[256] = "";
  if (h.model != name) {
    std::snprintf(why, sizeof why, "model '%s', this program runs '%s'", h.model.c_str(),
                  name.c_str());
  } else if (h.inputs != z.inputs || h.outputs != z.outputs) {
    std::snprintf(why, sizeof why, "%u inputs and %u outputs, the model has %zu and %zu", h.inputs,
                  h.outputs, z.inputs, z.outputs);
  } else if (h.substeps != static_cast<std::uint32_t>(config.substeps)) {
    std::snprintf(why, sizeof why, "%u substeps per frame, the model runs %d", h.substeps,
                  config.substeps);
  } else if (!same_bits(h.period, config.period)) {
    std::snprintf(why, sizeof why, "period %.17g s, the model's frame period is %.17g s", h.period,
                  config.period);
  } else if (!same_bits(h.dt, store.model.dt)) {
    std::snprintf(why, sizeof why, "dt %.17g s, the model's is %.17g s", h.dt, store.model.dt);
  }
  if (why[0] != '\0') {
    std::fprintf(stderr, "error: %s was recorded with another model or step: %s\n", path.c_str(),
                 why);
    return 2;
  }
  ntn::hil::LogFrame frame;
  LogRead r = LogRead::kFrame;
  while ((r = check.next(frame)) == LogRead::kFrame) {
  }
  if (r == LogRead::kError) {
    std::fprintf(stderr, "error: %s\n", check.error().c_str());
    return 2;
  }
  const std::int64_t frames = check.frames();
  if (frames == 0) {
    std::fprintf(stderr, "error: %s: the log holds no complete frame: nothing to replay (%s)\n",
                 path.c_str(), check.error().c_str());
    return 2;
  }

  ntn::hil::LogReader reader;
  if (!reader.open(path)) {
    std::fprintf(stderr, "error: %s\n", reader.error().c_str());
    return 2;
  }
  volatile std::sig_atomic_t stop = 0;
  config.frames = frames;
  config.sampling = h.interpolate != 0 ? ntn::hil::InputSampling::kFrameInterpolated
                                       : ntn::hil::InputSampling::kFrameHeld;
  config.stop = &stop;
  ReplaySource source{&reader, &stop, {}, {}};
  ReplaySink sink{&source, &stop};
  ntn::hil::VirtualClock clock;
  ntn::hil::FrameTimes times;
  std::vector<ntn::hil::Alarm> no_alarms;
  const ntn::hil::LoopResult result =
      ntn::hil::run_loop(store.model, store.state, store.scratch, clock, source, sink, nullptr,
                         config, no_alarms, times, static_cast<State<S>*>(nullptr), nullptr,
                         static_cast<TeamWork<S>*>(nullptr), store.buffers);
  if (!source.error.empty()) {
    std::fprintf(stderr, "error: %s (the file changed while it was replayed?)\n",
                 source.error.c_str());
    return 2;
  }
  if (sink.differs >= 0) {
    const double t = static_cast<double>(sink.differs) * config.period;
    if (sink.channel >= 0) {
      std::printf(
          "replay: DIFFERS at frame %lld (t = %.6f s), channel %s: recorded %.17g, now %.17g\n",
          static_cast<long long>(sink.differs), t,
          std::string(info.output_names[static_cast<std::size_t>(sink.channel)]).c_str(),
          sink.recorded, sink.now);
    } else {
      std::printf(
          "replay: DIFFERS at frame %lld (t = %.6f s): the log's output flags 0x%04x say %s, the "
          "replay %s\n",
          static_cast<long long>(sink.differs), t, static_cast<unsigned>(sink.recorded_flags),
          (sink.recorded_flags & ntn::hil::flag::kDiverged) != 0 ? "diverged" : "not diverged",
          (sink.now_flags & ntn::hil::flag::kDiverged) != 0 ? "diverged" : "not diverged");
    }
    return 1;
  }
  if (result.frames != frames) {
    std::fprintf(stderr, "error: %s: replayed %lld of %lld frames\n", path.c_str(),
                 static_cast<long long>(result.frames), static_cast<long long>(frames));
    return 2;
  }
  if (r == LogRead::kTruncated) {
    std::printf("replay: bit-identical over %lld frames (0..%lld); the log is incomplete\n",
                static_cast<long long>(frames), static_cast<long long>(frames - 1));
    std::fprintf(stderr, "warning: %s\n", check.error().c_str());
    return 4;
  }
  std::printf("replay: bit-identical over %lld frames\n", static_cast<long long>(frames));
  return 0;
}

// The command line (parse_args): the same for every program; `model_path` only for ntn-hil.
struct HilOptions {
  std::string model_path;
  std::vector<std::string> input_args, alarm_args;
  std::string clock_name = "real", out_path, json_path, log_path, replay_path, sampling_name;
  double duration = -1, first_wait_s = 10;
  std::int64_t frames = -1;
  int listen_port = -1, reply_port = 0, cpu = -1, threads = 1;
  bool interpolate = false, quiet = false;
  bool fifo = true, mlock = true;  // real clock: ntn::hil::RealTimeOptions' defaults
  int priority = 80;
  std::int64_t timer_slack_ns = 1;
  int cpu_latency_us = 0;
  bool replay = false;                       // the replay subcommand (else run)
  std::map<std::string, std::size_t> given;  // times each of some run options was given
  std::size_t count(const std::string& option) const {
    const auto it = given.find(option);
    return it == given.end() ? 0 : it->second;
  }
};

// Parses the command line into `o` (with a MODEL.toml argument before the others when
// `model_file`). The exit code when the program ends there (--help: 0, a usage error: 2).
inline std::optional<int> parse_args(int argc, char** argv, const std::string& title,
                                     bool model_file, HilOptions& o) {
  ntn::cli::App app{title};
  app.require_subcommand(1);
  auto* run = app.add_subcommand("run", "run the loop");
  auto* replay = app.add_subcommand("replay", "re-run a log on the virtual clock and compare");
  if (model_file) {
    run->add_option("model", o.model_path, "model file (.toml)")->required();
    replay->add_option("model", o.model_path, "model file (.toml) the log was recorded with")
        ->required();
  }
  auto& input_args = o.input_args;
  auto& alarm_args = o.alarm_args;
  auto& clock_name = o.clock_name;
  auto& out_path = o.out_path;
  auto& json_path = o.json_path;
  auto& log_path = o.log_path;
  auto& replay_path = o.replay_path;
  auto& sampling_name = o.sampling_name;
  auto& duration = o.duration;
  auto& first_wait_s = o.first_wait_s;
  auto& frames = o.frames;
  auto& listen_port = o.listen_port;
  auto& reply_port = o.reply_port;
  auto& cpu = o.cpu;
  auto& threads = o.threads;
  auto& interpolate = o.interpolate;
  auto& fifo = o.fifo;
  auto& mlock = o.mlock;
  auto& quiet = o.quiet;
  run->add_option("-i,--input", input_args,
                  "NAME=FILE: feed an input from a record (AT2, CSV; FILE*FACTOR scales it)");
  run->add_option("--listen", listen_port, "take inputs as UDP packets on 127.0.0.1:PORT")
      ->check(ntn::cli::Integer(0, 65535));
  run->add_option("--reply", reply_port, "send output packets to 127.0.0.1:PORT")
      ->check(ntn::cli::Integer(1, 65535));
  run->add_option("--clock", clock_name,
                  "real (absolute deadlines) or virtual (as fast as "
                  "possible; lock-step with UDP)")
      ->check(ntn::cli::IsMember({"real", "virtual"}));
  run->add_option("--wait-first", first_wait_s,
                  "real time with --listen: seconds to wait for the sender's first packet, which "
                  "fixes the frame deadlines (default 10, at most 3600)")
      ->check(ntn::cli::Positive(3600));
  run->add_option("-t,--duration", duration, "seconds to run (default: the longest record)")
      ->check(ntn::cli::Positive());
  run->add_option("-n,--frames", frames, "frames to run (overrides --duration)")
      ->check(ntn::cli::Integer(1, kMaxFrames));
  auto* sampling_option =
      run->add_option("-s,--sampling", sampling_name,
                      "hold (inputs at frame times, held over the frame; default), interpolate "
                      "(linear over the frame, one frame of delay) or step (--input records at "
                      "every kernel step, as ntn-run-<model> by default)")
          ->check(ntn::cli::IsMember({"step", "hold", "interpolate"}));
  run->add_flag("--interpolate", interpolate, "the same as --sampling interpolate")
      ->excludes(sampling_option);
  run->add_option("--alarm", alarm_args,
                  "NAME=LIMIT[:HYSTERESIS] or NAME=off: limit alarm on an output, replacing the "
                  "model file's for that channel");
  run->add_option("-o,--out", out_path, "CSV of the outputs, one row per frame, with flags");
  run->add_option("--record", log_path, "binary log of accepted inputs and outputs (replay)");
  run->add_option("--summary-json", json_path, "write the summary as JSON");
  run->add_flag("--fifo,!--no-fifo", fifo,
                "real clock: SCHED_FIFO at --priority (the default; falls back with a warning)");
  run->add_option("--priority", o.priority, "real clock: the SCHED_FIFO priority (default 80)")
      ->check(ntn::cli::Integer(1, 99));
  run->add_flag("--mlock,!--no-mlock", mlock,
                "real clock: mlockall, every page locked (the default; falls back with a warning)");
  run->add_option("--cpu-latency", o.cpu_latency_us,
                  "real clock: the CPU wake-up latency to hold in us (PM QoS, "
                  "/dev/cpu_dma_latency; default 0; -1: leave it)")
      ->check(ntn::cli::Integer(-1, 10'000'000));
  run->add_option("--timer-slack", o.timer_slack_ns,
                  "real clock: the thread's timer slack in ns (default 1; 0: the system's "
                  "default, 50 us on Linux)")
      ->check(ntn::cli::Integer(0, 1'000'000'000));
  run->add_option("--cpu", cpu, "pin to this CPU (falls back with a warning)")
      ->check(ntn::cli::Integer(0, std::numeric_limits<int>::max()));
  run->add_option("--threads", threads,
                  "workers of the multi-core step, made before the loop (1 = the loop's thread "
                  "alone; with --cpu C, worker k is pinned to CPU C + k): the same bits for any "
                  "number")
      ->check(ntn::cli::Integer(1, ntn::kMaxTeam));
  run->add_flag("-q,--quiet", quiet, "print only warnings, errors and the output hash");
  replay->add_option("log", replay_path, "log written by run --record")->required();
  if (const auto code = ntn::cli::parse(app, argc, argv)) return code;
  o.replay = replay->parsed();
  for (const char* option : {"--out", "--record", "--summary-json", "--frames", "--duration"})
    o.given[option] = run->count(option);
  return std::nullopt;
}

// Runs (or replays) the model as the options say and prints the summary; the exit code.
template <Sizes S>
int hil_execute(const HilOptions& o, const ModelInfo& info, const ModelSpec<S>& spec,
                HilStorage<S> store) {
  const Sizes z = sizes_of(view(spec));
  auto input_args = o.input_args;
  auto alarm_args = o.alarm_args;
  auto clock_name = o.clock_name;
  auto out_path = o.out_path;
  auto json_path = o.json_path;
  auto log_path = o.log_path;
  auto replay_path = o.replay_path;
  auto sampling_name = o.sampling_name;
  auto duration = o.duration;
  auto first_wait_s = o.first_wait_s;
  auto frames = o.frames;
  auto listen_port = o.listen_port;
  auto reply_port = o.reply_port;
  auto cpu = o.cpu;
  auto threads = o.threads;
  auto interpolate = o.interpolate;
  auto fifo = o.fifo;
  auto mlock = o.mlock;
  auto quiet = o.quiet;
  if (const ntn::InitStatus st = ntn::init(spec, store.model, store.init_work); !st.ok()) {
    std::fprintf(stderr, "error: model '%s': %s (at %d)\n", std::string(info.name).c_str(),
                 ntn::to_string(st.error), st.where);
    return 1;
  }
  const double period = spec.settings.frame_period;
  ntn::hil::LoopConfig config;
  config.period = period;
  // N by the kernel's frame rule (ntn::frame_substeps), stored once by init; the model compiler
  // checked it.
  const ntn::Substeps& substeps = store.model.substeps;
  if (!substeps.ok()) {
    std::fprintf(stderr, "error: model '%s': dt = %g s, frame period %g s: %s\n",
                 std::string(info.name).c_str(), store.model.dt, period,
                 ntn::to_string(substeps.error));
    return 1;
  }
  config.substeps = static_cast<int>(substeps.count);

  // ---- replay ----
  if (o.replay) return replay_log(info, store, replay_path, config);
  // ---- run ----
  // Every output file is checked before anything is read or run: an unwritable path ends here,
  // not after the run with its results lost.
  for (const auto& [path, option] :
       {std::pair{&out_path, "--out"}, std::pair{&log_path, "--record"},
        std::pair{&json_path, "--summary-json"}}) {
    if (o.count(option) == 0) continue;
    // --out creates its directory, as the runners do; the other files' must exist.
    if (const auto problem =
            ntn::cli::output_path_problem(*path, option, std::string_view(option) == "--out")) {
      std::fprintf(stderr, "error: %s\n", problem->c_str());
      return 2;
    }
  }
  const ntn::cli::InputArgs inputs = ntn::cli::parse_input_args(input_args, "--input");
  if (inputs.error) {
    std::fprintf(stderr, "error: %s\n", inputs.error->c_str());
    return 2;
  }
  const ntn::hil::InputSampling sampling =
      interpolate ? ntn::hil::InputSampling::kFrameInterpolated
                  : ntn::hil::parse_sampling(sampling_name.empty() ? "hold" : sampling_name)
                        .value_or(ntn::hil::InputSampling::kFrameHeld);
  const bool per_step = sampling == ntn::hil::InputSampling::kStep;
  // Per-step sampling reads the records between frames: a sender's packets carry one value per
  // frame, and a log holds the inputs the loop accepted per frame, which replay cannot turn
  // back into per-step values.
  if (per_step && listen_port >= 0) {
    std::fprintf(stderr,
                 "error: --sampling step reads --input records at every kernel step; --listen "
                 "takes one value per frame (use --sampling hold or interpolate)\n");
    return 2;
  }
  if (per_step && !log_path.empty()) {
    std::fprintf(stderr,
                 "error: --sampling step with --record: the log holds one input per frame and "
                 "could not replay the per-step inputs (use --sampling hold or interpolate)\n");
    return 2;
  }
  // The records' values in each input's unit (gal to g, ...), as ntn-run reads them; per step
  // (not through the gate, which sees frame values) every sample must be in range.
  std::vector<ntn::io::Record> records;
  std::vector<char> fed;  // the channels given a record
  if (const auto e = ntn::hil::load_input_records(spec.inputs, info.input_names, inputs.args,
                                                  per_step, records, fed)) {
    std::fprintf(stderr, "%s\n", e->c_str());
    return 2;
  }
  double record_duration = 0;
  for (const ntn::io::Record& r : records)
    record_duration = std::max(record_duration, r.duration());
  const bool udp_in = listen_port >= 0;
  if (!udp_in && inputs.args.size() != z.inputs && z.inputs > 0) {
    std::fprintf(stderr,
                 "error: give --input NAME=FILE for every input channel, or --listen PORT\n");
    return 2;
  }
  // The run's length: --frames (checked by its validator), else --duration, else the longest
  // record; compared as numbers before any conversion.
  if (o.count("--frames") == 0) {
    const bool given = o.count("--duration") > 0;
    const double seconds = given ? duration : record_duration;
    const double n = std::ceil(seconds / period - 1e-9);
    const std::string what = given
                                 ? "--duration " + ntn::cli::num(duration) + " s"
                                 : "the longest --input record (" + ntn::cli::num(seconds) + " s)";
    if (!given && udp_in && inputs.args.empty()) {
      std::fprintf(stderr,
                   "error: with --listen and no --input record, give --frames or --duration\n");
      return 2;
    }
    if (!(n >= 1)) {
      std::fprintf(stderr, "error: %s is shorter than one frame (%s s)\n", what.c_str(),
                   ntn::cli::num(period).c_str());
      return 2;
    }
    if (n > static_cast<double>(kMaxFrames)) {
      std::fprintf(stderr,
                   "error: %s is longer than a run may be: at most %lld frames of %s s (%s s)%s\n",
                   what.c_str(), static_cast<long long>(kMaxFrames), ntn::cli::num(period).c_str(),
                   ntn::cli::num(static_cast<double>(kMaxFrames) * period).c_str(),
                   given ? "" : "; give --frames or --duration");
      return 2;
    }
    frames = static_cast<std::int64_t>(n);
  }
  config.frames = frames;
  config.sampling = sampling;

  // Alarms: the model file's ([[outputs]] alarm, alarm_hysteresis), then --alarm per channel.
  std::vector<ntn::hil::Alarm> alarms(z.outputs);
  for (std::size_t c = 0; c < alarms.size(); ++c) {
    alarms[c].enabled = info.alarm_limits[c] > 0;
    alarms[c].limit = info.alarm_limits[c];
    alarms[c].hysteresis = info.alarm_hysteresis[c];
  }
  for (const std::string& arg : alarm_args) {
    if (const std::string e = parse_alarm(info, arg, alarms); !e.empty()) {
      std::fprintf(stderr, "error: --alarm %s: %s\n", arg.c_str(), e.c_str());
      return 2;
    }
  }

  // SIGINT / SIGTERM from here on end the run after the frame in progress, with every file
  // written (exit 4); before, they end the program as usual (nothing written yet).
  ntn::hil::catch_stop_signals();
  config.stop = &g_stop_signal;

  ntn::hil::InputGate gate(std::span<const ntn::InputSpec>(spec.inputs));
  (void)gate.set_run_frames(frames);  // a packet for a frame outside the run: out_of_run
  const auto frame_ns = static_cast<std::int64_t>(std::llround(period * 1e9));
  ntn::hil::SenderSchedule schedule(frame_ns, frames);
  if (!schedule.valid()) {
    std::fprintf(stderr,
                 "error: --frames/--duration: %lld frames of %g s do not fit the clock's range "
                 "(at most %lld frames)\n",
                 static_cast<long long>(frames), period,
                 static_cast<long long>(ntn::hil::SenderSchedule::kMaxSpan /
                                        std::max<std::int64_t>(frame_ns, 1)));
    return 2;
  }
  ntn::hil::UdpSocket socket;  // opened last, when the loop is ready (below)
  ntn::hil::CsvWriter csv;
  if (!out_path.empty()) {
    if (!csv.open(out_path)) {
      std::fprintf(stderr, "error: --out: cannot write '%s': %s\n", out_path.c_str(),
                   csv.error().c_str());
      return 2;
    }
    csv.header(info.output_names, info.output_units, true);
  }
  ntn::hil::OutputHash run_hash;
  if (!run_hash.ok()) {
    std::fprintf(stderr, "error: cannot set up the output hash\n");
    return 2;
  }
  Sink<S> sink;
  sink.peak.assign(z.outputs, 0.0);
  sink.peak_frame.assign(z.outputs, 0);
  sink.csv = &csv;
  sink.socket = reply_port != 0 ? &socket : nullptr;
  sink.reply_port = static_cast<std::uint16_t>(reply_port);
  sink.period = period;
  sink.hash = &run_hash;

  ntn::hil::Recorder recorder;
  if (!log_path.empty()) {
    ntn::hil::LogHeader h;
    h.inputs = static_cast<std::uint32_t>(z.inputs);
    h.outputs = static_cast<std::uint32_t>(z.outputs);
    h.substeps = static_cast<std::uint32_t>(config.substeps);
    h.interpolate = sampling == ntn::hil::InputSampling::kFrameInterpolated ? 1U : 0U;
    h.period = period, h.dt = store.model.dt, h.model = std::string(info.name);
    if (!recorder.open(log_path, h)) {
      std::fprintf(stderr, "error: --record: %s\n", recorder.error().c_str());
      return 2;
    }
    sink.recorder = &recorder;
  }
  sink.flush_every = std::max<std::int64_t>(1, std::llround(1.0 / period));

  const bool virtual_clock = clock_name == "virtual";
  ntn::hil::RealTimeState real_time;
  if (!virtual_clock) {
    real_time = ntn::hil::apply_real_time(
        {fifo, o.priority, mlock, cpu, o.timer_slack_ns, o.cpu_latency_us});
    for (const std::string& w : real_time.warnings)
      std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  // The multi-core step's workers, made (and pinned) before the loop, and its partition.
  ntn::hil::WorkerTeam workers({threads, virtual_clock ? -1 : cpu});
  for (const std::string& w : workers.warnings())
    std::fprintf(stderr, "warning: %s\n", w.c_str());
  const ntn::Team team = workers.team();
  const bool with_team = threads > 1 && ntn::prepare_team(store.model, threads, store.team_work);
  const ntn::Team* team_ptr = with_team ? &team : nullptr;
  ntn::hil::FrameTimes times;
  times.reserve(std::min(frames, kTimedFrames));
  // The port is bound only now, after every allocation, mlockall and the scheduler change: a
  // sender that waits for the port (tools/demo, tests/hil) then starts when the loop can take
  // its packets at once.
  if (udp_in || reply_port != 0) {
    const auto st = socket.open(static_cast<std::uint16_t>(std::max(listen_port, 0)));
    if (!st.ok()) {
      std::fprintf(stderr, "error: %s\n", st.message().c_str());
      return 2;
    }
    // The port actually bound (the OS's choice for --listen 0), for the sender: flushed now.
    if (udp_in && (!quiet || listen_port == 0)) {
      std::printf("ntn-hil  listening on 127.0.0.1:%u\n", static_cast<unsigned>(socket.port()));
      std::fflush(stdout);
    }
  }
  ntn::hil::LoopResult result;
  std::uint64_t udp_timeouts = 0;
  std::int64_t first_frame = -1, first_waited_ns = 0;
  const std::int64_t wall0 = ntn::hil::monotonic_ns();
  auto go = [&](auto& clock) {
    if (udp_in) {
      UdpSource source{&socket, &gate, virtual_clock};
      source.period_ns = frame_ns;
      if (!virtual_clock) source.schedule = &schedule;
      source.first_wait_ns = static_cast<std::int64_t>(first_wait_s * 1e9);
      result = ntn::hil::run_loop(store.model, store.state, store.scratch, clock, source, sink,
                                  log_path.empty() ? nullptr : &recorder, config, alarms, times,
                                  &store.checkpoint, team_ptr, &store.team_work, store.buffers);
      udp_timeouts = source.timeouts;
      first_frame = source.first_frame;
      first_waited_ns = source.waited_ns;
    } else {
      ntn::hil::RecordSource source(records, gate, period, store.model.dt);
      result = ntn::hil::run_loop(store.model, store.state, store.scratch, clock, source, sink,
                                  log_path.empty() ? nullptr : &recorder, config, alarms, times,
                                  &store.checkpoint, team_ptr, &store.team_work, store.buffers);
    }
  };
  if (virtual_clock) {
    ntn::hil::VirtualClock clock;
    go(clock);
  } else {
    ntn::hil::RealClock clock;
    go(clock);
  }
  // The wait for the sender's first packet is not part of the run.
  const double wall = static_cast<double>(ntn::hil::monotonic_ns() - wall0 - first_waited_ns) / 1e9;
  if (udp_in && !virtual_clock && first_frame < 0 && !result.stopped) {
    std::fprintf(
        stderr,
        "warning: no plausible input packet within %g s: the loop started on its own clock%s\n",
        first_wait_s,
        schedule.anchored() ? " and followed the sender after a resync" : ", every frame missing");
  }
  // Files are finished whatever happened; a write error (disk full) is an error of the run.
  std::vector<std::string> write_errors;
  if (!log_path.empty() && !recorder.close()) write_errors.push_back(recorder.error());
  if (csv.is_open() && !csv.close()) {
    write_errors.push_back("--out: write error in " + out_path + ": " + csv.error() +
                           " (the CSV is incomplete)");
  }
  const std::uint64_t hash_value = run_hash.finish(store.state);
  const char* stop_signal = ntn::hil::stop_signal_name();

  // ---- summary ----
  const auto& gc = gate.counters();
  const double period_ns = period * 1e9;
  const std::int64_t lat50 = ntn::hil::percentile(times.latency_ns, 50);
  const std::int64_t lat99 = ntn::hil::percentile(times.latency_ns, 99);
  const std::int64_t lat999 = ntn::hil::percentile(times.latency_ns, 99.9);
  const std::int64_t latmax = ntn::hil::percentile(times.latency_ns, 100);
  const std::int64_t cmp50 = ntn::hil::percentile(times.compute_ns, 50);
  const std::int64_t cmp99 = ntn::hil::percentile(times.compute_ns, 99);
  const std::int64_t cmp999 = ntn::hil::percentile(times.compute_ns, 99.9);
  const std::int64_t cmpmax = ntn::hil::percentile(times.compute_ns, 100);
  if (!quiet) {
    std::printf(
        "ntn-hil  %s, %s clock, %lld frames of %g ms x %d substeps (dt %.4g us), %s inputs%s\n",
        std::string(info.name).c_str(), clock_name.c_str(), static_cast<long long>(result.frames),
        period * 1e3, config.substeps, store.model.dt * 1e6, udp_in ? "UDP" : "file",
        sampling == ntn::hil::InputSampling::kStep                ? " per kernel step"
        : sampling == ntn::hil::InputSampling::kFrameInterpolated ? " interpolated"
                                                                  : " held");
    if (!virtual_clock) std::printf("  real time: %s\n", real_time.describe().c_str());
    std::printf("  wall %.3f s for %.3f s simulated (%.1fx real time)\n", wall,
                static_cast<double>(result.frames) * period,
                static_cast<double>(result.frames) * period / wall);
    std::printf("  wake-up latency  p50 %.1f us  p99 %.1f us  p99.9 %.1f us  max %.1f us\n",
                us(lat50), us(lat99), us(lat999), us(latmax));
    std::printf("  compute / period p50 %.3f  p99 %.3f  p99.9 %.3f  max %.3f\n",
                static_cast<double>(cmp50) / period_ns, static_cast<double>(cmp99) / period_ns,
                static_cast<double>(cmp999) / period_ns, static_cast<double>(cmpmax) / period_ns);
    std::printf("  overruns %lld (longest run %lld frames)\n",
                static_cast<long long>(times.overruns),
                static_cast<long long>(times.max_late_frames));
    const auto u = [](std::uint64_t x) { return static_cast<unsigned long long>(x); };
    std::printf(
        "  inputs   accepted %llu, missing %llu (lost %llu), late %llu, early %llu\n"
        "           reordered %llu, duplicate %llu, corrupt %llu, wrong count %llu, too early "
        "%llu\n"
        "           values held: non-finite %llu, out of range %llu\n"
        "           frame out of run %llu, out of window %llu; sender restarts %llu\n",
        u(gc.accepted), u(gc.missing), u(gc.lost()), u(gc.late), u(gc.early), u(gc.reordered),
        u(gc.duplicate), u(gc.corrupt), u(gc.wrong_count), u(gc.too_early), u(gc.nonfinite),
        u(gc.out_of_range), u(gc.out_of_run), u(gc.out_of_window), u(gc.sender_restart));
    for (std::size_t c = 0; c < z.outputs; ++c) {
      const auto& a = alarms[c];
      if (!a.enabled) continue;
      const std::string name(info.output_names[c]);
      if (a.raised == 0) {
        std::printf("  alarm    |%s| > %g, off < %g: not raised\n", name.c_str(), a.limit,
                    a.limit - a.hysteresis);
      } else {
        std::printf(
            "  ALARM    |%s| > %g, off < %g: raised %llu times, %llu frames on, first at %.3f s\n",
            name.c_str(), a.limit, a.limit - a.hysteresis, u(a.raised), u(a.frames_on),
            static_cast<double>(a.first_frame) * period);
      }
    }
    int width = 0;
    for (const std::string_view name : info.output_names)
      width = std::max(width, static_cast<int>(name.size()));
    for (std::size_t c = 0; c < z.outputs; ++c) {
      std::printf("  %s %-*s %11.4g %-5s at %.3f s\n", c == 0 ? "peak |y|" : "        ", width,
                  std::string(info.output_names[c]).c_str(), sink.peak[c],
                  std::string(info.output_units[c]).c_str(),
                  static_cast<double>(sink.peak_frame[c]) * period);
    }
    // The plastic hinge directions that yielded: from the state the run ended in
    // (after a divergence: the last good frame's).
    if (const int np = ntn::hil::plastic_directions(store.model); np > 0) {
      const auto yielded = ntn::hil::yielded_directions(store.model, store.state);
      std::printf("  plastic  %zu of %d plastic hinge directions yielded\n", yielded.size(), np);
      for (const auto& y : yielded) {
        std::printf("    %s %s: peak plastic %.4g, residual %.4g (%s), dissipated %.4g J, %s\n",
                    std::string(info.hinge_names[static_cast<std::size_t>(y.hinge)]).c_str(),
                    ntn::hil::direction_name(y.direction), y.peak, y.residual,
                    y.direction >= 3 ? "rad" : "m", y.dissipated,
                    ntn::hil::level_name(y.level, y.has_limits));
        if (y.first_slip >= 0)  // a rigid-plastic direction's event
          std::printf("      %s at t = %.6g s\n", y.failed ? "failed" : "first slid", y.first_slip);
      }
    }
    if (result.kinetic_limit < std::numeric_limits<double>::infinity()) {
      std::printf(
          "  divergence check: kinetic energy limit %.4g J; peak %.4g J (%.3g of it) at %.3f s\n",
          result.kinetic_limit, result.peak_kinetic, result.peak_kinetic / result.kinetic_limit,
          static_cast<double>(result.peak_kinetic_frame) * period);
    } else {
      std::printf("  divergence check: non-finite state only (the model has no energy bound)\n");
    }
    if (result.diverged_frame >= 0) {
      const long long kd = static_cast<long long>(result.diverged_frame);
      std::printf("  DIVERGED at frame %lld (t = %.3f s, kernel step %lld): %s (%.4g J)\n", kd,
                  static_cast<double>(kd) * period, static_cast<long long>(result.diverged_step),
                  ntn::hil::to_string(result.reason), result.kinetic_at_detection);
      if (kd > 0) {
        std::printf(
            "  SAFE STATE from frame %lld: no more steps; outputs held at frame %lld's values and "
            "flagged diverged (bit 14); state kept at the end of frame %lld\n",
            kd, kd - 1, kd - 1);
      } else {  // no frame was good: there are no good outputs to hold yet
        std::printf(
            "  SAFE STATE from frame 0: no more steps; no frame completed before it, so the "
            "outputs are 0, flagged diverged (bit 14); state kept at the initial state\n");
      }
    }
    if (udp_in && !virtual_clock && first_frame >= 0) {
      std::printf(
          "  deadlines follow the sender from its packet of frame %lld (waited %.3f s): "
          "frame k at packet k + T/2\n",
          static_cast<long long>(first_frame), static_cast<double>(first_waited_ns) / 1e9);
    }
    if (udp_in) std::printf("  UDP on 127.0.0.1:%u\n", static_cast<unsigned>(socket.port()));
    if (schedule.resyncs() > 0) {
      std::printf(
          "  resync   %llu (deadlines re-anchored to the sender's stream), last at frame %lld\n",
          u(schedule.resyncs()), static_cast<long long>(schedule.last_resync_frame()));
    }
    if (udp_timeouts > 0)
      std::printf("  %llu frames timed out waiting for the sender\n",
                  static_cast<unsigned long long>(udp_timeouts));
  }
  if (result.stopped) {
    std::printf(
        "  STOPPED by %s after %lld of %lld frames (t = %.3f s): the CSV, the log and the "
        "summary hold frames 0..%lld\n",
        stop_signal, static_cast<long long>(result.frames), static_cast<long long>(frames),
        static_cast<double>(result.frames) * period, static_cast<long long>(result.frames - 1));
    std::fprintf(stderr, "stopped by %s after %lld frames\n", stop_signal,
                 static_cast<long long>(result.frames));
  }
  std::printf("  output hash %016llx\n", static_cast<unsigned long long>(hash_value));
  if (!json_path.empty()) {
    std::ofstream js(json_path);
    js << "{\n  \"model\": \"" << info.name << "\",\n  \"clock\": \"" << clock_name
       << "\",\n  \"sampling\": \"" << ntn::hil::to_string(sampling)
       << "\",\n  \"frames\": " << result.frames << ",\n  \"frames_requested\": " << frames
       << ",\n  \"stopped_by\": "
       << (result.stopped ? "\"" + std::string(stop_signal) + "\"" : std::string("null"))
       << ",\n  \"real_time\": "
       << (virtual_clock
               ? std::string("null")
               : "{\"fifo\": " + std::string(real_time.fifo ? "true" : "false") +
                     ", \"priority\": " + std::to_string(real_time.priority) +
                     ", \"memory_locked\": " + (real_time.memory_locked ? "true" : "false") +
                     ", \"timer_slack_ns\": " + std::to_string(real_time.timer_slack_ns) +
                     ", \"cpu_latency_us\": " + std::to_string(real_time.cpu_latency_us) +
                     ", \"cpu\": " + std::to_string(real_time.cpu) + "}")
       << ",\n  \"period_s\": " << period << ",\n  \"substeps\": " << config.substeps
       << ",\n  \"overruns\": " << times.overruns << ",\n  \"latency_us\": {\"p50\": " << us(lat50)
       << ", \"p99\": " << us(lat99) << ", \"p99.9\": " << us(lat999) << ", \"max\": " << us(latmax)
       << "}"
       << ",\n  \"compute_fraction\": {\"p50\": " << static_cast<double>(cmp50) / period_ns
       << ", \"p99\": " << static_cast<double>(cmp99) / period_ns
       << ", \"p99.9\": " << static_cast<double>(cmp999) / period_ns
       << ", \"max\": " << static_cast<double>(cmpmax) / period_ns << "}"
       << ",\n  \"inputs\": {\"accepted\": " << gc.accepted << ", \"missing\": " << gc.missing
       << ", \"lost\": " << gc.lost() << ", \"late\": " << gc.late
       << ", \"duplicate\": " << gc.duplicate << ", \"reordered\": " << gc.reordered
       << ", \"early\": " << gc.early << ", \"too_early\": " << gc.too_early
       << ", \"corrupt\": " << gc.corrupt << ", \"wrong_count\": " << gc.wrong_count
       << ", \"nonfinite\": " << gc.nonfinite << ", \"out_of_range\": " << gc.out_of_range
       << ", \"out_of_run\": " << gc.out_of_run << ", \"out_of_window\": " << gc.out_of_window
       << ", \"sender_restart\": " << gc.sender_restart << "}"
       << ",\n  \"resync\": " << schedule.resyncs()
       << ",\n  \"listen_port\": " << (udp_in ? static_cast<int>(socket.port()) : -1)
       << ",\n  \"first_packet_frame\": " << first_frame << ",\n  \"alarms\": [";
    bool first_alarm = true;
    for (std::size_t c = 0; c < z.outputs; ++c) {
      const auto& a = alarms[c];
      if (!a.enabled) continue;
      js << (first_alarm ? "" : ",") << "\n    {\"channel\": \"" << info.output_names[c]
         << "\", \"limit\": " << a.limit << ", \"hysteresis\": " << a.hysteresis
         << ", \"raised\": " << a.raised << ", \"frames_on\": " << a.frames_on
         << ", \"first_frame\": " << a.first_frame << "}";
      first_alarm = false;
    }
    js << "],\n  \"peaks\": {";
    for (std::size_t c = 0; c < z.outputs; ++c) {
      js << (c == 0 ? "" : ", ") << "\"" << info.output_names[c] << "\": " << sink.peak[c];
    }
    const auto number = [](double x) {
      if (!(x - x == 0)) return std::string("null");  // JSON has no Inf / NaN
      char text[32];
      std::snprintf(text, sizeof text, "%.17g", x);
      return std::string(text);
    };
    js << "}"
       << ",\n  \"divergence\": {\"kinetic_limit_J\": " << number(result.kinetic_limit)
       << ", \"peak_kinetic_J\": " << number(result.peak_kinetic)
       << ", \"peak_kinetic_frame\": " << result.peak_kinetic_frame
       << ", \"diverged_frame\": " << result.diverged_frame << ", \"reason\": \""
       << ntn::hil::to_string(result.reason) << "\""
       << ", \"step\": " << result.diverged_step
       << ", \"kinetic_at_detection_J\": " << number(result.kinetic_at_detection)
       << ", \"safe_state\": " << (result.diverged_frame >= 0 ? "true" : "false")
       << ", \"last_good_frame\": "
       << (result.diverged_frame >= 0 ? result.diverged_frame - 1 : result.frames - 1)
       << ", \"state_restored\": " << (result.state_restored ? "true" : "false") << "}"
       << ",\n  \"diverged_frame\": " << result.diverged_frame << ",\n  \"output_hash\": \""
       << std::hex << hash_value << std::dec << "\"\n}\n";
    if (auto e = ntn::cli::close_output(js, "--summary-json", json_path))
      write_errors.push_back(*e);
  }
  for (const std::string& e : write_errors)
    std::fprintf(stderr, "error: %s\n", e.c_str());
  // Exit codes (README "Exit codes"): 2 a file could not be written, 3 diverged, 4 stopped by
  // SIGINT / SIGTERM, 0 otherwise.
  if (!write_errors.empty()) return 2;
  if (result.diverged_frame >= 0) return 3;
  return result.stopped ? 4 : 0;
}

}  // namespace ntn::hil::program
