// ntn-hil-<model>: the model in the fixed-rate frame loop (DESIGN §8). Inputs from recorded
// files or from UDP on loopback through the input gate; outputs to CSV and back over UDP;
// real-time or virtual clock; a log for bit-exact replay; a summary on screen and as JSON.
#include <xxhash.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "ntn/hil/clock.hpp"
#include "ntn/hil/gate.hpp"
#include "ntn/hil/loop.hpp"
#include "ntn/hil/packet.hpp"
#include "ntn/hil/recorder.hpp"
#include "ntn/hil/schedule.hpp"
#include "ntn/hil/udp.hpp"
#include "ntn/kernel.hpp"
#include "record.hpp"
#include NTN_MODEL_HEADER

namespace {

namespace mdl = NTN_MODEL_NS;
constexpr ntn::Sizes kS = mdl::kSizes;
using Inputs = std::array<double, kS.inputs>;

ntn::Model<kS> g_model;
ntn::State<kS> g_state;
ntn::Scratch<kS> g_scratch;
ntn::State<kS> g_checkpoint;  // the end of the last good frame (the loop's safe state)

// Recorded inputs (AT2, CSV), sampled at frame times, through the gate (NaN, range).
struct FileSource {
  std::array<ntn::io::Record, kS.inputs>* records;
  ntn::hil::InputGate* gate;
  double period;
  void frame_inputs(std::int64_t k, std::span<double> v, std::uint16_t& flags) {
    Inputs x{};
    for (std::size_t c = 0; c < x.size(); ++c)
      x[c] = (*records)[c].at(static_cast<double>(k) * period);
    gate->begin_frame(k);
    (void)gate->accept_values(k, x);
    gate->end_frame(v, flags);
  }
};

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
    for (std::int64_t left = first_wait_ns; left > 0;
         left = start + first_wait_ns - ntn::hil::monotonic_ns()) {
      if (socket->wait_readable(std::chrono::nanoseconds(left)) != ntn::hil::WaitStatus::kReadable)
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
    while (lock_step && !ended) {
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

// Inputs from a log, as they were accepted.
struct ReplaySource {
  const ntn::hil::Log* log;
  void frame_inputs(std::int64_t k, std::span<double> v, std::uint16_t& flags) {
    const ntn::hil::LogFrame& f = log->frames[static_cast<std::size_t>(k)];
    std::copy(f.inputs.begin(), f.inputs.end(), v.begin());
    flags = static_cast<std::uint16_t>(f.input_flags);
  }
};

// CSV rows into a buffer reserved before the run; output packets back to the sender.
struct Sink {
  std::string* csv = nullptr;
  ntn::hil::UdpSocket* socket = nullptr;
  std::uint16_t reply_port = 0;
  std::uint32_t sequence = 0;
  double period = 1e-3;
  std::array<std::byte, ntn::hil::kMaxPacketBytes> packet{};
  std::vector<std::uint64_t>* hashes = nullptr;       // per-frame output hash (replay compares)
  std::array<double, kS.outputs> peak{};              // largest |value| per channel
  std::array<std::int64_t, kS.outputs> peak_frame{};  // and its first frame
  void frame_outputs(std::int64_t k, std::span<const double> v, std::uint16_t flags) {
    for (std::size_t c = 0; c < peak.size(); ++c) {
      if (std::abs(v[c]) > peak[c]) peak[c] = std::abs(v[c]), peak_frame[c] = k;
    }
    if (csv != nullptr) {
      char row[64];
      std::snprintf(row, sizeof row, "%.9g", static_cast<double>(k) * period);
      csv->append(row);
      for (double x : v) {
        std::snprintf(row, sizeof row, ",%.17g", x);
        csv->append(row);
      }
      std::snprintf(row, sizeof row, ",%u\n", static_cast<unsigned>(flags));
      csv->append(row);
    }
    if (socket != nullptr && reply_port != 0) {
      const std::size_t n =
          ntn::hil::encode(ntn::hil::PacketKind::kOutput, sequence++, k, flags, v, packet);
      (void)socket->send_to(reply_port, std::span<const std::byte>(packet.data(), n));
    }
    if (hashes != nullptr && hashes->size() < hashes->capacity())
      hashes->push_back(ntn::hil::hash_outputs(v));
  }
};

// "NAME=LIMIT[:HYSTERESIS]" or "NAME=off" for one output channel, as the model file's alarm
// keys: 0 < LIMIT finite, 0 <= HYSTERESIS < LIMIT. "" on success, else what is wrong.
std::string parse_alarm(const std::string& arg, std::vector<ntn::hil::Alarm>& alarms) {
  const auto eq = arg.find('=');
  const std::string name = arg.substr(0, eq);
  std::size_t c = 0;
  while (c < kS.outputs && mdl::kOutputNames[c] != name)
    ++c;
  if (eq == std::string::npos) return "want OUTPUT=LIMIT[:HYSTERESIS] or OUTPUT=off";
  if (c == kS.outputs) return "the model has no output '" + name + "'";
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

double us(std::int64_t ns) {
  return static_cast<double>(ns) / 1e3;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Run the model '" + std::string(mdl::kName) + "' in the real-time frame loop"};
  app.require_subcommand(1);
  auto* run = app.add_subcommand("run", "run the loop");
  auto* replay = app.add_subcommand("replay", "re-run a log on the virtual clock and compare");

  std::vector<std::string> input_args, alarm_args;
  std::string clock_name = "real", out_path, json_path, log_path, replay_path;
  double duration = -1, first_wait_s = 10;
  std::int64_t frames = -1;
  int listen_port = -1, reply_port = 0, cpu = -1;
  bool interpolate = false, fifo = false, mlock = false, quiet = false;
  run->add_option("-i,--input", input_args, "NAME=FILE: feed an input from a record (AT2, CSV)");
  run->add_option("--listen", listen_port, "take inputs as UDP packets on 127.0.0.1:PORT")
      ->check(CLI::Range(0, 65535));
  run->add_option("--reply", reply_port, "send output packets to 127.0.0.1:PORT")
      ->check(CLI::Range(1, 65535));
  run->add_option("--clock", clock_name,
                  "real (absolute deadlines) or virtual (as fast as "
                  "possible; lock-step with UDP)")
      ->check(CLI::IsMember({"real", "virtual"}));
  run->add_option("--wait-first", first_wait_s,
                  "real time with --listen: seconds to wait for the sender's first packet, which "
                  "fixes the frame deadlines (default 10)")
      ->check(CLI::PositiveNumber);
  run->add_option("-t,--duration", duration, "seconds to run (default: the longest record)");
  run->add_option("-n,--frames", frames, "frames to run (overrides --duration)");
  run->add_flag("--interpolate", interpolate,
                "interpolate inputs linearly within a frame (one frame of delay); default: hold");
  run->add_option("--alarm", alarm_args,
                  "NAME=LIMIT[:HYSTERESIS] or NAME=off: limit alarm on an output, replacing the "
                  "model file's for that channel");
  run->add_option("-o,--out", out_path, "CSV of the outputs, one row per frame, with flags");
  run->add_option("--record", log_path, "binary log of accepted inputs and outputs (replay)");
  run->add_option("--summary-json", json_path, "write the summary as JSON");
  run->add_flag("--fifo", fifo, "SCHED_FIFO (falls back with a warning)");
  run->add_flag("--mlock", mlock, "mlockall (falls back with a warning)");
  run->add_option("--cpu", cpu, "pin to this CPU (falls back with a warning)");
  run->add_flag("-q,--quiet", quiet, "print only warnings, errors and the output hash");
  replay->add_option("log", replay_path, "log written by run --record")->required();
  CLI11_PARSE(app, argc, argv);

  if (const ntn::InitStatus st = ntn::init(mdl::kSpec, g_model); !st.ok()) {
    std::fprintf(stderr, "error: model '%s': %s (at %d)\n", std::string(mdl::kName).c_str(),
                 ntn::to_string(st.error), st.where);
    return 1;
  }
  const double period = mdl::kSpec.settings.frame_period;
  ntn::hil::LoopConfig config;
  config.period = period;
  // The kernel's frame rule, the one the model compiler checked (ntn::frame_substeps).
  const ntn::Substeps substeps = ntn::frame_substeps(g_model.dt, period);
  if (!substeps.ok()) {
    std::fprintf(stderr, "error: model '%s': dt = %g s, frame period %g s: %s\n",
                 std::string(mdl::kName).c_str(), g_model.dt, period,
                 ntn::to_string(substeps.error));
    return 1;
  }
  config.substeps = static_cast<int>(substeps.count);

  // ---- replay ----
  if (replay->parsed()) {
    std::string error;
    const auto log = ntn::hil::read_log(replay_path, error);
    if (!log) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return 2;
    }
    if (log->header.inputs != kS.inputs || log->header.outputs != kS.outputs ||
        log->header.model != mdl::kName ||
        log->header.substeps != static_cast<unsigned>(config.substeps)) {
      std::fprintf(stderr,
                   "error: %s was recorded with another model or step (%s, %u inputs, %u outputs, "
                   "%u substeps)\n",
                   replay_path.c_str(), log->header.model.c_str(), log->header.inputs,
                   log->header.outputs, log->header.substeps);
      return 2;
    }
    config.frames = static_cast<std::int64_t>(log->frames.size());
    config.interpolate = log->header.interpolate != 0;
    ReplaySource source{&*log};
    std::vector<std::uint64_t> hashes;
    hashes.reserve(log->frames.size());
    Sink sink;
    sink.hashes = &hashes;
    ntn::hil::VirtualClock clock;
    ntn::hil::FrameTimes times;
    std::vector<ntn::hil::Alarm> no_alarms;
    // Outputs of each frame are compared value by value: keep them from the sink's hash and
    // re-derive the first differing channel by running again only when a hash differs.
    (void)ntn::hil::run_loop(g_model, g_state, g_scratch, clock, source, sink, nullptr, config,
                             no_alarms, times);
    for (std::size_t k = 0; k < hashes.size(); ++k) {
      if (hashes[k] == log->frames[k].hash) continue;
      // Find the channel: re-run up to frame k and compare the outputs.
      ntn::hil::LoopConfig upto = config;
      upto.frames = static_cast<std::int64_t>(k) + 1;
      struct Capture {
        std::array<double, kS.outputs> last{};
        void frame_outputs(std::int64_t, std::span<const double> v, std::uint16_t) {
          std::copy(v.begin(), v.end(), last.begin());
        }
      } capture;
      g_state = {};
      (void)ntn::hil::run_loop(g_model, g_state, g_scratch, clock, source, capture, nullptr, upto,
                               no_alarms, times);
      std::size_t channel = 0;
      for (; channel < capture.last.size(); ++channel) {
        if (std::memcmp(&capture.last[channel], &log->frames[k].outputs[channel], sizeof(double)) !=
            0)
          break;
      }
      const std::string name = channel < kS.outputs ? std::string(mdl::kOutputNames[channel]) : "?";
      std::printf(
          "replay: DIFFERS at frame %zu (t = %.6f s), channel %s: recorded %.17g, now %.17g\n", k,
          static_cast<double>(k) * period, name.c_str(),
          channel < kS.outputs ? log->frames[k].outputs[channel] : 0.0,
          channel < kS.outputs ? capture.last[channel] : 0.0);
      return 1;
    }
    std::printf("replay: bit-identical over %zu frames\n", hashes.size());
    return 0;
  }

  // ---- run ----
  std::array<ntn::io::Record, kS.inputs> records{};
  double record_duration = 0;
  for (const std::string& arg : input_args) {
    const auto eq = arg.find('=');
    if (eq == std::string::npos) {
      std::fprintf(stderr, "error: --input wants NAME=FILE, got '%s'\n", arg.c_str());
      return 2;
    }
    const std::string name = arg.substr(0, eq), file = arg.substr(eq + 1);
    int index = -1;
    for (int k = 0; k < kS.inputs; ++k)
      if (mdl::kInputNames[static_cast<std::size_t>(k)] == name) index = k;
    if (index < 0) {
      std::fprintf(stderr, "error: the model has no input channel '%s'\n", name.c_str());
      return 2;
    }
    ntn::io::ReadResult r = ntn::io::read_record(file);
    if (r.error) {
      std::fprintf(stderr, "%s\n", r.error->format().c_str());
      return 2;
    }
    // The record's values in the input's unit (gal to g, ...): the runner's rule (tools/io).
    const ntn::InputSpec& spec = mdl::kSpec.inputs[static_cast<std::size_t>(index)];
    if (const auto e = r.record->to_unit(ntn::io::input_unit(
            spec.kind == ntn::InputKind::kGroundAcceleration, spec.dof, spec.scale))) {
      std::fprintf(stderr, "%s: error: input '%s': %s\n", file.c_str(), name.c_str(), e->c_str());
      return 2;
    }
    record_duration = std::max(record_duration, r.record->duration());
    records[static_cast<std::size_t>(index)] = std::move(*r.record);
  }
  const bool udp_in = listen_port >= 0;
  if (!udp_in && input_args.size() != static_cast<std::size_t>(kS.inputs) && kS.inputs > 0) {
    std::fprintf(stderr,
                 "error: give --input NAME=FILE for every input channel, or --listen PORT\n");
    return 2;
  }
  if (frames < 0) {
    if (duration < 0) duration = record_duration;
    frames = static_cast<std::int64_t>(std::ceil(duration / period - 1e-9));
  }
  if (frames <= 0) {
    std::fprintf(stderr, "error: give --frames or --duration\n");
    return 2;
  }
  config.frames = frames;
  config.interpolate = interpolate;

  // Alarms: the model file's ([[outputs]] alarm, alarm_hysteresis), then --alarm per channel.
  std::vector<ntn::hil::Alarm> alarms(kS.outputs);
  for (std::size_t c = 0; c < alarms.size(); ++c) {
    alarms[c].enabled = mdl::kAlarmLimits[c] > 0;
    alarms[c].limit = mdl::kAlarmLimits[c];
    alarms[c].hysteresis = mdl::kAlarmHysteresis[c];
  }
  for (const std::string& arg : alarm_args) {
    if (const std::string e = parse_alarm(arg, alarms); !e.empty()) {
      std::fprintf(stderr, "error: --alarm %s: %s\n", arg.c_str(), e.c_str());
      return 2;
    }
  }

  ntn::hil::InputGate gate(std::span<const ntn::InputSpec>(mdl::kSpec.inputs));
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
  std::string csv;
  if (!out_path.empty()) {
    csv.reserve(static_cast<std::size_t>(frames + 2) * (kS.outputs + 2) * 24);
    csv += "time[s]";
    for (int c = 0; c < kS.outputs; ++c) {
      csv += "," + std::string(mdl::kOutputNames[static_cast<std::size_t>(c)]) + "[" +
             std::string(mdl::kOutputUnits[static_cast<std::size_t>(c)]) + "]";
    }
    csv += ",flags\n";
  }
  std::vector<std::uint64_t> hashes;
  hashes.reserve(static_cast<std::size_t>(frames));
  Sink sink;
  sink.csv = out_path.empty() ? nullptr : &csv;
  sink.socket = reply_port != 0 ? &socket : nullptr;
  sink.reply_port = static_cast<std::uint16_t>(reply_port);
  sink.period = period;
  sink.hashes = &hashes;

  ntn::hil::Recorder recorder;
  if (!log_path.empty()) {
    ntn::hil::LogHeader h;
    h.inputs = kS.inputs, h.outputs = kS.outputs;
    h.substeps = static_cast<std::uint32_t>(config.substeps);
    h.interpolate = interpolate ? 1U : 0U;
    h.period = period, h.dt = g_model.dt, h.model = std::string(mdl::kName);
    if (!recorder.open(log_path, h)) {
      std::fprintf(stderr, "error: %s\n", recorder.error().c_str());
      return 2;
    }
  }

  const bool virtual_clock = clock_name == "virtual";
  if (!virtual_clock) {
    for (const std::string& w : ntn::hil::apply_real_time({fifo, 80, mlock, cpu}))
      std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  ntn::hil::FrameTimes times;
  times.reserve(frames);
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
      result = ntn::hil::run_loop(g_model, g_state, g_scratch, clock, source, sink,
                                  log_path.empty() ? nullptr : &recorder, config, alarms, times,
                                  &g_checkpoint);
      udp_timeouts = source.timeouts;
      first_frame = source.first_frame;
      first_waited_ns = source.waited_ns;
    } else {
      FileSource source{&records, &gate, period};
      result = ntn::hil::run_loop(g_model, g_state, g_scratch, clock, source, sink,
                                  log_path.empty() ? nullptr : &recorder, config, alarms, times,
                                  &g_checkpoint);
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
  if (udp_in && !virtual_clock && first_frame < 0) {
    std::fprintf(
        stderr,
        "warning: no plausible input packet within %g s: the loop started on its own clock%s\n",
        first_wait_s,
        schedule.anchored() ? " and followed the sender after a resync" : ", every frame missing");
  }
  if (!log_path.empty() && !recorder.close()) {
    std::fprintf(stderr, "error: %s\n", recorder.error().c_str());
    return 1;
  }
  if (!out_path.empty()) {
    const std::filesystem::path p(out_path);
    if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
    std::ofstream(out_path, std::ios::binary) << csv;
  }
  const std::uint64_t run_hash = XXH3_64bits(hashes.data(), hashes.size() * sizeof(std::uint64_t));

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
        std::string(mdl::kName).c_str(), clock_name.c_str(), static_cast<long long>(result.frames),
        period * 1e3, config.substeps, g_model.dt * 1e6, udp_in ? "UDP" : "file",
        interpolate ? " interpolated" : " held");
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
    for (std::size_t c = 0; c < kS.outputs; ++c) {
      const auto& a = alarms[c];
      if (!a.enabled) continue;
      const std::string name(mdl::kOutputNames[c]);
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
    for (const std::string_view name : mdl::kOutputNames)
      width = std::max(width, static_cast<int>(name.size()));
    for (std::size_t c = 0; c < kS.outputs; ++c) {
      std::printf("  %s %-*s %11.4g %-5s at %.3f s\n", c == 0 ? "peak |y|" : "        ", width,
                  std::string(mdl::kOutputNames[c]).c_str(), sink.peak[c],
                  std::string(mdl::kOutputUnits[c]).c_str(),
                  static_cast<double>(sink.peak_frame[c]) * period);
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
      std::printf(
          "  SAFE STATE from frame %lld: no more steps; outputs held at frame %lld's values and "
          "flagged diverged (bit 14); state kept at the end of frame %lld\n",
          kd, kd - 1, kd - 1);
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
  std::printf("  output hash %016llx\n", static_cast<unsigned long long>(run_hash));
  if (!json_path.empty()) {
    std::ofstream js(json_path);
    js << "{\n  \"model\": \"" << mdl::kName << "\",\n  \"clock\": \"" << clock_name
       << "\",\n  \"frames\": " << result.frames << ",\n  \"period_s\": " << period
       << ",\n  \"substeps\": " << config.substeps << ",\n  \"overruns\": " << times.overruns
       << ",\n  \"latency_us\": {\"p50\": " << us(lat50) << ", \"p99\": " << us(lat99)
       << ", \"p99.9\": " << us(lat999) << ", \"max\": " << us(latmax) << "}"
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
    for (std::size_t c = 0; c < kS.outputs; ++c) {
      const auto& a = alarms[c];
      if (!a.enabled) continue;
      js << (first_alarm ? "" : ",") << "\n    {\"channel\": \"" << mdl::kOutputNames[c]
         << "\", \"limit\": " << a.limit << ", \"hysteresis\": " << a.hysteresis
         << ", \"raised\": " << a.raised << ", \"frames_on\": " << a.frames_on
         << ", \"first_frame\": " << a.first_frame << "}";
      first_alarm = false;
    }
    js << "],\n  \"peaks\": {";
    for (std::size_t c = 0; c < kS.outputs; ++c) {
      js << (c == 0 ? "" : ", ") << "\"" << mdl::kOutputNames[c] << "\": " << sink.peak[c];
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
       << std::hex << run_hash << std::dec << "\"\n}\n";
  }
  return result.diverged_frame >= 0 ? 3 : 0;
}
