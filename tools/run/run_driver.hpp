// The run of ntn-run and of the compiled runners ntn-run-<model> (tools/run/README.md): one
// template over the model's storage, compiled (a model header, static storage) or run-time (a
// model file loaded when the program starts, one block bound before init). Both run the same
// lines on the same kernel code: the same model and records give the same bits either way.
#pragma once

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
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
};

// What a run gives: the loop's result, the output hash (every output of every step, then the
// final state: XXH3), per channel the peak |value| and its time and the value at the last step,
// the energy balance. Not an error: a run that diverged (`diverged`, the loop's safe state).
struct RunResult {
  std::string error;  // not empty: the run could not be set up
  std::vector<std::string> warnings;
  hil::LoopResult loop;
  std::int64_t steps = 0;  // kernel steps taken
  double wall = 0;         // s, at least 1 ns
  bool diverged = false;
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
  std::snprintf(out.hash, sizeof out.hash, "%016llx",
                static_cast<unsigned long long>(hash.finish(store.state)));
  out.peaks = std::move(sink.peaks);
  out.last = std::move(sink.last);
  out.energy = sink.energy.numbers();
  out.accounts = sink.energy.accounts(store.model, store.state);
  return out;
}

// Runs the model on the options' records and prints the summary; the program's exit code.
template <Sizes S>
int run_model(const RunOptions& options, const ModelInfo& info, const ModelSpec<S>& spec,
              RunStorage<S> store) {
  using detail::fmt;
  using detail::is_translation;
  using detail::kMaxSteps;
  using detail::Peak;
  using detail::RunSink;
  const Sizes z = sizes_of(view(spec));
  const RunOptions& opt = options;
  const std::vector<std::string>& input_args = opt.input_args;
  double duration = opt.duration;
  const std::string& out_path = opt.out_path;
  const std::string& json_path = opt.json_path;
  const std::string& sampling_name = opt.sampling_name;
  const bool quiet = opt.quiet;
  const bool flags = opt.flags;
  const std::string& element_pass = opt.element_pass;
  const int threads = opt.threads;
  const ntn::hil::InputSampling sampling = *ntn::hil::parse_sampling(sampling_name);

  // Output files: found unwritable before the run, not after it (the --out directory is
  // created, as a build step writing into a build tree wants).
  for (const auto& [path, option] : {std::pair{out_path, "--out"}, {json_path, "--summary-json"}}) {
    if (path.empty()) continue;
    if (const auto problem = ntn::cli::output_path_problem(path, option, true)) {
      std::fprintf(stderr, "error: %s\n", problem->c_str());
      return 2;
    }
  }

  // Records for the input channels, by name, in each input's unit, every sample in range.
  const ntn::cli::InputArgs inputs = ntn::cli::parse_input_args(input_args, "--input");
  if (inputs.error) {
    std::fprintf(stderr, "error: %s\n", inputs.error->c_str());
    return 2;
  }
  std::vector<ntn::io::Record> records;
  std::vector<char> fed;
  if (const auto e = ntn::hil::load_input_records(spec.inputs, info.input_names, inputs.args, true,
                                                  records, fed)) {
    std::fprintf(stderr, "%s\n", e->c_str());
    return 2;
  }
  double record_duration = 0;
  std::string longest;
  for (std::size_t k = 0; k < z.inputs; ++k) {
    const auto& r = records[k];
    if (!fed[k]) {
      std::fprintf(stderr, "error: no record for input channel '%s' (use --input %s=FILE)\n",
                   std::string(info.input_names[k]).c_str(),
                   std::string(info.input_names[k]).c_str());
      return 2;
    }
    if (r.duration() > record_duration) record_duration = r.duration(), longest = r.source;
  }
  const bool from_records = duration < 0;
  if (from_records) duration = record_duration;  // default: the longest record
  if (!(duration > 0)) {
    std::fprintf(stderr, "error: give --duration (the model has no input records)\n");
    return 2;
  }

  if (const ntn::InitStatus st = ntn::init(spec, store.model, store.init_work); !st.ok()) {
    std::fprintf(stderr, "error: model '%s': %s (at %d)\n", std::string(info.name).c_str(),
                 ntn::to_string(st.error), st.where);
    return 1;
  }
  store.model.element_pass =
      element_pass == "scalar" ? ntn::ElementPass::kScalar : ntn::ElementPass::kSimd;
  const double dt = store.model.dt;
  // The step count as a checked integer: compared as a double before any conversion or
  // allocation, and a run of no step at all is refused (it would report nothing as success).
  const std::string what =
      from_records ? "the longest record (" + longest + ", " + ntn::cli::num(duration) + " s)"
                   : "--duration " + ntn::cli::num(duration) + " s";
  const double wanted_steps = std::ceil(duration / dt - 1e-9);
  if (!(wanted_steps <= kMaxSteps)) {
    std::fprintf(stderr, "error: %s is %s steps of dt = %g s; a run takes at most %g steps\n",
                 what.c_str(), ntn::cli::num(wanted_steps).c_str(), dt, kMaxSteps);
    return 2;
  }
  if (!(wanted_steps >= 1)) {
    std::fprintf(stderr, "error: %s is shorter than one time step (dt = %g s): nothing would run\n",
                 what.c_str(), dt);
    return 2;
  }
  const auto steps = static_cast<std::int64_t>(wanted_steps);
  const double period = spec.settings.frame_period;
  // N by the kernel's frame rule (ntn::frame_substeps), stored once by init; the model compiler
  // checked it.
  const ntn::Substeps& substeps = store.model.substeps;
  if (!substeps.ok()) {
    std::fprintf(stderr, "error: model '%s': dt = %g s, frame period %g s: %s\n",
                 std::string(info.name).c_str(), dt, period, ntn::to_string(substeps.error));
    return 1;
  }
  const std::int64_t per_frame = substeps.count;

  ntn::hil::CsvWriter csv;
  if (!out_path.empty() && !csv.open(out_path)) {
    std::fprintf(stderr, "error: --out: cannot write '%s': %s\n", out_path.c_str(),
                 csv.error().c_str());
    return 2;
  }
  std::vector<std::string_view> names(info.output_names.begin(), info.output_names.end());
  std::vector<std::string_view> units(info.output_units.begin(), info.output_units.end());
  std::vector<std::string> energy_names;
  if (opt.energy) {
    for (const std::string_view a : ntn::hil::kEnergyChannels)
      energy_names.push_back("energy_" + std::string(a));
    for (const std::string& a : energy_names)
      names.push_back(a), units.push_back("J");
  }
  csv.header(names, units, flags);
  RunRequest request;
  request.csv_energy = opt.energy;
  // SIGINT / SIGTERM from here on end the run after the frame in progress, with the CSV and the
  // summary written (exit 4), as ntn-hil does.
  ntn::hil::catch_stop_signals();
  request.stop = &ntn::hil::g_stop_signal;
  request.steps = steps;
  request.sampling = sampling;
  request.threads = threads;
  request.csv = csv.is_open() ? &csv : nullptr;
  request.csv_flags = flags;
  const RunResult run = simulate(store, spec, info, records, request);
  for (const std::string& w : run.warnings)
    std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (!run.error.empty()) {
    std::fprintf(stderr, "error: %s\n", run.error.c_str());
    return 2;
  }
  const ntn::hil::LoopResult& result = run.loop;
  const double wall = run.wall;
  const std::int64_t n = run.steps;
  const bool diverged = run.diverged;
  const char* digest = run.hash;
  const auto& sink = run;  // peaks, last, energy

  if (csv.is_open() && !csv.close()) {
    std::fprintf(stderr, "error: --out: writing '%s' failed: %s\n", out_path.c_str(),
                 csv.error().c_str());
    return 2;
  }

  const double simulated = static_cast<double>(n) * dt;
  const auto& peaks = sink.peaks;
  const auto& stable = store.model.stable;
  const int gov = stable.governing_element;
  if (!quiet) {
    std::printf("ntn-run  model %s (%s)\n", std::string(info.name).c_str(),
                std::string(info.source_file).c_str());
    for (std::size_t k = 0; k < z.inputs; ++k) {
      const auto& r = records[k];
      std::string notes;
      if (!r.converted_from.empty()) notes += ", converted from " + r.converted_from;
      if (r.unit_assumed) notes += " (the file states no unit: taken as " + r.units + ")";
      if (r.t0 != 0)
        notes += ", file time " + ntn::cli::num(r.t0) + " s played at t = 0 (its first row)";
      if (r.scaled_by != 1) notes += ", scaled by " + ntn::cli::num(r.scaled_by) + " (FILE*FACTOR)";
      if (spec.inputs[k].factor != 1)
        notes += ", then by the model file's scale " + ntn::cli::num(spec.inputs[k].factor);
      std::printf("  input %-12s %s: %zu samples at %g s, peak %.4g %s%s\n",
                  std::string(info.input_names[k]).c_str(), r.source.c_str(), r.values.size(), r.dt,
                  r.peak_abs(), r.units.c_str(), notes.c_str());
    }
    std::printf("  size        %zu nodes, %zu elements, %zu hinges, %zu DOFs\n", z.nodes,
                z.elements, z.hinges, 6 * z.nodes);
    std::printf("  elements    %s pass (%s)\n", element_pass.c_str(),
                store.model.element_pass == ntn::ElementPass::kSimd ? ntn::element_pass_target()
                                                                    : "reference");
    std::string governing;
    if (stable.governing_hinge >= 0) {
      governing = "hinge " + std::to_string(stable.governing_hinge) + ", direction " +
                  std::to_string(stable.hinge_direction);
    } else {
      governing = "element " + std::to_string(gov) + " of member " +
                  std::string(info.member_names[static_cast<std::size_t>(
                      spec.elements[static_cast<std::size_t>(gov)].member)]);
    }
    std::printf("  time step   dt = %.6g s (stable %.6g s, %s), %lld per %g ms frame\n", dt,
                stable.dt_stable, governing.c_str(), static_cast<long long>(per_frame),
                period * 1e3);
    if (sampling != ntn::hil::InputSampling::kStep) {
      std::printf("  sampling    %s: inputs at frame times%s\n", ntn::hil::to_string(sampling),
                  sampling == ntn::hil::InputSampling::kFrameHeld
                      ? ", held over the frame"
                      : ", linear over the frame (one frame of delay)");
    }
    std::printf(
        "  run         %lld steps, %.3f s simulated, wall %.3f s, real-time factor %.1fx, "
        "%.3f us/step\n",
        static_cast<long long>(n), simulated, wall, simulated / wall,
        wall / static_cast<double>(n) * 1e6);
    for (std::size_t c = 0; c < z.outputs; ++c) {
      const auto& o = spec.outputs[c];
      const auto& p = peaks[c];
      const std::string name(info.output_names[c]);
      if (o.kind == ntn::OutputKind::kDrift) {
        std::printf("  peak drift       %-16s %s %% at t = %.3f s\n", name.c_str(),
                    fmt("%.5g", 100 * p.value).c_str(), p.time);
      } else if (o.kind == ntn::OutputKind::kReaction) {
        std::printf("  peak base %s %-16s %s %s at t = %.3f s\n",
                    is_translation(o) ? "shear " : "moment", name.c_str(),
                    fmt("%.5g", p.value / 1e3).c_str(), is_translation(o) ? "kN" : "kN m", p.time);
      } else if (o.kind == ntn::OutputKind::kHingeForce) {
        std::printf("  peak hinge force %-16s %s %s at t = %.3f s\n", name.c_str(),
                    fmt("%.4g", p.value / 1e3).c_str(), o.dof < 3 ? "kN" : "kN m", p.time);
      } else {
        std::printf("  peak             %-16s %s %s at t = %.3f s\n", name.c_str(),
                    fmt("%.5g", p.value).c_str(), std::string(info.output_units[c]).c_str(),
                    p.time);
      }
    }
    for (std::size_t c = 0; c < z.outputs; ++c) {
      if (spec.outputs[c].kind != ntn::OutputKind::kDrift) continue;
      std::printf("  residual drift   %-16s %s %% at the end (t = %.3f s)\n",
                  std::string(info.output_names[c]).c_str(),
                  fmt("%.5g", 100 * sink.last[c]).c_str(), simulated);
    }
    {
      const auto& e = run.accounts;
      std::printf(
          "  energy      external work %s J = kinetic %s J + elastic %s J + viscous %s J + "
          "hysteretic %s J + friction %s J + impacts %s J + fracture %s J; balance residual "
          "%.2g of the input\n",
          fmt("%.6g", e.external).c_str(), fmt("%.4g", e.kinetic).c_str(),
          fmt("%.6g", e.elastic).c_str(), fmt("%.6g", e.viscous).c_str(),
          fmt("%.6g", e.hysteretic).c_str(), fmt("%.6g", e.friction).c_str(),
          fmt("%.6g", e.impacts).c_str(), fmt("%.6g", e.fracture).c_str(), e.relative_residual());
    }
    if (const int np = ntn::hil::plastic_directions(store.model); np > 0) {
      const auto yielded = ntn::hil::yielded_directions(store.model, store.state);
      std::printf("  plastic     %zu of %d plastic hinge directions yielded\n", yielded.size(), np);
      for (const auto& y : yielded) {
        const bool rot = y.direction >= 3;
        std::printf("    %-16s %s  peak %s %s, residual %s %s, dissipated %s J, %s\n",
                    std::string(info.hinge_names[static_cast<std::size_t>(y.hinge)]).c_str(),
                    ntn::hil::direction_name(y.direction), fmt("%.4g", y.peak).c_str(),
                    rot ? "rad" : "m", fmt("%.4g", y.residual).c_str(), rot ? "rad" : "m",
                    fmt("%.4g", y.dissipated).c_str(), ntn::hil::level_name(y.level, y.has_limits));
        if (y.first_slip >= 0)  // a rigid-plastic direction's event
          std::printf("      %s at t = %s s\n", y.failed ? "failed" : "first slid",
                      fmt("%.6g", y.first_slip).c_str());
      }
    }
    if (result.input_held_frames > 0)
      std::printf(
          "  inputs held %llu frames had an input the gate refused (last good value held)\n",
          static_cast<unsigned long long>(result.input_held_frames));
    if (diverged)
      std::printf("  DIVERGED    the state became non-finite at step %lld\n",
                  static_cast<long long>(n));
    if (result.stopped)
      std::printf("  STOPPED     by %s after %lld of %lld frames (%.3f s simulated)\n",
                  ntn::hil::stop_signal_name(), static_cast<long long>(result.frames),
                  static_cast<long long>((steps + per_frame - 1) / per_frame), simulated);
    if (!out_path.empty()) {
      std::printf("  response    %s (%lld rows, one per frame)\n", out_path.c_str(),
                  static_cast<long long>(result.frames));
    }
  }
  std::printf("  output hash %s\n", digest);

  if (!json_path.empty()) {
    errno = 0;
    std::ofstream js(json_path, std::ios::binary | std::ios::trunc);
    js << "{\n  \"model\": \"" << info.name << "\",\n  \"dt\": " << fmt("%.17g", dt)
       << ",\n  \"dt_stable\": " << fmt("%.17g", stable.dt_stable) << ",\n  \"sampling\": \""
       << ntn::hil::to_string(sampling) << "\",\n  \"steps\": " << n
       << ",\n  \"simulated_s\": " << fmt("%.17g", simulated)
       << ",\n  \"wall_s\": " << fmt("%.6g", wall)
       << ",\n  \"real_time_factor\": " << fmt("%.6g", simulated / wall)
       << ",\n  \"diverged\": " << (diverged ? "true" : "false") << ",\n  \"stopped_by\": "
       << (result.stopped ? "\"" + std::string(ntn::hil::stop_signal_name()) + "\""
                          : std::string("null"))
       << ",\n  \"output_hash\": \"" << digest << "\",\n  \"peaks\": {";
    for (std::size_t c = 0; c < z.outputs; ++c) {
      js << (c ? ",\n" : "\n") << "    \"" << info.output_names[c]
         << "\": {\"abs\": " << fmt("%.17g", peaks[c].value)
         << ", \"time\": " << fmt("%.9g", peaks[c].time) << "}";
    }
    js << "\n  },\n  \"end\": {";
    for (std::size_t c = 0; c < z.outputs; ++c) {
      js << (c ? ",\n" : "\n") << "    \"" << info.output_names[c]
         << "\": " << fmt("%.17g", sink.last[c]);
    }
    const auto& bal = run.accounts;
    js << "\n  },\n  \"energy_J\": {\"external\": " << fmt("%.17g", bal.external)
       << ", \"kinetic_change\": " << fmt("%.17g", bal.kinetic)
       << ", \"elastic\": " << fmt("%.17g", bal.elastic)
       << ", \"viscous\": " << fmt("%.17g", bal.viscous)
       << ", \"hysteretic\": " << fmt("%.17g", bal.hysteretic)
       << ", \"friction\": " << fmt("%.17g", bal.friction)
       << ", \"impacts\": " << fmt("%.17g", bal.impacts)
       << ", \"fracture\": " << fmt("%.17g", bal.fracture)
       << ", \"residual\": " << fmt("%.17g", bal.residual) << "},\n  \"yielded\": [";
    const auto yielded = ntn::hil::yielded_directions(store.model, store.state);
    for (std::size_t i = 0; i < yielded.size(); ++i) {
      const auto& y = yielded[i];
      js << (i ? ",\n" : "\n") << "    {\"hinge\": \""
         << info.hinge_names[static_cast<std::size_t>(y.hinge)]
         << "\", \"direction\": " << y.direction << ", \"peak\": " << fmt("%.17g", y.peak)
         << ", \"residual\": " << fmt("%.17g", y.residual)
         << ", \"dissipated_J\": " << fmt("%.17g", y.dissipated) << ", \"level\": " << y.level;
      if (y.first_slip >= 0)
        js << ", \"first_slip_s\": " << fmt("%.17g", y.first_slip)
           << ", \"failed\": " << (y.failed ? "true" : "false");
      js << "}";
    }
    js << "\n  ]\n}\n";
    if (auto e = ntn::cli::close_output(js, "--summary-json", json_path)) {
      std::fprintf(stderr, "error: %s\n", e->c_str());
      return 2;
    }
  }
  if (result.stopped) {
    std::fprintf(stderr, "stopped by %s after %lld frames\n", ntn::hil::stop_signal_name(),
                 static_cast<long long>(result.frames));
  }
  // Exit codes (README): 2 a file could not be written, 3 diverged, 4 stopped by SIGINT /
  // SIGTERM, 0 otherwise.
  if (diverged) return 3;
  return result.stopped ? 4 : 0;
}

}  // namespace ntn::run
