// The run itself of ntn-run, the compiled runners ntn-run-<model> and the Python module
// (simulate), over the model's storage, compiled or run-time, and the runners' command line
// (RunOptions, add_options). The program around it is run_driver.hpp.
#pragma once

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cli.hpp"  // tools/io
#include "ntn/hil/clock.hpp"
#include "ntn/hil/csv_sink.hpp"
#include "ntn/hil/energy.hpp"
#include "ntn/hil/gate.hpp"
#include "ntn/hil/loop.hpp"
#include "ntn/hil/model_info.hpp"
#include "ntn/hil/output_hash.hpp"
#include "ntn/hil/record_source.hpp"
#include "ntn/hil/sampling.hpp"
#include "ntn/hil/stop_signals.hpp"
#include "ntn/hil/worker_team.hpp"
#include "ntn/hil/yield_report.hpp"
#include "ntn/kernel.hpp"
#include "record.hpp"

namespace ntn::run {

// The command line's options (add_options): the same for every runner.
struct RunOptions {
  std::vector<std::string> input_args;
  double duration = -1;
  std::string out_path;
  std::string json_path;
  std::string sampling_name = "step";
  bool quiet = false;
  bool flags = false;
  std::string element_pass = "simd";
  int threads = 1;
  bool energy = false;
};

inline void add_options(ntn::cli::App& app, RunOptions& o) {
  auto& input_args = o.input_args;
  auto& duration = o.duration;
  auto& out_path = o.out_path;
  auto& json_path = o.json_path;
  auto& sampling_name = o.sampling_name;
  auto& quiet = o.quiet;
  auto& flags = o.flags;
  auto& element_pass = o.element_pass;
  auto& threads = o.threads;
  app.add_option("-i,--input", input_args,
                 "NAME=FILE: feed input channel NAME from a record (AT2 or CSV; "
                 "FILE:COLUMN picks a CSV column; values are converted to the input's unit; "
                 "FILE*FACTOR scales them)");
  app.add_option("-t,--duration", duration, "simulated time in s (default: longest record)")
      ->check(ntn::cli::Positive());
  app.add_option("-s,--sampling", sampling_name,
                 "step (the records at every kernel step; default), hold (at frame times, held "
                 "over the frame) or interpolate (at frame times, linear over the frame, one "
                 "frame of delay): hold and interpolate are what ntn-hil's loop does")
      ->check(ntn::cli::IsMember({"step", "hold", "interpolate"}));
  app.add_option("-o,--out", out_path, "CSV file for the response, one row per I/O frame");
  app.add_flag("--flags", flags,
               "add the loop's flags column to the CSV (input gate, alarm, diverged bits), as "
               "ntn-hil writes it");
  app.add_flag("--energy", o.energy,
               "add the energy books as channels: CSV columns energy_external, energy_kinetic, "
               "energy_elastic, energy_viscous, energy_hysteretic, energy_friction, "
               "energy_impacts, energy_fracture, energy_residual [J] after the outputs, each "
               "frame's after its last step");
  app.add_option("--summary-json", json_path, "also write the summary as JSON");
  app.add_flag("-q,--quiet", quiet, "print only errors and the output hash");
  app.add_option("--element-pass", element_pass,
                 "simd (default: the widest vectors this CPU has) or scalar (the reference): the "
                 "same bits either way")
      ->check(ntn::cli::IsMember({"simd", "scalar"}));
  app.add_option("--threads", threads,
                 "workers of the multi-core step (1 = the caller's thread alone): the same bits "
                 "for any number")
      ->check(ntn::cli::Integer(1, ntn::kMaxTeam));
}

using hil::ModelInfo;  // the names the summary uses (ntn/hil/model_info.hpp)

// The caller's storage of the model: static objects (compiled) or bound to one block
// (ntn/runtime_storage.hpp); `buffers`: the loop's channels (run-time storage: made before init).
template <Sizes S>
struct RunStorage {
  Model<S>& model;
  InitWorkspace<S>& init_work;
  State<S>& state;
  Scratch<S>& scratch;
  TeamWork<S>& team_work;
  hil::LoopBuffers<S>* buffers = nullptr;
};

namespace detail {

struct Peak {
  double value = 0;  // largest |value|
  double time = 0;   // s
};

inline std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

inline bool is_translation(const OutputSpec& o) {
  return o.dof < 3;
}

// The most steps one run takes: t = n dt stays exact in a double far beyond it, and at ~1 us a
// step it is 12 days of wall time. A longer run is a slip of --duration (or of a record's DT).
inline constexpr double kMaxSteps = 1e12;

// The loop's sink: every kernel step's outputs into the output hash and the peaks (at the step's
// time), every frame's outputs as a CSV row (with the loop's flags under --flags).
template <Sizes S>
struct RunSink {
  Model<S>* model;  // the books turn Model::books on (after_start)
  hil::OutputHash* hash;
  hil::CsvWriter* csv;
  bool flags = false;
  double period = 1e-3;
  std::vector<Peak> peaks;
  std::vector<double> last;  // the channels at the last step (residual drifts)
  std::int64_t steps = 0;
  hil::EnergyBalance<S> energy;     // the run's work-energy identity (hil/energy.hpp)
  const State<S>* state = nullptr;  // the loop's state (after_start)
  void after_start(const State<S>& s, const Scratch<S>&) {
    energy.begin(*model, s);
    state = &s;
  }
  void after_step(const State<S>& s, const Scratch<S>& w) {
    ++steps;
    energy.after_step(*model, s, w);
    hash->add_step(w);
    std::copy(w.outputs.begin(), w.outputs.end(), last.begin());
    for (std::size_t c = 0; c < peaks.size(); ++c) {
      const double v = std::abs(w.outputs[c]);
      if (v > peaks[c].value) peaks[c] = {v, w.time};
    }
  }
  std::vector<double>* frames = nullptr;  // every frame's outputs appended (reserved)
  // The energy accounts as channels after the outputs (kEnergyChannels): every frame's
  // appended to energy_frames (reserved), and in the CSV rows with csv_energy.
  std::vector<double>* energy_frames = nullptr;
  bool csv_energy = false;
  std::vector<double> row;  // a CSV row: the outputs, then the accounts (reserved)
  void frame_outputs(std::int64_t k, std::span<const double> v, std::uint16_t f) {
    if (frames != nullptr) frames->insert(frames->end(), v.begin(), v.end());
    const bool to_csv = csv != nullptr && csv->is_open();
    std::span<const double> values = v;
    if (energy_frames != nullptr || (to_csv && csv_energy)) {
      const auto accounts = energy.accounts(*model, *state).channels();
      if (energy_frames != nullptr)
        energy_frames->insert(energy_frames->end(), accounts.begin(), accounts.end());
      if (csv_energy) {
        row.assign(v.begin(), v.end());
        row.insert(row.end(), accounts.begin(), accounts.end());
        values = row;
      }
    }
    if (!to_csv) return;
    if (flags) {
      csv->row(static_cast<double>(k) * period, values, f);
    } else {
      csv->row(static_cast<double>(k) * period, values);
    }
  }
};

}  // namespace detail

// What simulate() runs: `steps` kernel steps from the model's initial state, the records (one
// per input channel, in its unit) sampled as `sampling` says, on `threads` workers.
struct RunRequest {
  std::int64_t steps = 0;
  hil::InputSampling sampling = hil::InputSampling::kStep;
  int threads = 1;
  hil::CsvWriter* csv = nullptr;          // every frame's outputs as a row (opened, header written)
  bool csv_flags = false;                 // with the loop's flags column
  std::vector<double>* frames = nullptr;  // every frame's outputs appended (reserved here)
  // Every frame's energy accounts appended (kEnergyChannels, after the frame's last step;
  // reserved here), and with csv_energy in the CSV rows after the outputs.
  std::vector<double>* energy_frames = nullptr;
  bool csv_energy = false;
  // Not null: the run ends after the frame in which *stop became non-zero (LoopConfig::stop).
  const volatile std::sig_atomic_t* stop = nullptr;
  // The run ends after the first frame past the stable step's bound of second-order geometry
  // (LoopConfig::stop_at_geometry_bound; ntn-ida): else it goes on, counted (geometry_bound).
  bool stop_at_geometry_bound = false;
};

// What a run gives: the loop's result, the output hash (every output of every step, then the
// final state: XXH3), per channel the peak |value| and its time and the value at the last step,
// the energy balance. Not an error: a run that diverged (`diverged`, the loop's safe state), and
// one whose elements passed the stable step's bound of second-order geometry (`geometry_bound`,
// from loop.geometry_bound_frame on: its results past that frame are not valid).
struct RunResult {
  std::string error;  // not empty: the run could not be set up
  std::vector<std::string> warnings;
  hil::LoopResult loop;
  std::int64_t steps = 0;  // kernel steps taken
  double wall = 0;         // s, at least 1 ns
  bool diverged = false;
  // Element evaluations past the bound of second-order geometry (State::geometry_bound, with
  // kFaultGeometryBound in State::faults when not 0).
  std::uint64_t geometry_bound = 0;
  char hash[17] = {};  // 16 hex digits
  std::vector<detail::Peak> peaks;
  std::vector<double> last;
  hil::EnergyTotals energy;
  hil::EnergyAccounts accounts;  // the energy books by mechanism at the end (hil/energy.hpp)
};

// Runs an init()ed model on its records through the real-time loop on the virtual clock, as
// ntn-run does: the one run of ntn-run, ntn-run-<model> and the Python module (run()).
template <Sizes S>
RunResult simulate(RunStorage<S> store, const ModelSpec<S>& spec, const ModelInfo& info,
                   std::span<const io::Record> records, const RunRequest& request) {
  RunResult out;
  const Sizes z = sizes_of(view(spec));
  const double period = spec.settings.frame_period;
  const std::int64_t per_frame = store.model.substeps.count;
  hil::OutputHash hash;
  if (!hash.ok()) {
    out.error = "cannot set up the output hash";
    return out;
  }
  // The loop (hil_sim/include/ntn/hil/loop.hpp) on the virtual clock: the frames that hold
  // the steps, the last one cut short; the model file's alarms (they only set the flags).
  hil::LoopConfig config;
  config.period = period;
  config.substeps = static_cast<int>(per_frame);
  config.steps = request.steps;
  config.frames = (request.steps + per_frame - 1) / per_frame;
  config.sampling = request.sampling;
  config.kinetic_limit = std::numeric_limits<double>::infinity();
  config.stop_at_divergence = true;
  config.stop = request.stop;
  config.stop_at_geometry_bound = request.stop_at_geometry_bound;
  std::vector<hil::Alarm> alarms(z.outputs);
  for (std::size_t c = 0; c < alarms.size(); ++c) {
    alarms[c].enabled = info.alarm_limits[c] > 0;
    alarms[c].limit = info.alarm_limits[c];
    alarms[c].hysteresis = info.alarm_hysteresis[c];
  }
  hil::InputGate gate(std::span<const InputSpec>(spec.inputs));
  hil::RecordSource source(records, gate, period, store.model.dt);
  detail::RunSink<S> sink{&store.model,
                          &hash,
                          request.csv,
                          request.csv_flags,
                          period,
                          std::vector<detail::Peak>(z.outputs),
                          std::vector<double>(z.outputs),
                          0,
                          {},
                          nullptr,
                          request.frames,
                          request.energy_frames,
                          request.csv_energy,
                          {}};
  if (request.frames != nullptr)
    request.frames->reserve(request.frames->size() +
                            static_cast<std::size_t>(config.frames) * z.outputs);
  if (request.energy_frames != nullptr)
    request.energy_frames->reserve(request.energy_frames->size() +
                                   static_cast<std::size_t>(config.frames) *
                                       hil::kEnergyChannels.size());
  sink.row.reserve(z.outputs + hil::kEnergyChannels.size());
  sink.energy.reserve(store.model.dofs());
  hil::VirtualClock clock;
  hil::FrameTimes times;  // not kept: no latency on the virtual clock

  // The workers are made before the run (and the partition built): none is made in the loop.
  hil::WorkerTeam workers({request.threads, -1});
  out.warnings = workers.warnings();
  const Team team = workers.team();
  const bool with_team =
      request.threads > 1 && prepare_team(store.model, request.threads, store.team_work);
  const auto t0 = std::chrono::steady_clock::now();
  out.loop = hil::run_loop(store.model, store.state, store.scratch, clock, source, sink, nullptr,
                           config, alarms, times, static_cast<State<S>*>(nullptr),
                           with_team ? &team : nullptr, &store.team_work, store.buffers);
  // At least 1 ns: a run of one step on a coarse clock must not print an infinite speed.
  out.wall =
      std::max(1e-9, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  out.steps = sink.steps;
  out.diverged = out.loop.diverged_frame >= 0;
  out.geometry_bound = store.state.geometry_bound;
  std::snprintf(out.hash, sizeof out.hash, "%016llx",
                static_cast<unsigned long long>(hash.finish(store.state)));
  out.peaks = std::move(sink.peaks);
  out.last = std::move(sink.last);
  out.energy = sink.energy.numbers();
  out.accounts = sink.energy.accounts(store.model, store.state);
  return out;
}

}  // namespace ntn::run
