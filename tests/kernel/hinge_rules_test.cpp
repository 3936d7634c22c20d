// Kernel rules with hinges (zero heap allocations and bit-identical repeat runs still hold with
// hinges of every kind): a model with a rigid hinge in a skewed frame, a
// pin (free direction), springs with dashpots, a gap (curve with rigid branches), an eccentric
// rigid hinge and a hinge to the ground, driven by every input kind, under each hinge method:
// init, start and 2e4 steps allocate nothing (malloc & co. and every operator new counted,
// tests/support/alloc_counter.cpp, with Eigen's no-malloc guard on), and two runs, and a run
// resumed from a State checkpoint, are bit-identical (memcmp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "ntn/kernel.hpp"
#include "support/alloc_counter.hpp"
#include "support/assemble.hpp"
#include "support/builders.hpp"
#include "support/frames.hpp"
#include "support/hinges.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"

namespace hinge_rules_test {

using ntn_test::dof;
using B = ntn::HingeBehaviour;

// A line of six 1 m segments along x (one element each, 12 nodes: segment k runs from node 2k
// to node 2k + 1), the first clamped at x = 0, joined at x = 1 ... 5 by hinges 0-4, the last
// segment 0.1 m higher (hinge 4 is eccentric), its far end on an inclined roller (hinge 5, to
// the ground).
constexpr ntn::Sizes kS{.nodes = 12,
                        .elements = 6,
                        .time_functions = 1,
                        .time_points = 3,
                        .loads = 2,
                        .inputs = 3,
                        .outputs = 12,
                        .hinges = 6,
                        .curves = 1,
                        .curve_points = 4};
constexpr long kSteps = 20'000;
using Inputs = std::array<double, kS.inputs>;

ntn::ModelSpec<kS> spec;
ntn::Model<kS> model_a, model_b;
ntn::InitWorkspace<kS> init_work;  // static: init() is inside the allocation count
ntn::State<kS> a, b, checkpoint;
ntn::Scratch<kS> wa, wb;

void build(ntn::HingeMethod method) {
  spec = {};
  const ntn_test::Section sec = ntn_test::rectangle(0.06, 0.1);
  for (int k = 0; k < 6; ++k) {
    const double z = k == 5 ? 0.1 : 0.0;
    spec.nodes[static_cast<std::size_t>(2 * k)] = {static_cast<double>(k), 0, z, 0, {}};
    spec.nodes[static_cast<std::size_t>(2 * k + 1)] = {static_cast<double>(k + 1), 0, z, 0, {}};
    spec.elements[static_cast<std::size_t>(k)] =
        ntn_test::element(2 * k, 2 * k + 1, ntn_test::kSteel, sec, {0, 0, 1});
  }
  spec.nodes[0].fixed = ntn_test::kFixedAll;
  const ntn_test::Mat3 member = ntn_test::member_frame({0, 0, 0}, {1, 0, 0}, {0, 0, 1});
  // Hinge k joins segment k + 1's start (node 1) to segment k's end (node 2).
  auto h = [](int k) { return 2 * (k + 1); };
  auto j = [](int k) { return 2 * k + 1; };
  spec.hinges[0] = ntn_test::hinge(h(0), j(0), ntn_test::skewed_frame(member));  // rigid
  spec.hinges[1] = ntn_test::hinge(h(1), j(1), member, ntn_test::released(1U << ntn::kRy));
  spec.hinges[2] = ntn_test::hinge(h(2), j(2), member);  // springs with dashpots
  for (const int d : {ntn::kRx, ntn::kRy}) {
    spec.hinges[2].behaviour[static_cast<std::size_t>(d)] = B::kLinear;
    spec.hinges[2].stiffness[static_cast<std::size_t>(d)] = d == ntn::kRx ? 1e5 : 2e5;
    spec.hinges[2].dashpot[static_cast<std::size_t>(d)] = d == ntn::kRx ? 50 : 100;
  }
  spec.hinges[3] = ntn_test::hinge(h(3), j(3), member);  // 1 mm gap across the beam
  spec.hinges[3].behaviour[ntn::kUz] = B::kCurve;
  spec.hinges[3].curve[ntn::kUz] = 0;
  spec.curve_points = {{{-1.1e-3, -1e9}, {-1e-3, 0.0}, {1e-3, 0.0}, {1.1e-3, 1e9}}};
  spec.curves[0] = {0, 4};
  spec.settings.limit_stiffness = 1e12;
  // Eccentric: e = x2 - x1 = (0, 0, -0.1). ntn_paper takes no eccentricity (the model compiler
  // refuses one): there it joins the two nodes centrically.
  spec.hinges[4] = ntn_test::hinge(h(4), j(4), member, ntn_test::kAllRigid,
                                   {0, 0, method == ntn::HingeMethod::kNtnPaper ? 0.0 : -0.1});
  const ntn_test::Mat3 incline = ntn_test::rotate_frame(
      ntn_test::kIdentity3, ntn_test::rotation({0, 1, 0}, 25 * ntn_test::kDegree));
  spec.hinges[5] = ntn_test::hinge(11, ntn::kGround, incline,
                                   ntn_test::released((1U << ntn::kUx) | 0x38));  // roller
  spec.settings.hinge_method = method;
  spec.settings.penalty_stiffness = 1e2 * ntn_test::kSteel.E * sec.A;
  spec.settings.penalty_rotational_stiffness = 4e2 * ntn_test::kSteel.E * sec.Iy;
  spec.settings.alpha = 0.5;
  spec.settings.gravity = {0, 0, -9.81};
  spec.time_points = ntn_test::triangle_pulse(0.01);
  spec.time_functions[0] = {0, 3};
  spec.loads[0] = {7, ntn::kUz, 3e4, 0};
  spec.loads[1] = {5, ntn::kUy, -1e4, 0};
  spec.inputs[0] = {ntn::InputKind::kGroundAcceleration, 0, ntn::kUx, 9.80665, -5, 5};
  spec.inputs[1] = {ntn::InputKind::kGroundAcceleration, 0, ntn::kUz, 9.80665, -5, 5};
  spec.inputs[2] = {ntn::InputKind::kNodalForce, 9, ntn::kUz, 1e4, -100, 100};
  for (int k = 0; k < 6; ++k) {  // every hinge's force and displacement in one direction
    const int d = k == 3 ? ntn::kUz : k == 2 ? ntn::kRx : ntn::kUy;
    spec.outputs[static_cast<std::size_t>(2 * k)] = {};
    spec.outputs[static_cast<std::size_t>(2 * k)].kind = ntn::OutputKind::kHingeForce;
    spec.outputs[static_cast<std::size_t>(2 * k)].hinge = k;
    spec.outputs[static_cast<std::size_t>(2 * k)].dof = d;
    spec.outputs[static_cast<std::size_t>(2 * k + 1)] =
        spec.outputs[static_cast<std::size_t>(2 * k)];
    spec.outputs[static_cast<std::size_t>(2 * k + 1)].kind = ntn::OutputKind::kHingeDisplacement;
  }
  // 0.9 of the smaller of the kernel's estimate and the exact step of the assembled system (the
  // estimate is not conservative for penalty at eccentric hinges: hinge_time_step_test).
  const bool pen = method == ntn::HingeMethod::kPenalty;
  const double exact =
      ntn_test::assembled_stable_step(ntn::view(spec), pen ? spec.settings.penalty_stiffness : 0,
                                      pen ? spec.settings.penalty_rotational_stiffness : 0);
  spec.settings.dt = 0.9 * std::min(exact, ntn_test::hinged_stable_step(spec).dt_stable);
}

Inputs inputs_at(long n) {
  return {
      ntn_test::input_sample(0, n), ntn_test::input_sample(1, n),
      n % 997 == 5 ? std::numeric_limits<double>::quiet_NaN() : 20 * ntn_test::input_sample(2, n)};
}

// Steps [from, to); returns the number of steps at the gap's stops (|d| = 1 mm).
long run(const ntn::Model<kS>& m, ntn::State<kS>& s, ntn::Scratch<kS>& w, long from, long to) {
  long at_stop = 0;
  for (long n = from; n < to; ++n) {
    const ntn::StepStatus st = ntn::step(m, s, w, inputs_at(n));
    if (st == ntn::StepStatus::kDiverged) {
      ADD_FAILURE() << "diverged at step " << n;
      break;
    }
    at_stop += std::abs(w.outputs[7]) >= 1e-3 * (1 - 1e-9) ? 1 : 0;
  }
  return at_stop;
}

void expect_identical(const ntn::State<kS>& x, const ntn::State<kS>& y) {
  EXPECT_EQ(std::memcmp(x.u.data(), y.u.data(), sizeof(x.u)), 0);
  EXPECT_EQ(std::memcmp(x.v.data(), y.v.data(), sizeof(x.v)), 0);
  EXPECT_EQ(std::memcmp(x.held_inputs.data(), y.held_inputs.data(), sizeof(x.held_inputs)), 0);
  EXPECT_EQ(x.tick, y.tick);
  EXPECT_EQ(x.inputs_held, y.inputs_held);
  EXPECT_EQ(x.faults, y.faults);
}

const char* name(ntn::HingeMethod m) {
  return m == ntn::HingeMethod::kNtnExact   ? "ntn_exact"
         : m == ntn::HingeMethod::kNtnPaper ? "ntn_paper"
                                            : "penalty";
}

class HingeRules : public ::testing::TestWithParam<ntn::HingeMethod> {};

TEST_P(HingeRules, NoHeapAllocationInInitStartAndSteps) {
  build(GetParam());
  ntn::InitStatus st;
  ntn::StepStatus first = ntn::StepStatus::kDiverged;
  long at_stop = 0;
  ntn_test::AllocationCounts c;
  {
    const ntn_test::AllocationScope scope;
    const ntn_test::EigenNoMalloc guard;
    st = ntn::init(spec, model_a, init_work);
    a = {};
    first = ntn::start(model_a, a, wa, inputs_at(-1));
    at_stop = run(model_a, a, wa, 0, kSteps);
    c = scope.counts();
  }
  ASSERT_TRUE(st.ok()) << name(GetParam()) << ": " << ntn::to_string(st.error) << " at "
                       << st.where;
  EXPECT_EQ(first, ntn::StepStatus::kOk);
  std::printf("  %s: dt %.3e s, %ld steps, %ld at the gap's stops, %llu inputs held\n",
              name(GetParam()), model_a.dt, kSteps, at_stop,
              static_cast<unsigned long long>(a.inputs_held));
  EXPECT_GT(at_stop, 0) << "the gap's stops are reached";
  EXPECT_EQ(a.inputs_held, static_cast<std::uint64_t>((kSteps - 5 + 996) / 997));
  EXPECT_EQ(c.allocations, 0U);
  EXPECT_EQ(c.deallocations, 0U);
}

TEST_P(HingeRules, RepeatRunsAndCheckpointsAreBitIdentical) {
  build(GetParam());
  {
    const ntn_test::EigenNoMalloc guard;
    ASSERT_TRUE(ntn_test::init_model(spec, model_a).ok());
    ASSERT_TRUE(ntn_test::init_model(spec, model_b).ok());  // a second, independently built model
  }
  EXPECT_EQ(std::memcmp(model_a.inv_mass.data(), model_b.inv_mass.data(), sizeof(model_a.inv_mass)),
            0);
  constexpr long kHalf = kSteps / 2;
  {
    const ntn_test::EigenNoMalloc guard;
    a = {}, b = {};
    ASSERT_EQ(ntn::start(model_a, a, wa, inputs_at(-1)), ntn::StepStatus::kOk);
    ASSERT_EQ(ntn::start(model_b, b, wb, inputs_at(-1)), ntn::StepStatus::kOk);
    run(model_a, a, wa, 0, kHalf);
    checkpoint = a;
    run(model_a, a, wa, kHalf, kSteps);
    run(model_b, b, wb, 0, kSteps);
  }
  expect_identical(a, b);
  EXPECT_EQ(std::memcmp(wa.outputs.data(), wb.outputs.data(), sizeof(wa.outputs)), 0);
  // Resume from the State alone, with a fresh Scratch.
  b = checkpoint, wb = {};
  {
    const ntn_test::EigenNoMalloc guard;
    run(model_b, b, wb, kHalf, kSteps);
  }
  expect_identical(a, b);
  EXPECT_EQ(std::memcmp(wa.outputs.data(), wb.outputs.data(), sizeof(wa.outputs)), 0);
  EXPECT_NE(a.u[dof(7, ntn::kUz)], 0.0);  // something happened
}

INSTANTIATE_TEST_SUITE_P(Methods, HingeRules,
                         ::testing::Values(ntn::HingeMethod::kNtnExact, ntn::HingeMethod::kNtnPaper,
                                           ntn::HingeMethod::kPenalty),
                         [](const ::testing::TestParamInfo<ntn::HingeMethod>& i) {
                           return std::string(name(i.param));
                         });

}  // namespace hinge_rules_test
