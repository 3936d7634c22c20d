// The summary of a run of the real-time frame loop: on screen (unless --quiet) and as JSON
// (--summary-json), from what the run set up and what the loop found (HilRun, hil_run.hpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include "cli.hpp"
#include "hil_options.hpp"
#include "hil_replay.hpp"
#include "hil_run.hpp"
#include "ntn/hil/geometry_report.hpp"
#include "ntn/hil/model_info.hpp"
#include "ntn/hil/yield_report.hpp"
#include "ntn/kernel.hpp"

namespace ntn::hil::program {

inline double us(std::int64_t ns) {
  return static_cast<double>(ns) / 1e3;
}

inline unsigned long long ull(std::uint64_t x) {
  return static_cast<unsigned long long>(x);
}

// The frames' wake-up latency and compute time, as percentiles.
struct FrameStats {
  std::int64_t lat50, lat99, lat999, latmax, cmp50, cmp99, cmp999, cmpmax;
};

inline FrameStats frame_stats(const ntn::hil::FrameTimes& times) {
  return {
      ntn::hil::percentile(times.latency_ns, 50),   ntn::hil::percentile(times.latency_ns, 99),
      ntn::hil::percentile(times.latency_ns, 99.9), ntn::hil::percentile(times.latency_ns, 100),
      ntn::hil::percentile(times.compute_ns, 50),   ntn::hil::percentile(times.compute_ns, 99),
      ntn::hil::percentile(times.compute_ns, 99.9), ntn::hil::percentile(times.compute_ns, 100)};
}

// The run's first lines: the model, the clock, the frames, the real-time settings, the timing.
template <Sizes S>
void print_run_timing(const HilOptions& o, const ModelInfo& info, const HilStorage<S>& store,
                      const HilRun<S>& run, const FrameStats& t) {
  const ntn::hil::LoopResult& result = run.outcome.result;
  const double period = run.config.period;
  const double period_ns = period * 1e9;
  const ntn::hil::InputSampling sampling = run.plan.sampling;
  std::printf(
      "ntn-hil  %s, %s clock, %lld frames of %g ms x %d substeps (dt %.4g us), %s inputs%s\n",
      std::string(info.name).c_str(), o.clock_name.c_str(), static_cast<long long>(result.frames),
      period * 1e3, run.config.substeps, store.model.dt * 1e6, run.plan.udp_in ? "UDP" : "file",
      sampling == ntn::hil::InputSampling::kStep                ? " per kernel step"
      : sampling == ntn::hil::InputSampling::kFrameInterpolated ? " interpolated"
                                                                : " held");
  if (!run.virtual_clock) std::printf("  real time: %s\n", run.real_time.describe().c_str());
  const double wall = run.outcome.wall;
  std::printf("  wall %.3f s for %.3f s simulated (%.1fx real time)\n", wall,
              static_cast<double>(result.frames) * period,
              static_cast<double>(result.frames) * period / wall);
  std::printf("  wake-up latency  p50 %.1f us  p99 %.1f us  p99.9 %.1f us  max %.1f us\n",
              us(t.lat50), us(t.lat99), us(t.lat999), us(t.latmax));
  std::printf("  compute / period p50 %.3f  p99 %.3f  p99.9 %.3f  max %.3f\n",
              static_cast<double>(t.cmp50) / period_ns, static_cast<double>(t.cmp99) / period_ns,
              static_cast<double>(t.cmp999) / period_ns, static_cast<double>(t.cmpmax) / period_ns);
  std::printf("  overruns %lld (longest run %lld frames)\n",
              static_cast<long long>(run.times.overruns),
              static_cast<long long>(run.times.max_late_frames));
}

// The input gate's counters.
inline void print_input_counters(const ntn::hil::GateCounters& gc) {
  std::printf(
      "  inputs   accepted %llu, missing %llu (lost %llu), late %llu, early %llu\n"
      "           reordered %llu, duplicate %llu, corrupt %llu, wrong count %llu, too early "
      "%llu\n"
      "           values held: non-finite %llu, out of range %llu\n"
      "           frame out of run %llu, out of window %llu; sender restarts %llu\n",
      ull(gc.accepted), ull(gc.missing), ull(gc.lost()), ull(gc.late), ull(gc.early),
      ull(gc.reordered), ull(gc.duplicate), ull(gc.corrupt), ull(gc.wrong_count), ull(gc.too_early),
      ull(gc.nonfinite), ull(gc.out_of_range), ull(gc.out_of_run), ull(gc.out_of_window),
      ull(gc.sender_restart));
}

// Each enabled alarm, then each output's peak |value| and when.
template <Sizes S>
void print_alarms_and_peaks(const ModelInfo& info, const HilRun<S>& run) {
  const double period = run.config.period;
  const std::size_t outputs = run.plan.alarms.size();
  for (std::size_t c = 0; c < outputs; ++c) {
    const auto& a = run.plan.alarms[c];
    if (!a.enabled) continue;
    const std::string name(info.output_names[c]);
    if (a.raised == 0) {
      std::printf("  alarm    |%s| > %g, off < %g: not raised\n", name.c_str(), a.limit,
                  a.limit - a.hysteresis);
    } else {
      std::printf(
          "  ALARM    |%s| > %g, off < %g: raised %llu times, %llu frames on, first at %.3f s\n",
          name.c_str(), a.limit, a.limit - a.hysteresis, ull(a.raised), ull(a.frames_on),
          static_cast<double>(a.first_frame) * period);
    }
  }
  int width = 0;
  for (const std::string_view name : info.output_names)
    width = std::max(width, static_cast<int>(name.size()));
  for (std::size_t c = 0; c < outputs; ++c) {
    std::printf("  %s %-*s %11.4g %-5s at %.3f s\n", c == 0 ? "peak |y|" : "        ", width,
                std::string(info.output_names[c]).c_str(), run.sink.peak[c],
                std::string(info.output_units[c]).c_str(),
                static_cast<double>(run.sink.peak_frame[c]) * period);
  }
}

// The plastic hinge directions that yielded: from the state the run ended in (after a
// divergence: the last good frame's).
template <Sizes S>
void print_yielded(const ModelInfo& info, const HilStorage<S>& store) {
  const int np = ntn::hil::plastic_directions(store.model);
  if (np <= 0) return;
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

// The divergence check, and the safe state when it fired.
inline void print_divergence(const ntn::hil::LoopResult& result, double period) {
  if (result.kinetic_limit < std::numeric_limits<double>::infinity()) {
    std::printf(
        "  divergence check: kinetic energy limit %.4g J; peak %.4g J (%.3g of it) at %.3f s\n",
        result.kinetic_limit, result.peak_kinetic, result.peak_kinetic / result.kinetic_limit,
        static_cast<double>(result.peak_kinetic_frame) * period);
  } else {
    std::printf("  divergence check: non-finite state only (the model has no energy bound)\n");
  }
  if (result.diverged_frame < 0) return;
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

// The sender: whose packet the deadlines follow, the port, the resyncs and the timeouts.
template <Sizes S>
void print_sender(const HilRun<S>& run) {
  const LoopOutcome& out = run.outcome;
  if (run.plan.udp_in && !run.virtual_clock && out.first_frame >= 0) {
    std::printf(
        "  deadlines follow the sender from its packet of frame %lld (waited %.3f s): "
        "frame k at packet k + T/2\n",
        static_cast<long long>(out.first_frame), static_cast<double>(out.first_waited_ns) / 1e9);
  }
  if (run.plan.udp_in)
    std::printf("  UDP on 127.0.0.1:%u\n", static_cast<unsigned>(run.socket.port()));
  if (run.schedule->resyncs() > 0) {
    std::printf(
        "  resync   %llu (deadlines re-anchored to the sender's stream), last at frame %lld\n",
        ull(run.schedule->resyncs()), static_cast<long long>(run.schedule->last_resync_frame()));
  }
  if (out.udp_timeouts > 0)
    std::printf("  %llu frames timed out waiting for the sender\n",
                static_cast<unsigned long long>(out.udp_timeouts));
}

// The summary on screen (not with --quiet).
template <Sizes S>
void print_summary(const HilOptions& o, const ModelInfo& info, const HilStorage<S>& store,
                   const HilRun<S>& run, const FrameStats& t) {
  print_run_timing(o, info, store, run, t);
  print_input_counters(run.gate.counters());
  print_alarms_and_peaks(info, run);
  print_yielded(info, store);
  const std::string geometry = ntn::hil::geometry_bound_text(
      store.model, store.state, run.outcome.result.geometry_bound_frame, run.config.period);
  if (!geometry.empty()) std::printf("  geometry %s\n", geometry.c_str());
  print_divergence(run.outcome.result, run.config.period);
  print_sender(run);
}

// A run stopped by SIGINT / SIGTERM: what the files hold (always printed, also on stderr).
template <Sizes S>
void print_stopped(const HilRun<S>& run, const char* stop_signal) {
  const ntn::hil::LoopResult& result = run.outcome.result;
  std::printf(
      "  STOPPED by %s after %lld of %lld frames (t = %.3f s): the CSV, the log and the "
      "summary hold frames 0..%lld\n",
      stop_signal, static_cast<long long>(result.frames), static_cast<long long>(run.plan.frames),
      static_cast<double>(result.frames) * run.config.period,
      static_cast<long long>(result.frames - 1));
  std::fprintf(stderr, "stopped by %s after %lld frames\n", stop_signal,
               static_cast<long long>(result.frames));
}

// The real-time settings as a JSON object, or null on the virtual clock.
inline std::string real_time_json(const ntn::hil::RealTimeState& rt, bool virtual_clock) {
  if (virtual_clock) return std::string("null");
  return "{\"fifo\": " + std::string(rt.fifo ? "true" : "false") +
         ", \"priority\": " + std::to_string(rt.priority) +
         ", \"memory_locked\": " + (rt.memory_locked ? "true" : "false") +
         ", \"timer_slack_ns\": " + std::to_string(rt.timer_slack_ns) +
         ", \"cpu_latency_us\": " + std::to_string(rt.cpu_latency_us) +
         ", \"cpu\": " + std::to_string(rt.cpu) + "}";
}

// A finite number in 17 digits; null for Inf and NaN, which JSON has not.
inline std::string json_number(double x) {
  if (!(x - x == 0)) return std::string("null");
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);
  return std::string(text);
}

// The summary as JSON (--summary-json): the error of writing it, or nullopt.
template <Sizes S>
std::optional<std::string> write_summary_json(const HilOptions& o, const ModelInfo& info,
                                              const HilStorage<S>& store, const HilRun<S>& run,
                                              const FrameStats& t, std::uint64_t hash_value,
                                              const char* stop_signal) {
  const ntn::hil::LoopResult& result = run.outcome.result;
  const auto& gc = run.gate.counters();
  const double period_ns = run.config.period * 1e9;
  std::ofstream js(o.json_path);
  js << "{\n  \"model\": \"" << info.name << "\",\n  \"clock\": \"" << o.clock_name
     << "\",\n  \"sampling\": \"" << ntn::hil::to_string(run.plan.sampling)
     << "\",\n  \"frames\": " << result.frames << ",\n  \"frames_requested\": " << run.plan.frames
     << ",\n  \"stopped_by\": "
     << (result.stopped ? "\"" + std::string(stop_signal) + "\"" : std::string("null"))
     << ",\n  \"real_time\": " << real_time_json(run.real_time, run.virtual_clock)
     << ",\n  \"period_s\": " << run.config.period << ",\n  \"substeps\": " << run.config.substeps
     << ",\n  \"overruns\": " << run.times.overruns
     << ",\n  \"latency_us\": {\"p50\": " << us(t.lat50) << ", \"p99\": " << us(t.lat99)
     << ", \"p99.9\": " << us(t.lat999) << ", \"max\": " << us(t.latmax) << "}"
     << ",\n  \"compute_fraction\": {\"p50\": " << static_cast<double>(t.cmp50) / period_ns
     << ", \"p99\": " << static_cast<double>(t.cmp99) / period_ns
     << ", \"p99.9\": " << static_cast<double>(t.cmp999) / period_ns
     << ", \"max\": " << static_cast<double>(t.cmpmax) / period_ns << "}"
     << ",\n  \"inputs\": {\"accepted\": " << gc.accepted << ", \"missing\": " << gc.missing
     << ", \"lost\": " << gc.lost() << ", \"late\": " << gc.late
     << ", \"duplicate\": " << gc.duplicate << ", \"reordered\": " << gc.reordered
     << ", \"early\": " << gc.early << ", \"too_early\": " << gc.too_early
     << ", \"corrupt\": " << gc.corrupt << ", \"wrong_count\": " << gc.wrong_count
     << ", \"nonfinite\": " << gc.nonfinite << ", \"out_of_range\": " << gc.out_of_range
     << ", \"out_of_run\": " << gc.out_of_run << ", \"out_of_window\": " << gc.out_of_window
     << ", \"sender_restart\": " << gc.sender_restart << "}"
     << ",\n  \"resync\": " << run.schedule->resyncs()
     << ",\n  \"listen_port\": " << (run.plan.udp_in ? static_cast<int>(run.socket.port()) : -1)
     << ",\n  \"first_packet_frame\": " << run.outcome.first_frame << ",\n  \"alarms\": [";
  bool first_alarm = true;
  for (std::size_t c = 0; c < run.plan.alarms.size(); ++c) {
    const auto& a = run.plan.alarms[c];
    if (!a.enabled) continue;
    js << (first_alarm ? "" : ",") << "\n    {\"channel\": \"" << info.output_names[c]
       << "\", \"limit\": " << a.limit << ", \"hysteresis\": " << a.hysteresis
       << ", \"raised\": " << a.raised << ", \"frames_on\": " << a.frames_on
       << ", \"first_frame\": " << a.first_frame << "}";
    first_alarm = false;
  }
  js << "],\n  \"peaks\": {";
  for (std::size_t c = 0; c < run.plan.alarms.size(); ++c) {
    js << (c == 0 ? "" : ", ") << "\"" << info.output_names[c] << "\": " << run.sink.peak[c];
  }
  js << "}"
     << ",\n  \"divergence\": {\"kinetic_limit_J\": " << json_number(result.kinetic_limit)
     << ", \"peak_kinetic_J\": " << json_number(result.peak_kinetic)
     << ", \"peak_kinetic_frame\": " << result.peak_kinetic_frame
     << ", \"diverged_frame\": " << result.diverged_frame << ", \"reason\": \""
     << ntn::hil::to_string(result.reason) << "\""
     << ", \"step\": " << result.diverged_step
     << ", \"kinetic_at_detection_J\": " << json_number(result.kinetic_at_detection)
     << ", \"safe_state\": " << (result.diverged_frame >= 0 ? "true" : "false")
     << ", \"last_good_frame\": "
     << (result.diverged_frame >= 0 ? result.diverged_frame - 1 : result.frames - 1)
     << ", \"state_restored\": " << (result.state_restored ? "true" : "false") << "}"
     << ",\n  \"diverged_frame\": " << result.diverged_frame << ",\n  \"geometry_bound\": "
     << ntn::hil::geometry_bound_json(store.model, store.state, result.geometry_bound_frame,
                                      run.config.period)
     << ",\n  \"faults\": " << ntn::hil::fault_names_json(store.state.faults)
     << ",\n  \"output_hash\": \"" << std::hex << hash_value << std::dec << "\"\n}\n";
  return ntn::cli::close_output(js, "--summary-json", o.json_path);
}

}  // namespace ntn::hil::program
