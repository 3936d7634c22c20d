// `replay LOG`: a log of a run re-run on the virtual clock and compared with it bit for bit, over
// the caller's storage of the model (HilStorage, also the run's).
#pragma once

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <span>
#include <string>

#include "ntn/hil/clock.hpp"
#include "ntn/hil/loop.hpp"
#include "ntn/hil/model_info.hpp"
#include "ntn/hil/recorder.hpp"
#include "ntn/kernel.hpp"

namespace ntn::hil::program {

// The caller's storage of the model: static objects (compiled) or bound to one block
// (ntn/runtime_storage.hpp); `buffers`: the loop's channels (run-time storage: made before init).
template <Sizes S>
struct HilStorage {
  Model<S>& model;
  InitWorkspace<S>& init_work;
  State<S>& state;
  Scratch<S>& scratch;
  State<S>& checkpoint;  // the end of the last good frame (the loop's safe state)
  TeamWork<S>& team_work;
  LoopBuffers<S>* buffers = nullptr;
};

// Inputs from a log, as they were accepted, read frame by frame (the log was checked whole
// before; a record that fails now, the file having changed, stops the replay).
struct ReplaySource {
  ntn::hil::LogReader* reader;
  volatile std::sig_atomic_t* stop;
  ntn::hil::LogFrame frame;
  std::string error;  // not empty: frame k could not be read, the loop stops after it
  void frame_inputs(std::int64_t, std::span<double> v, std::uint16_t& flags) {
    if (!error.empty() || reader->next(frame) != ntn::hil::LogRead::kFrame) {
      if (error.empty()) error = reader->error();
      std::fill(v.begin(), v.end(), 0.0);
      flags = 0;
      *stop = 1;
      return;
    }
    std::copy(frame.inputs.begin(), frame.inputs.end(), v.begin());
    flags = static_cast<std::uint16_t>(frame.input_flags);
  }
};

// Compares each replayed frame with the log: every output value bit for bit, and the diverged
// flag (the alarm bit depends on --alarm and the overrun bit on timing: neither is replayed).
struct ReplaySink {
  const ReplaySource* source;
  volatile std::sig_atomic_t* stop;
  std::int64_t differs = -1;  // first differing frame
  int channel = -1;           // its first differing channel, or -1: the diverged flag
  double recorded = 0, now = 0;
  std::uint16_t recorded_flags = 0, now_flags = 0;
  void frame_outputs(std::int64_t k, std::span<const double> v, std::uint16_t flags) {
    if (differs >= 0 || !source->error.empty()) return;
    const ntn::hil::LogFrame& f = source->frame;
    for (std::size_t c = 0; c < v.size(); ++c) {
      if (std::memcmp(&v[c], &f.outputs[c], sizeof(double)) != 0) {
        differs = k, channel = static_cast<int>(c), recorded = f.outputs[c], now = v[c];
        *stop = 1;
        return;
      }
    }
    if ((flags & ntn::hil::flag::kDiverged) != (f.output_flags & ntn::hil::flag::kDiverged)) {
      differs = k, recorded_flags = static_cast<std::uint16_t>(f.output_flags), now_flags = flags;
      *stop = 1;
    }
  }
};

inline bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// `replay LOG`: checks the whole log first (every record's checksum, the frame numbers, the end
// record; the header against this model), then re-runs its complete frames on the virtual clock
// and compares every output with the recorded one. Exit 0: bit-identical over a complete log;
// 1: a frame differs; 2: the log cannot be used; 4: the log is incomplete (no end record: the
// run was killed, or the disk filled) and its complete frames replay bit-identical.
template <Sizes S>
int replay_log(const ModelInfo& info, HilStorage<S> store, const std::string& path,
               ntn::hil::LoopConfig config) {
  const Sizes z = store.model.sizes;
  using ntn::hil::LogRead;
  ntn::hil::LogReader check;
  if (!check.open(path)) {
    std::fprintf(stderr, "error: %s\n", check.error().c_str());
    return 2;
  }
  const ntn::hil::LogHeader& h = check.header();
  const std::string name(info.name);
  char why[256] = "";
  if (h.model != name) {
    std::snprintf(why, sizeof why, "model '%s', this program runs '%s'", h.model.c_str(),
                  name.c_str());
  } else if (h.inputs != z.inputs || h.outputs != z.outputs) {
    std::snprintf(why, sizeof why, "%u inputs and %u outputs, the model has %zu and %zu", h.inputs,
                  h.outputs, z.inputs, z.outputs);
  } else if (h.substeps != static_cast<std::uint32_t>(config.substeps)) {
    std::snprintf(why, sizeof why, "%u substeps per frame, the model runs %d", h.substeps,
                  config.substeps);
  } else if (!same_bits(h.period, config.period)) {
    std::snprintf(why, sizeof why, "period %.17g s, the model's frame period is %.17g s", h.period,
                  config.period);
  } else if (!same_bits(h.dt, store.model.dt)) {
    std::snprintf(why, sizeof why, "dt %.17g s, the model's is %.17g s", h.dt, store.model.dt);
  }
  if (why[0] != '\0') {
    std::fprintf(stderr, "error: %s was recorded with another model or step: %s\n", path.c_str(),
                 why);
    return 2;
  }
  ntn::hil::LogFrame frame;
  LogRead r = LogRead::kFrame;
  while ((r = check.next(frame)) == LogRead::kFrame) {
  }
  if (r == LogRead::kError) {
    std::fprintf(stderr, "error: %s\n", check.error().c_str());
    return 2;
  }
  const std::int64_t frames = check.frames();
  if (frames == 0) {
    std::fprintf(stderr, "error: %s: the log holds no complete frame: nothing to replay (%s)\n",
                 path.c_str(), check.error().c_str());
    return 2;
  }

  ntn::hil::LogReader reader;
  if (!reader.open(path)) {
    std::fprintf(stderr, "error: %s\n", reader.error().c_str());
    return 2;
  }
  volatile std::sig_atomic_t stop = 0;
  config.frames = frames;
  config.sampling = h.interpolate != 0 ? ntn::hil::InputSampling::kFrameInterpolated
                                       : ntn::hil::InputSampling::kFrameHeld;
  config.stop = &stop;
  ReplaySource source{&reader, &stop, {}, {}};
  ReplaySink sink{&source, &stop};
  ntn::hil::VirtualClock clock;
  ntn::hil::FrameTimes times;
  std::vector<ntn::hil::Alarm> no_alarms;
  const ntn::hil::LoopResult result =
      ntn::hil::run_loop(store.model, store.state, store.scratch, clock, source, sink, nullptr,
                         config, no_alarms, times, static_cast<State<S>*>(nullptr), nullptr,
                         static_cast<TeamWork<S>*>(nullptr), store.buffers);
  if (!source.error.empty()) {
    std::fprintf(stderr, "error: %s (the file changed while it was replayed?)\n",
                 source.error.c_str());
    return 2;
  }
  if (sink.differs >= 0) {
    const double t = static_cast<double>(sink.differs) * config.period;
    if (sink.channel >= 0) {
      std::printf(
          "replay: DIFFERS at frame %lld (t = %.6f s), channel %s: recorded %.17g, now %.17g\n",
          static_cast<long long>(sink.differs), t,
          std::string(info.output_names[static_cast<std::size_t>(sink.channel)]).c_str(),
          sink.recorded, sink.now);
    } else {
      std::printf(
          "replay: DIFFERS at frame %lld (t = %.6f s): the log's output flags 0x%04x say %s, the "
          "replay %s\n",
          static_cast<long long>(sink.differs), t, static_cast<unsigned>(sink.recorded_flags),
          (sink.recorded_flags & ntn::hil::flag::kDiverged) != 0 ? "diverged" : "not diverged",
          (sink.now_flags & ntn::hil::flag::kDiverged) != 0 ? "diverged" : "not diverged");
    }
    return 1;
  }
  if (result.frames != frames) {
    std::fprintf(stderr, "error: %s: replayed %lld of %lld frames\n", path.c_str(),
                 static_cast<long long>(result.frames), static_cast<long long>(frames));
    return 2;
  }
  if (r == LogRead::kTruncated) {
    std::printf("replay: bit-identical over %lld frames (0..%lld); the log is incomplete\n",
                static_cast<long long>(frames), static_cast<long long>(frames - 1));
    std::fprintf(stderr, "warning: %s\n", check.error().c_str());
    return 4;
  }
  std::printf("replay: bit-identical over %lld frames\n", static_cast<long long>(frames));
  return 0;
}

}  // namespace ntn::hil::program
