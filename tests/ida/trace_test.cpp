// The tracing of one record's IDA curve (tools/ida/include/ntn/ida/trace.hpp): stepping, and
// Vamvatsikos and Cornell's hunt and fill, against sequences worked out by hand and against a
// made-up record whose collapse intensity is known (every run at or above it collapses).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ntn/ida/trace.hpp"

namespace trace_test {

using ntn::ida::TraceMode;
using ntn::ida::TracePlan;
using ntn::ida::TracePoint;

// Traces a record that collapses at and above `capacity`; the intensities in run order.
std::vector<double> trace(const TracePlan& plan, double capacity, std::vector<TracePoint>* out) {
  std::vector<TracePoint> done;
  while (const auto im = ntn::ida::next_intensity(plan, done))
    done.push_back({*im, *im >= capacity});
  std::vector<double> ims;
  for (const TracePoint& p : done)
    ims.push_back(p.im);
  if (out != nullptr) *out = done;
  return ims;
}

TEST(IdaTrace, SteppingRunsTheLevelsUpToTheFirstCollapse) {
  TracePlan plan;
  plan.mode = TraceMode::kStepping;
  plan.levels = {0.1, 0.2, 0.3, 0.4, 0.5};
  EXPECT_EQ(trace(plan, 0.35, nullptr), (std::vector<double>{0.1, 0.2, 0.3, 0.4}));
  EXPECT_EQ(trace(plan, 9.0, nullptr), plan.levels);  // never collapses: every level
  std::vector<TracePoint> done;
  trace(plan, 0.35, &done);
  ASSERT_TRUE(ntn::ida::collapse_capacity(done));
  EXPECT_EQ(*ntn::ida::collapse_capacity(done), 0.3);
}

// Hand-worked: first 0.1, increment 0.05: the hunt runs 0.1, 0.2 (+0.1), 0.35 (+0.15), 0.55
// (+0.2); 0.55 collapses (capacity 0.5). The bracket [0.35, 0.55] is bisected: 0.45 stands,
// 0.5 collapses, 0.475 stands: 0.025 <= resolution 0.03. Then the largest gaps between standing
// runs are filled: [0.2, 0.35] -> 0.275, then [0.0, 0.1] -> 0.05 ... until the budget of 10.
TEST(IdaTrace, HuntThenBracketThenFillAsWorkedByHand) {
  TracePlan plan;
  plan.first = 0.1, plan.increment = 0.05, plan.resolution = 0.03, plan.max = 5, plan.runs = 10;
  std::vector<TracePoint> done;
  const std::vector<double> ims = trace(plan, 0.5, &done);
  const std::vector<double> expected = {0.1, 0.2, 0.35, 0.55, 0.45, 0.5, 0.475, 0.275, 0.05, 0.15};
  ASSERT_EQ(ims.size(), expected.size());
  for (std::size_t k = 0; k < ims.size(); ++k)
    EXPECT_NEAR(ims[k], expected[k], 1e-12) << "run " << k;
  ASSERT_TRUE(ntn::ida::collapse_capacity(done));
  EXPECT_NEAR(*ntn::ida::collapse_capacity(done), 0.475, 1e-12);
}

// The bracket closes to the resolution wherever the capacity is, when the budget allows.
TEST(IdaTrace, BracketIsWithinTheResolutionOfTheCapacity) {
  TracePlan plan;
  plan.first = 0.1, plan.increment = 0.1, plan.resolution = 0.01, plan.runs = 40;
  for (const double capacity : {0.07, 0.33, 0.999, 1.7, 3.21}) {
    std::vector<TracePoint> done;
    trace(plan, capacity, &done);
    const auto c = ntn::ida::collapse_capacity(done);
    ASSERT_TRUE(c) << capacity;
    EXPECT_LT(*c, capacity);
    EXPECT_GE(*c, capacity - plan.resolution) << capacity;
  }
}

TEST(IdaTrace, WithoutCollapseTheHuntStopsAtTheTopAndFills) {
  TracePlan plan;
  plan.first = 0.5, plan.increment = 0.5, plan.max = 2.0, plan.resolution = 0.3, plan.runs = 20;
  std::vector<TracePoint> done;
  const std::vector<double> ims = trace(plan, 100.0, &done);
  // 0.5, 1.0 (+0.5), 2.0 (+1.0, capped at the top), then fill [1, 2] -> 1.5, [0, 0.5] -> 0.25,
  // [0.5, 1] -> 0.75, [1, 1.5] -> 1.25, [1.5, 2] -> 1.75: every gap now 0.25 <= 0.3.
  const std::vector<double> expected = {0.5, 1.0, 2.0, 1.5, 0.25, 0.75, 1.25, 1.75};
  ASSERT_EQ(ims.size(), expected.size());
  for (std::size_t k = 0; k < ims.size(); ++k)
    EXPECT_NEAR(ims[k], expected[k], 1e-12) << "run " << k;
  EXPECT_FALSE(ntn::ida::collapse_capacity(done));
}

TEST(IdaTrace, BudgetIsKept) {
  TracePlan plan;
  plan.runs = 5;
  EXPECT_EQ(trace(plan, 3.0, nullptr).size(), 5U);
}

TEST(IdaTrace, BadPlansAreNamed) {
  TracePlan plan;
  plan.mode = TraceMode::kStepping;
  EXPECT_TRUE(ntn::ida::check_plan(plan));  // no levels
  plan.levels = {0.2, 0.1};
  EXPECT_TRUE(ntn::ida::check_plan(plan));
  plan.levels = {0.1, NAN};
  EXPECT_TRUE(ntn::ida::check_plan(plan));
  plan.levels = {0.1, 0.2};
  EXPECT_FALSE(ntn::ida::check_plan(plan));
  TracePlan hunt;
  EXPECT_FALSE(ntn::ida::check_plan(hunt));
  hunt.resolution = 0;
  EXPECT_TRUE(ntn::ida::check_plan(hunt));
  hunt.resolution = 0.01, hunt.max = 0.01;  // below the first
  EXPECT_TRUE(ntn::ida::check_plan(hunt));
}

}  // namespace trace_test
