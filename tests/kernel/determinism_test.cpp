// Determinism (DESIGN §2): the result of a run is a function of (model, dt, inputs)
// only. Two runs give bit-identical states; a checkpoint (a copy of the State) resumed gives
// bit-identical results to the uninterrupted run, with or without the Scratch (which step()
// recomputes and never reads across steps).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "ntn/kernel.hpp"
#include "support/frames.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"

namespace determinism_test {

constexpr ntn::Sizes kS = ntn_test::kFeatureSizes;
using Inputs = std::array<double, kS.inputs>;

ntn::ModelSpec<kS> spec;
ntn::Model<kS> model_a, model_b;
ntn::State<kS> a, b, checkpoint;
ntn::Scratch<kS> wa, wb, w_checkpoint;

Inputs inputs_at(long n) {
  return {ntn_test::input_sample(0, n), ntn_test::input_sample(1, n),
          10 * ntn_test::input_sample(2, n)};
}

// Steps [from, to) with the recorded inputs; returns false if a step did not return kOk.
bool run(const ntn::Model<kS>& m, ntn::State<kS>& s, ntn::Scratch<kS>& w, long from, long to) {
  const ntn_test::EigenNoMalloc guard;
  for (long n = from; n < to; ++n) {
    if (ntn::step(m, s, w, inputs_at(n)) != ntn::StepStatus::kOk) return false;
  }
  return true;
}

bool start(const ntn::Model<kS>& m, ntn::State<kS>& s, ntn::Scratch<kS>& w) {
  const ntn_test::EigenNoMalloc guard;
  s = {};
  return ntn::start(m, s, w, inputs_at(-1)) == ntn::StepStatus::kOk;
}

void expect_identical(const ntn::State<kS>& x, const ntn::State<kS>& y) {
  EXPECT_EQ(std::memcmp(x.u.data(), y.u.data(), sizeof(x.u)), 0);
  EXPECT_EQ(std::memcmp(x.v.data(), y.v.data(), sizeof(x.v)), 0);
  EXPECT_EQ(std::memcmp(x.held_inputs.data(), y.held_inputs.data(), sizeof(x.held_inputs)), 0);
  EXPECT_EQ(x.tick, y.tick);
  EXPECT_EQ(x.inputs_held, y.inputs_held);
  EXPECT_EQ(x.faults, y.faults);
}

class Determinism : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(ntn_test::feature_frame(spec));
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(spec, model_a).ok());
    ASSERT_TRUE(ntn_test::init_model(spec, model_b).ok());  // a second, independently built model
  }
};

TEST_F(Determinism, InitIsRepeatable) {
  EXPECT_EQ(std::memcmp(model_a.mass.data(), model_b.mass.data(), sizeof(model_a.mass)), 0);
  EXPECT_EQ(std::memcmp(model_a.beams.data(), model_b.beams.data(), sizeof(model_a.beams)), 0);
  EXPECT_EQ(
      std::memcmp(model_a.rotations.data(), model_b.rotations.data(), sizeof(model_a.rotations)),
      0);
  EXPECT_EQ(
      std::memcmp(model_a.stiffness.data(), model_b.stiffness.data(), sizeof(model_a.stiffness)),
      0);
  EXPECT_EQ(model_a.dt, model_b.dt);
  EXPECT_EQ(model_a.stable.dt_stable, model_b.stable.dt_stable);
}

TEST_F(Determinism, TwoRunsAreBitIdentical) {
  constexpr long kSteps = 20'000;
  ASSERT_TRUE(start(model_a, a, wa));
  ASSERT_TRUE(start(model_b, b, wb));
  ASSERT_TRUE(run(model_a, a, wa, 0, kSteps));
  ASSERT_TRUE(run(model_b, b, wb, 0, kSteps));
  expect_identical(a, b);
  EXPECT_EQ(std::memcmp(wa.outputs.data(), wb.outputs.data(), sizeof(wa.outputs)), 0);
  EXPECT_EQ(a.tick, kSteps);
  EXPECT_NE(a.u[ntn_test::dof(6, ntn::kUx)], 0.0);  // something happened
}

TEST_F(Determinism, CheckpointResumesBitIdentically) {
  constexpr long kHalf = 10'000, kEnd = 20'000;
  ASSERT_TRUE(start(model_a, a, wa));
  ASSERT_TRUE(run(model_a, a, wa, 0, kHalf));
  checkpoint = a, w_checkpoint = wa;              // the checkpoint: a copy
  ASSERT_TRUE(run(model_a, a, wa, kHalf, kEnd));  // uninterrupted run

  // Resume from the State and Scratch copies.
  b = checkpoint, wb = w_checkpoint;
  ASSERT_TRUE(run(model_b, b, wb, kHalf, kEnd));
  expect_identical(a, b);
  EXPECT_EQ(std::memcmp(wa.outputs.data(), wb.outputs.data(), sizeof(wa.outputs)), 0);

  // Resume from the State alone, with a fresh Scratch: Scratch is not part of a checkpoint.
  b = checkpoint, wb = {};
  ASSERT_TRUE(run(model_b, b, wb, kHalf, kEnd));
  expect_identical(a, b);
  EXPECT_EQ(std::memcmp(wa.outputs.data(), wb.outputs.data(), sizeof(wa.outputs)), 0);
}

// With stiffness-proportional damping (beta K_el, 20 % of critical at the elements' highest
// frequency, in the element pass's own loop) two independently built models give bit-identical
// runs too, and beta changes the result (the same inputs without it end elsewhere).
TEST_F(Determinism, TwoRunsWithStiffnessProportionalDampingAreBitIdentical) {
  constexpr long kSteps = 20'000;
  ASSERT_TRUE(start(model_a, a, wa));
  ASSERT_TRUE(run(model_a, a, wa, 0, kSteps));
  checkpoint = a;  // the run without beta
  spec.settings.beta = 0.4 / ntn::stable_time_step(ntn::view(spec)).omega_max;
  spec.settings.dt = 0.9 * ntn::stable_time_step(ntn::view(spec)).dt_stable;
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(spec, model_a).ok());
    ASSERT_TRUE(ntn_test::init_model(spec, model_b).ok());
  }
  ASSERT_TRUE(start(model_a, a, wa));
  ASSERT_TRUE(start(model_b, b, wb));
  ASSERT_TRUE(run(model_a, a, wa, 0, kSteps));
  ASSERT_TRUE(run(model_b, b, wb, 0, kSteps));
  expect_identical(a, b);
  EXPECT_EQ(std::memcmp(wa.outputs.data(), wb.outputs.data(), sizeof(wa.outputs)), 0);
  EXPECT_NE(std::memcmp(a.u.data(), checkpoint.u.data(), sizeof(a.u)), 0);
}

// A run is a function of its inputs: perturbing one input sample by a part in 2^30 changes the
// result (so the comparisons above are not comparing a state the inputs never reach). Not one
// ulp: a one-ulp change of a ground acceleration moves u by dt^2 x 1e-16 relative, below the ulp
// of u, so whether it shows depends on rounding luck (it stopped showing when dt moved by an ulp
// with the cancellation-free stable-step formula).
TEST_F(Determinism, ATinyChangeOfOneInputChangesTheState) {
  ASSERT_TRUE(start(model_a, a, wa));
  ASSERT_TRUE(start(model_b, b, wb));
  ASSERT_TRUE(run(model_a, a, wa, 0, 1000));
  ASSERT_TRUE(run(model_b, b, wb, 0, 500));
  Inputs in = inputs_at(500);
  in[0] += std::ldexp(std::abs(in[0]) + 1e-3, -30);
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_EQ(ntn::step(model_b, b, wb, in), ntn::StepStatus::kOk);
  }
  ASSERT_TRUE(run(model_b, b, wb, 501, 1000));
  EXPECT_NE(std::memcmp(a.u.data(), b.u.data(), sizeof(a.u)), 0);
}

}  // namespace determinism_test
