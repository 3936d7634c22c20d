// The frame loop (hil_sim/include/ntn/hil/loop.hpp): no allocation once running, the real-time
// and the virtual clock give the same outputs for the same accepted inputs, inputs through the
// gate never carry a NaN into the state, a diverging model goes to a safe state, and a long
// virtual run repeats bit for bit (soak).
#include <gtest/gtest.h>
#include <xxhash.h>

#include <cmath>
#include <limits>
#include <vector>

#include "ntn/hil/gate.hpp"
#include "ntn/hil/loop.hpp"
#include "ntn/kernel.hpp"
#include "support/alloc_counter.hpp"
#include "support/frames.hpp"

namespace {

constexpr ntn::Sizes kS = ntn_test::kFeatureSizes;
ntn::ModelSpec<kS> spec;
ntn::Model<kS> model;
ntn::State<kS> state;
ntn::Scratch<kS> scratch;

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
  config.substeps = static_cast<int>(std::llround(config.period / model.dt));
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
    spec.settings.dt = ntn::auto_time_step(ntn::stable_time_step(ntn::view(spec)).dt_stable, 1e-3);
    ASSERT_TRUE(ntn::init(spec, model).ok());
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
  config.substeps = static_cast<int>(std::llround(config.period / model.dt));
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

// A model driven unstable on purpose (dt at least 1.3 x the stable step, with the explicit
// override) is caught within the frame its state stops being finite; the outputs are then the last
// good ones, flagged, and the loop carries on without a NaN.
TEST_F(Loop, DivergenceGoesToASafeState) {
  ASSERT_TRUE(ntn_test::feature_frame(spec));
  const double stable = ntn::stable_time_step(ntn::view(spec)).dt_stable;
  // The frame must hold a whole number of steps: n = floor(1 ms / (1.3 dt_stable)) steps of
  // dt = 1 ms / n >= 1.3 dt_stable.
  const int n = std::max(1, static_cast<int>(1e-3 / (1.3 * stable)));
  spec.settings.dt = 1e-3 / n;
  spec.settings.allow_unstable = true;
  ASSERT_TRUE(ntn::init(spec, model).ok());
  ASSERT_GT(model.dt, stable);
  state = {};
  ntn::hil::InputGate gate(std::span<const ntn::InputSpec>(spec.inputs));
  SyntheticSource source{&gate, 0};
  HashSink sink;
  ntn::hil::LoopConfig config;
  config.frames = 3'000;
  config.substeps = static_cast<int>(std::llround(1e-3 / model.dt));
  ntn::hil::VirtualClock clock;
  ntn::hil::FrameTimes times;
  std::vector<ntn::hil::Alarm> alarms(kS.outputs);
  const auto result = ntn::hil::run_loop(model, state, scratch, clock, source, sink, nullptr,
                                         config, alarms, times);
  ASSERT_GE(result.diverged_frame, 0) << "dt / dt_stable = " << model.dt / stable;
  EXPECT_EQ(result.frames, 3'000);
  EXPECT_EQ(sink.nan_outputs, 0);
  EXPECT_NE(sink.flags_or & ntn::hil::flag::kDiverged, 0);
  EXPECT_NE(state.faults & ntn::kFaultDiverged, 0U);
}

// Soak: 10^6 frames on the virtual clock, no allocation after the start, and a second run gives
// the same hash of every frame's outputs (label soak: about a minute in Release).
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

}  // namespace
