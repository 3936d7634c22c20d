// Kernel rules with a yielding run: `plastic` hinge directions keep their history in
// State (State::plastic, State::dissipated), so
// - init, start and the steps of a run that yields allocate nothing (every malloc and operator
//   new counted, tests/support/alloc_counter.cpp, with Eigen's no-malloc guard on);
// - two runs are bit-identical (memcmp of u, v, the history and the outputs);
// - a copy of State taken while a direction is yielding (its d_p changed in the step before and
//   changes in the step after) and resumed with a fresh Scratch gives the bits of the
//   uninterrupted run.
// The model: the hinged cantilever of support/plastic_models.hpp, its hinge plastic about y and z
// (kinematic hardening 0.05 and 0, asymmetric yields, dashpots), under a tip pulse and a noisy
// ground acceleration and tip force (inputs), with Rayleigh damping. The same with `backbone`
// directions (kinematic about y, peak_oriented about z, both degrading past C): their history
// also holds the excursions and the reloading lines' anchors (State::excursion). And with
// `rigid_plastic` directions (held exactly until they yield, by the slip stage, which
// solves the hinge's tree): their slip and its first time (State::plastic, first_slip); with
// hardening with the slip (a parallel spring), and as a friction circle (one limit on the
// resultant moment: the Gauss-Seidel pair step).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "ntn/kernel.hpp"
#include "support/alloc_counter.hpp"
#include "support/builders.hpp"
#include "support/frames.hpp"
#include "support/hinges.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"
#include "support/plastic_models.hpp"

namespace plastic_rules_test {

using ntn_test::dof;
using K = ntn::OutputKind;

constexpr ntn::Sizes kS = ntn_test::hinged_cantilever_sizes(
    {.time_functions = 1, .time_points = 3, .loads = 2, .inputs = 2, .outputs = 6});
constexpr long kSteps = 20'000;
using Inputs = std::array<double, kS.inputs>;

ntn::ModelSpec<kS> spec;
ntn::Model<kS> model_a, model_b;
ntn::InitWorkspace<kS> init_work;  // static: init() is inside the allocation count
ntn::State<kS> a, b, checkpoint;
ntn::Scratch<kS> wa, wb;

// A backbone law of elastic stiffness 2e6 N m/rad through B = (f_B / k, f_B).
ntn::HysteresisSpec backbone(ntn::HysteresisRule rule, double fb, double dc, double fc, double dd,
                             double fd, double de) {
  ntn::HysteresisSpec h;
  h.rule = rule;
  h.backbone_pos = {{{fb / 2e6, fb}, {dc, fc}, {dd, fd}, {de, fd}}};
  h.backbone_neg = h.backbone_pos;
  h.yield_pos = h.yield_neg = fb;
  return h;
}

enum class Law { kBilinear, kBackbones, kRigidPlastic, kHardeningSlip, kFrictionCircle };

void build(Law laws = Law::kBilinear) {
  const bool backbones = laws == Law::kBackbones;
  ntn_test::hinged_cantilever(spec, ntn::HingeBehaviour::kPlastic, 2e6);
  spec.hinges[0].dashpot[ntn::kRy] = 50;
  spec.hinges[0].dashpot[ntn::kRz] = 20;
  spec.hystereses[0] = {6e3, 4e3, 0.05};
  spec.hystereses[1] = {3e3, 5e3, 0.0};
  if (laws == Law::kRigidPlastic || laws == Law::kHardeningSlip ||
      laws == Law::kFrictionCircle) {  // rigid until they yield (slip.hpp), in the hinge's tree
    for (const int d : {ntn::kRy, ntn::kRz}) {
      const auto k = static_cast<std::size_t>(d);
      spec.hinges[0].behaviour[k] = ntn::HingeBehaviour::kRigidPlastic;
      spec.hinges[0].stiffness[k] = laws == Law::kHardeningSlip ? 2e5 : 0.0;  // hardening
      spec.hinges[0].dashpot[k] = 0;
    }
    spec.hystereses[0] = {6e3, 4e3, 0.0};
  }
  if (laws == Law::kFrictionCircle) {  // one limit on the resultant moment (Gauss-Seidel pairs)
    for (std::size_t i = 0; i < 2; ++i) {
      spec.hystereses[i] = {};
      spec.hystereses[i].normal = ntn::kUx;
      spec.hystereses[i].mu = 0.3;
      spec.hystereses[i].cohesion = 4e3;
      spec.hystereses[i].circle = i == 0 ? ntn::kRz : ntn::kRy;
    }
  }
  if (backbones) {
    spec.hinges[0].dashpot[ntn::kRy] = spec.hinges[0].dashpot[ntn::kRz] = 0;
    spec.hystereses[0] =
        backbone(ntn::HysteresisRule::kKinematic, 6e3, 0.01, 6.5e3, 0.012, 2e3, 0.5);
    spec.hystereses[1] =
        backbone(ntn::HysteresisRule::kPeakOriented, 3e3, 0.005, 3.3e3, 0.005, 1e3, 0.5);
  }
  spec.time_points = ntn_test::triangle_pulse(0.01);
  spec.time_functions[0] = {0, 3};
  spec.loads[0] = {4, ntn::kUz, 2e4, 0};
  spec.loads[1] = {4, ntn::kUy, -1.5e4, 0};
  spec.inputs[0] = {ntn::InputKind::kGroundAcceleration, 0, ntn::kUy, 9.80665, -5, 5};
  spec.inputs[1] = {ntn::InputKind::kNodalForce, 4, ntn::kUz, 1e4, -5, 5};
  int c = 0;
  for (const int d : {ntn::kRy, ntn::kRz}) {
    for (const K kind : {K::kHingeForce, K::kHingePlastic, K::kHingeDissipated})
      spec.outputs[static_cast<std::size_t>(c++)] = ntn_test::hinge_channel(kind, 0, d);
  }
  spec.settings.alpha = 0.5;
  spec.settings.beta = 1e-6;
  spec.settings.dt = 0.9 * ntn_test::hinged_stable_step(spec).dt_stable;
}

Inputs inputs_at(long n) {
  return {2 * ntn_test::input_sample(0, n), 2 * ntn_test::input_sample(1, n)};
}

void run(const ntn::Model<kS>& m, ntn::State<kS>& s, ntn::Scratch<kS>& w, long from, long to) {
  for (long n = from; n < to; ++n) {
    if (ntn::step(m, s, w, inputs_at(n)) != ntn::StepStatus::kOk) {
      ADD_FAILURE() << "step " << n;
      break;
    }
  }
}

void expect_identical(const ntn::State<kS>& x, const ntn::State<kS>& y) {
  EXPECT_EQ(std::memcmp(x.u.data(), y.u.data(), sizeof(x.u)), 0);
  EXPECT_EQ(std::memcmp(x.v.data(), y.v.data(), sizeof(x.v)), 0);
  EXPECT_EQ(std::memcmp(x.plastic.data(), y.plastic.data(), sizeof(x.plastic)), 0);
  EXPECT_EQ(std::memcmp(x.dissipated.data(), y.dissipated.data(), sizeof(x.dissipated)), 0);
  EXPECT_EQ(std::memcmp(x.law_state.data(), y.law_state.data(), sizeof(x.law_state)), 0);
  EXPECT_EQ(x.first_slip, y.first_slip);
  EXPECT_EQ(x.slip_state, y.slip_state);
  EXPECT_EQ(x.tick, y.tick);
}

void no_heap_in_a_yielding_run(Law laws) {
  const bool backbones = laws == Law::kBackbones;
  build(laws);
  ntn::InitStatus st;
  ntn::StepStatus first = ntn::StepStatus::kDiverged;
  ntn_test::AllocationCounts c;
  {
    const ntn_test::AllocationScope scope;
    const ntn_test::EigenNoMalloc guard;
    st = ntn::init(spec, model_a, init_work);
    a = {};
    first = ntn::start(model_a, a, wa, inputs_at(-1));
    run(model_a, a, wa, 0, kSteps);
    c = scope.counts();
  }
  ASSERT_TRUE(st.ok()) << ntn::to_string(st.error) << " at " << st.where;
  EXPECT_EQ(first, ntn::StepStatus::kOk);
  std::printf("  dt %.3e s, %ld steps: d_p %.3e / %.3e rad, dissipated %.1f / %.1f J (ry / rz)\n",
              model_a.dt, kSteps, a.plastic[0], a.plastic[1], a.dissipated[0], a.dissipated[1]);
  EXPECT_GT(a.dissipated[0], 0.0) << "ry yields";
  EXPECT_GT(a.dissipated[1], 0.0) << "rz yields";
  if (backbones) {  // both went past their capping points: the run degrades
    EXPECT_GT(std::max(a.law_state[0][0], a.law_state[0][1]), 0.012);
    EXPECT_GT(std::max(a.law_state[1][0], a.law_state[1][1]), 0.005);
  }
  EXPECT_EQ(c.allocations, 0U);
  EXPECT_EQ(c.deallocations, 0U);
}

void repeat_runs_and_checkpoints(Law laws) {
  build(laws);
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(spec, model_a).ok());
    ASSERT_TRUE(ntn_test::init_model(spec, model_b).ok());
  }
  // Run a to the first step at or after kSteps / 4 where a direction yields in two consecutive
  // steps, checkpoint between the two, then finish; b runs uninterrupted.
  long at = -1;
  {
    const ntn_test::EigenNoMalloc guard;
    a = {}, b = {};
    ASSERT_EQ(ntn::start(model_a, a, wa, inputs_at(-1)), ntn::StepStatus::kOk);
    ASSERT_EQ(ntn::start(model_b, b, wb, inputs_at(-1)), ntn::StepStatus::kOk);
    run(model_a, a, wa, 0, kSteps / 4);
    bool yielded_before = false;
    for (long n = kSteps / 4; n < kSteps; ++n) {
      const auto before = a.plastic;
      run(model_a, a, wa, n, n + 1);
      const bool yields = a.plastic != before;
      if (at < 0 && yields && yielded_before) at = n;  // steps n - 1 and n both yielded
      if (at < 0 && yields) checkpoint = a;            // candidate: after step n
      yielded_before = yields;
    }
    run(model_b, b, wb, 0, kSteps);
  }
  ASSERT_GE(at, 0) << "no direction yields in two consecutive steps";
  std::printf("  checkpoint after step %ld, mid-yield (d_p %.6e, %.6e rad)\n", at - 1,
              checkpoint.plastic[0], checkpoint.plastic[1]);
  expect_identical(a, b);
  EXPECT_EQ(std::memcmp(wa.outputs.data(), wb.outputs.data(), sizeof(wa.outputs)), 0);
  // Resume from the State alone, with a fresh Scratch; its tick says which step is next.
  EXPECT_EQ(checkpoint.tick, static_cast<std::int64_t>(at));
  b = checkpoint, wb = {};
  {
    const ntn_test::EigenNoMalloc guard;
    run(model_b, b, wb, at, kSteps);
  }
  expect_identical(a, b);
  EXPECT_EQ(std::memcmp(wa.outputs.data(), wb.outputs.data(), sizeof(wa.outputs)), 0);
  EXPECT_GT(a.dissipated[0] + a.dissipated[1], checkpoint.dissipated[0] + checkpoint.dissipated[1]);
}

TEST(PlasticRules, NoHeapAllocationInAYieldingRun) {
  no_heap_in_a_yielding_run(Law::kBilinear);
}
TEST(PlasticRules, NoHeapAllocationInAYieldingRunWithBackbones) {
  no_heap_in_a_yielding_run(Law::kBackbones);
}
TEST(PlasticRules, RepeatRunsAndCheckpointsMidYieldAreBitIdentical) {
  repeat_runs_and_checkpoints(Law::kBilinear);
}
TEST(PlasticRules, RepeatRunsAndCheckpointsMidYieldAreBitIdenticalWithBackbones) {
  repeat_runs_and_checkpoints(Law::kBackbones);
}

TEST(PlasticRules, NoHeapAllocationInASlidingRunWithRigidPlasticDirections) {
  no_heap_in_a_yielding_run(Law::kRigidPlastic);
}
TEST(PlasticRules, RepeatRunsAndCheckpointsMidSlideAreBitIdenticalWithRigidPlasticDirections) {
  repeat_runs_and_checkpoints(Law::kRigidPlastic);
}
TEST(PlasticRules, NoHeapAllocationAndBitIdenticalCheckpointsWithHardeningSlip) {
  no_heap_in_a_yielding_run(Law::kHardeningSlip);
  repeat_runs_and_checkpoints(Law::kHardeningSlip);
}
TEST(PlasticRules, NoHeapAllocationAndBitIdenticalCheckpointsWithAFrictionCircle) {
  no_heap_in_a_yielding_run(Law::kFrictionCircle);
  repeat_runs_and_checkpoints(Law::kFrictionCircle);
}

}  // namespace plastic_rules_test
