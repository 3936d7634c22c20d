// ntn-feeder: streams recorded inputs as UDP input packets to 127.0.0.1:PORT at a fixed frame
// rate, as a controller or DAQ would, reads the loop's output packets back and writes them as
// CSV. Optionally injects faults (see ntn/hil/faults.hpp) and prints what it injected.
//
// Real time: frame k is sent at t0 + k * period (clock_nanosleep, TIMER_ABSTIME,
// CLOCK_MONOTONIC). --virtual: no sleeping; after frame k's packets a frame-end marker, then wait
// for the loop's output of frame k before frame k+1 (lock-step, deterministic).
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "cli.hpp"
#include "ntn/hil/clock.hpp"
#include "ntn/hil/faults.hpp"
#include "ntn/hil/packet.hpp"
#include "ntn/hil/udp.hpp"
#include "record.hpp"

namespace {

using namespace ntn::hil;

constexpr std::int64_t kNsPerS = 1'000'000'000;

// What the feeder keeps per frame is bounded: at most kMaxFrames frames (2.8 h at 1 kHz; ~12
// bytes a frame: the fault plan, the output flags, the wake-up latency), and with --out, which
// keeps every output value for the CSV, at most kMaxCsvFrames (1 GiB at 64 channels).
constexpr std::int64_t kMaxFrames = 10'000'000;
constexpr std::int64_t kMaxCsvFrames = 2'000'000;

std::int64_t now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * kNsPerS + ts.tv_nsec;
}

void sleep_until_ns(std::int64_t t) {
  const timespec ts{static_cast<time_t>(t / kNsPerS), static_cast<long>(t % kNsPerS)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

struct Channel {
  std::string name;
  ntn::io::Record record;
};

// What came back from the loop, per frame.
struct Outputs {
  std::int64_t frames = 0;
  bool keep_values = false;    // for the CSV (--out)
  int count = -1;              // channels of the first output packet
  std::vector<double> values;  // frames x count, when keep_values
  std::vector<std::uint16_t> flags;
  std::vector<bool> have;
  std::int64_t received = 0, distinct = 0, undecodable = 0, wrong_count = 0, outside = 0;
  std::int64_t highest = -1;  // highest frame received

  void take(std::span<const std::byte> bytes) {
    Packet p;
    if (decode(bytes, p, PacketKind::kOutput) != DecodeError::kOk) {
      ++undecodable;
      return;
    }
    ++received;
    if (p.frame < 0 || p.frame >= frames) {
      ++outside;
      return;
    }
    if (count < 0) {
      count = p.count;
      if (keep_values) values.assign(static_cast<std::size_t>(frames) * p.count, 0.0);
      flags.assign(static_cast<std::size_t>(frames), 0);
      have.assign(static_cast<std::size_t>(frames), false);
    }
    if (p.count != count) {
      ++wrong_count;
      return;
    }
    const auto k = static_cast<std::size_t>(p.frame);
    if (!have[k]) ++distinct;
    have[k] = true;
    flags[k] = p.flags;
    if (keep_values)
      std::copy_n(p.values.begin(), count, values.begin() + static_cast<std::ptrdiff_t>(k) * count);
    highest = std::max(highest, p.frame);
  }
};

struct Percentiles {
  double p50 = 0, p99 = 0, max = 0;  // us
};

Percentiles percentiles(std::vector<std::int64_t> ns) {
  Percentiles r;
  if (ns.empty()) return r;
  std::sort(ns.begin(), ns.end());
  auto at = [&ns](double q) {
    const auto i = static_cast<std::size_t>(q * static_cast<double>(ns.size() - 1) + 0.5);
    return static_cast<double>(ns[i]) * 1e-3;
  };
  r.p50 = at(0.5), r.p99 = at(0.99), r.max = at(1.0);
  return r;
}

constexpr std::array<const char*, 16> kFlagNames{
    "held",      "missing", "nonfinite", "out_of_range", "corrupt",   "wrong_count",
    "duplicate", "late",    "early",     "reordered",    "too_early", "resync",
    "alarm",     "overrun", "diverged",  "bad_frame"};

// The command line.
struct FeederOptions {
  int port = 0, listen_port = 0;
  std::vector<std::string> input_args;
  std::string record_arg;
  bool record_given = false;  // --record, even empty
  double scale = 1.0, rate = 1000.0, range_value = 1e308, timeout_s = 10.0, linger_ms = 200;
  std::int64_t frames = -1;
  bool lockstep = false, quiet = false;
  std::vector<std::string> fault_lists, fault_rates;
  std::uint64_t seed = 1;
  std::string out_path, json_path;
  bool out_given = false, json_given = false;
  ntn::hil::RealTimeOptions rt;  // parse_options: one priority below the loop's
  bool no_fifo = false;
};

// The exit code when the program ends at its command line (--help: 0, a usage error: 2).
std::optional<int> parse_options(int argc, char** argv, FeederOptions& o) {
  ntn::cli::App app{
      "Stream recorded inputs over UDP to the real-time loop and read its outputs back"};
  app.add_option("-p,--port", o.port, "the loop's input port on 127.0.0.1")
      ->required()
      ->check(ntn::cli::Integer(1, 65535));
  app.add_option("--listen-port", o.listen_port,
                 "own port for sending and for the loop's outputs (0: any free port)")
      ->check(ntn::cli::Integer(0, 65535));
  app.add_option("-i,--input", o.input_args,
                 "NAME=FILE[:COLUMN][*FACTOR]: one input channel from a record (AT2 or CSV), "
                 "its values times FACTOR; channels are numbered in the order given");
  app.add_option("-r,--record", o.record_arg, "FILE[:COLUMN][*FACTOR]: a single input channel");
  app.add_option("--scale", o.scale, "multiply every record value by this")
      ->check(ntn::cli::Finite());
  app.add_option("--rate", o.rate, "frame rate in Hz, in [0.01, 1e6]")
      ->check(ntn::cli::Number(0.01, 1e6));
  app.add_option("-n,--frames", o.frames, "frames to send (default: the longest record)")
      ->check(ntn::cli::Integer(1, kMaxFrames));
  app.add_flag("--virtual", o.lockstep,
               "no sleeping: send frame k, a frame-end marker, then wait for the output of k");
  app.add_option("--fault", o.fault_lists, "KIND@FRAME[,KIND@FRAME...]: inject a fault at a frame");
  app.add_option("--fault-rate", o.fault_rates, "KIND=P: inject a fault kind with probability P");
  app.add_option("--seed", o.seed, "seed of the fault draws and corrupted bytes")
      ->check(ntn::cli::Integer(0, std::numeric_limits<std::int64_t>::max()));
  app.add_option("--range-value", o.range_value, "the value a 'range' fault sends")
      ->check(ntn::cli::Finite());
  app.add_option("--timeout", o.timeout_s,
                 "lock-step: seconds to wait for an output (at most 3600)")
      ->check(ntn::cli::Positive(3600));
  app.add_option("--linger", o.linger_ms,
                 "real time: ms to wait for outputs after the last frame (at most 3.6e6)")
      ->check(ntn::cli::NonNegative(3.6e6));
  app.add_option("-o,--out", o.out_path, "CSV of the outputs received: time, channels, flags");
  app.add_option("--summary-json", o.json_path, "also write the summary as JSON");
  app.add_flag("-q,--quiet", o.quiet, "print only the fault line and errors");
  // Real time asks for what a real-time sender needs by default (ntn::hil::RealTimeOptions),
  // one priority below the loop's 80.
  ntn::hil::RealTimeOptions& rt = o.rt;
  rt.priority = 70;
  app.add_option("--fifo", rt.priority,
                 "real time: the SCHED_FIFO priority (default 70; 0: normal scheduling; falls "
                 "back with a warning where not permitted)")
      ->check(ntn::cli::Integer(0, 99));
  app.add_flag("--no-fifo", o.no_fifo, "real time: normal scheduling (the same as --fifo 0)");
  app.add_flag("--mlock,!--no-mlock", rt.lock_memory,
               "real time: mlockall, every page locked (the default; falls back with a warning)");
  app.add_option("--cpu-latency", rt.cpu_latency_us,
                 "real time: the CPU wake-up latency to hold in us (PM QoS, "
                 "/dev/cpu_dma_latency; default 0; -1: leave it)")
      ->check(ntn::cli::Integer(-1, 10'000'000));
  app.add_option("--timer-slack", rt.timer_slack_ns,
                 "real time: the thread's timer slack in ns (default 1; 0: the system's default, "
                 "50 us on Linux)")
      ->check(ntn::cli::Integer(0, 1'000'000'000));
  if (const auto code = ntn::cli::parse(app, argc, argv)) return code;
  o.record_given = app.count("--record") > 0;
  o.out_given = app.count("--out") > 0;
  o.json_given = app.count("--summary-json") > 0;
  return std::nullopt;
}

// Output files first: an unwritable path ends here, not after the run.
std::optional<int> check_output_paths(const FeederOptions& o) {
  for (const auto& [path, option, given] :
       {std::tuple{&o.out_path, "--out", o.out_given},
        std::tuple{&o.json_path, "--summary-json", o.json_given}}) {
    if (!given) continue;
    // --out creates its directory, as the runners do; the other files' must exist.
    if (const auto problem =
            ntn::cli::output_path_problem(*path, option, std::string_view(option) == "--out")) {
      std::fprintf(stderr, "error: %s\n", problem->c_str());
      return 2;
    }
  }
  return std::nullopt;
}

// Channels: --record FILE[:COLUMN] first, then each --input NAME=FILE[:COLUMN].
std::optional<int> read_channels(const FeederOptions& o, std::vector<Channel>& channels) {
  if (o.record_given && o.record_arg.empty()) {
    std::fprintf(stderr, "error: --record wants FILE[:COLUMN], got ''\n");
    return 2;
  }
  std::vector<std::string> raw = o.input_args;
  if (o.record_given) raw.insert(raw.begin(), "record=" + o.record_arg);
  const ntn::cli::InputArgs parsed =
      ntn::cli::parse_input_args(raw, o.record_given ? "--record/--input" : "--input");
  if (parsed.error) {
    std::fprintf(stderr, "error: %s\n", parsed.error->c_str());
    return 2;
  }
  const std::vector<ntn::cli::InputArg>& args = parsed.args;
  if (args.empty()) {
    std::fprintf(stderr, "error: give --record FILE or --input NAME=FILE\n");
    return 2;
  }
  if (args.size() > static_cast<std::size_t>(kMaxChannels)) {
    std::fprintf(stderr, "error: %zu channels (--record, --input): at most %d\n", args.size(),
                 kMaxChannels);
    return 2;
  }
  for (const ntn::cli::InputArg& arg : args) {
    ntn::io::ReadResult r = ntn::io::read_record(arg.file, arg.column);
    if (r.error) {
      std::fprintf(stderr, "%s\n", r.error->format().c_str());
      return 2;
    }
    r.record->scale(arg.factor);  // as the loop scales a record it reads (load_input_record)
    channels.push_back({arg.name, std::move(*r.record)});
  }
  return std::nullopt;
}

// The frames to send: --frames, else the longest record, compared as a number before the
// conversion; bounded by what --out keeps.
std::optional<int> count_frames(const std::vector<Channel>& channels, double period,
                                FeederOptions& o) {
  if (o.frames < 0) {
    double longest = 0;
    for (const Channel& c : channels)
      longest = std::max(longest, c.record.duration());
    const double n = std::ceil(longest / period - 1e-9);
    if (!(n >= 1) || n > static_cast<double>(kMaxFrames)) {
      std::fprintf(stderr,
                   "error: the longest record (%s s at --rate %s Hz) gives %s frames; a run has 1 "
                   "to %lld: give --frames\n",
                   ntn::cli::num(longest).c_str(), ntn::cli::num(o.rate).c_str(),
                   ntn::cli::num(n).c_str(), static_cast<long long>(kMaxFrames));
      return 2;
    }
    o.frames = static_cast<std::int64_t>(n);
  }
  if (!o.out_path.empty() && o.frames > kMaxCsvFrames) {
    std::fprintf(stderr,
                 "error: --out with %lld frames: the feeder keeps every output for its CSV, at "
                 "most %lld frames (--frames)\n",
                 static_cast<long long>(o.frames), static_cast<long long>(kMaxCsvFrames));
    return 2;
  }
  return std::nullopt;
}

// The fault plan: --fault at given frames, --fault-rate drawn with --seed.
std::optional<int> plan_faults(const FeederOptions& o, FaultPlan& plan) {
  std::vector<FaultAt> fault_at;
  std::vector<FaultRate> rates;
  for (const std::string& s : o.fault_lists) {
    if (std::string e = parse_fault_list(s, fault_at); !e.empty()) {
      std::fprintf(stderr, "error: %s\n", e.c_str());
      return 2;
    }
  }
  for (const std::string& s : o.fault_rates) {
    FaultRate r;
    if (std::string e = parse_fault_rate(s, r); !e.empty()) {
      std::fprintf(stderr, "error: %s\n", e.c_str());
      return 2;
    }
    rates.push_back(r);
  }
  if (std::string e = make_fault_plan(o.frames, fault_at, rates, o.seed, plan); !e.empty()) {
    std::fprintf(stderr, "error: %s\n", e.c_str());
    return 2;
  }
  return std::nullopt;
}

// The stream: the socket, the packets of each frame with their faults, what came back.
struct Stream {
  Stream(const FeederOptions& options, const std::vector<Channel>& chs, const FaultPlan& faults,
         double frame_period)
      : o(options), channels(chs), plan(faults), period(frame_period) {}
  const FeederOptions& o;
  const std::vector<Channel>& channels;
  const FaultPlan& plan;
  double period;
  UdpSocket sock;
  std::uint16_t dest = 0;
  Outputs outputs;
  std::array<std::byte, kReceiveBufferBytes> rx{};
  std::int64_t send_errors = 0, packets_sent = 0;
  int first_send_errno = 0;
  std::array<std::byte, kMaxPacketBytes> late_buf{}, buf{}, next_buf{}, end_buf{};
  std::span<const std::byte> late_packet;  // held back by a late fault, sent next frame
  std::vector<std::int64_t> wake_ns;
  std::int64_t sent_frames = 0;  // frames streamed
  bool timed_out = false;

  void drain() {
    for (;;) {
      const Received r = sock.receive(rx);
      if (!r.has_datagram()) return;
      outputs.take(std::span<const std::byte>(rx.data(), r.size));
    }
  }
  void send(std::span<const std::byte> bytes) {
    const SocketStatus st = sock.send_to(dest, bytes);
    if (st.ok()) {
      ++packets_sent;
    } else {
      if (send_errors++ == 0) first_send_errno = st.error;
    }
  }
  // The packet of frame k with its value fault, if any.
  std::span<std::byte> make_packet(std::int64_t k, std::span<std::byte> out) const {
    const std::size_t nch = channels.size();
    std::array<double, kMaxChannels> v{};
    const double t = static_cast<double>(k) * period;
    for (std::size_t c = 0; c < nch; ++c)
      v[c] = o.scale * channels[c].record.at(t);
    const FaultKind f = plan[k];
    const std::size_t hit = static_cast<std::size_t>(k) % nch;
    if (f == FaultKind::kNan) v[hit] = std::numeric_limits<double>::quiet_NaN();
    if (f == FaultKind::kInf)
      v[hit] = (k % 2 == 0 ? 1 : -1) * std::numeric_limits<double>::infinity();
    if (f == FaultKind::kRange) v[hit] = o.range_value;
    const std::size_t n = encode(PacketKind::kInput, static_cast<std::uint32_t>(k), k, 0,
                                 std::span<const double>(v.data(), nch), out);
    if (f == FaultKind::kCorrupt) {
      out[fault_hash(o.seed, k) % n] ^= std::byte{0xFF};
    }
    return out.first(n);
  }
  // Frame k's input packets as its fault says: none (lost), held back to the next frame (late),
  // twice (duplicate), or after frame k + 1's (reorder, which sent k + 1 early).
  void send_frame(std::int64_t k) {
    if (!late_packet.empty()) {
      send(late_packet);
      late_packet = {};
    }
    const FaultKind f = plan[k];
    const bool sent_early = k > 0 && plan[k - 1] == FaultKind::kReorder;
    if (sent_early) return;
    switch (f) {
      case FaultKind::kLost:
        break;
      case FaultKind::kLate: {
        const auto p = make_packet(k, late_buf);
        late_packet = p;
        break;
      }
      case FaultKind::kDuplicate: {
        const auto p = make_packet(k, buf);
        send(p);
        send(p);
        break;
      }
      case FaultKind::kReorder: {
        const auto p = make_packet(k, buf);
        send(make_packet(k + 1, next_buf));
        send(p);
        break;
      }
      default:
        send(make_packet(k, buf));
        break;
    }
  }
  // Lock-step: frame k's end marker, then the loop's output of frame k, within --timeout.
  bool end_frame_and_wait(std::int64_t k) {
    const std::size_t n =
        encode(PacketKind::kFrameEnd, static_cast<std::uint32_t>(k), k, 0, {}, end_buf);
    send(std::span<const std::byte>(end_buf.data(), n));
    const std::int64_t give_up = now_ns() + static_cast<std::int64_t>(o.timeout_s * 1e9);
    while (outputs.highest < k) {
      const std::int64_t left = give_up - now_ns();
      if (left <= 0) break;
      if (sock.wait_readable(std::chrono::nanoseconds(left)) == WaitStatus::kReadable) drain();
    }
    if (outputs.highest < k) {
      std::fprintf(stderr, "error: no output for frame %lld within %g s\n",
                   static_cast<long long>(k), o.timeout_s);
      return false;
    }
    return true;
  }
};

// Every frame: in real time at its deadline t0 + k period (its wake-up latency kept), in
// lock-step after the loop's output of the frame before; then, in real time, --linger for the
// last outputs.
void stream_frames(Stream& s) {
  const FeederOptions& o = s.o;
  if (!o.lockstep) s.wake_ns.reserve(static_cast<std::size_t>(o.frames));
  const auto period_ns = static_cast<std::int64_t>(std::llround(s.period * 1e9));
  const std::int64_t t0 = now_ns() + 2'000'000;  // first deadline 2 ms from now
  std::int64_t k = 0;
  for (; k < o.frames; ++k) {
    if (!o.lockstep) {
      const std::int64_t deadline = t0 + k * period_ns;
      sleep_until_ns(deadline);
      s.wake_ns.push_back(now_ns() - deadline);
    }
    s.send_frame(k);
    if (o.lockstep) {
      if (!s.end_frame_and_wait(k)) {
        s.timed_out = true;
        break;
      }
    } else {
      s.drain();
    }
  }
  s.sent_frames = k;
  if (!o.lockstep && !s.timed_out) {
    const std::int64_t until = now_ns() + static_cast<std::int64_t>(o.linger_ms * 1e6);
    for (std::int64_t left; s.outputs.highest < o.frames - 1 && (left = until - now_ns()) > 0;) {
      if (s.sock.wait_readable(std::chrono::nanoseconds(left)) == WaitStatus::kReadable) s.drain();
    }
    s.drain();
  }
}

// CSV of the outputs received (--out): the error of writing it, or nullopt.
std::optional<std::string> write_csv(const FeederOptions& o, const Outputs& outputs,
                                     double period) {
  std::ofstream out(o.out_path, std::ios::binary);
  out << "time[s]";
  for (int c = 0; c < outputs.count; ++c)
    out << ",y" << c;
  out << ",flags\n";
  char cell[40];
  for (std::int64_t j = 0; j < o.frames && outputs.count >= 0; ++j) {
    const auto u = static_cast<std::size_t>(j);
    if (!outputs.have[u]) continue;
    std::snprintf(cell, sizeof cell, "%.9g", static_cast<double>(j) * period);
    out << cell;
    for (int c = 0; c < outputs.count; ++c) {
      std::snprintf(
          cell, sizeof cell, ",%.17g",
          outputs
              .values[u * static_cast<std::size_t>(outputs.count) + static_cast<std::size_t>(c)]);
      out << cell;
    }
    out << ',' << outputs.flags[u] << '\n';
  }
  return ntn::cli::close_output(out, "--out", o.out_path);
}

// The frames received with each output flag bit set.
std::array<std::int64_t, 16> count_flag_frames(const Outputs& outputs, std::int64_t frames) {
  std::array<std::int64_t, 16> flag_frames{};
  for (std::int64_t j = 0; j < frames && outputs.count >= 0; ++j) {
    if (!outputs.have[static_cast<std::size_t>(j)]) continue;
    for (std::size_t b = 0; b < 16; ++b) {
      if ((outputs.flags[static_cast<std::size_t>(j)] >> b) & 1U) ++flag_frames[b];
    }
  }
  return flag_frames;
}

// The summary on screen (not with --quiet; the fault line is printed after it in any case).
void print_summary(const Stream& s, const ntn::hil::RealTimeState& real_time,
                   const Percentiles& wake, const std::array<std::int64_t, 16>& flag_frames) {
  const FeederOptions& o = s.o;
  const std::size_t nch = s.channels.size();
  std::printf("ntn-feeder  %zu channel%s -> 127.0.0.1:%d from port %u, %g Hz, %lld frames, %s\n",
              nch, nch == 1 ? "" : "s", o.port, s.sock.port(), o.rate,
              static_cast<long long>(o.frames), o.lockstep ? "lock-step (virtual)" : "real time");
  for (std::size_t c = 0; c < nch; ++c) {
    const ntn::io::Record& r = s.channels[c].record;
    const std::string factor =
        r.scaled_by != 1 ? " (scaled by " + ntn::cli::num(r.scaled_by) + ")" : "";
    std::printf("  channel %zu  %-10s %s: %zu samples at %g s, peak %.4g %s%s x %g\n", c,
                s.channels[c].name.c_str(), r.source.c_str(), r.values.size(), r.dt, r.peak_abs(),
                r.units.c_str(), factor.c_str(), o.scale);
  }
  const std::string first_error =
      s.send_errors ? std::string(" (first: ") + std::strerror(s.first_send_errno) + ")" : "";
  std::printf("  sent        %lld datagrams for %lld frames, %lld send errors%s\n",
              static_cast<long long>(s.packets_sent), static_cast<long long>(s.sent_frames),
              static_cast<long long>(s.send_errors), first_error.c_str());
  if (!o.lockstep) {
    std::printf("  real time   %s\n", real_time.describe().c_str());
    std::printf("  wake-up     latency p50 %.1f us, p99 %.1f us, max %.1f us\n", wake.p50, wake.p99,
                wake.max);
  }
  const Outputs& outputs = s.outputs;
  std::printf(
      "  outputs     %lld of %lld frames received (%lld packets, %lld undecodable, %lld "
      "wrong count, %lld outside the run)\n",
      static_cast<long long>(outputs.distinct), static_cast<long long>(o.frames),
      static_cast<long long>(outputs.received), static_cast<long long>(outputs.undecodable),
      static_cast<long long>(outputs.wrong_count), static_cast<long long>(outputs.outside));
  std::string flags_line;
  for (std::size_t b = 0; b < 16; ++b) {
    if (flag_frames[b] > 0) {
      flags_line += std::string(" ") + kFlagNames[b] + "=" + std::to_string(flag_frames[b]);
    }
  }
  std::printf("  out flags  %s\n", flags_line.empty() ? " none" : flags_line.c_str());
  std::string skipped;
  for (FaultKind f : kAllFaults) {
    if (const auto n = s.plan.skipped[static_cast<std::size_t>(f)]; n > 0)
      skipped += std::string(" ") + to_string(f) + "=" + std::to_string(n);
  }
  if (!skipped.empty()) std::printf("  skipped     (draws on taken frames)%s\n", skipped.c_str());
  if (!o.out_path.empty()) std::printf("  csv         %s\n", o.out_path.c_str());
}

// The summary as JSON (--summary-json): the error of writing it, or nullopt.
std::optional<std::string> write_summary_json(const Stream& s, const Percentiles& wake,
                                              const std::array<std::int64_t, 16>& flag_frames) {
  const FeederOptions& o = s.o;
  std::ofstream js(o.json_path);
  js << "{\n  \"frames\": " << o.frames << ",\n  \"frames_sent\": " << s.sent_frames
     << ",\n  \"rate_hz\": " << o.rate << ",\n  \"mode\": \""
     << (o.lockstep ? "lock-step" : "real-time") << "\",\n  \"datagrams_sent\": " << s.packets_sent
     << ",\n  \"send_errors\": " << s.send_errors << ",\n  \"faults\": {";
  bool first = true;
  for (FaultKind f : kAllFaults) {
    js << (first ? "" : ", ") << '"' << to_string(f) << "\": " << s.plan.count(f);
    first = false;
  }
  js << "},\n  \"outputs_received\": " << s.outputs.distinct
     << ",\n  \"outputs_undecodable\": " << s.outputs.undecodable;
  if (!o.lockstep) {
    js << ",\n  \"wake_latency_us\": {\"p50\": " << wake.p50 << ", \"p99\": " << wake.p99
       << ", \"max\": " << wake.max << "}";
  }
  js << ",\n  \"output_flag_frames\": {";
  first = true;
  for (std::size_t b = 0; b < 16; ++b) {
    if (flag_frames[b] == 0) continue;
    js << (first ? "" : ", ") << '"' << kFlagNames[b] << "\": " << flag_frames[b];
    first = false;
  }
  js << "}\n}\n";
  return ntn::cli::close_output(js, "--summary-json", o.json_path);
}

int feeder_main(int argc, char** argv) {
  FeederOptions o;
  if (const auto code = parse_options(argc, argv, o)) return *code;
  if (const auto code = check_output_paths(o)) return *code;
  std::vector<Channel> channels;
  if (const auto code = read_channels(o, channels)) return *code;
  const double period = 1.0 / o.rate;
  if (const auto code = count_frames(channels, period, o)) return *code;
  FaultPlan plan;
  if (const auto code = plan_faults(o, plan)) return *code;

  Stream s(o, channels, plan, period);
  if (const SocketStatus st = s.sock.open(static_cast<std::uint16_t>(o.listen_port)); !st.ok()) {
    std::fprintf(stderr, "error: cannot open 127.0.0.1:%d: %s\n", o.listen_port,
                 st.message().c_str());
    return 1;
  }
  s.dest = static_cast<std::uint16_t>(o.port);
  ntn::hil::RealTimeState real_time;
  if (!o.lockstep) {
    ntn::hil::RealTimeOptions rt = o.rt;
    rt.fifo = !o.no_fifo && rt.priority > 0;
    real_time = ntn::hil::apply_real_time(rt);
    for (const std::string& w : real_time.warnings)
      std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  s.outputs.frames = o.frames;
  s.outputs.keep_values = !o.out_path.empty();
  stream_frames(s);

  std::vector<std::string> write_errors;  // reported after the summary: exit 2
  if (!o.out_path.empty()) {
    if (auto e = write_csv(o, s.outputs, period)) write_errors.push_back(*e);
  }
  const std::array<std::int64_t, 16> flag_frames = count_flag_frames(s.outputs, o.frames);
  std::string fault_line = "faults";
  for (FaultKind f : kAllFaults) {
    fault_line += std::string(" ") + to_string(f) + "=" + std::to_string(plan.count(f));
  }
  const Percentiles wake = percentiles(s.wake_ns);
  if (!o.quiet) print_summary(s, real_time, wake, flag_frames);
  std::printf("%s\n", fault_line.c_str());
  std::fflush(stdout);
  if (!o.json_path.empty()) {
    if (auto e = write_summary_json(s, wake, flag_frames)) write_errors.push_back(*e);
  }
  for (const std::string& e : write_errors)
    std::fprintf(stderr, "error: %s\n", e.c_str());
  if (!write_errors.empty()) return 2;
  if (s.timed_out) return 3;
  return s.send_errors > 0 ? 1 : 0;
}

}  // namespace

// No exception may end the program unreported (a backstop: the checks above come first).
int main(int argc, char** argv) {
  try {
    return feeder_main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}
