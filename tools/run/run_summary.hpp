// The summary of a run of ntn-run and ntn-run-<model>: on screen (unless --quiet) and as JSON
// (--summary-json), from the run's result (RunResult, run_simulate.hpp) and the model it ran.
#pragma once

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <optional>
#include <span>
#include <string>

#include "cli.hpp"  // tools/io
#include "ntn/hil/geometry_report.hpp"
#include "ntn/hil/sampling.hpp"
#include "ntn/hil/stop_signals.hpp"
#include "ntn/hil/yield_report.hpp"
#include "ntn/kernel.hpp"
#include "record.hpp"
#include "run_simulate.hpp"

namespace ntn::run::detail {

// What the summary reads: the options, the model, its records and the run's result.
template <Sizes S>
struct RunReport {
  const RunOptions& opt;
  const ModelInfo& info;
  const ModelSpec<S>& spec;
  const RunStorage<S>& store;
  std::span<const io::Record> records;
  const RunResult& run;
  hil::InputSampling sampling;
  std::int64_t steps;  // asked for
  double simulated() const { return static_cast<double>(run.steps) * store.model.dt; }
};

// Each input's record: its file, samples, peak, and what was done to its values.
template <Sizes S>
void print_inputs(const RunReport<S>& r) {
  const Sizes z = sizes_of(view(r.spec));
  for (std::size_t k = 0; k < z.inputs; ++k) {
    const auto& rec = r.records[k];
    std::string notes;
    if (!rec.converted_from.empty()) notes += ", converted from " + rec.converted_from;
    if (rec.unit_assumed) notes += " (the file states no unit: taken as " + rec.units + ")";
    if (rec.t0 != 0)
      notes += ", file time " + ntn::cli::num(rec.t0) + " s played at t = 0 (its first row)";
    if (rec.scaled_by != 1)
      notes += ", scaled by " + ntn::cli::num(rec.scaled_by) + " (FILE*FACTOR)";
    if (r.spec.inputs[k].factor != 1)
      notes += ", then by the model file's scale " + ntn::cli::num(r.spec.inputs[k].factor);
    std::printf("  input %-12s %s: %zu samples at %g s, peak %.4g %s%s\n",
                std::string(r.info.input_names[k]).c_str(), rec.source.c_str(), rec.values.size(),
                rec.dt, rec.peak_abs(), rec.units.c_str(), notes.c_str());
  }
}

// The model's size, the element pass, the time step and what governs it, the sampling, the run.
template <Sizes S>
void print_model_and_run(const RunReport<S>& r) {
  const Sizes z = sizes_of(view(r.spec));
  const Model<S>& model = r.store.model;
  const auto& stable = model.stable;
  const int gov = stable.governing_element;
  std::printf("  size        %zu nodes, %zu elements, %zu hinges, %zu DOFs\n", z.nodes, z.elements,
              z.hinges, 6 * z.nodes);
  std::printf(
      "  elements    %s pass (%s)\n", r.opt.element_pass.c_str(),
      model.element_pass == ntn::ElementPass::kSimd ? ntn::element_pass_target() : "reference");
  std::string governing;
  if (stable.governing_hinge >= 0) {
    governing = "hinge " + std::to_string(stable.governing_hinge) + ", direction " +
                std::to_string(stable.hinge_direction);
  } else {
    governing = "element " + std::to_string(gov) + " of member " +
                std::string(r.info.member_names[static_cast<std::size_t>(
                    r.spec.elements[static_cast<std::size_t>(gov)].member)]);
  }
  std::printf("  time step   dt = %.6g s (stable %.6g s, %s), %lld per %g ms frame\n", model.dt,
              stable.dt_stable, governing.c_str(), static_cast<long long>(model.substeps.count),
              r.spec.settings.frame_period * 1e3);
  if (r.sampling != ntn::hil::InputSampling::kStep) {
    std::printf("  sampling    %s: inputs at frame times%s\n", ntn::hil::to_string(r.sampling),
                r.sampling == ntn::hil::InputSampling::kFrameHeld
                    ? ", held over the frame"
                    : ", linear over the frame (one frame of delay)");
  }
  const double simulated = r.simulated();
  const double wall = r.run.wall;
  const std::int64_t n = r.run.steps;
  std::printf(
      "  run         %lld steps, %.3f s simulated, wall %.3f s, real-time factor %.1fx, "
      "%.3f us/step\n",
      static_cast<long long>(n), simulated, wall, simulated / wall,
      wall / static_cast<double>(n) * 1e6);
}

// Each output's peak |value| in its domain's unit, then the drifts' residuals.
template <Sizes S>
void print_peaks(const RunReport<S>& r) {
  const Sizes z = sizes_of(view(r.spec));
  for (std::size_t c = 0; c < z.outputs; ++c) {
    const auto& o = r.spec.outputs[c];
    const auto& p = r.run.peaks[c];
    const std::string name(r.info.output_names[c]);
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
                  fmt("%.5g", p.value).c_str(), std::string(r.info.output_units[c]).c_str(),
                  p.time);
    }
  }
  for (std::size_t c = 0; c < z.outputs; ++c) {
    if (r.spec.outputs[c].kind != ntn::OutputKind::kDrift) continue;
    std::printf("  residual drift   %-16s %s %% at the end (t = %.3f s)\n",
                std::string(r.info.output_names[c]).c_str(),
                fmt("%.5g", 100 * r.run.last[c]).c_str(), r.simulated());
  }
}

// The energy books, and the plastic hinge directions that yielded.
template <Sizes S>
void print_energy_and_yielding(const RunReport<S>& r) {
  const auto& e = r.run.accounts;
  std::printf(
      "  energy      external work %s J = kinetic %s J + elastic %s J + viscous %s J + "
      "hysteretic %s J + friction %s J + impacts %s J + fracture %s J; balance residual "
      "%.2g of the input\n",
      fmt("%.6g", e.external).c_str(), fmt("%.4g", e.kinetic).c_str(),
      fmt("%.6g", e.elastic).c_str(), fmt("%.6g", e.viscous).c_str(),
      fmt("%.6g", e.hysteretic).c_str(), fmt("%.6g", e.friction).c_str(),
      fmt("%.6g", e.impacts).c_str(), fmt("%.6g", e.fracture).c_str(), e.relative_residual());
  const int np = ntn::hil::plastic_directions(r.store.model);
  if (np <= 0) return;
  const auto yielded = ntn::hil::yielded_directions(r.store.model, r.store.state);
  std::printf("  plastic     %zu of %d plastic hinge directions yielded\n", yielded.size(), np);
  for (const auto& y : yielded) {
    const bool rot = y.direction >= 3;
    std::printf("    %-16s %s  peak %s %s, residual %s %s, dissipated %s J, %s\n",
                std::string(r.info.hinge_names[static_cast<std::size_t>(y.hinge)]).c_str(),
                ntn::hil::direction_name(y.direction), fmt("%.4g", y.peak).c_str(),
                rot ? "rad" : "m", fmt("%.4g", y.residual).c_str(), rot ? "rad" : "m",
                fmt("%.4g", y.dissipated).c_str(), ntn::hil::level_name(y.level, y.has_limits));
    if (y.first_slip >= 0)  // a rigid-plastic direction's event
      std::printf("      %s at t = %s s\n", y.failed ? "failed" : "first slid",
                  fmt("%.6g", y.first_slip).c_str());
  }
}

// How the run ended: inputs held, the bound of second-order geometry, diverged, stopped; where
// the response went.
template <Sizes S>
void print_ending(const RunReport<S>& r) {
  const ntn::hil::LoopResult& result = r.run.loop;
  const std::int64_t per_frame = r.store.model.substeps.count;
  const std::string geometry = ntn::hil::geometry_bound_text(
      r.store.model, r.store.state, result.geometry_bound_frame, r.spec.settings.frame_period);
  if (!geometry.empty()) std::printf("  geometry    %s\n", geometry.c_str());
  if (result.input_held_frames > 0)
    std::printf("  inputs held %llu frames had an input the gate refused (last good value held)\n",
                static_cast<unsigned long long>(result.input_held_frames));
  if (r.run.diverged)
    std::printf("  DIVERGED    the state became non-finite at step %lld\n",
                static_cast<long long>(r.run.steps));
  if (result.stopped)
    std::printf("  STOPPED     by %s after %lld of %lld frames (%.3f s simulated)\n",
                ntn::hil::stop_signal_name(), static_cast<long long>(result.frames),
                static_cast<long long>((r.steps + per_frame - 1) / per_frame), r.simulated());
  if (!r.opt.out_path.empty()) {
    std::printf("  response    %s (%lld rows, one per frame)\n", r.opt.out_path.c_str(),
                static_cast<long long>(result.frames));
  }
}

// The summary on screen (not with --quiet).
template <Sizes S>
void print_summary(const RunReport<S>& r) {
  std::printf("ntn-run  model %s (%s)\n", std::string(r.info.name).c_str(),
              std::string(r.info.source_file).c_str());
  print_inputs(r);
  print_model_and_run(r);
  print_peaks(r);
  print_energy_and_yielding(r);
  print_ending(r);
}

// The summary as JSON (--summary-json): the error of writing it, or nullopt.
template <Sizes S>
std::optional<std::string> write_summary_json(const RunReport<S>& r) {
  const Sizes z = sizes_of(view(r.spec));
  const ModelInfo& info = r.info;
  const RunResult& run = r.run;
  const double simulated = r.simulated();
  errno = 0;
  std::ofstream js(r.opt.json_path, std::ios::binary | std::ios::trunc);
  js << "{\n  \"model\": \"" << info.name << "\",\n  \"dt\": " << fmt("%.17g", r.store.model.dt)
     << ",\n  \"dt_stable\": " << fmt("%.17g", r.store.model.stable.dt_stable)
     << ",\n  \"sampling\": \"" << ntn::hil::to_string(r.sampling)
     << "\",\n  \"steps\": " << run.steps << ",\n  \"simulated_s\": " << fmt("%.17g", simulated)
     << ",\n  \"wall_s\": " << fmt("%.6g", run.wall)
     << ",\n  \"real_time_factor\": " << fmt("%.6g", simulated / run.wall)
     << ",\n  \"diverged\": " << (run.diverged ? "true" : "false") << ",\n  \"geometry_bound\": "
     << ntn::hil::geometry_bound_json(r.store.model, r.store.state, run.loop.geometry_bound_frame,
                                      r.spec.settings.frame_period)
     << ",\n  \"faults\": " << ntn::hil::fault_names_json(r.store.state.faults)
     << ",\n  \"stopped_by\": "
     << (run.loop.stopped ? "\"" + std::string(ntn::hil::stop_signal_name()) + "\""
                          : std::string("null"))
     << ",\n  \"output_hash\": \"" << run.hash << "\",\n  \"peaks\": {";
  for (std::size_t c = 0; c < z.outputs; ++c) {
    js << (c ? ",\n" : "\n") << "    \"" << info.output_names[c]
       << "\": {\"abs\": " << fmt("%.17g", run.peaks[c].value)
       << ", \"time\": " << fmt("%.9g", run.peaks[c].time) << "}";
  }
  js << "\n  },\n  \"end\": {";
  for (std::size_t c = 0; c < z.outputs; ++c) {
    js << (c ? ",\n" : "\n") << "    \"" << info.output_names[c]
       << "\": " << fmt("%.17g", run.last[c]);
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
  const auto yielded = ntn::hil::yielded_directions(r.store.model, r.store.state);
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
  return ntn::cli::close_output(js, "--summary-json", r.opt.json_path);
}

}  // namespace ntn::run::detail
