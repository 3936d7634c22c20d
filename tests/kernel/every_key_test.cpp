// The kernel's rules on a model with every one of these model keys (every_key.toml: plane, Rayleigh
// damping, member loads, points inside members, a point mass on a rigid offset, a rolled hinge
// frame, the gravity preload and initial values): no allocation in init, initial_state, start and
// 2 x 10^4 steps; two runs give the same bits, and a run resumed from a checkpoint the same bits as
// the uninterrupted one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "every_key_model.hpp"
#include "ntn/kernel.hpp"
#include "support/alloc_counter.hpp"
#include "support/no_heap.hpp"

namespace every_key_test {

namespace model = ntn::models::every_key;
constexpr ntn::Sizes kS = model::kSizes;

ntn::Model<kS> m;
ntn::InitWorkspace<kS> work;  // static: init() is inside the allocation count
ntn::State<kS> a, b, checkpoint;
ntn::Scratch<kS> wa, wb;

// 0.3 g at 1.7 Hz for 2 s, then free: the ground acceleration input (in g) at step n.
std::array<double, kS.inputs> input(long n) {
  const double t = static_cast<double>(n) * m.dt;
  return {t < 2.0 ? 0.3 * std::sin(2 * 3.141592653589793 * 1.7 * t) : 0.0};
}

bool run(ntn::State<kS>& s, ntn::Scratch<kS>& w, long from, long to) {
  for (long n = from; n < to; ++n) {
    if (ntn::step(m, s, w, input(n)) != ntn::StepStatus::kOk) return false;
  }
  return true;
}

constexpr long kSteps = 20'000;  // 2.9 s at the model's dt = 1/7 ms

TEST(EveryKeyModel, NoAllocationInInitStartAndSteps) {
  bool ok = false, ran = false;
  ntn_test::AllocationCounts c;
  {
    const ntn_test::AllocationScope scope;
    const ntn_test::EigenNoMalloc guard;
    ok = ntn::init(model::kSpec, m, work).ok();
    ntn::initial_state(m, a);
    ran = ntn::start(m, a, wa, input(0)) == ntn::StepStatus::kOk && run(a, wa, 0, kSteps);
    c = scope.counts();
  }
  ASSERT_TRUE(ok);
  EXPECT_TRUE(ran);
  EXPECT_EQ(c.allocations, 0U);
  EXPECT_EQ(c.deallocations, 0U);
  EXPECT_GT(m.num_edges, 0);  // the offset mass and the release are rigid trees
  EXPECT_GT(m.num_spring_hinges, 0);
}

TEST(EveryKeyModel, RepeatAndCheckpointGiveTheSameBits) {
  ASSERT_TRUE(ntn::init(model::kSpec, m, work).ok());
  ntn::initial_state(m, a);
  ntn::initial_state(m, b);
  ASSERT_EQ(ntn::start(m, a, wa, input(0)), ntn::StepStatus::kOk);
  ASSERT_EQ(ntn::start(m, b, wb, input(0)), ntn::StepStatus::kOk);
  ASSERT_TRUE(run(a, wa, 0, kSteps / 2));
  checkpoint = a;
  ASSERT_TRUE(run(a, wa, kSteps / 2, kSteps));
  ASSERT_TRUE(run(b, wb, 0, kSteps));
  EXPECT_EQ(std::memcmp(a.u.data(), b.u.data(), sizeof a.u), 0);
  EXPECT_EQ(std::memcmp(a.v.data(), b.v.data(), sizeof a.v), 0);
  ASSERT_TRUE(run(checkpoint, wb, kSteps / 2, kSteps));  // another Scratch: never read across
  EXPECT_EQ(std::memcmp(a.u.data(), checkpoint.u.data(), sizeof a.u), 0);
  EXPECT_EQ(std::memcmp(a.v.data(), checkpoint.v.data(), sizeof a.v), 0);
  EXPECT_EQ(a.tick, checkpoint.tick);
  double moved = 0;  // the run did something: the record moved the frame off the preload
  for (std::size_t j = 0; j < a.u.size(); ++j)
    moved = std::max(moved, std::abs(a.u[j] - m.u0[j]));
  EXPECT_GT(moved, 1e-5);  // measured 6e-5 m
}

}  // namespace every_key_test
