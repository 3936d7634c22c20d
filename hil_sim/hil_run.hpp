// One run of the real-time frame loop, its parts: the UDP input source, the sink of each frame's
// outputs (CSV, output packets, the output hash, the peaks), and HilRun, what the run set up and
// what it found, which the driver's stages (hil_driver.hpp) fill and the summary
// (hil_summary.hpp) reads.
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "ntn/hil/clock.hpp"
#include "ntn/hil/csv_sink.hpp"
#include "ntn/hil/gate.hpp"
#include "ntn/hil/loop.hpp"
#include "ntn/hil/output_hash.hpp"
#include "ntn/hil/packet.hpp"
#include "ntn/hil/recorder.hpp"
#include "ntn/hil/sampling.hpp"
#include "ntn/hil/schedule.hpp"
#include "ntn/hil/stop_signals.hpp"
#include "ntn/hil/udp.hpp"
#include "ntn/kernel.hpp"
#include "record.hpp"

namespace ntn::hil::program {

// SIGINT / SIGTERM (stop_signals.hpp): the loop ends after the frame it is in, and the program
// flushes the CSV, the log and the JSON and says so.
using ntn::hil::g_stop_signal;

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

// What a run is given, from the options and the model, every part checked before anything runs.
struct RunPlan {
  ntn::hil::InputSampling sampling = ntn::hil::InputSampling::kFrameHeld;
  std::vector<ntn::io::Record> records;  // the records' values in each input's unit
  std::size_t records_given = 0;         // --input arguments
  double record_duration = 0;            // the longest record's, s
  bool udp_in = false;                   // --listen: the inputs come from a sender
  std::int64_t frames = -1;
  std::vector<ntn::hil::Alarm> alarms;  // per output channel
};

// What the loop reports of the run beyond its LoopResult.
struct LoopOutcome {
  ntn::hil::LoopResult result;
  std::uint64_t udp_timeouts = 0;
  std::int64_t first_frame = -1;     // the sender's packet the deadlines follow
  std::int64_t first_waited_ns = 0;  // frame 0's wait for it
  double wall = 0;                   // s, the run's, without that wait
};

// One run: its configuration and plan, its inputs' gate and schedule, its output files and
// socket, the real-time settings, and what the loop found. Made once, before the loop.
template <Sizes S>
struct HilRun {
  explicit HilRun(const ModelSpec<S>& spec) : gate(std::span<const ntn::InputSpec>(spec.inputs)) {}
  HilRun(const HilRun&) = delete;
  HilRun& operator=(const HilRun&) = delete;

  ntn::hil::LoopConfig config;
  RunPlan plan;
  bool virtual_clock = false;
  std::int64_t frame_ns = 0;  // the frame period in the clock's ns
  ntn::hil::InputGate gate;
  std::optional<ntn::hil::SenderSchedule> schedule;
  ntn::hil::UdpSocket socket;  // opened last, when the loop is ready
  ntn::hil::CsvWriter csv;
  ntn::hil::OutputHash hash;
  Sink<S> sink;
  ntn::hil::Recorder recorder;
  ntn::hil::RealTimeState real_time;
  ntn::hil::FrameTimes times;
  LoopOutcome outcome;
};

}  // namespace ntn::hil::program
