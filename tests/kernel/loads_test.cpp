// External loads (kernel/include/ntn/loads.hpp and the load stage of step(), DESIGN §5):
// piecewise-linear time functions, nodal loads, gravity, base excitation and force inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "ntn/kernel.hpp"
#include "support/builders.hpp"
#include "support/frames.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"

namespace loads_test {

using ntn_test::dof;

// Values at and between the points are the linear interpolation (to rounding, 1e-15 of the
// values' scale); outside the points the end values hold.
TEST(TimeFunction, InterpolatesLinearlyAndHoldsTheEnds) {
  const std::vector<ntn::TimePoint> pts = {{0.0, 0.0}, {1.0, 2.0}, {3.0, -2.0}};
  const ntn::TimeFunctionSpec f{0, 3};
  EXPECT_EQ(ntn::time_function_value(pts, f, -5.0), 0.0);
  EXPECT_EQ(ntn::time_function_value(pts, f, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(ntn::time_function_value(pts, f, 0.25), 0.5);
  EXPECT_EQ(ntn::time_function_value(pts, f, 1.0), 2.0);
  EXPECT_DOUBLE_EQ(ntn::time_function_value(pts, f, 2.0), 0.0);
  EXPECT_DOUBLE_EQ(ntn::time_function_value(pts, f, 2.5), -1.0);
  EXPECT_EQ(ntn::time_function_value(pts, f, 3.0), -2.0);
  EXPECT_EQ(ntn::time_function_value(pts, f, 1e9), -2.0);
}

TEST(TimeFunction, SinglePointIsConstantAndNoPointsIsOne) {
  const std::vector<ntn::TimePoint> pts = {{0.0, 9.0}, {2.0, 7.5}};
  EXPECT_EQ(ntn::time_function_value(pts, {1, 1}, -1.0), 7.5);
  EXPECT_EQ(ntn::time_function_value(pts, {1, 1}, 2.0), 7.5);
  EXPECT_EQ(ntn::time_function_value(pts, {1, 1}, 50.0), 7.5);
  EXPECT_EQ(ntn::time_function_value(pts, {0, 0}, 1.0), 1.0);
  const std::vector<ntn::TimeFunctionSpec> fns = {{0, 2}};
  EXPECT_EQ(ntn::load_factor(pts, fns, ntn::kConstant, 123.0), 1.0);
  EXPECT_DOUBLE_EQ(ntn::load_factor(pts, fns, 0, 1.0), 8.25);
}

// A step: two points at the same time switch the value there (the later point wins at t).
TEST(TimeFunction, RepeatedTimeMakesAStep) {
  const std::vector<ntn::TimePoint> pts = {{0, 0}, {1, 0}, {1, 1}, {2, 1}};
  const ntn::TimeFunctionSpec f{0, 4};
  EXPECT_EQ(ntn::time_function_value(pts, f, std::nextafter(1.0, 0.0)), 0.0);
  EXPECT_EQ(ntn::time_function_value(pts, f, 1.0), 1.0);
  EXPECT_EQ(ntn::time_function_value(pts, f, 1.5), 1.0);
}

// Against a linear search over a long function with uneven spacing (the kernel bisects), at
// random times including before and after the points. Functions share one point array: the
// second starts at its offset. Tolerance: rounding, 4 ulp of the values' scale.
TEST(TimeFunction, AgreesWithALinearSearch) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<ntn::TimePoint> pts = {{0, 123}, {1, 456}};  // another function's points first
  double t = -1;
  for (int k = 0; k < 200; ++k) {
    t += 0.01 + u(rng);
    pts.push_back({t, 10 * (u(rng) - 0.5)});
  }
  const ntn::TimeFunctionSpec f{2, 200};
  for (int trial = 0; trial < 5000; ++trial) {
    const double x = -3 + (pts.back().t + 6) * u(rng);
    double expected;
    if (x <= pts[2].t) {
      expected = pts[2].value;
    } else if (x >= pts.back().t) {
      expected = pts.back().value;
    } else {
      std::size_t k = 2;
      while (pts[k + 1].t <= x)
        ++k;
      const double w = (x - pts[k].t) / (pts[k + 1].t - pts[k].t);
      expected = (1 - w) * pts[k].value + w * pts[k + 1].value;
    }
    EXPECT_NEAR(ntn::time_function_value(pts, f, x), expected, 4 * 5 * 2.3e-16) << x;
  }
}

// --- Loads through step() -------------------------------------------------------------------

constexpr int kDiv = 2;
constexpr ntn::Sizes kS = ntn_test::portal_frame_sizes(
    kDiv, {.time_functions = 2, .time_points = 4, .loads = 2, .inputs = 2});

ntn::ModelSpec<kS> spec;
ntn::Model<kS> model;
ntn::State<kS> state;
ntn::Scratch<kS> scratch;

void base_spec() {
  spec = {};
  ASSERT_TRUE(ntn_test::portal_frame(spec, kDiv));
  spec.time_points = {{{0, 0}, {0.01, 1}, {0, 2}, {0.02, -1}}};
  spec.time_functions = {{{0, 2}, {2, 2}}};
  spec.settings.alpha = 1.0;
  spec.settings.dt = 0.9 * ntn::stable_time_step(ntn::view(spec)).dt_stable;
}

// P_n at t_n = tick * dt: a nodal load times its time function, and gravity M g (on every
// translation, with its own time function). Exact: the same products the kernel forms.
TEST(Loads, NodalLoadsAndGravityAtTheStepTime) {
  base_spec();
  spec.loads[0] = {5, ntn::kUy, 300.0, 0};
  spec.loads[1] = {6, ntn::kRz, -40.0, ntn::kConstant};
  spec.settings.gravity = {0, 0, -9.81};
  spec.settings.gravity_function = 1;
  const ntn_test::EigenNoMalloc guard;
  ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
  state = {};
  ASSERT_EQ(ntn::start(model, state, scratch, {0, 0}), ntn::StepStatus::kOk);
  for (int n = 0; n < 50; ++n) {
    const double t = n * model.dt;
    ASSERT_EQ(ntn::step(model, state, scratch, {0, 0}), ntn::StepStatus::kOk);
    EXPECT_EQ(scratch.time, t);
    const double fl = ntn::time_function_value(spec.time_points, spec.time_functions[0], t);
    const double fg = ntn::time_function_value(spec.time_points, spec.time_functions[1], t);
    EXPECT_EQ(ntn::external_load(model, scratch, dof(5, ntn::kUy)),
              model.mass[dof(5, ntn::kUy)] * 0.0 + 300.0 * fl);
    EXPECT_EQ(ntn::external_load(model, scratch, dof(6, ntn::kRz)), -40.0);
    EXPECT_EQ(ntn::external_load(model, scratch, dof(9, ntn::kUz)),
              model.mass[dof(9, ntn::kUz)] * (-9.81 * fg));
    EXPECT_EQ(ntn::external_load(model, scratch, dof(9, ntn::kUx)), 0.0);
  }
}

// Equivalent models, bit-identical runs: a ground acceleration input a_g along x (scaled) is the
// load -M iota a_g, i.e. gravity (-a_g, 0, 0); a nodal force input equals a nodal load of the
// same value. Same arithmetic in the kernel, so the states must match with memcmp.
TEST(Loads, BaseExcitationAndForceInputsEqualTheEquivalentLoads) {
  const double ag = 0.35, scale = 9.80665, force = 1234.5;
  base_spec();
  spec.inputs[0] = {ntn::InputKind::kGroundAcceleration, 0, ntn::kUx, scale};
  spec.inputs[1] = {ntn::InputKind::kNodalForce, 7, ntn::kUy, 1.0};
  const ntn_test::EigenNoMalloc guard;
  static ntn::Model<kS> model_in;
  static ntn::State<kS> state_in;
  ASSERT_TRUE(ntn_test::init_model(spec, model_in).ok());
  spec.inputs = {};
  spec.settings.gravity = {-(ag * scale), 0, 0};
  spec.loads[0] = {7, ntn::kUy, force, ntn::kConstant};
  ASSERT_TRUE(ntn_test::init_model(spec, model).ok());
  state_in = {}, state = {};
  ASSERT_EQ(ntn::start(model_in, state_in, scratch, {ag, force}), ntn::StepStatus::kOk);
  ASSERT_EQ(ntn::start(model, state, scratch, {0, 0}), ntn::StepStatus::kOk);
  for (int n = 0; n < 2000; ++n) {
    ASSERT_EQ(ntn::step(model_in, state_in, scratch, {ag, force}), ntn::StepStatus::kOk);
    ASSERT_EQ(ntn::step(model, state, scratch, {0, 0}), ntn::StepStatus::kOk);
  }
  EXPECT_EQ(std::memcmp(state.u.data(), state_in.u.data(), sizeof(state.u)), 0);
  EXPECT_EQ(std::memcmp(state.v.data(), state_in.v.data(), sizeof(state.v)), 0);
  EXPECT_NE(state.u[dof(6, ntn::kUx)], 0.0);  // the frame did move
  EXPECT_NE(state.u[dof(7, ntn::kUy)], 0.0);
}

}  // namespace loads_test
