// ntn-run-<model>: runs one compiled model on recorded inputs as fast as possible and writes
// the response as CSV with a one-screen summary. The model comes from the header that
// ntn_add_model() generated (NTN_MODEL_HEADER, namespace NTN_MODEL_NS).
#include <xxhash.h>

#include <CLI/CLI.hpp>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "ntn/kernel.hpp"
#include "record.hpp"
#include NTN_MODEL_HEADER

namespace {

namespace mdl = NTN_MODEL_NS;
constexpr ntn::Sizes kS = mdl::kSizes;

// Static storage: the kernel never allocates, and large models do not fit on the stack.
ntn::Model<kS> g_model;
ntn::State<kS> g_state;
ntn::Scratch<kS> g_scratch;

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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Run the model '" + std::string(mdl::kName) + "' (" + std::string(mdl::kSourceFile) +
               ") on recorded inputs"};
  std::vector<std::string> input_args;
  double duration = -1;
  std::string out_path;
  std::string json_path;
  bool quiet = false;
  app.add_option("-i,--input", input_args,
                 "NAME=FILE: feed input channel NAME from a record (AT2 or CSV; "
                 "FILE:COLUMN picks a CSV column)");
  app.add_option("-t,--duration", duration, "simulated time in s (default: longest record)")
      ->check(CLI::PositiveNumber);
  app.add_option("-o,--out", out_path, "CSV file for the response, one row per I/O frame");
  app.add_option("--summary-json", json_path, "also write the summary as JSON");
  app.add_flag("-q,--quiet", quiet, "print only errors and the output hash");
  CLI11_PARSE(app, argc, argv);

  // Records for the input channels, by name.
  std::array<ntn::io::Record, kS.inputs> records{};
  std::array<bool, kS.inputs> fed{};
  for (const std::string& arg : input_args) {
    const auto eq = arg.find('=');
    if (eq == std::string::npos) {
      std::fprintf(stderr, "error: --input wants NAME=FILE, got '%s'\n", arg.c_str());
      return 2;
    }
    const std::string name = arg.substr(0, eq);
    std::string file = arg.substr(eq + 1), column;
    if (const auto c = file.rfind(':'); c != std::string::npos && c > 1) {
      column = file.substr(c + 1);
      file = file.substr(0, c);
    }
    int index = -1;
    for (int k = 0; k < kS.inputs; ++k) {
      if (mdl::kInputNames[static_cast<std::size_t>(k)] == name) index = k;
    }
    if (index < 0) {
      std::fprintf(stderr, "error: the model has no input channel '%s'\n", name.c_str());
      return 2;
    }
    ntn::io::ReadResult r = ntn::io::read_record(file, column);
    if (r.error) {
      std::fprintf(stderr, "%s\n", r.error->format().c_str());
      return 2;
    }
    const auto k = static_cast<std::size_t>(index);
    const ntn::InputSpec& spec = mdl::kSpec.inputs[k];
    for (std::size_t s = 0; s < r.record->values.size(); ++s) {
      const double v = r.record->values[s];
      if (v < spec.min || v > spec.max) {
        std::fprintf(stderr,
                     "%s: error: sample %zu (t = %g s) = %g is outside the accepted range "
                     "[%g, %g] of input '%s'\n",
                     file.c_str(), s + 1, static_cast<double>(s) * r.record->dt, v, spec.min,
                     spec.max, name.c_str());
        return 2;
      }
    }
    records[k] = std::move(*r.record);
    fed[k] = true;
  }
  double record_duration = 0;
  for (int k = 0; k < kS.inputs; ++k) {
    if (!fed[static_cast<std::size_t>(k)]) {
      std::fprintf(stderr, "error: no record for input channel '%s' (use --input %s=FILE)\n",
                   std::string(mdl::kInputNames[static_cast<std::size_t>(k)]).c_str(),
                   std::string(mdl::kInputNames[static_cast<std::size_t>(k)]).c_str());
      return 2;
    }
    record_duration = std::max(record_duration, records[static_cast<std::size_t>(k)].duration());
  }
  if (duration < 0) duration = record_duration;  // default: the longest record
  if (duration <= 0) {
    std::fprintf(stderr, "error: give --duration (the model has no input records)\n");
    return 2;
  }

  if (const ntn::InitStatus st = ntn::init(mdl::kSpec, g_model); !st.ok()) {
    std::fprintf(stderr, "error: model '%s': %s (at %d)\n", std::string(mdl::kName).c_str(),
                 ntn::to_string(st.error), st.where);
    return 1;
  }
  const double dt = g_model.dt;
  const auto steps = static_cast<std::int64_t>(std::ceil(duration / dt - 1e-9));
  const double period = mdl::kSpec.settings.frame_period;
  // The kernel's frame rule (ntn::frame_substeps), the one the model compiler checked.
  const ntn::Substeps substeps = ntn::frame_substeps(dt, period);
  if (!substeps.ok()) {
    std::fprintf(stderr, "error: model '%s': dt = %g s, frame period %g s: %s\n",
                 std::string(mdl::kName).c_str(), dt, period, ntn::to_string(substeps.error));
    return 1;
  }
  const std::int64_t per_frame = substeps.count;

  auto inputs_at = [&records](double t) {
    std::array<double, kS.inputs> in{};
    for (std::size_t k = 0; k < in.size(); ++k)
      in[k] = records[k].at(t);
    return in;
  };

  std::string csv;
  csv.reserve(static_cast<std::size_t>(steps / per_frame + 2) * (kS.outputs + 1) * 24);
  csv += "time[s]";
  for (int c = 0; c < kS.outputs; ++c) {
    csv += ',';
    csv += mdl::kOutputNames[static_cast<std::size_t>(c)];
    csv += '[';
    csv += mdl::kOutputUnits[static_cast<std::size_t>(c)];
    csv += ']';
  }
  csv += '\n';

  std::array<Peak, kS.outputs> peaks{};
  XXH3_state_t* hash = XXH3_createState();
  XXH3_64bits_reset(hash);
  int held = 0;
  bool diverged = false;

  const auto t0 = std::chrono::steady_clock::now();
  if (ntn::start(g_model, g_state, g_scratch, inputs_at(0.0)) != ntn::StepStatus::kOk) ++held;
  char row[64];
  std::int64_t n = 0;
  for (; n < steps; ++n) {
    const double t = static_cast<double>(n) * dt;
    const ntn::StepStatus st = ntn::step(g_model, g_state, g_scratch, inputs_at(t));
    if (st == ntn::StepStatus::kInputHeld) ++held;
    XXH3_64bits_update(hash, g_scratch.outputs.data(), sizeof g_scratch.outputs);
    for (std::size_t c = 0; c < peaks.size(); ++c) {
      const double v = std::abs(g_scratch.outputs[c]);
      if (v > peaks[c].value) peaks[c] = {v, g_scratch.time};
    }
    if (n % per_frame == 0) {
      std::snprintf(row, sizeof row, "%.9g", g_scratch.time);
      csv += row;
      for (double v : g_scratch.outputs) {
        std::snprintf(row, sizeof row, ",%.17g", v);
        csv += row;
      }
      csv += '\n';
    }
    if (st == ntn::StepStatus::kDiverged) {
      diverged = true;
      ++n;
      break;
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  XXH3_64bits_update(hash, g_state.u.data(), sizeof g_state.u);
  XXH3_64bits_update(hash, g_state.v.data(), sizeof g_state.v);
  char digest[17];
  std::snprintf(digest, sizeof digest, "%016llx",
                static_cast<unsigned long long>(XXH3_64bits_digest(hash)));
  XXH3_freeState(hash);

  if (!out_path.empty()) {
    const std::filesystem::path p(out_path);
    if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
    std::ofstream out(out_path, std::ios::binary);
    out << csv;
    if (!out) {
      std::fprintf(stderr, "error: cannot write %s\n", out_path.c_str());
      return 1;
    }
  }

  const double simulated = static_cast<double>(n) * dt;
  const auto& stable = g_model.stable;
  const int gov = stable.governing_element;
  if (!quiet) {
    std::printf("ntn-run  model %s (%s)\n", std::string(mdl::kName).c_str(),
                std::string(mdl::kSourceFile).c_str());
    for (int k = 0; k < kS.inputs; ++k) {
      const auto& r = records[static_cast<std::size_t>(k)];
      std::printf("  input %-12s %s: %zu samples at %g s, peak %.4g %s\n",
                  std::string(mdl::kInputNames[static_cast<std::size_t>(k)]).c_str(),
                  r.source.c_str(), r.values.size(), r.dt, r.peak_abs(), r.units.c_str());
    }
    std::printf("  size        %d nodes, %d elements, %d hinges, %d DOFs\n", kS.nodes, kS.elements,
                kS.hinges, 6 * kS.nodes);
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
    std::printf(
        "  run         %lld steps, %.3f s simulated, wall %.3f s, real-time factor %.1fx, "
        "%.3f us/step\n",
        static_cast<long long>(n), simulated, wall, simulated / wall,
        wall / static_cast<double>(n) * 1e6);
    for (int c = 0; c < kS.outputs; ++c) {
      const auto& o = mdl::kSpec.outputs[static_cast<std::size_t>(c)];
      const auto& p = peaks[static_cast<std::size_t>(c)];
      const std::string name(mdl::kOutputNames[static_cast<std::size_t>(c)]);
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
                    fmt("%.5g", p.value).c_str(),
                    std::string(mdl::kOutputUnits[static_cast<std::size_t>(c)]).c_str(), p.time);
      }
    }
    if (held > 0)
      std::printf("  inputs held %d steps had a non-finite input (last good value held)\n", held);
    if (diverged)
      std::printf("  DIVERGED    the state became non-finite at step %lld\n",
                  static_cast<long long>(n));
    if (!out_path.empty()) {
      std::printf("  response    %s (%lld rows, one per frame)\n", out_path.c_str(),
                  static_cast<long long>((n + per_frame - 1) / per_frame));
    }
  }
  std::printf("  output hash %s\n", digest);

  if (!json_path.empty()) {
    std::ofstream js(json_path);
    js << "{\n  \"model\": \"" << mdl::kName << "\",\n  \"dt\": " << fmt("%.17g", dt)
       << ",\n  \"dt_stable\": " << fmt("%.17g", stable.dt_stable) << ",\n  \"steps\": " << n
       << ",\n  \"simulated_s\": " << fmt("%.17g", simulated)
       << ",\n  \"wall_s\": " << fmt("%.6g", wall)
       << ",\n  \"real_time_factor\": " << fmt("%.6g", simulated / wall)
       << ",\n  \"diverged\": " << (diverged ? "true" : "false") << ",\n  \"output_hash\": \""
       << digest << "\",\n  \"peaks\": {";
    for (int c = 0; c < kS.outputs; ++c) {
      js << (c ? ",\n" : "\n") << "    \"" << mdl::kOutputNames[static_cast<std::size_t>(c)]
         << "\": {\"abs\": " << fmt("%.17g", peaks[static_cast<std::size_t>(c)].value)
         << ", \"time\": " << fmt("%.9g", peaks[static_cast<std::size_t>(c)].time) << "}";
    }
    js << "\n  }\n}\n";
  }
  return diverged ? 3 : 0;
}
