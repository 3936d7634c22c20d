// The fixed-rate frame loop (DESIGN §8): one I/O frame per period, N kernel substeps per frame
// (dt = period / N), inputs sampled per kernel step or per frame, held or linearly interpolated
// within the frame (sampling.hpp), outputs and alarms per frame, per-frame wake-up latency,
// compute time and overruns, and an optional log. ntn-hil-<model> runs it on either clock and
// ntn-run-<model> on the virtual clock (the one run driver of both).
//
// Overrun policy: catch up. Frames are processed strictly in index order, each with its own
// accepted inputs; a late frame is followed at once by the next one, without sleeping, until
// the loop is back on its deadlines. No frame is ever skipped, so the response is a function
// of the accepted inputs alone, however late the computer was (and a replay reproduces it).
//
// Divergence (divergence.hpp): after each frame's substeps the loop checks the kinetic energy
// 1/2 v^T M v against `LoopConfig::kinetic_limit`; a frame that fails it, or whose state stopped
// being finite (step() says kDiverged), is the diverged frame. From it on the loop is in its
// safe state: no more steps, the outputs are the last good frame's, flagged kDiverged, and the
// state is put back to the end of the last good frame (when a checkpoint is given).
#pragma once

#include <algorithm>
#include <array>
#include <csignal>
#include <cstdint>
#include <span>
#include <vector>

#include "ntn/hil/clock.hpp"
#include "ntn/hil/divergence.hpp"
#include "ntn/hil/packet.hpp"
#include "ntn/hil/recorder.hpp"
#include "ntn/hil/sampling.hpp"
#include "ntn/kernel.hpp"

namespace ntn::hil {

struct LoopConfig {
  std::int64_t frames = 0;
  int substeps = 1;  // kernel steps per frame: period = substeps x dt
  // What each kernel step is given (sampling.hpp): the frame's inputs held, interpolated from
  // the previous frame's (one frame of delay), or the source's value at that step (a source
  // with `step_inputs`; one without it is held).
  InputSampling sampling = InputSampling::kFrameHeld;
  // When >= 0: the run ends after this many kernel steps, its last frame cut short (its outputs
  // are still those after its first substep); `frames` must then be ceil(steps / substeps).
  // ntn-run-<model> runs ceil(duration / dt) steps. < 0: frames x substeps.
  std::int64_t steps = -1;
  // End the run after the frame that diverged (its outputs given to the sink and recorded)
  // instead of holding the safe state to the last frame (ntn-run-<model>).
  bool stop_at_divergence = false;
  double period = 1e-3;       // s
  double kinetic_limit = -1;  // J: a frame whose 1/2 v^T M v passes it is diverged; < 0: the
                              // model's kinetic_energy_limit (+Inf where it has no bound)
  // When given and non-zero after a frame (a signal handler sets it), the loop ends after that
  // frame, its outputs given to the sink and recorded, and says so in LoopResult::stopped.
  const volatile std::sig_atomic_t* stop = nullptr;
  // End the run after the first frame in which an element passed the stable step's bound of
  // second-order geometry (LoopResult::geometry_bound_frame): nothing after it is a result.
  bool stop_at_geometry_bound = false;
};

// A limit alarm on one output channel: on when |value| > limit, off again when
// |value| < limit - hysteresis.
struct Alarm {
  bool enabled = false;
  double limit = 0;
  double hysteresis = 0;
  bool active = false;
  std::uint64_t raised = 0;       // times it went on
  std::uint64_t frames_on = 0;    // frames it was on
  std::int64_t first_frame = -1;  // frame it first went on
};

struct FrameTimes {
  std::vector<std::int64_t> latency_ns;  // wake-up minus deadline (0 on the virtual clock)
  std::vector<std::int64_t> compute_ns;  // inputs to outputs of the frame
  std::int64_t overruns = 0;
  std::int64_t max_late_frames = 0;  // longest run of consecutive overrunning frames
  void reserve(std::int64_t frames) {
    latency_ns.reserve(static_cast<std::size_t>(frames));
    compute_ns.reserve(static_cast<std::size_t>(frames));
  }
};

struct LoopResult {
  std::int64_t frames = 0;
  std::int64_t epoch_ns = 0;         // deadline of frame 0 (real clock: monotonic ns)
  std::int64_t diverged_frame = -1;  // first frame that failed the divergence check, or -1
  DivergenceReason reason = DivergenceReason::kNone;
  std::int64_t diverged_step = -1;  // kernel step (tick) at which it was caught
  double kinetic_at_detection = 0;  // J, 1/2 v^T M v then (NaN / Inf for kNonFinite)
  double kinetic_limit = 0;         // J, the limit the loop used (+Inf: none)
  double peak_kinetic = 0;          // J, largest 1/2 v^T M v at the end of a good frame
  std::int64_t peak_kinetic_frame = -1;
  bool state_restored = false;  // the state was put back to the end of the last good frame
  std::uint64_t input_held_frames = 0;
  bool stopped = false;  // ended early by LoopConfig::stop (`frames` says after how many)
  // The first frame after whose steps State::geometry_bound was not 0 (an element past the stable
  // step's bound of second-order geometry, ntn/geometry.hpp; start() counts in frame 0), or -1.
  std::int64_t geometry_bound_frame = -1;
};

// The deadline of frame 0 a source asks for on the real clock, or -1 (the loop then starts one
// period from now). A source that takes packets from a sender in real time fixes it from the
// arrival of the sender's first packet, so that the loop's frames fall between the sender's
// (hil_main.cpp, UdpSource, with a SenderSchedule); a source without `epoch_ns()` leaves it to
// the loop. The loop asks again after every frame's inputs: an epoch that moved (a resync,
// schedule.hpp) sets the deadlines of the frames after it.
template <class Source>
std::int64_t source_epoch_ns(const Source& source) {
  if constexpr (requires { source.epoch_ns(); }) {
    return source.epoch_ns();
  } else {
    return -1;
  }
}

// The loop's own channel buffers: the frame's inputs (current, previous), one step's inputs, the
// frame's outputs and the last good ones. Compiled storage: arrays, on the loop's stack; run-time
// storage: vectors the caller makes before init (LoopBuffers(model sizes)), so that the loop
// allocates nothing.
template <Sizes S>
struct LoopBuffers {
  std::array<double, S.inputs> current{}, previous{}, step_in{};
  std::array<double, S.outputs> out{}, last_good{};
};
template <Sizes S>
requires(S.runtime) struct LoopBuffers<S> {
  LoopBuffers() = default;
  explicit LoopBuffers(const Sizes& z)
      : current(z.inputs),
        previous(z.inputs),
        step_in(z.inputs),
        out(z.outputs),
        last_good(z.outputs) {}
  std::vector<double> current, previous, step_in, out, last_good;
};

// Runs `config.frames` frames from the model's initial state (ntn::initial_state: u_0, v_0 of the
// model, every counter of `state` reset). Source: `void frame_inputs(std::int64_t k,
// std::span<double> v, std::uint16_t& flags)` gives frame k's accepted inputs (through the input
// gate: finite, in range) and the gate's flag:: bits; it is called for frame 0 before the loop
// fixes its deadlines, so it may wait there for its first input and then say, through an optional
// `std::int64_t epoch_ns() const`, when frame 0 is due (see source_epoch_ns). Sink: `void
// frame_outputs(std::int64_t k,
// std::span<const double> v, std::uint16_t flags)` gets the outputs with the gate's bits and
// the loop's (flag::kAlarm, kOverrun, kDiverged).
// Outputs of frame k are the channels at t_k = k period (after the frame's first substep).
// With InputSampling::kStep the source also has `void step_inputs(std::int64_t n,
// std::span<double> v)`, kernel step n's inputs (n = k substeps + i for substep i of frame k).
// A sink may also have `void after_start(const State<S>&, const Scratch<S>&)`, called once after
// ntn::start (the energy balance takes v_{-1/2} there), and
// `void after_step(const State<S>&, const Scratch<S>&)`, called after every
// kernel step (soak tests measure energy and constraints there).
// `checkpoint`, when given, holds the state at the end of the last good frame (at the start
// before frame 0); after a divergence `state` is set back to it, so the run can be inspected or
// restarted from there. It is caller storage, as `state`: no heap, no large stack frame.
// `team` and `team_work`, when given (prepare_team() for team->size workers), run every kernel
// step with the team (the multi-core step, ntn/team.hpp): the same bits as without.
// `buffers`: the loop's channel buffers (LoopBuffers); none given, the loop makes its own (for
// run-time storage, vectors: pass them to allocate nothing here).
// Nothing here allocates after the vectors in `times` were reserved.
template <Sizes S, class Clock, class Source, class Sink>
LoopResult run_loop(const Model<S>& model, State<S>& state, Scratch<S>& scratch, Clock& clock,
                    Source& source, Sink& sink, Recorder* recorder, const LoopConfig& config,
                    std::span<Alarm> alarms, FrameTimes& times, State<S>* checkpoint = nullptr,
                    const Team* team = nullptr, TeamWork<S>* team_work = nullptr,
                    LoopBuffers<S>* buffers = nullptr) {
  LoopResult result;
  result.kinetic_limit =
      config.kinetic_limit < 0 ? kinetic_energy_limit(model) : config.kinetic_limit;
  LoopBuffers<S> own;
  if constexpr (S.runtime) {
    if (buffers == nullptr) own = LoopBuffers<S>(model.sizes);
  }
  LoopBuffers<S>& b = buffers != nullptr ? *buffers : own;
  auto& current = b.current;
  auto& previous = b.previous;
  auto& step_in = b.step_in;
  auto& out = b.out;
  auto& last_good = b.last_good;
  std::uint16_t in_flags = 0;
  source.frame_inputs(0, current, in_flags);
  initial_state(model, state);  // the model's u_0, v_0 (static preload, [initial]; zero by default)
  (void)start(model, state, scratch, current);
  if constexpr (requires { sink.after_start(state, scratch); }) {
    sink.after_start(state, scratch);
  }
  if (checkpoint != nullptr) *checkpoint = state;
  previous = current;
  const auto period_ns = static_cast<std::int64_t>(config.period * 1e9 + 0.5);
  const std::int64_t asked = Clock::kVirtual ? -1 : source_epoch_ns(source);
  std::int64_t t0 = Clock::kVirtual ? clock.now() : (asked >= 0 ? asked : clock.now() + period_ns);
  result.epoch_ns = t0;
  std::int64_t late_run = 0;
  bool diverged = false;
  for (std::int64_t k = 0; k < config.frames; ++k) {
    const std::int64_t deadline = t0 + k * period_ns;
    const std::int64_t woke = clock.wait_until(deadline);
    const std::int64_t c0 = monotonic_ns();
    if (k > 0) source.frame_inputs(k, current, in_flags);
    // The source may move its epoch while the run goes on (a resync to the sender's stream,
    // schedule.hpp): the next frames are due from the new one.
    if constexpr (!Clock::kVirtual) {
      if (k > 0) {
        if (const std::int64_t e = source_epoch_ns(source); e >= 0) t0 = e;
      }
    }
    std::uint16_t flags = in_flags;
    if ((in_flags & flag::kHeld) != 0) ++result.input_held_frames;
    if (!diverged) {
      const std::int64_t first_step = k * config.substeps;
      const int substeps = config.steps < 0 ? config.substeps
                                            : static_cast<int>(std::min<std::int64_t>(
                                                  config.substeps, config.steps - first_step));
      for (int i = 0; i < substeps; ++i) {
        if (config.sampling == InputSampling::kFrameInterpolated) {
          const double s = static_cast<double>(i) / static_cast<double>(config.substeps);
          for (std::size_t c = 0; c < step_in.size(); ++c)
            step_in[c] = previous[c] + s * (current[c] - previous[c]);
        } else if constexpr (requires {
                               source.step_inputs(first_step, std::span<double>(step_in));
                             }) {
          if (config.sampling == InputSampling::kStep) {
            source.step_inputs(first_step + i, step_in);
          } else {
            step_in = current;
          }
        } else {
          step_in = current;
        }
        const StepStatus st = team != nullptr && team_work != nullptr
                                  ? step(model, state, scratch, step_in, *team, *team_work)
                                  : step(model, state, scratch, step_in);
        if constexpr (requires { sink.after_step(state, scratch); }) {
          sink.after_step(state, scratch);
        }
        if (i == 0) std::copy(scratch.outputs.begin(), scratch.outputs.end(), out.begin());
        if (st == StepStatus::kDiverged) {
          diverged = true;
          result.reason = DivergenceReason::kNonFinite;
          break;
        }
      }
      // Before a divergence puts the state back: the bound may have been passed on the way.
      if (result.geometry_bound_frame < 0 && state.geometry_bound != 0)
        result.geometry_bound_frame = k;
      // The frame's check (divergence.hpp): T above the limit, or T not finite.
      const double kinetic = kinetic_energy(model, state);
      if (!diverged && (!(kinetic <= result.kinetic_limit) || !(kinetic - kinetic == 0))) {
        diverged = true;
        result.reason =
            kinetic - kinetic == 0 ? DivergenceReason::kEnergy : DivergenceReason::kNonFinite;
      }
      if (diverged) {
        result.diverged_frame = k;
        result.diverged_step = state.tick;
        result.kinetic_at_detection = kinetic;
        if (checkpoint != nullptr) {
          state = *checkpoint;  // the end of the last good frame
          result.state_restored = true;
        }
      } else {
        if (kinetic > result.peak_kinetic)
          result.peak_kinetic = kinetic, result.peak_kinetic_frame = k;
        if (checkpoint != nullptr) *checkpoint = state;
      }
    }
    if (diverged) {
      out = last_good;  // safe state: hold the last good outputs, flagged
      flags |= flag::kDiverged;
    } else {
      last_good = out;
    }
    previous = current;
    for (std::size_t c = 0; c < alarms.size() && c < out.size(); ++c) {
      Alarm& a = alarms[c];
      if (!a.enabled) continue;
      const double v = out[c] < 0 ? -out[c] : out[c];
      if (!a.active && v > a.limit) {
        a.active = true, ++a.raised;
        if (a.first_frame < 0) a.first_frame = k;
      } else if (a.active && v < a.limit - a.hysteresis) {
        a.active = false;
      }
      if (a.active) ++a.frames_on, flags |= flag::kAlarm;
    }
    const std::int64_t c1 = monotonic_ns();
    const std::int64_t finish = Clock::kVirtual ? deadline : c1 - c0 + woke;
    if (!Clock::kVirtual && finish > deadline + period_ns) {
      flags |= flag::kOverrun;
      ++times.overruns;
      times.max_late_frames = std::max(times.max_late_frames, ++late_run);
    } else {
      late_run = 0;
    }
    sink.frame_outputs(k, out, flags);
    if (recorder != nullptr) recorder->write_frame(k, in_flags, flags, current, out);
    if (times.latency_ns.size() < times.latency_ns.capacity()) {
      times.latency_ns.push_back(woke - deadline);
      times.compute_ns.push_back(monotonic_ns() - c0);
    }
    ++result.frames;
    if (diverged && config.stop_at_divergence) break;
    if (config.stop_at_geometry_bound && result.geometry_bound_frame >= 0) break;
    if (config.stop != nullptr && *config.stop != 0) {
      result.stopped = result.frames < config.frames;
      break;
    }
  }
  return result;
}

// Percentile of a sample (nearest rank), for the summary; sorts a copy.
inline std::int64_t percentile(std::vector<std::int64_t> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  auto rank = static_cast<std::size_t>(p / 100.0 * static_cast<double>(v.size()) + 0.999999);
  rank = std::clamp<std::size_t>(rank, 1, v.size());
  return v[rank - 1];
}

}  // namespace ntn::hil
