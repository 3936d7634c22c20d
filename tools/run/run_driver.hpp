// The run of ntn-run and of the compiled runners ntn-run-<model> (tools/run/README.md): one
// template over the model's storage, compiled (a model header, static storage) or run-time (a
// model file loaded when the program starts, one block bound before init). Both run the same
// lines on the same kernel code: the same model and records give the same bits either way. The
// run itself is run_simulate.hpp (simulate), its summary run_summary.hpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cli.hpp"  // tools/io
#include "ntn/hil/csv_sink.hpp"
#include "ntn/hil/energy.hpp"
#include "ntn/hil/geometry_report.hpp"
#include "ntn/hil/record_source.hpp"
#include "ntn/hil/sampling.hpp"
#include "ntn/hil/stop_signals.hpp"
#include "ntn/kernel.hpp"
#include "record.hpp"
#include "run_simulate.hpp"
#include "run_summary.hpp"

namespace ntn::run {

namespace detail {

// The records a run is fed and how long it runs: the records for the input channels, by name, in
// each input's unit, every sample in range; the duration, given or the longest record's.
struct RunInputs {
  std::vector<io::Record> records;
  double duration = 0;        // s
  bool from_records = false;  // the duration is the longest record's
  std::string longest;        // that record's source
};

// Output files: found unwritable before the run, not after it (the --out directory is
// created, as a build step writing into a build tree wants).
inline std::optional<int> check_output_paths(const RunOptions& opt) {
  for (const auto& [path, option] :
       {std::pair{opt.out_path, "--out"}, {opt.json_path, "--summary-json"}}) {
    if (path.empty()) continue;
    if (const auto problem = ntn::cli::output_path_problem(path, option, true)) {
      std::fprintf(stderr, "error: %s\n", problem->c_str());
      return 2;
    }
  }
  return std::nullopt;
}

template <Sizes S>
std::optional<int> read_records(const RunOptions& opt, const ModelInfo& info,
                                const ModelSpec<S>& spec, RunInputs& in) {
  const Sizes z = sizes_of(view(spec));
  const ntn::cli::InputArgs inputs = ntn::cli::parse_input_args(opt.input_args, "--input");
  if (inputs.error) {
    std::fprintf(stderr, "error: %s\n", inputs.error->c_str());
    return 2;
  }
  std::vector<char> fed;
  if (const auto e = ntn::hil::load_input_records(spec.inputs, info.input_names, inputs.args, true,
                                                  in.records, fed)) {
    std::fprintf(stderr, "%s\n", e->c_str());
    return 2;
  }
  double record_duration = 0;
  for (std::size_t k = 0; k < z.inputs; ++k) {
    const auto& r = in.records[k];
    if (!fed[k]) {
      std::fprintf(stderr, "error: no record for input channel '%s' (use --input %s=FILE)\n",
                   std::string(info.input_names[k]).c_str(),
                   std::string(info.input_names[k]).c_str());
      return 2;
    }
    if (r.duration() > record_duration) record_duration = r.duration(), in.longest = r.source;
  }
  in.duration = opt.duration;
  in.from_records = in.duration < 0;
  if (in.from_records) in.duration = record_duration;  // default: the longest record
  if (!(in.duration > 0)) {
    std::fprintf(stderr, "error: give --duration (the model has no input records)\n");
    return 2;
  }
  return std::nullopt;
}

// ntn::init into the caller's storage, and the element pass the options chose.
template <Sizes S>
std::optional<int> init_model(const RunOptions& opt, const ModelInfo& info,
                              const ModelSpec<S>& spec, const RunStorage<S>& store) {
  if (const ntn::InitStatus st = ntn::init(spec, store.model, store.init_work); !st.ok()) {
    std::fprintf(stderr, "error: model '%s': %s (at %d)\n", std::string(info.name).c_str(),
                 ntn::to_string(st.error), st.where);
    return 1;
  }
  store.model.element_pass =
      opt.element_pass == "scalar" ? ntn::ElementPass::kScalar : ntn::ElementPass::kSimd;
  return std::nullopt;
}

// The step count as a checked integer: compared as a double before any conversion or
// allocation, and a run of no step at all is refused (it would report nothing as success).
inline std::optional<int> count_steps(const RunInputs& in, double dt, std::int64_t& steps) {
  const std::string what = in.from_records ? "the longest record (" + in.longest + ", " +
                                                 ntn::cli::num(in.duration) + " s)"
                                           : "--duration " + ntn::cli::num(in.duration) + " s";
  const double wanted_steps = std::ceil(in.duration / dt - 1e-9);
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
  steps = static_cast<std::int64_t>(wanted_steps);
  return std::nullopt;
}

// N by the kernel's frame rule (ntn::frame_substeps), stored once by init; the model compiler
// checked it.
template <Sizes S>
std::optional<int> check_substeps(const ModelInfo& info, const ModelSpec<S>& spec,
                                  const Model<S>& model) {
  const ntn::Substeps& substeps = model.substeps;
  if (!substeps.ok()) {
    std::fprintf(stderr, "error: model '%s': dt = %g s, frame period %g s: %s\n",
                 std::string(info.name).c_str(), model.dt, spec.settings.frame_period,
                 ntn::to_string(substeps.error));
    return 1;
  }
  return std::nullopt;
}

// The CSV (--out) and its header: the outputs, then with --energy the energy accounts.
inline std::optional<int> open_csv(const RunOptions& opt, const ModelInfo& info,
                                   hil::CsvWriter& csv) {
  if (!opt.out_path.empty() && !csv.open(opt.out_path)) {
    std::fprintf(stderr, "error: --out: cannot write '%s': %s\n", opt.out_path.c_str(),
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
  csv.header(names, units, opt.flags);
  return std::nullopt;
}

}  // namespace detail

// Runs the model on the options' records and prints the summary; the program's exit code.
template <Sizes S>
int run_model(const RunOptions& options, const ModelInfo& info, const ModelSpec<S>& spec,
              RunStorage<S> store) {
  const RunOptions& opt = options;
  const ntn::hil::InputSampling sampling = *ntn::hil::parse_sampling(opt.sampling_name);
  detail::RunInputs in;
  if (const auto code = detail::check_output_paths(opt)) return *code;
  if (const auto code = detail::read_records(opt, info, spec, in)) return *code;
  if (const auto code = detail::init_model(opt, info, spec, store)) return *code;
  std::int64_t steps = 0;
  if (const auto code = detail::count_steps(in, store.model.dt, steps)) return *code;
  if (const auto code = detail::check_substeps(info, spec, store.model)) return *code;
  ntn::hil::CsvWriter csv;
  if (const auto code = detail::open_csv(opt, info, csv)) return *code;

  RunRequest request;
  request.csv_energy = opt.energy;
  // SIGINT / SIGTERM from here on end the run after the frame in progress, with the CSV and the
  // summary written (exit 4), as ntn-hil does.
  ntn::hil::catch_stop_signals();
  request.stop = &ntn::hil::g_stop_signal;
  request.steps = steps;
  request.sampling = sampling;
  request.threads = opt.threads;
  request.csv = csv.is_open() ? &csv : nullptr;
  request.csv_flags = opt.flags;
  const RunResult run = simulate(store, spec, info, in.records, request);
  for (const std::string& w : run.warnings)
    std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (!run.error.empty()) {
    std::fprintf(stderr, "error: %s\n", run.error.c_str());
    return 2;
  }
  if (csv.is_open() && !csv.close()) {
    std::fprintf(stderr, "error: --out: writing '%s' failed: %s\n", opt.out_path.c_str(),
                 csv.error().c_str());
    return 2;
  }

  const detail::RunReport<S> report{opt, info, spec, store, in.records, run, sampling, steps};
  if (!opt.quiet) detail::print_summary(report);
  // Said on stderr too, with --quiet: the run's results past the bound are not valid.
  if (run.geometry_bound > 0) {
    std::fprintf(stderr,
                 "warning: past the stable step's bound of second-order geometry from t = %.3f s "
                 "(%llu element evaluations); %s\n",
                 static_cast<double>(std::max<std::int64_t>(run.loop.geometry_bound_frame, 0)) *
                     spec.settings.frame_period,
                 static_cast<unsigned long long>(run.geometry_bound),
                 ntn::hil::kGeometryBoundMeaning);
  }
  std::printf("  output hash %s\n", run.hash);
  if (!opt.json_path.empty()) {
    if (auto e = detail::write_summary_json(report)) {
      std::fprintf(stderr, "error: %s\n", e->c_str());
      return 2;
    }
  }
  if (run.loop.stopped) {
    std::fprintf(stderr, "stopped by %s after %lld frames\n", ntn::hil::stop_signal_name(),
                 static_cast<long long>(run.loop.frames));
  }
  // Exit codes (README): 2 a file could not be written, 3 diverged, 4 stopped by SIGINT /
  // SIGTERM, 0 otherwise.
  if (run.diverged) return 3;
  return run.loop.stopped ? 4 : 0;
}

}  // namespace ntn::run
