// Input holding (DESIGN §8): a non-finite input never reaches the state. It is replaced by the
// channel's last good value, counted in State::inputs_held, flagged in State::faults (sticky) and
// reported by the step's status; the run is then bit-identical to one fed the held value.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>

#include "ntn/kernel.hpp"
#include "support/frames.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"

namespace input_test {

constexpr ntn::Sizes kS = ntn_test::kFeatureSizes;
using Inputs = std::array<double, kS.inputs>;

ntn::ModelSpec<kS> spec;
ntn::Model<kS> model;
ntn::State<kS> bad, good;
ntn::Scratch<kS> wbad, wgood;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

Inputs inputs_at(long n) {
  return {ntn_test::input_sample(0, n), ntn_test::input_sample(1, n),
          10 * ntn_test::input_sample(2, n)};
}

class InputHolding : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(ntn_test::feature_frame(spec));
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
    bad = {}, good = {};
  }
};

// Bad samples on several channels and steps (NaN, +Inf, -Inf, two at once). The reference run
// gets, for each bad sample, the value the channel last accepted.
TEST_F(InputHolding, BadSamplesAreHeldCountedAndFlagged) {
  struct Bad {
    long step;
    int channel;
    double value;
  };
  const Bad bads[] = {{100, 0, kNaN},  {101, 0, kNaN}, {250, 1, kInf},
                      {400, 2, -kInf}, {400, 0, kNaN}, {900, 2, kNaN}};
  const ntn_test::EigenNoMalloc guard;
  ASSERT_EQ(ntn::start(model, bad, wbad, inputs_at(-1)), ntn::StepStatus::kOk);
  ASSERT_EQ(ntn::start(model, good, wgood, inputs_at(-1)), ntn::StepStatus::kOk);
  Inputs last = inputs_at(-1);
  std::uint64_t expected_held = 0;
  for (long n = 0; n < 2000; ++n) {
    Inputs in = inputs_at(n), ref = in;
    bool any_bad = false;
    for (const Bad& b : bads) {
      if (b.step == n) {
        in[static_cast<std::size_t>(b.channel)] = b.value;
        ref[static_cast<std::size_t>(b.channel)] = last[static_cast<std::size_t>(b.channel)];
        any_bad = true;
        ++expected_held;
      }
    }
    const ntn::StepStatus st = ntn::step(model, bad, wbad, in);
    ASSERT_EQ(ntn::step(model, good, wgood, ref), ntn::StepStatus::kOk);
    ASSERT_EQ(st, any_bad ? ntn::StepStatus::kInputHeld : ntn::StepStatus::kOk) << "step " << n;
    EXPECT_EQ(std::memcmp(bad.held_inputs.data(), ref.data(), sizeof(ref)), 0) << "step " << n;
    EXPECT_EQ(bad.inputs_held, expected_held);
    last = ref;
    EXPECT_EQ(bad.faults, n < 100 ? 0U : ntn::kFaultInputHeld) << "step " << n;  // sticky
  }
  EXPECT_EQ(std::memcmp(bad.u.data(), good.u.data(), sizeof(bad.u)), 0);
  EXPECT_EQ(std::memcmp(bad.v.data(), good.v.data(), sizeof(bad.v)), 0);
  EXPECT_EQ(bad.tick, good.tick);
  EXPECT_EQ(std::memcmp(wbad.outputs.data(), wgood.outputs.data(), sizeof(wbad.outputs)), 0);
  EXPECT_EQ(good.inputs_held, 0U);
  EXPECT_EQ(good.faults, 0U);
}

// At start there is no last good value yet: a bad sample is held at 0.
TEST_F(InputHolding, BadSampleAtStartIsHeldAtZero) {
  const ntn_test::EigenNoMalloc guard;
  EXPECT_EQ(ntn::start(model, bad, wbad, {kNaN, 0.1, kInf}), ntn::StepStatus::kInputHeld);
  ASSERT_EQ(ntn::start(model, good, wgood, {0.0, 0.1, 0.0}), ntn::StepStatus::kOk);
  EXPECT_EQ(bad.inputs_held, 2U);
  EXPECT_EQ(bad.faults, ntn::kFaultInputHeld);
  for (long n = 0; n < 100; ++n) {
    ASSERT_EQ(ntn::step(model, bad, wbad, inputs_at(n)), ntn::StepStatus::kOk);
    ASSERT_EQ(ntn::step(model, good, wgood, inputs_at(n)), ntn::StepStatus::kOk);
  }
  EXPECT_EQ(std::memcmp(bad.u.data(), good.u.data(), sizeof(bad.u)), 0);
  EXPECT_EQ(std::memcmp(bad.v.data(), good.v.data(), sizeof(bad.v)), 0);
}

// A finite sample outside the channel's [min, max] (here +-5 g and +-100 x 1 kN) is held the
// same way, counted apart from non-finite ones, and flagged with its own fault bit.
TEST_F(InputHolding, OutOfRangeSamplesAreHeldAndCountedApart) {
  const ntn_test::EigenNoMalloc guard;
  ASSERT_EQ(ntn::start(model, bad, wbad, inputs_at(-1)), ntn::StepStatus::kOk);
  ASSERT_EQ(ntn::start(model, good, wgood, inputs_at(-1)), ntn::StepStatus::kOk);
  for (long n = 0; n < 500; ++n) {
    Inputs in = inputs_at(n);
    const Inputs ref = n == 200 ? Inputs{good.held_inputs[0], in[1], good.held_inputs[2]} : in;
    if (n == 200) in[0] = 5.0001, in[2] = -1e6;  // just past +5 g; far past -100
    const ntn::StepStatus st = ntn::step(model, bad, wbad, in);
    ASSERT_EQ(ntn::step(model, good, wgood, ref), ntn::StepStatus::kOk);
    ASSERT_EQ(st, n == 200 ? ntn::StepStatus::kInputHeld : ntn::StepStatus::kOk) << "step " << n;
  }
  EXPECT_EQ(bad.inputs_out_of_range, 2U);
  EXPECT_EQ(bad.inputs_held, 0U);
  EXPECT_EQ(bad.faults, ntn::kFaultInputRange);
  EXPECT_EQ(std::memcmp(bad.u.data(), good.u.data(), sizeof(bad.u)), 0);
  EXPECT_EQ(std::memcmp(bad.v.data(), good.v.data(), sizeof(bad.v)), 0);
}

// The bounds themselves are accepted: the range is closed.
TEST_F(InputHolding, RangeBoundsAreAccepted) {
  const ntn_test::EigenNoMalloc guard;
  EXPECT_EQ(ntn::start(model, bad, wbad, {5.0, -5.0, 100.0}), ntn::StepStatus::kOk);
  EXPECT_EQ(ntn::step(model, bad, wbad, {-5.0, 5.0, -100.0}), ntn::StepStatus::kOk);
  EXPECT_EQ(bad.faults, 0U);
}

struct ChannelCase {
  const char* name;
  void (*edit)(ntn::ModelSpec<kS>&);
  ntn::InitError error;
  int where;
};

// A hand-built spec whose channels point outside the model is refused by init, with the
// channel index, before step() could index out of bounds.
TEST(ChannelReferences, InitRefusesBadInputsAndOutputs) {
  using E = ntn::InitError;
  const ChannelCase cases[] = {
      {"ground acceleration about a rotation", [](ntn::ModelSpec<kS>& s) { s.inputs[1].dof = 5; },
       E::kBadInput, 1},
      {"nodal force at a missing node", [](ntn::ModelSpec<kS>& s) { s.inputs[2].node = kS.nodes; },
       E::kBadInput, 2},
      {"empty range", [](ntn::ModelSpec<kS>& s) { s.inputs[0].min = 1, s.inputs[0].max = -1; },
       E::kBadInput, 0},
      {"displacement of a missing node", [](ntn::ModelSpec<kS>& s) { s.outputs[0].node = -1; },
       E::kBadOutput, 0},
      {"DOF 6", [](ntn::ModelSpec<kS>& s) { s.outputs[1].dof = 6; }, E::kBadOutput, 1},
      {"missing element", [](ntn::ModelSpec<kS>& s) { s.outputs[3].element = kS.elements; },
       E::kBadOutput, 3},
      {"element end 2", [](ntn::ModelSpec<kS>& s) { s.outputs[3].end = 2; }, E::kBadOutput, 3},
      {"drift to a missing node", [](ntn::ModelSpec<kS>& s) { s.outputs[4].node2 = 999; },
       E::kBadOutput, 4},
  };
  for (const ChannelCase& c : cases) {
    ASSERT_TRUE(ntn_test::feature_frame(spec));
    ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
    c.edit(spec);
    const ntn::InitStatus st = ntn_test::init_model(spec, model);
    EXPECT_EQ(st.error, c.error) << c.name;
    EXPECT_EQ(st.where, c.where) << c.name;
  }
}

}  // namespace input_test
