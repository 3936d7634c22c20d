// The command line of ntn-hil and ntn-hil-<model> (parse_args), the same for every program, and
// the run's bounds it checks.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cli.hpp"
#include "ntn/hil/loop.hpp"
#include "ntn/hil/model_info.hpp"
#include "ntn/kernel.hpp"

namespace ntn::hil::program {

// Runs are bounded so that nothing the run keeps grows without limit: at most kMaxFrames frames
// (11.6 days at 1 kHz; the CSV's time column, %.9g, resolves 1 ms frames up to 10^6 s), and the
// wake-up latency and compute time of the first kTimedFrames frames (64 MiB) for the summary's
// percentiles (overruns are counted over the whole run). The CSV and the log are streamed to
// their files through 1 MiB buffers; the output hash is computed as the run goes.
constexpr std::int64_t kMaxFrames = 1'000'000'000;

// "NAME=LIMIT[:HYSTERESIS]" or "NAME=off" for one output channel, as the model file's alarm
// keys: 0 < LIMIT finite, 0 <= HYSTERESIS < LIMIT. "" on success, else what is wrong.
inline std::string parse_alarm(const ModelInfo& info, const std::string& arg,
                               std::vector<ntn::hil::Alarm>& alarms) {
  const auto eq = arg.find('=');
  const std::string name = arg.substr(0, eq);
  std::size_t c = 0;
  while (c < info.output_names.size() && info.output_names[c] != name)
    ++c;
  if (eq == std::string::npos) return "want OUTPUT=LIMIT[:HYSTERESIS] or OUTPUT=off";
  if (c == info.output_names.size()) return "the model has no output '" + name + "'";
  const std::string spec = arg.substr(eq + 1);
  if (spec == "off") {
    alarms[c] = {};
    return "";
  }
  const auto number = [](const std::string& text, double& out) {
    char* end = nullptr;
    out = std::strtod(text.c_str(), &end);
    return !text.empty() && end == text.c_str() + text.size() && std::isfinite(out);
  };
  const auto colon = spec.find(':');
  double limit = 0, hysteresis = 0;
  if (!number(spec.substr(0, colon), limit) || !(limit > 0))
    return "the limit must be a finite number > 0";
  if (colon != std::string::npos &&
      (!number(spec.substr(colon + 1), hysteresis) || hysteresis < 0 || !(hysteresis < limit)))
    return "the hysteresis must be a number >= 0 and below the limit";
  alarms[c] = {};
  alarms[c].enabled = true, alarms[c].limit = limit, alarms[c].hysteresis = hysteresis;
  return "";
}

// The command line (parse_args): the same for every program; `model_path` only for ntn-hil.
struct HilOptions {
  std::string model_path;
  std::vector<std::string> input_args, alarm_args;
  std::string clock_name = "real", out_path, json_path, log_path, replay_path, sampling_name;
  double duration = -1, first_wait_s = 10;
  std::int64_t frames = -1;
  int listen_port = -1, reply_port = 0, cpu = -1, threads = 1;
  bool interpolate = false, quiet = false;
  bool fifo = true, mlock = true;  // real clock: ntn::hil::RealTimeOptions' defaults
  int priority = 80;
  std::int64_t timer_slack_ns = 1;
  int cpu_latency_us = 0;
  bool replay = false;                       // the replay subcommand (else run)
  std::map<std::string, std::size_t> given;  // times each of some run options was given
  std::size_t count(const std::string& option) const {
    const auto it = given.find(option);
    return it == given.end() ? 0 : it->second;
  }
};

// Parses the command line into `o` (with a MODEL.toml argument before the others when
// `model_file`). The exit code when the program ends there (--help: 0, a usage error: 2).
inline std::optional<int> parse_args(int argc, char** argv, const std::string& title,
                                     bool model_file, HilOptions& o) {
  ntn::cli::App app{title};
  app.require_subcommand(1);
  auto* run = app.add_subcommand("run", "run the loop");
  auto* replay = app.add_subcommand("replay", "re-run a log on the virtual clock and compare");
  if (model_file) {
    run->add_option("model", o.model_path, "model file (.toml)")->required();
    replay->add_option("model", o.model_path, "model file (.toml) the log was recorded with")
        ->required();
  }
  auto& input_args = o.input_args;
  auto& alarm_args = o.alarm_args;
  auto& clock_name = o.clock_name;
  auto& out_path = o.out_path;
  auto& json_path = o.json_path;
  auto& log_path = o.log_path;
  auto& replay_path = o.replay_path;
  auto& sampling_name = o.sampling_name;
  auto& duration = o.duration;
  auto& first_wait_s = o.first_wait_s;
  auto& frames = o.frames;
  auto& listen_port = o.listen_port;
  auto& reply_port = o.reply_port;
  auto& cpu = o.cpu;
  auto& threads = o.threads;
  auto& interpolate = o.interpolate;
  auto& fifo = o.fifo;
  auto& mlock = o.mlock;
  auto& quiet = o.quiet;
  run->add_option("-i,--input", input_args,
                  "NAME=FILE: feed an input from a record (AT2, CSV; FILE*FACTOR scales it)");
  run->add_option("--listen", listen_port, "take inputs as UDP packets on 127.0.0.1:PORT")
      ->check(ntn::cli::Integer(0, 65535));
  run->add_option("--reply", reply_port, "send output packets to 127.0.0.1:PORT")
      ->check(ntn::cli::Integer(1, 65535));
  run->add_option("--clock", clock_name,
                  "real (absolute deadlines) or virtual (as fast as "
                  "possible; lock-step with UDP)")
      ->check(ntn::cli::IsMember({"real", "virtual"}));
  run->add_option("--wait-first", first_wait_s,
                  "real time with --listen: seconds to wait for the sender's first packet, which "
                  "fixes the frame deadlines (default 10, at most 3600)")
      ->check(ntn::cli::Positive(3600));
  run->add_option("-t,--duration", duration, "seconds to run (default: the longest record)")
      ->check(ntn::cli::Positive());
  run->add_option("-n,--frames", frames, "frames to run (overrides --duration)")
      ->check(ntn::cli::Integer(1, kMaxFrames));
  auto* sampling_option =
      run->add_option("-s,--sampling", sampling_name,
                      "hold (inputs at frame times, held over the frame; default), interpolate "
                      "(linear over the frame, one frame of delay) or step (--input records at "
                      "every kernel step, as ntn-run-<model> by default)")
          ->check(ntn::cli::IsMember({"step", "hold", "interpolate"}));
  run->add_flag("--interpolate", interpolate, "the same as --sampling interpolate")
      ->excludes(sampling_option);
  run->add_option("--alarm", alarm_args,
                  "NAME=LIMIT[:HYSTERESIS] or NAME=off: limit alarm on an output, replacing the "
                  "model file's for that channel");
  run->add_option("-o,--out", out_path, "CSV of the outputs, one row per frame, with flags");
  run->add_option("--record", log_path, "binary log of accepted inputs and outputs (replay)");
  run->add_option("--summary-json", json_path, "write the summary as JSON");
  run->add_flag("--fifo,!--no-fifo", fifo,
                "real clock: SCHED_FIFO at --priority (the default; falls back with a warning)");
  run->add_option("--priority", o.priority, "real clock: the SCHED_FIFO priority (default 80)")
      ->check(ntn::cli::Integer(1, 99));
  run->add_flag("--mlock,!--no-mlock", mlock,
                "real clock: mlockall, every page locked (the default; falls back with a warning)");
  run->add_option("--cpu-latency", o.cpu_latency_us,
                  "real clock: the CPU wake-up latency to hold in us (PM QoS, "
                  "/dev/cpu_dma_latency; default 0; -1: leave it)")
      ->check(ntn::cli::Integer(-1, 10'000'000));
  run->add_option("--timer-slack", o.timer_slack_ns,
                  "real clock: the thread's timer slack in ns (default 1; 0: the system's "
                  "default, 50 us on Linux)")
      ->check(ntn::cli::Integer(0, 1'000'000'000));
  run->add_option("--cpu", cpu, "pin to this CPU (falls back with a warning)")
      ->check(ntn::cli::Integer(0, std::numeric_limits<int>::max()));
  run->add_option("--threads", threads,
                  "workers of the multi-core step, made before the loop (1 = the loop's thread "
                  "alone; with --cpu C, worker k is pinned to CPU C + k): the same bits for any "
                  "number")
      ->check(ntn::cli::Integer(1, ntn::kMaxTeam));
  run->add_flag("-q,--quiet", quiet, "print only warnings, errors and the output hash");
  replay->add_option("log", replay_path, "log written by run --record")->required();
  if (const auto code = ntn::cli::parse(app, argc, argv)) return code;
  o.replay = replay->parsed();
  for (const char* option : {"--out", "--record", "--summary-json", "--frames", "--duration"})
    o.given[option] = run->count(option);
  return std::nullopt;
}

}  // namespace ntn::hil::program
