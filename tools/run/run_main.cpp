// ntn-run-<model>: runs one compiled model on recorded inputs as fast as possible and writes
// the response as CSV with a one-screen summary. The model comes from the header that
// ntn_add_model() generated (NTN_MODEL_HEADER, namespace NTN_MODEL_NS).
//
// The run is the real-time loop's (hil_sim: ntn::hil::run_loop on the virtual clock, the record
// source, the CSV sink and the output hash), so that for the same --sampling this program and
// `ntn-hil-<model> run --clock virtual` compute the same steps, hash and CSV. What differs from
// ntn-hil: the length is ceil(duration / dt) kernel steps (the last frame may be cut short), the
// inputs are fed at every kernel step by default (--sampling step), every record sample is
// checked against the input's range before the run, no kinetic energy limit (a run is diverged
// when its state is no longer finite) and the run ends at the frame that diverged.
#include <CLI/CLI.hpp>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "cli.hpp"  // tools/io
#include "ntn/hil/clock.hpp"
#include "ntn/hil/csv_sink.hpp"
#include "ntn/hil/energy.hpp"
#include "ntn/hil/gate.hpp"
#include "ntn/hil/loop.hpp"
#include "ntn/hil/output_hash.hpp"
#include "ntn/hil/record_source.hpp"
#include "ntn/hil/sampling.hpp"
#include "ntn/hil/worker_team.hpp"
#include "ntn/hil/yield_report.hpp"
#include "ntn/kernel.hpp"
#include "record.hpp"
#include NTN_MODEL_HEADER

namespace {

namespace mdl = NTN_MODEL_NS;
constexpr ntn::Sizes kS = mdl::kSizes;

// Static storage: the kernel never allocates, and large models do not fit on the stack.
ntn::Model<kS> g_model;
ntn::InitWorkspace<kS> g_init_work;  // what init() works in (static: no heap, little stack)
ntn::State<kS> g_state;
ntn::Scratch<kS> g_scratch;
ntn::TeamWork<kS> g_team_work;  // the multi-core step's partition and end forces (--threads)

struct Peak {
  double value = 0;  // largest |value|
  double time = 0;   // s
};

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

bool is_translation(const ntn::OutputSpec& o) {
  return o.dof < 3;
}

// The most steps one run takes: t = n dt stays exact in a double far beyond it, and at ~1 us a
// step it is 12 days of wall time. A longer run is a slip of --duration (or of a record's DT).
constexpr double kMaxSteps = 1e12;

// The loop's sink: every kernel step's outputs into the output hash and the peaks (at the step's
// time), every frame's outputs as a CSV row (with the loop's flags under --flags).
struct RunSink {
  ntn::hil::OutputHash* hash;
  ntn::hil::CsvWriter* csv;
  bool flags = false;
  double period = 1e-3;
  std::array<Peak, kS.outputs> peaks{};
  std::array<double, kS.outputs> last{};  // the channels at the last step (residual drifts)
  std::int64_t steps = 0;
  ntn::hil::EnergyBalance<kS> energy;  // the run's work-energy identity (hil/energy.hpp)
  void after_start(const ntn::State<kS>& s, const ntn::Scratch<kS>&) { energy.begin(g_model, s); }
  void after_step(const ntn::State<kS>& s, const ntn::Scratch<kS>& w) {
    ++steps;
    energy.after_step(g_model, s, w);
    hash->add_step(w);
    last = w.outputs;
    for (std::size_t c = 0; c < peaks.size(); ++c) {
      const double v = std::abs(w.outputs[c]);
      if (v > peaks[c].value) peaks[c] = {v, w.time};
    }
  }
  void frame_outputs(std::int64_t k, std::span<const double> v, std::uint16_t f) {
    if (!csv->is_open()) return;
    if (flags) {
      csv->row(static_cast<double>(k) * period, v, f);
    } else {
      csv->row(static_cast<double>(k) * period, v);
    }
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Run the model '" + std::string(mdl::kName) + "' (" + std::string(mdl::kSourceFile) +
               ") on recorded inputs"};
  std::vector<std::string> input_args;
  double duration = -1;
  std::string out_path;
  std::string json_path;
  std::string sampling_name = "step";
  bool quiet = false;
  bool flags = false;
  std::string element_pass = "simd";
  int threads = 1;
  app.add_option("-i,--input", input_args,
                 "NAME=FILE: feed input channel NAME from a record (AT2 or CSV; "
                 "FILE:COLUMN picks a CSV column; values are converted to the input's unit)");
  app.add_option("-t,--duration", duration, "simulated time in s (default: longest record)")
      ->check(ntn::cli::Positive());
  app.add_option("-s,--sampling", sampling_name,
                 "step (the records at every kernel step; default), hold (at frame times, held "
                 "over the frame) or interpolate (at frame times, linear over the frame, one "
                 "frame of delay): hold and interpolate are what ntn-hil's loop does")
      ->check(CLI::IsMember({"step", "hold", "interpolate"}));
  app.add_option("-o,--out", out_path, "CSV file for the response, one row per I/O frame");
  app.add_flag("--flags", flags,
               "add the loop's flags column to the CSV (input gate, alarm, diverged bits), as "
               "ntn-hil writes it");
  app.add_option("--summary-json", json_path, "also write the summary as JSON");
  app.add_flag("-q,--quiet", quiet, "print only errors and the output hash");
  app.add_option("--element-pass", element_pass,
                 "simd (default: the widest vectors this CPU has) or scalar (the reference): the "
                 "same bits either way")
      ->check(CLI::IsMember({"simd", "scalar"}));
  app.add_option("--threads", threads,
                 "workers of the multi-core step (1 = the caller's thread alone): the same bits "
                 "for any number")
      ->check(ntn::cli::Integer(1, ntn::kMaxTeam));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints the message (or --help)
    return code == 0 ? 0 : 2;      // a usage error is bad input: 2, as every ntn tool
  }
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
  std::array<ntn::io::Record, kS.inputs> records{};
  std::array<bool, kS.inputs> fed{};
  for (const ntn::cli::InputArg& in : inputs.args) {
    std::size_t k = kS.inputs;  // the channel; kS.inputs: none
    for (std::size_t c = 0; c < kS.inputs; ++c) {
      if (mdl::kInputNames[c] == in.name) k = c;
    }
    if (k == kS.inputs) {
      std::fprintf(stderr, "error: --input %s: the model has no input channel '%s'\n",
                   in.name.c_str(), in.name.c_str());
      return 2;
    }
    if (const auto e = ntn::hil::load_input_record(mdl::kSpec.inputs[k], in.name, in.file,
                                                   in.column, true, records[k])) {
      std::fprintf(stderr, "%s\n", e->c_str());
      return 2;
    }
    fed[k] = true;
  }
  double record_duration = 0;
  std::string longest;
  for (std::size_t k = 0; k < kS.inputs; ++k) {
    const auto& r = records[k];
    if (!fed[k]) {
      std::fprintf(stderr, "error: no record for input channel '%s' (use --input %s=FILE)\n",
                   std::string(mdl::kInputNames[k]).c_str(),
                   std::string(mdl::kInputNames[k]).c_str());
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

  if (const ntn::InitStatus st = ntn::init(mdl::kSpec, g_model, g_init_work); !st.ok()) {
    std::fprintf(stderr, "error: model '%s': %s (at %d)\n", std::string(mdl::kName).c_str(),
                 ntn::to_string(st.error), st.where);
    return 1;
  }
  g_model.element_pass =
      element_pass == "scalar" ? ntn::ElementPass::kScalar : ntn::ElementPass::kSimd;
  const double dt = g_model.dt;
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
  const double period = mdl::kSpec.settings.frame_period;
  // N by the kernel's frame rule (ntn::frame_substeps), stored once by init; the model compiler
  // checked it.
  const ntn::Substeps& substeps = g_model.substeps;
  if (!substeps.ok()) {
    std::fprintf(stderr, "error: model '%s': dt = %g s, frame period %g s: %s\n",
                 std::string(mdl::kName).c_str(), dt, period, ntn::to_string(substeps.error));
    return 1;
  }
  const std::int64_t per_frame = substeps.count;

  ntn::hil::CsvWriter csv;
  if (!out_path.empty() && !csv.open(out_path)) {
    std::fprintf(stderr, "error: --out: cannot write '%s': %s\n", out_path.c_str(),
                 csv.error().c_str());
    return 2;
  }
  csv.header(mdl::kOutputNames, mdl::kOutputUnits, flags);
  ntn::hil::OutputHash hash;
  if (!hash.ok()) {
    std::fprintf(stderr, "error: cannot set up the output hash\n");
    return 2;
  }

  // The loop (hil_sim/include/ntn/hil/loop.hpp) on the virtual clock: the frames that hold
  // the steps, the last one cut short; the model file's alarms (they only set the flags).
  ntn::hil::LoopConfig config;
  config.period = period;
  config.substeps = static_cast<int>(per_frame);
  config.steps = steps;
  config.frames = (steps + per_frame - 1) / per_frame;
  config.sampling = sampling;
  config.kinetic_limit = std::numeric_limits<double>::infinity();
  config.stop_at_divergence = true;
  std::vector<ntn::hil::Alarm> alarms(kS.outputs);
  for (std::size_t c = 0; c < alarms.size(); ++c) {
    alarms[c].enabled = mdl::kAlarmLimits[c] > 0;
    alarms[c].limit = mdl::kAlarmLimits[c];
    alarms[c].hysteresis = mdl::kAlarmHysteresis[c];
  }
  ntn::hil::InputGate gate(std::span<const ntn::InputSpec>(mdl::kSpec.inputs));
  ntn::hil::RecordSource source(records, gate, period, dt);
  RunSink sink{&hash, &csv, flags, period, {}, {}, 0, {}};
  ntn::hil::VirtualClock clock;
  ntn::hil::FrameTimes times;  // not kept: no latency on the virtual clock

  // The workers are made before the run (and the partition built): none is made in the loop.
  ntn::hil::WorkerTeam workers({threads, -1});
  for (const std::string& w : workers.warnings())
    std::fprintf(stderr, "warning: %s\n", w.c_str());
  const ntn::Team team = workers.team();
  const bool with_team = threads > 1 && ntn::prepare_team(g_model, threads, g_team_work);
  const auto t0 = std::chrono::steady_clock::now();
  const ntn::hil::LoopResult result = ntn::hil::run_loop(
      g_model, g_state, g_scratch, clock, source, sink, nullptr, config, alarms, times,
      static_cast<ntn::State<kS>*>(nullptr), with_team ? &team : nullptr, &g_team_work);
  // At least 1 ns: a run of one step on a coarse clock must not print an infinite speed.
  const double wall =
      std::max(1e-9, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  const std::int64_t n = sink.steps;
  const bool diverged = result.diverged_frame >= 0;
  char digest[17];
  std::snprintf(digest, sizeof digest, "%016llx",
                static_cast<unsigned long long>(hash.finish(g_state)));

  if (csv.is_open() && !csv.close()) {
    std::fprintf(stderr, "error: --out: writing '%s' failed: %s\n", out_path.c_str(),
                 csv.error().c_str());
    return 2;
  }

  const double simulated = static_cast<double>(n) * dt;
  const auto& peaks = sink.peaks;
  const auto& stable = g_model.stable;
  const int gov = stable.governing_element;
  if (!quiet) {
    std::printf("ntn-run  model %s (%s)\n", std::string(mdl::kName).c_str(),
                std::string(mdl::kSourceFile).c_str());
    for (std::size_t k = 0; k < kS.inputs; ++k) {
      const auto& r = records[k];
      std::string notes;
      if (!r.converted_from.empty()) notes += ", converted from " + r.converted_from;
      if (r.unit_assumed) notes += " (the file states no unit: taken as " + r.units + ")";
      if (r.t0 != 0)
        notes += ", file time " + ntn::cli::num(r.t0) + " s played at t = 0 (its first row)";
      std::printf("  input %-12s %s: %zu samples at %g s, peak %.4g %s%s\n",
                  std::string(mdl::kInputNames[k]).c_str(), r.source.c_str(), r.values.size(), r.dt,
                  r.peak_abs(), r.units.c_str(), notes.c_str());
    }
    std::printf("  size        %zu nodes, %zu elements, %zu hinges, %zu DOFs\n", kS.nodes,
                kS.elements, kS.hinges, 6 * kS.nodes);
    std::printf(
        "  elements    %s pass (%s)\n", element_pass.c_str(),
        g_model.element_pass == ntn::ElementPass::kSimd ? ntn::element_pass_target() : "reference");
    std::string governing;
    if (stable.governing_hinge >= 0) {
      governing = "hinge " + std::to_string(stable.governing_hinge) + ", direction " +
                  std::to_string(stable.hinge_direction);
    } else {
      governing = "element " + std::to_string(gov) + " of member " +
                  std::string(mdl::kMemberNames[static_cast<std::size_t>(
                      mdl::kSpec.elements[static_cast<std::size_t>(gov)].member)]);
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
    for (std::size_t c = 0; c < kS.outputs; ++c) {
      const auto& o = mdl::kSpec.outputs[c];
      const auto& p = peaks[c];
      const std::string name(mdl::kOutputNames[c]);
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
                    fmt("%.5g", p.value).c_str(), std::string(mdl::kOutputUnits[c]).c_str(),
                    p.time);
      }
    }
    for (std::size_t c = 0; c < kS.outputs; ++c) {
      if (mdl::kSpec.outputs[c].kind != ntn::OutputKind::kDrift) continue;
      std::printf("  residual drift   %-16s %s %% at the end (t = %.3f s)\n",
                  std::string(mdl::kOutputNames[c]).c_str(),
                  fmt("%.5g", 100 * sink.last[c]).c_str(), simulated);
    }
    {
      const auto& e = sink.energy;
      const double hyst = ntn::hil::hysteretic_energy(g_state);
      std::printf(
          "  energy      external work %s J = kinetic %s J + internal %s J (hysteretic %s J) "
          "+ damping %s J; balance residual %.2g of the input\n",
          fmt("%.6g", e.external()).c_str(), fmt("%.4g", e.kinetic() - e.kinetic0()).c_str(),
          fmt("%.6g", e.internal()).c_str(), fmt("%.6g", hyst).c_str(),
          fmt("%.6g", e.damping()).c_str(),
          e.input_scale() > 0 ? std::fabs(e.residual()) / e.input_scale() : 0.0);
    }
    if (const int np = ntn::hil::plastic_directions(g_model); np > 0) {
      const auto yielded = ntn::hil::yielded_directions(g_model, g_state);
      std::printf("  plastic     %zu of %d plastic hinge directions yielded\n", yielded.size(), np);
      for (const auto& y : yielded) {
        const bool rot = y.direction >= 3;
        std::printf("    %-16s %s  peak %s %s, residual %s %s, dissipated %s J, %s\n",
                    std::string(mdl::kHingeNames[static_cast<std::size_t>(y.hinge)]).c_str(),
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
    if (!out_path.empty()) {
      std::printf("  response    %s (%lld rows, one per frame)\n", out_path.c_str(),
                  static_cast<long long>(result.frames));
    }
  }
  std::printf("  output hash %s\n", digest);

  if (!json_path.empty()) {
    errno = 0;
    std::ofstream js(json_path, std::ios::binary | std::ios::trunc);
    js << "{\n  \"model\": \"" << mdl::kName << "\",\n  \"dt\": " << fmt("%.17g", dt)
       << ",\n  \"dt_stable\": " << fmt("%.17g", stable.dt_stable) << ",\n  \"sampling\": \""
       << ntn::hil::to_string(sampling) << "\",\n  \"steps\": " << n
       << ",\n  \"simulated_s\": " << fmt("%.17g", simulated)
       << ",\n  \"wall_s\": " << fmt("%.6g", wall)
       << ",\n  \"real_time_factor\": " << fmt("%.6g", simulated / wall)
       << ",\n  \"diverged\": " << (diverged ? "true" : "false") << ",\n  \"output_hash\": \""
       << digest << "\",\n  \"peaks\": {";
    for (std::size_t c = 0; c < kS.outputs; ++c) {
      js << (c ? ",\n" : "\n") << "    \"" << mdl::kOutputNames[c]
         << "\": {\"abs\": " << fmt("%.17g", peaks[c].value)
         << ", \"time\": " << fmt("%.9g", peaks[c].time) << "}";
    }
    js << "\n  },\n  \"end\": {";
    for (std::size_t c = 0; c < kS.outputs; ++c) {
      js << (c ? ",\n" : "\n") << "    \"" << mdl::kOutputNames[c]
         << "\": " << fmt("%.17g", sink.last[c]);
    }
    const auto& bal = sink.energy;
    js << "\n  },\n  \"energy_J\": {\"external\": " << fmt("%.17g", bal.external())
       << ", \"kinetic_change\": " << fmt("%.17g", bal.kinetic() - bal.kinetic0())
       << ", \"internal\": " << fmt("%.17g", bal.internal())
       << ", \"hysteretic\": " << fmt("%.17g", ntn::hil::hysteretic_energy(g_state))
       << ", \"damping\": " << fmt("%.17g", bal.damping())
       << ", \"residual\": " << fmt("%.17g", bal.residual()) << "},\n  \"yielded\": [";
    const auto yielded = ntn::hil::yielded_directions(g_model, g_state);
    for (std::size_t i = 0; i < yielded.size(); ++i) {
      const auto& y = yielded[i];
      js << (i ? ",\n" : "\n") << "    {\"hinge\": \""
         << mdl::kHingeNames[static_cast<std::size_t>(y.hinge)]
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
  return diverged ? 3 : 0;
}
