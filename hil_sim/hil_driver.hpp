// The real-time frame loop's program (DESIGN §8), for ntn-hil MODEL.toml (run-time storage) and
// the compiled ntn-hil-<model>: one template over the model's storage (hil_main.cpp,
// ntn_hil_main.cpp), so that both run the same lines on the same kernel code. Inputs from
// recorded files or from UDP on loopback through the input gate; outputs to CSV and back over
// UDP; real-time or virtual clock; a log for bit-exact replay; a summary on screen and as JSON.
// The record source, the CSV sink and the output hash are the loop library's, shared with
// ntn-run (tools/run): for the same --sampling, `run --clock virtual` and ntn-run give the same
// output hash and CSV. The command line is hil_options.hpp, the replay hil_replay.hpp, the run's
// parts hil_run.hpp and its summary hil_summary.hpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cli.hpp"
#include "hil_options.hpp"
#include "hil_replay.hpp"
#include "hil_run.hpp"
#include "hil_summary.hpp"
#include "ntn/hil/clock.hpp"
#include "ntn/hil/geometry_report.hpp"
#include "ntn/hil/loop.hpp"
#include "ntn/hil/model_info.hpp"
#include "ntn/hil/record_source.hpp"
#include "ntn/hil/sampling.hpp"
#include "ntn/hil/stop_signals.hpp"
#include "ntn/hil/worker_team.hpp"
#include "ntn/kernel.hpp"
#include "record.hpp"

namespace ntn::hil::program {

// ntn::init into the caller's storage, then the frame: its period and its N substeps by the
// kernel's frame rule (ntn::frame_substeps, stored once by init; the model compiler checked it).
template <Sizes S>
std::optional<int> init_model(const ModelInfo& info, const ModelSpec<S>& spec,
                              const HilStorage<S>& store, ntn::hil::LoopConfig& config) {
  if (const ntn::InitStatus st = ntn::init(spec, store.model, store.init_work); !st.ok()) {
    std::fprintf(stderr, "error: model '%s': %s (at %d)\n", std::string(info.name).c_str(),
                 ntn::to_string(st.error), st.where);
    return 1;
  }
  const double period = spec.settings.frame_period;
  config.period = period;
  const ntn::Substeps& substeps = store.model.substeps;
  if (!substeps.ok()) {
    std::fprintf(stderr, "error: model '%s': dt = %g s, frame period %g s: %s\n",
                 std::string(info.name).c_str(), store.model.dt, period,
                 ntn::to_string(substeps.error));
    return 1;
  }
  config.substeps = static_cast<int>(substeps.count);
  return std::nullopt;
}

// Every output file is checked before anything is read or run: an unwritable path ends here,
// not after the run with its results lost.
inline std::optional<int> check_output_paths(const HilOptions& o) {
  for (const auto& [path, option] :
       {std::pair{&o.out_path, "--out"}, std::pair{&o.log_path, "--record"},
        std::pair{&o.json_path, "--summary-json"}}) {
    if (o.count(option) == 0) continue;
    // --out creates its directory, as the runners do; the other files' must exist.
    if (const auto problem =
            ntn::cli::output_path_problem(*path, option, std::string_view(option) == "--out")) {
      std::fprintf(stderr, "error: %s\n", problem->c_str());
      return 2;
    }
  }
  return std::nullopt;
}

// The inputs: --input records (the values in each input's unit, gal to g, ..., as ntn-run reads
// them) or --listen, and how they feed the kernel (--sampling).
template <Sizes S>
std::optional<int> read_inputs(const HilOptions& o, const ModelInfo& info, const ModelSpec<S>& spec,
                               RunPlan& plan) {
  const Sizes z = sizes_of(view(spec));
  const ntn::cli::InputArgs inputs = ntn::cli::parse_input_args(o.input_args, "--input");
  if (inputs.error) {
    std::fprintf(stderr, "error: %s\n", inputs.error->c_str());
    return 2;
  }
  plan.sampling = o.interpolate
                      ? ntn::hil::InputSampling::kFrameInterpolated
                      : ntn::hil::parse_sampling(o.sampling_name.empty() ? "hold" : o.sampling_name)
                            .value_or(ntn::hil::InputSampling::kFrameHeld);
  const bool per_step = plan.sampling == ntn::hil::InputSampling::kStep;
  // Per-step sampling reads the records between frames: a sender's packets carry one value per
  // frame, and a log holds the inputs the loop accepted per frame, which replay cannot turn
  // back into per-step values.
  if (per_step && o.listen_port >= 0) {
    std::fprintf(stderr,
                 "error: --sampling step reads --input records at every kernel step; --listen "
                 "takes one value per frame (use --sampling hold or interpolate)\n");
    return 2;
  }
  if (per_step && !o.log_path.empty()) {
    std::fprintf(stderr,
                 "error: --sampling step with --record: the log holds one input per frame and "
                 "could not replay the per-step inputs (use --sampling hold or interpolate)\n");
    return 2;
  }
  // Per step (not through the gate, which sees frame values) every sample must be in range.
  std::vector<char> fed;  // the channels given a record
  if (const auto e = ntn::hil::load_input_records(spec.inputs, info.input_names, inputs.args,
                                                  per_step, plan.records, fed)) {
    std::fprintf(stderr, "%s\n", e->c_str());
    return 2;
  }
  for (const ntn::io::Record& r : plan.records)
    plan.record_duration = std::max(plan.record_duration, r.duration());
  plan.records_given = inputs.args.size();
  plan.udp_in = o.listen_port >= 0;
  if (!plan.udp_in && inputs.args.size() != z.inputs && z.inputs > 0) {
    std::fprintf(stderr,
                 "error: give --input NAME=FILE for every input channel, or --listen PORT\n");
    return 2;
  }
  return std::nullopt;
}

// The run's length: --frames (checked by its validator), else --duration, else the longest
// record; compared as numbers before any conversion.
inline std::optional<int> run_length(const HilOptions& o, double period, RunPlan& plan) {
  plan.frames = o.frames;
  if (o.count("--frames") > 0) return std::nullopt;
  const bool given = o.count("--duration") > 0;
  const double seconds = given ? o.duration : plan.record_duration;
  const double n = std::ceil(seconds / period - 1e-9);
  const std::string what = given ? "--duration " + ntn::cli::num(o.duration) + " s"
                                 : "the longest --input record (" + ntn::cli::num(seconds) + " s)";
  if (!given && plan.udp_in && plan.records_given == 0) {
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
  plan.frames = static_cast<std::int64_t>(n);
  return std::nullopt;
}

// Alarms: the model file's ([[outputs]] alarm, alarm_hysteresis), then --alarm per channel.
inline std::optional<int> set_alarms(const HilOptions& o, const ModelInfo& info,
                                     std::size_t outputs, RunPlan& plan) {
  plan.alarms.assign(outputs, ntn::hil::Alarm{});
  for (std::size_t c = 0; c < plan.alarms.size(); ++c) {
    plan.alarms[c].enabled = info.alarm_limits[c] > 0;
    plan.alarms[c].limit = info.alarm_limits[c];
    plan.alarms[c].hysteresis = info.alarm_hysteresis[c];
  }
  for (const std::string& arg : o.alarm_args) {
    if (const std::string e = parse_alarm(info, arg, plan.alarms); !e.empty()) {
      std::fprintf(stderr, "error: --alarm %s: %s\n", arg.c_str(), e.c_str());
      return 2;
    }
  }
  return std::nullopt;
}

// The inputs' gate and the sender's schedule for the run's frames, and the outputs: the CSV
// (--out), the output hash, the sink of each frame's outputs and the log (--record).
template <Sizes S>
std::optional<int> open_outputs(const HilOptions& o, const ModelInfo& info, const Sizes& z,
                                const HilStorage<S>& store, HilRun<S>& run) {
  const double period = run.config.period;
  (void)run.gate.set_run_frames(run.plan.frames);  // a packet for a frame outside: out_of_run
  run.frame_ns = static_cast<std::int64_t>(std::llround(period * 1e9));
  run.schedule.emplace(run.frame_ns, run.plan.frames);
  if (!run.schedule->valid()) {
    std::fprintf(stderr,
                 "error: --frames/--duration: %lld frames of %g s do not fit the clock's range "
                 "(at most %lld frames)\n",
                 static_cast<long long>(run.plan.frames), period,
                 static_cast<long long>(ntn::hil::SenderSchedule::kMaxSpan /
                                        std::max<std::int64_t>(run.frame_ns, 1)));
    return 2;
  }
  if (!o.out_path.empty()) {
    if (!run.csv.open(o.out_path)) {
      std::fprintf(stderr, "error: --out: cannot write '%s': %s\n", o.out_path.c_str(),
                   run.csv.error().c_str());
      return 2;
    }
    run.csv.header(info.output_names, info.output_units, true);
  }
  if (!run.hash.ok()) {
    std::fprintf(stderr, "error: cannot set up the output hash\n");
    return 2;
  }
  Sink<S>& sink = run.sink;
  sink.peak.assign(z.outputs, 0.0);
  sink.peak_frame.assign(z.outputs, 0);
  sink.csv = &run.csv;
  sink.socket = o.reply_port != 0 ? &run.socket : nullptr;
  sink.reply_port = static_cast<std::uint16_t>(o.reply_port);
  sink.period = period;
  sink.hash = &run.hash;
  if (!o.log_path.empty()) {
    ntn::hil::LogHeader h;
    h.inputs = static_cast<std::uint32_t>(z.inputs);
    h.outputs = static_cast<std::uint32_t>(z.outputs);
    h.substeps = static_cast<std::uint32_t>(run.config.substeps);
    h.interpolate = run.plan.sampling == ntn::hil::InputSampling::kFrameInterpolated ? 1U : 0U;
    h.period = period, h.dt = store.model.dt, h.model = std::string(info.name);
    if (!run.recorder.open(o.log_path, h)) {
      std::fprintf(stderr, "error: --record: %s\n", run.recorder.error().c_str());
      return 2;
    }
    sink.recorder = &run.recorder;
  }
  sink.flush_every = std::max<std::int64_t>(1, std::llround(1.0 / period));
  return std::nullopt;
}

inline void print_warnings(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings)
    std::fprintf(stderr, "warning: %s\n", w.c_str());
}

// The real clock's settings (SCHED_FIFO, mlockall, the CPU, timer slack), their warnings printed.
template <Sizes S>
void apply_real_time_settings(const HilOptions& o, HilRun<S>& run) {
  run.virtual_clock = o.clock_name == "virtual";
  if (run.virtual_clock) return;
  run.real_time = ntn::hil::apply_real_time(
      {o.fifo, o.priority, o.mlock, o.cpu, o.timer_slack_ns, o.cpu_latency_us});
  print_warnings(run.real_time.warnings);
}

// The port is bound only now, after every allocation, mlockall and the scheduler change: a
// sender that waits for the port (tools/demo, tests/hil) then starts when the loop can take
// its packets at once.
template <Sizes S>
std::optional<int> open_socket(const HilOptions& o, HilRun<S>& run) {
  const bool udp_in = run.plan.udp_in;
  if (!udp_in && o.reply_port == 0) return std::nullopt;
  const auto st = run.socket.open(static_cast<std::uint16_t>(std::max(o.listen_port, 0)));
  if (!st.ok()) {
    std::fprintf(stderr, "error: %s\n", st.message().c_str());
    return 2;
  }
  // The port actually bound (the OS's choice for --listen 0), for the sender: flushed now.
  if (udp_in && (!o.quiet || o.listen_port == 0)) {
    std::printf("ntn-hil  listening on 127.0.0.1:%u\n", static_cast<unsigned>(run.socket.port()));
    std::fflush(stdout);
  }
  return std::nullopt;
}

// The loop on the clock the options chose, from the sender (UDP) or the records.
template <Sizes S>
void run_frames(const HilOptions& o, const HilStorage<S>& store, const ntn::Team* team,
                HilRun<S>& run) {
  LoopOutcome& out = run.outcome;
  ntn::hil::Recorder* recorder = o.log_path.empty() ? nullptr : &run.recorder;
  const std::int64_t wall0 = ntn::hil::monotonic_ns();
  auto go = [&](auto& clock) {
    if (run.plan.udp_in) {
      UdpSource source{&run.socket, &run.gate, run.virtual_clock};
      source.period_ns = run.frame_ns;
      if (!run.virtual_clock) source.schedule = &*run.schedule;
      source.first_wait_ns = static_cast<std::int64_t>(o.first_wait_s * 1e9);
      out.result = ntn::hil::run_loop(store.model, store.state, store.scratch, clock, source,
                                      run.sink, recorder, run.config, run.plan.alarms, run.times,
                                      &store.checkpoint, team, &store.team_work, store.buffers);
      out.udp_timeouts = source.timeouts;
      out.first_frame = source.first_frame;
      out.first_waited_ns = source.waited_ns;
    } else {
      ntn::hil::RecordSource source(run.plan.records, run.gate, run.config.period, store.model.dt);
      out.result = ntn::hil::run_loop(store.model, store.state, store.scratch, clock, source,
                                      run.sink, recorder, run.config, run.plan.alarms, run.times,
                                      &store.checkpoint, team, &store.team_work, store.buffers);
    }
  };
  if (run.virtual_clock) {
    ntn::hil::VirtualClock clock;
    go(clock);
  } else {
    ntn::hil::RealClock clock;
    go(clock);
  }
  // The wait for the sender's first packet is not part of the run.
  out.wall = static_cast<double>(ntn::hil::monotonic_ns() - wall0 - out.first_waited_ns) / 1e9;
  if (run.plan.udp_in && !run.virtual_clock && out.first_frame < 0 && !out.result.stopped) {
    std::fprintf(
        stderr,
        "warning: no plausible input packet within %g s: the loop started on its own clock%s\n",
        o.first_wait_s,
        run.schedule->anchored() ? " and followed the sender after a resync"
                                 : ", every frame missing");
  }
}

// Files are finished whatever happened; a write error (disk full) is an error of the run.
template <Sizes S>
std::vector<std::string> close_files(const HilOptions& o, HilRun<S>& run) {
  std::vector<std::string> write_errors;
  if (!o.log_path.empty() && !run.recorder.close()) write_errors.push_back(run.recorder.error());
  if (run.csv.is_open() && !run.csv.close()) {
    write_errors.push_back("--out: write error in " + o.out_path + ": " + run.csv.error() +
                           " (the CSV is incomplete)");
  }
  return write_errors;
}

// Runs (or replays) the model as the options say and prints the summary; the exit code.
template <Sizes S>
int hil_execute(const HilOptions& o, const ModelInfo& info, const ModelSpec<S>& spec,
                HilStorage<S> store) {
  const Sizes z = sizes_of(view(spec));
  ntn::hil::LoopConfig config;
  if (const auto code = init_model(info, spec, store, config)) return *code;
  if (o.replay) return replay_log(info, store, o.replay_path, config);

  // The run's plan, every part checked before anything is read into the loop.
  HilRun<S> run(spec);
  run.config = config;
  RunPlan& plan = run.plan;
  if (const auto code = check_output_paths(o)) return *code;
  if (const auto code = read_inputs(o, info, spec, plan)) return *code;
  if (const auto code = run_length(o, config.period, plan)) return *code;
  run.config.frames = plan.frames;
  run.config.sampling = plan.sampling;
  if (const auto code = set_alarms(o, info, z.outputs, plan)) return *code;

  // SIGINT / SIGTERM from here on end the run after the frame in progress, with every file
  // written (exit 4); before, they end the program as usual (nothing written yet).
  ntn::hil::catch_stop_signals();
  run.config.stop = &g_stop_signal;
  if (const auto code = open_outputs(o, info, z, store, run)) return *code;
  apply_real_time_settings(o, run);
  // The multi-core step's workers, made (and pinned) before the loop, and its partition.
  ntn::hil::WorkerTeam workers({o.threads, run.virtual_clock ? -1 : o.cpu});
  print_warnings(workers.warnings());
  const ntn::Team team = workers.team();
  const bool with_team =
      o.threads > 1 && ntn::prepare_team(store.model, o.threads, store.team_work);
  run.times.reserve(std::min(plan.frames, kTimedFrames));
  if (const auto code = open_socket(o, run)) return *code;

  run_frames(o, store, with_team ? &team : nullptr, run);
  std::vector<std::string> write_errors = close_files(o, run);
  const std::uint64_t hash_value = run.hash.finish(store.state);
  const char* stop_signal = ntn::hil::stop_signal_name();

  const FrameStats stats = frame_stats(run.times);
  if (!o.quiet) print_summary(o, info, store, run, stats);
  if (run.outcome.result.stopped) print_stopped(run, stop_signal);
  // Said on stderr too, with --quiet: the run's results past the bound are not valid.
  if (const std::int64_t k = run.outcome.result.geometry_bound_frame; k >= 0) {
    std::fprintf(stderr,
                 "warning: past the stable step's bound of second-order geometry from t = %.3f s "
                 "(%llu element evaluations); %s\n",
                 static_cast<double>(k) * run.config.period,
                 static_cast<unsigned long long>(store.state.geometry_bound),
                 ntn::hil::kGeometryBoundMeaning);
  }
  std::printf("  output hash %016llx\n", static_cast<unsigned long long>(hash_value));
  if (!o.json_path.empty()) {
    if (auto e = write_summary_json(o, info, store, run, stats, hash_value, stop_signal))
      write_errors.push_back(*e);
  }
  for (const std::string& e : write_errors)
    std::fprintf(stderr, "error: %s\n", e.c_str());
  // Exit codes (README "Exit codes"): 2 a file could not be written, 3 diverged, 4 stopped by
  // SIGINT / SIGTERM, 0 otherwise.
  if (!write_errors.empty()) return 2;
  if (run.outcome.result.diverged_frame >= 0) return 3;
  return run.outcome.result.stopped ? 4 : 0;
}

}  // namespace ntn::hil::program
