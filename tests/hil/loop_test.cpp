// The frame loop (hil_sim/include/ntn/hil/loop.hpp): no allocation once running, the real-time
// and the virtual clock give the same outputs for the same accepted inputs, inputs through the
// gate never carry a NaN into the state, a diverging model is caught within its bound and goes to
// a safe state, the check raises no false alarm, and a long
// virtual run repeats bit for bit (soak).
#include <gtest/gtest.h>
#include <xxhash.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include "ntn/hil/gate.hpp"
#include "ntn/hil/loop.hpp"
#include "ntn/hil/schedule.hpp"
#include "ntn/kernel.hpp"
#include "support/alloc_counter.hpp"
#include "support/assemble.hpp"
#include "support/frames.hpp"
#include "support/init_model.hpp"

namespace loop_test {

constexpr ntn::Sizes kS = ntn_test::kFeatureSizes;
ntn::ModelSpec<kS> spec;
ntn::Model<kS> model;
ntn::State<kS> state;
ntn::Scratch<kS> scratch;
ntn::State<kS> checkpoint;

// Deterministic inputs through the gate; every `nan_every`-th frame channel 0 is NaN.
struct SyntheticSource {
  ntn::hil::InputGate* gate;
  long nan_every = 0;
  void frame_inputs(std::int64_t k, std::span<double> v, std::uint16_t& flags) {
    std::array<double, kS.inputs> x{ntn_test::input_sample(0, k), ntn_test::input_sample(1, k),
                                    10 * ntn_test::input_sample(2, k)};
    if (nan_every > 0 && k % nan_every == 0) x[0] = std::numeric_limits<double>::quiet_NaN();
    gate->begin_frame(k);
    (void)gate->accept_values(k, x);
    gate->end_frame(v, flags);
  }
};

// Hashes every frame's outputs; counts NaNs.
struct HashSink {
  XXH3_state_t* h = XXH3_createState();
  long nan_outputs = 0;
  std::uint16_t flags_or = 0;
  HashSink() { XXH3_64bits_reset(h); }
  ~HashSink() { XXH3_freeState(h); }
  HashSink(const HashSink&) = delete;
  HashSink& operator=(const HashSink&) = delete;
  void frame_outputs(std::int64_t, std::span<const double> v, std::uint16_t flags) {
    XXH3_64bits_update(h, v.data(), v.size_bytes());
    for (double x : v)
      nan_outputs += std::isnan(x) ? 1 : 0;
    flags_or |= flags;
  }
  std::uint64_t digest() const { return XXH3_64bits_digest(h); }
};

template <class Clock>
std::uint64_t run(std::int64_t frames, long nan_every, Clock& clock, ntn::hil::FrameTimes& times,
                  std::uint64_t* allocations = nullptr, long* nan_outputs = nullptr) {
  state = {};
  ntn::hil::InputGate gate(std::span<const ntn::InputSpec>(spec.inputs));
  SyntheticSource source{&gate, nan_every};
  HashSink sink;
  ntn::hil::LoopConfig config;
  config.frames = frames;
  config.period = 1e-3;
  config.substeps = static_cast<int>(model.substeps.count);
  std::vector<ntn::hil::Alarm> alarms(kS.outputs);
  alarms[0] = {.enabled = true, .limit = 1e-4, .hysteresis = 1e-5};
  times.reserve(frames);
  const ntn_test::AllocationScope scope;
  (void)ntn::hil::run_loop(model, state, scratch, clock, source, sink, nullptr, config, alarms,
                           times);
  if (allocations != nullptr) *allocations = scope.counts().allocations;
  if (nan_outputs != nullptr) *nan_outputs = sink.nan_outputs;
  return sink.digest();
}

class Loop : public ::testing::Test {
 protected:
  void SetUp() override {
    // dt divides the 1 ms frame: the largest period / N below 0.9 dt_stable.
    ASSERT_TRUE(ntn_test::feature_frame(spec));
    spec.settings.frame_period = 1e-3;
    spec.settings.dt = ntn::auto_time_step(ntn::stable_time_step(ntn::view(spec)).dt_stable, 1e-3);
    ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
    ASSERT_TRUE(model.substeps.ok());  // N, stored once by init (ntn::frame_substeps)
  }
};

TEST_F(Loop, NoAllocationOnceRunning) {
  ntn::hil::VirtualClock clock;
  ntn::hil::FrameTimes times;
  std::uint64_t allocations = 1;
  (void)run(20'000, 7, clock, times, &allocations);
  EXPECT_EQ(allocations, 0U);
  EXPECT_EQ(times.compute_ns.size(), 20'000U);
}

// The clock only decides when a frame starts, never what it computes (DESIGN §8).
TEST_F(Loop, RealAndVirtualClocksGiveTheSameOutputs) {
  ntn::hil::VirtualClock virtual_clock;
  ntn::hil::RealClock real_clock;
  ntn::hil::FrameTimes tv, tr;
  const std::uint64_t hv = run(300, 11, virtual_clock, tv);
  const std::uint64_t hr = run(300, 11, real_clock, tr);
  EXPECT_EQ(hv, hr);
  // On the real clock the wake-up latency is measured and non-negative.
  for (std::int64_t l : tr.latency_ns)
    EXPECT_GE(l, 0);
}

// A source that fixes the first deadline (as the UDP source does from the sender's first
// packet) moves the whole frame grid: frame k is due at epoch + k period, on the real clock.
struct EpochSource : SyntheticSource {
  std::int64_t epoch = -1;
  std::int64_t epoch_ns() const { return epoch; }
};

TEST_F(Loop, SourceFixesTheDeadlines) {
  state = {};
  ntn::hil::InputGate gate(std::span<const ntn::InputSpec>(spec.inputs));
  EpochSource source{{&gate, 0}};
  // 30 ms ahead: well beyond the loop's default of one period from now, so a loop that ignored
  // the source would finish its 20 frames (20 ms) before the epoch.
  source.epoch = ntn::hil::monotonic_ns() + 30'000'000;
  HashSink sink;
  ntn::hil::LoopConfig config;
  config.frames = 20;
  config.substeps = static_cast<int>(model.substeps.count);
  ntn::hil::RealClock clock;
  ntn::hil::FrameTimes times;
  times.reserve(config.frames);
  std::vector<ntn::hil::Alarm> alarms(kS.outputs);
  const auto result = ntn::hil::run_loop(model, state, scratch, clock, source, sink, nullptr,
                                         config, alarms, times);
  const std::int64_t end = ntn::hil::monotonic_ns();
  EXPECT_EQ(result.epoch_ns, source.epoch);
  // The last frame woke at or after its deadline epoch + 19 periods.
  EXPECT_GE(end, source.epoch + 19 * 1'000'000);
  for (std::int64_t l : times.latency_ns)
    EXPECT_GE(l, 0);
  // Without an epoch from the source the loop starts one period after it began.
  source.epoch = -1;
  state = {};
  const std::int64_t before = ntn::hil::monotonic_ns();
  const auto own = ntn::hil::run_loop(model, state, scratch, clock, source, sink, nullptr, config,
                                      alarms, times);
  EXPECT_GE(own.epoch_ns, before + 1'000'000);
  EXPECT_LE(own.epoch_ns, ntn::hil::monotonic_ns());
}

// A NaN burst on an input never reaches an output: the gate holds the last good value.
TEST_F(Loop, NanBurstGivesNoNanOutput) {
  ntn::hil::VirtualClock clock;
  ntn::hil::FrameTimes times;
  long nan_outputs = -1;
  (void)run(5'000, 1, clock, times, nullptr, &nan_outputs);  // channel 0 NaN in every frame
  EXPECT_EQ(nan_outputs, 0);
}

// Per frame: flags and outputs; per step: the kinetic energy 1/2 v^T M v (divergence tests).
struct TraceSink : HashSink {
  std::vector<std::uint16_t> flags;
  std::vector<std::array<double, kS.outputs>> outputs;
  std::vector<double> kinetic;  // after each kernel step
  void frame_outputs(std::int64_t k, std::span<const double> v, std::uint16_t f) {
    HashSink::frame_outputs(k, v, f);
    flags.push_back(f);
    std::array<double, kS.outputs> row{};
    std::copy(v.begin(), v.end(), row.begin());
    outputs.push_back(row);
  }
  void after_step(const ntn::State<kS>& s, const ntn::Scratch<kS>&) {
    kinetic.push_back(ntn::hil::kinetic_energy(model, s));
  }
};

// The feature frame with dt at least `factor` x the stable step (with the explicit override),
// a whole number of steps per 1 ms frame: n = floor(1 ms / (factor dt_stable)), dt = 1 ms / n.
int make_unstable(double factor) {
  EXPECT_TRUE(ntn_test::feature_frame(spec));
  const double stable = ntn::stable_time_step(ntn::view(spec)).dt_stable;
  const int n = std::max(1, static_cast<int>(1e-3 / (factor * stable)));
  spec.settings.dt = 1e-3 / n;
  spec.settings.allow_unstable = true;
  EXPECT_TRUE(ntn_test::init_model(spec, model).ok());
  EXPECT_GT(model.dt, stable);
  return n;
}

ntn::hil::LoopResult run_unstable(TraceSink& sink, int substeps, double kinetic_limit,
                                  std::int64_t frames = 3'000) {
  state = {};
  ntn::hil::InputGate gate(std::span<const ntn::InputSpec>(spec.inputs));
  SyntheticSource source{&gate, 0};
  ntn::hil::LoopConfig config;
  config.frames = frames;
  config.substeps = substeps;
  config.kinetic_limit = kinetic_limit;
  ntn::hil::VirtualClock clock;
  ntn::hil::FrameTimes times;
  std::vector<ntn::hil::Alarm> alarms(kS.outputs);
  sink.kinetic.reserve(static_cast<std::size_t>(frames * substeps));
  return ntn::hil::run_loop(model, state, scratch, clock, source, sink, nullptr, config, alarms,
                            times, &checkpoint);
}

// |lambda| of central difference with C = alpha M for a mode omega at dt, omega dt > 2: the real
// root of l^2 - (2 - alpha dt - w^2 dt^2) l + (1 - alpha dt) = 0 of largest size (DESIGN §5: v
// and u updates with the damping force at v_{n-1/2}).
double amplification(double omega, double alpha, double dt) {
  const double b = 2 - alpha * dt - omega * omega * dt * dt;
  const double c = 1 - alpha * dt;
  return (std::abs(b) + std::sqrt(b * b - 4 * c)) / 2;
}

// A model driven unstable on purpose (dt >= 1.5 dt_stable, with the explicit override) is caught
// by the kinetic-energy check, before anything overflows; from that frame on the loop is in its
// safe state: every frame flagged kDiverged, the outputs bit for bit the last good frame's, no
// NaN, no step taken, and the state put back to the end of the last good frame (the same bits as
// a run stopped there).
TEST_F(Loop, DivergenceGoesToASafeState) {
  const int n = make_unstable(1.5);
  TraceSink sink;
  const auto result = run_unstable(sink, n, -1);  // the model's own limit
  ASSERT_GE(result.diverged_frame, 1) << "dt / dt_stable = " << model.dt / model.stable.dt_stable;
  EXPECT_EQ(result.reason, ntn::hil::DivergenceReason::kEnergy);
  EXPECT_TRUE(std::isfinite(result.kinetic_limit));
  EXPECT_GT(result.kinetic_at_detection, result.kinetic_limit);
  EXPECT_TRUE(std::isfinite(result.kinetic_at_detection));
  EXPECT_EQ(result.frames, 3'000);
  EXPECT_EQ(sink.nan_outputs, 0);
  const auto kd = static_cast<std::size_t>(result.diverged_frame);
  ASSERT_EQ(sink.flags.size(), 3'000U);
  for (std::size_t k = 0; k < sink.flags.size(); ++k) {
    EXPECT_EQ((sink.flags[k] & ntn::hil::flag::kDiverged) != 0, k >= kd) << "frame " << k;
    if (k >= kd) {
      EXPECT_EQ(
          std::memcmp(sink.outputs[k].data(), sink.outputs[kd - 1].data(), sizeof sink.outputs[k]),
          0)
          << "frame " << k;
    }
  }
  // No step after the diverged frame.
  EXPECT_EQ(static_cast<std::int64_t>(sink.kinetic.size()), result.diverged_step);
  // The state is that at the end of frame kd - 1: a run of kd frames ends with the same bits.
  EXPECT_TRUE(result.state_restored);
  const ntn::State<kS> kept = state;
  TraceSink upto;
  const auto short_run = run_unstable(upto, n, -1, result.diverged_frame);
  EXPECT_EQ(short_run.diverged_frame, -1);
  EXPECT_EQ(std::memcmp(kept.u.data(), state.u.data(), sizeof kept.u), 0);
  EXPECT_EQ(std::memcmp(kept.v.data(), state.v.data(), sizeof kept.v), 0);
  EXPECT_EQ(kept.tick, state.tick);
  EXPECT_EQ(kept.tick, result.diverged_frame * n);
}

// The detection bound (hil_sim/README.md, "Divergence"). The model's fastest mode omega_max (the
// dense eigenproblem of its K and lumped M, tests/support) grows by |lambda| per step at
// omega_max dt > 2, its kinetic energy by |lambda|^2. Once the energy has passed E_max (the
// bound no stable run exceeds), the check fires at the end of the frame in which it passes the
// limit kKineticLimitFactor x E_max, so within ceil(ln(1000) / (2 ln|lambda|)) + substeps steps.
// A check of non-finite values alone fires only when 1/2 v^T M v overflows, about
// ln(DBL_MAX / T_detect) / (2 ln|lambda|) steps later.
TEST_F(Loop, DetectionWithinTheBound) {
  const int n = make_unstable(1.5);
  const ntn_test::Modes modes = ntn_test::modes(ntn::view(spec));
  const double omega_max = modes.omega(modes.omega.size() - 1);
  const double lambda = amplification(omega_max, spec.settings.alpha, model.dt);
  const double e_max = ntn::hil::response_energy_bound(model);
  ASSERT_TRUE(std::isfinite(e_max));

  TraceSink sink;
  const auto result = run_unstable(sink, n, -1);
  ASSERT_GE(result.diverged_frame, 0);
  const std::int64_t n_detect = result.diverged_step;  // steps taken when caught
  // The growth per step at the end is |lambda|^2: the amplification of the fastest mode.
  ASSERT_GE(sink.kinetic.size(), 4U);
  const std::size_t last = sink.kinetic.size() - 1;
  const double growth = sink.kinetic[last] / sink.kinetic[last - 1];
  EXPECT_NEAR(growth / (lambda * lambda), 1.0, 0.02)
      << "omega_max dt = " << omega_max * model.dt << ", |lambda| = " << lambda;
  // The first step whose energy passed E_max, and the bound from there.
  std::int64_t n_cross = -1;
  for (std::size_t i = 0; i < sink.kinetic.size() && n_cross < 0; ++i)
    if (sink.kinetic[i] > e_max) n_cross = static_cast<std::int64_t>(i) + 1;
  ASSERT_GE(n_cross, 0);
  const auto bound = static_cast<std::int64_t>(
      std::ceil(std::log(ntn::hil::kKineticLimitFactor) / (2 * std::log(lambda))) + n);
  EXPECT_LE(n_detect - n_cross, bound);

  // Non-finite check only (no limit): caught when 1/2 v^T M v overflows.
  TraceSink nan_only;
  const auto late = run_unstable(nan_only, n, std::numeric_limits<double>::infinity());
  ASSERT_GE(late.diverged_frame, result.diverged_frame);
  EXPECT_EQ(late.reason, ntn::hil::DivergenceReason::kNonFinite);
  const double predicted =
      std::log(std::numeric_limits<double>::max() / result.kinetic_at_detection) /
      (2 * std::log(lambda));
  // Both are seen at frame ends: +- one frame.
  EXPECT_NEAR(static_cast<double>(late.diverged_step - n_detect), predicted, n + 1.0);
  std::printf(
      "divergence at dt = %.4g dt_stable (omega_max dt = %.3f, |lambda| = %.3f, %d steps per "
      "frame): energy passes E_max = %.4g J at step %lld, caught at step %lld (frame %lld, bound "
      "%lld steps after the crossing); non-finite check alone at step %lld (frame %lld; predicted "
      "%.1f steps after the energy check)\n",
      model.dt / model.stable.dt_stable, omega_max * model.dt, lambda, n, e_max,
      static_cast<long long>(n_cross), static_cast<long long>(n_detect),
      static_cast<long long>(result.diverged_frame), static_cast<long long>(bound),
      static_cast<long long>(late.diverged_step), static_cast<long long>(late.diverged_frame),
      predicted);
}

// No false alarm: the stable model (dt = 0.9 dt_stable) under its inputs at the full range,
// flipped in sign at the first mode's half period (the input that pumps the first mode hardest)
// for 20 000 frames, stays below the limit, and below E_max itself.
TEST_F(Loop, NoFalseAlarmAtFullRangeResonance) {
  const ntn_test::Modes modes = ntn_test::modes(ntn::view(spec));
  const double omega1 = modes.omega(0);
  struct BangBang {
    ntn::hil::InputGate* gate;
    double omega;
    void frame_inputs(std::int64_t k, std::span<double> v, std::uint16_t& flags) {
      const double sign = std::cos(omega * static_cast<double>(k) * 1e-3) >= 0 ? 1.0 : -1.0;
      const std::array<double, kS.inputs> x{5 * sign, 5 * sign, 100 * sign};
      gate->begin_frame(k);
      (void)gate->accept_values(k, x);
      gate->end_frame(v, flags);
    }
  };
  state = {};
  ntn::hil::InputGate gate(std::span<const ntn::InputSpec>(spec.inputs));
  BangBang source{&gate, omega1};
  TraceSink sink;
  ntn::hil::LoopConfig config;
  config.frames = 20'000;
  config.substeps = static_cast<int>(model.substeps.count);
  ntn::hil::VirtualClock clock;
  ntn::hil::FrameTimes times;
  std::vector<ntn::hil::Alarm> alarms(kS.outputs);
  const auto result = ntn::hil::run_loop(model, state, scratch, clock, source, sink, nullptr,
                                         config, alarms, times, &checkpoint);
  EXPECT_EQ(result.diverged_frame, -1);
  const double e_max = ntn::hil::response_energy_bound(model);
  EXPECT_LT(result.peak_kinetic, e_max);
  std::printf(
      "full-range input flipped at %.3f Hz: peak kinetic %.4g J = %.3g E_max (limit %.0f "
      "E_max)\n",
      omega1 / (2 * std::acos(-1.0)), result.peak_kinetic, result.peak_kinetic / e_max,
      ntn::hil::kKineticLimitFactor);
}

// ---- The input schedule in real time, on synthetic time ----
// A real-time clock whose time moves only when the loop waits: to the deadline plus a fixed
// 20 us wake-up latency, or not at all when the deadline is past (a frame that catches up does
// not sleep). A simulated sender's packets carry
// arrival times on that clock; the source below reads, at each frame, those that have arrived
// (as hil_main.cpp's UdpSource reads its socket): the gate, the SenderSchedule and run_loop are
// the real ones, and no result depends on the machine (compute time is measured but only the
// overrun flag, not checked here, uses it).
struct SimClock {
  std::int64_t t = 5'000'000'000;
  std::int64_t wait_until(std::int64_t deadline) {
    if (deadline > t) t = deadline + 20'000;
    return t;
  }
  std::int64_t now() const { return t; }
  static constexpr bool kVirtual = false;
};

struct Arrival {
  std::int64_t t;  // ns, on the SimClock
  std::int64_t frame;
  std::uint32_t sequence;
};

// As UdpSource: frame 0 waits (up to 100 ms) for the first packet whose frame the schedule takes
// as its anchor; every frame then offers what has arrived, in arrival order, to the gate and the
// schedule, and ORs the schedule's resync flag into the frame's.
struct SimUdpSource {
  ntn::hil::InputGate* gate;
  ntn::hil::SenderSchedule* schedule;
  SimClock* clock;
  const std::vector<Arrival>* arrivals;
  std::size_t next = 0;
  ntn::hil::OfferResult offer(const Arrival& a) {
    const double v[3] = {ntn_test::input_sample(0, a.frame), ntn_test::input_sample(1, a.frame),
                         10 * ntn_test::input_sample(2, a.frame)};
    std::array<std::byte, ntn::hil::kMaxPacketBytes> buf{};
    const std::size_t n =
        ntn::hil::encode(ntn::hil::PacketKind::kInput, a.sequence, a.frame, 0, v, buf);
    return gate->offer(std::span<const std::byte>(buf.data(), n));
  }
  void frame_inputs(std::int64_t k, std::span<double> v, std::uint16_t& flags) {
    gate->begin_frame(k);
    const auto& in = *arrivals;
    if (k == 0) {
      const std::int64_t give_up = clock->t + 100'000'000;
      while (next < in.size() && in[next].t <= give_up && !schedule->anchored()) {
        clock->t = std::max(clock->t, in[next].t);
        const auto r = offer(in[next]);
        using ntn::hil::OfferStatus;
        if (r.status == OfferStatus::kCurrent || r.status == OfferStatus::kBuffered ||
            r.status == OfferStatus::kTooEarly)
          (void)schedule->anchor(r.frame, in[next].t, 0);
        ++next;
      }
    }
    for (; next < in.size() && in[next].t <= clock->t; ++next)
      (void)schedule->observe(offer(in[next]), k, clock->t);
    gate->end_frame(v, flags);
    flags |= schedule->take_flags();
  }
  std::int64_t epoch_ns() const { return schedule->epoch_ns(); }
};

struct ScheduleRun {
  ntn::hil::GateCounters counters;
  std::uint64_t resyncs = 0;
  std::vector<std::int64_t> resync_frames;  // frames flagged kResync
  std::int64_t epoch = 0;                   // the loop's frame-0 deadline
  std::int64_t end = 0;                     // SimClock at the end
};

ScheduleRun run_schedule(std::int64_t frames, std::vector<Arrival> arrivals,
                         int resync_after = ntn::hil::SenderSchedule::kResyncAfter) {
  std::stable_sort(arrivals.begin(), arrivals.end(),
                   [](const Arrival& a, const Arrival& b) { return a.t < b.t; });
  state = {};
  ntn::hil::InputGate gate(std::span<const ntn::InputSpec>(spec.inputs));
  EXPECT_TRUE(gate.set_run_frames(frames));
  ntn::hil::SenderSchedule schedule(1'000'000, frames, resync_after);
  SimClock clock;
  SimUdpSource source{&gate, &schedule, &clock, &arrivals};
  TraceSink sink;
  ntn::hil::LoopConfig config;
  config.frames = frames;
  config.substeps = static_cast<int>(model.substeps.count);
  ntn::hil::FrameTimes times;
  times.reserve(frames);
  std::vector<ntn::hil::Alarm> alarms(kS.outputs);
  const auto result = ntn::hil::run_loop(model, state, scratch, clock, source, sink, nullptr,
                                         config, alarms, times);
  ScheduleRun r;
  r.counters = gate.counters();
  r.resyncs = schedule.resyncs();
  for (std::size_t k = 0; k < sink.flags.size(); ++k)
    if ((sink.flags[k] & ntn::hil::flag::kResync) != 0)
      r.resync_frames.push_back(static_cast<std::int64_t>(k));
  r.epoch = result.epoch_ns;
  r.end = clock.t;
  return r;
}

// A sender on its schedule: frame f at e + f P + jitter (0..99 us, deterministic), sequence f.
std::vector<Arrival> stream(std::int64_t e, std::int64_t from, std::int64_t to) {
  std::vector<Arrival> a;
  for (std::int64_t f = from; f < to; ++f)
    a.push_back({e + f * 1'000'000 + (f * 37 % 100) * 1'000, f, static_cast<std::uint32_t>(f)});
  return a;
}

// Regression: one valid packet for frame 18 445 744 073 710 came first; the loop took its
// deadlines from it (arrival - frame x period overflowed: frame 0 due in ~11 days) and hung. Now
// it is out of the run, never the anchor: the deadlines follow the first plausible packet and the
// run ends on time with every frame accepted.
TEST_F(Loop, HugeFrameIndexNeverSetsTheDeadlines) {
  const std::int64_t e = SimClock{}.t + 3'000'000;
  std::vector<Arrival> a = stream(e, 0, 1000);
  a.push_back({e - 1'000'000, 18'445'744'073'710, 77});    // before the stream
  a.push_back({e + 500'300'000, 18'445'744'073'710, 78});  // and in the middle
  a.push_back({e + 600'300'000, 999'999, 79});             // beyond the run
  const ScheduleRun r = run_schedule(1000, a);
  EXPECT_EQ(r.epoch, e + 0 * 1'000'000 + 500'000);  // packet 0 (jitter 0) + P / 2
  EXPECT_EQ(r.counters.out_of_run, 3u);
  EXPECT_EQ(r.counters.accepted, 1000u);
  EXPECT_EQ(r.resyncs, 0u);
  // Frame 999 due at epoch + 999 P, woken 20 us later.
  EXPECT_EQ(r.end, r.epoch + 999 * 1'000'000 + 20'000);
}

// Regression: the sender's first 15 ms arrive as one burst. The first packet's arrival put
// every deadline 15 ms late, so every later packet came more than the jitter buffer's 8 frames
// early and was dropped: 9 of 1000 frames accepted (resync off reproduces that). With the
// resync rule, K = 8 too-early packets at one lead re-anchor the schedule once;
// the frames lost are those whose packets were dropped before it: the lead (15) plus the K
// packets of the run less the 8 frames the jitter buffer held, at most 15 + K.
TEST_F(Loop, LateFirstBurstResyncsOnce) {
  const std::int64_t e = SimClock{}.t + 2'000'000;
  std::vector<Arrival> a = stream(e, 0, 1000);
  for (Arrival& x : a)
    if (x.frame < 15) x.t = e + 15'000'000;  // the burst
  const ScheduleRun off = run_schedule(1000, a, 0);
  EXPECT_EQ(off.counters.accepted, 9u);  // the rule without resync
  EXPECT_EQ(off.counters.too_early, 991u);
  const ScheduleRun r = run_schedule(1000, a);
  EXPECT_EQ(r.resyncs, 1u);
  ASSERT_EQ(r.resync_frames.size(), 1u);
  EXPECT_GE(r.counters.accepted,
            1000u - 15u - static_cast<unsigned>(ntn::hil::SenderSchedule::kResyncAfter));
  EXPECT_EQ(r.counters.late, 0u);
  EXPECT_EQ(r.counters.accepted + r.counters.missing, 1000u);
  std::printf("late first burst: %llu of 1000 accepted, resync at frame %lld\n",
              static_cast<unsigned long long>(r.counters.accepted),
              static_cast<long long>(r.resync_frames[0]));
}

// A DAQ that stalls once for 30 ms and then goes on 30 ms behind its schedule: every later packet
// would be late (after its frame ran). Late packets at one lead re-anchor the deadlines once,
// when they are K of the last 2K and the majority (K + 1 of a window full of used packets): the
// frames lost are the 30 of the stall and those K + 1.
TEST_F(Loop, SenderStallResyncsOnce) {
  const std::int64_t e = SimClock{}.t + 2'000'000;
  std::vector<Arrival> a = stream(e, 0, 2000);
  for (Arrival& x : a)
    if (x.frame >= 500) x.t += 30'000'000;
  const ScheduleRun off = run_schedule(2000, a, 0);
  EXPECT_LE(off.counters.accepted, 500u);
  const ScheduleRun r = run_schedule(2000, a);
  EXPECT_EQ(r.resyncs, 1u);
  EXPECT_EQ(r.resync_frames.size(), 1u);
  EXPECT_GE(r.counters.accepted,
            2000u - 30u - 1u - static_cast<unsigned>(ntn::hil::SenderSchedule::kResyncAfter));
  EXPECT_EQ(r.counters.accepted + r.counters.missing, 2000u);
  std::printf("sender stall: %llu of 2000 accepted (%llu without resync)\n",
              static_cast<unsigned long long>(r.counters.accepted),
              static_cast<unsigned long long>(off.counters.accepted));
}

// A DAQ whose clock runs 200 ppm slow: 10 000 frames drift 2 periods. The packets come later
// and later until they miss their frames; with 100 us of jitter the late ones start as a few and
// become all over 100 us / 0.2 us = 500 frames. The schedule re-anchors once late packets are the
// majority of the last 2K (K or more), so before each resync at most about a quarter of those
// 500 frames (late fraction rising linearly to 1/2) plus K + 1 are lost; a resync moves the
// deadlines to the latest the packets allow, so the next one comes only after about a period
// more of drift: at most 2 resyncs, at most 2 x (125 + K + 1) frames lost (measured: 156).
TEST_F(Loop, SlowSenderClockKeepsRunning) {
  const std::int64_t e = SimClock{}.t + 2'000'000;
  std::vector<Arrival> a;
  for (std::int64_t f = 0; f < 10'000; ++f)
    a.push_back({e + f * 1'000'200 + (f * 37 % 100) * 1'000, f, static_cast<std::uint32_t>(f)});
  const ScheduleRun off = run_schedule(10'000, a, 0);
  EXPECT_LT(off.counters.accepted, 3000u);  // late from ~frame 2000 on
  const ScheduleRun r = run_schedule(10'000, a);
  EXPECT_GE(r.resyncs, 1u);
  EXPECT_LE(r.resyncs, 2u);
  EXPECT_EQ(r.resync_frames.size(), r.resyncs);
  EXPECT_GE(r.counters.accepted,
            10'000u - r.resyncs * (125u + 1u +
                                   static_cast<unsigned>(ntn::hil::SenderSchedule::kResyncAfter)));
  std::printf("200 ppm slow sender: %llu of 10000 accepted, %llu resyncs (%llu without resync)\n",
              static_cast<unsigned long long>(r.counters.accepted),
              static_cast<unsigned long long>(r.resyncs),
              static_cast<unsigned long long>(off.counters.accepted));
}

// Rogue packets in a healthy stream never move the schedule: single packets far ahead or behind
// (within the window: too early / late), a stale first packet from a previous run excepted: it
// is the anchor, and the stream corrects it after K packets.
TEST_F(Loop, RoguePacketsDoNotMoveTheSchedule) {
  const std::int64_t e = SimClock{}.t + 2'000'000;
  std::vector<Arrival> a = stream(e, 0, 2000);
  for (std::int64_t i = 4; i < 17; ++i) {
    const std::int64_t at = i * 100;
    a.push_back(
        {e + at * 1'000'000 + 300'000, at + 200 + i, 1'000'000u + static_cast<unsigned>(i)});
    a.push_back({e + at * 1'000'000 + 400'000, at - 300, 2'000'000u + static_cast<unsigned>(i)});
  }
  const ScheduleRun r = run_schedule(2000, a);
  EXPECT_EQ(r.resyncs, 0u);
  EXPECT_EQ(r.counters.accepted, 2000u);
  EXPECT_EQ(r.counters.too_early, 13u);
  EXPECT_EQ(r.counters.late, 13u);
  EXPECT_EQ(r.epoch, e + 500'000);
  // A stale packet for frame 600 just before the stream: the loop runs frames 0..599 at once,
  // then sees the stream 600 frames late, K packets in a row: one resync, and the loop waits for
  // the sender from there (every frame from 600 + K + 2 on accepted).
  std::vector<Arrival> b = stream(e, 0, 2000);
  b.push_back({e - 100'000, 600, 5});
  const ScheduleRun s = run_schedule(2000, b);
  EXPECT_EQ(s.resyncs, 1u);
  EXPECT_GE(s.counters.accepted,
            2000u - 600u - 2u - static_cast<unsigned>(ntn::hil::SenderSchedule::kResyncAfter));
}

// Soak: 10^6 frames on the virtual clock, no allocation after the start, and a second run gives
// the same hash of every frame's outputs (label soak: about a minute in Release).
// Input sampling (sampling.hpp): with kStep every kernel step n gets the
// source's step_inputs(n), in order, and a step count that is not whole frames cuts the last
// frame short. The loop's state must equal, bit for bit, a plain start / step loop fed the same
// values (the runner's semantics before it ran the loop); the held run must not (the option does
// something). Synthetic values through start (frame 0's, which are step 0's) and every step.
struct StepSource {
  ntn::hil::InputGate* gate;
  int substeps = 1;
  std::int64_t next_step = 0;  // the step_inputs call expected next
  bool in_order = true;
  static std::array<double, kS.inputs> at(std::int64_t n) {
    return {ntn_test::input_sample(0, n), ntn_test::input_sample(1, n),
            10 * ntn_test::input_sample(2, n)};
  }
  void frame_inputs(std::int64_t k, std::span<double> v, std::uint16_t& flags) {
    gate->begin_frame(k);
    (void)gate->accept_values(k, at(k * substeps));
    gate->end_frame(v, flags);
  }
  void step_inputs(std::int64_t n, std::span<double> v) {
    in_order = in_order && n == next_step++;
    const auto x = at(n);
    std::copy(x.begin(), x.end(), v.begin());
  }
};

struct StepCountSink {
  std::int64_t steps = 0, frames = 0;
  void after_step(const ntn::State<kS>&, const ntn::Scratch<kS>&) { ++steps; }
  void frame_outputs(std::int64_t, std::span<const double>, std::uint16_t) { ++frames; }
};

TEST_F(Loop, StepSamplingFeedsEveryStepAndCutsTheLastFrame) {
  const int n_sub = static_cast<int>(std::llround(1e-3 / model.dt));
  ASSERT_GT(n_sub, 1);
  const std::int64_t steps = 57 * n_sub + n_sub / 2 + 1;  // 57 frames and part of one
  ntn::State<kS> reference;
  ntn::Scratch<kS> w;
  (void)ntn::start(model, reference, w, StepSource::at(0));
  for (std::int64_t n = 0; n < steps; ++n)
    (void)ntn::step(model, reference, w, StepSource::at(n));

  const auto run_with = [&](ntn::hil::InputSampling sampling, StepSource& source,
                            StepCountSink& sink) {
    state = {};
    ntn::hil::LoopConfig config;
    config.period = 1e-3;
    config.substeps = n_sub;
    config.steps = steps;
    config.frames = (steps + n_sub - 1) / n_sub;
    config.sampling = sampling;
    ntn::hil::VirtualClock clock;
    ntn::hil::FrameTimes times;
    std::vector<ntn::hil::Alarm> alarms(kS.outputs);
    return ntn::hil::run_loop(model, state, scratch, clock, source, sink, nullptr, config, alarms,
                              times);
  };
  ntn::hil::InputGate gate(std::span<const ntn::InputSpec>(spec.inputs));
  StepSource source{&gate, n_sub};
  StepCountSink sink;
  const ntn::hil::LoopResult r = run_with(ntn::hil::InputSampling::kStep, source, sink);
  EXPECT_EQ(r.frames, 58);
  EXPECT_EQ(sink.frames, 58);
  EXPECT_EQ(sink.steps, steps);
  EXPECT_EQ(state.tick, steps);
  EXPECT_EQ(source.next_step, steps);
  EXPECT_TRUE(source.in_order);
  EXPECT_EQ(std::memcmp(state.u.data(), reference.u.data(), sizeof state.u), 0);
  EXPECT_EQ(std::memcmp(state.v.data(), reference.v.data(), sizeof state.v), 0);

  ntn::hil::InputGate gate_held(std::span<const ntn::InputSpec>(spec.inputs));
  StepSource held{&gate_held, n_sub};
  StepCountSink held_sink;
  (void)run_with(ntn::hil::InputSampling::kFrameHeld, held, held_sink);
  EXPECT_EQ(held.next_step, 0);  // step_inputs is not asked for
  EXPECT_EQ(held_sink.steps, steps);
  EXPECT_NE(std::memcmp(state.u.data(), reference.u.data(), sizeof state.u), 0);
}

// stop_at_divergence ends the run at the diverged frame (ntn-run-<model>); without it the loop
// holds its safe state to the last frame.
TEST_F(Loop, StopAtDivergenceEndsTheRun) {
  for (const bool stop : {false, true}) {
    state = {};
    ntn::hil::InputGate gate(std::span<const ntn::InputSpec>(spec.inputs));
    StepSource source{&gate, 1};
    StepCountSink sink;
    ntn::hil::LoopConfig config;
    config.frames = 50;
    config.substeps = static_cast<int>(std::llround(config.period / model.dt));
    config.kinetic_limit = 0;  // any motion is "diverged": frame 0 already
    config.stop_at_divergence = stop;
    ntn::hil::VirtualClock clock;
    ntn::hil::FrameTimes times;
    std::vector<ntn::hil::Alarm> alarms(kS.outputs);
    const ntn::hil::LoopResult r = ntn::hil::run_loop(model, state, scratch, clock, source, sink,
                                                      nullptr, config, alarms, times);
    ASSERT_EQ(r.diverged_frame, 0);
    EXPECT_EQ(r.frames, stop ? 1 : 50);
    EXPECT_EQ(sink.frames, stop ? 1 : 50);
    EXPECT_FALSE(r.stopped);
  }
}

TEST_F(Loop, SoakMillionFramesRepeatable) {
  ntn::hil::VirtualClock clock;
  ntn::hil::FrameTimes t1, t2;
  std::uint64_t a1 = 1, a2 = 1;
  const std::uint64_t h1 = run(1'000'000, 997, clock, t1, &a1);
  const std::uint64_t h2 = run(1'000'000, 997, clock, t2, &a2);
  EXPECT_EQ(h1, h2);
  EXPECT_EQ(a1, 0U);
  EXPECT_EQ(a2, 0U);
}

}  // namespace loop_test
