// Fault plans of the feeder (hil_sim/include/ntn/hil/faults.hpp): parsing, placement rules,
// reproducible draws.
#include "ntn/hil/faults.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace faults_test {

using namespace ntn::hil;

TEST(Faults, ParseList) {
  std::vector<FaultAt> f;
  EXPECT_EQ(parse_fault_list("nan@3,lost@10,reorder@0", f), "");
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f[0].kind, FaultKind::kNan);
  EXPECT_EQ(f[0].frame, 3);
  EXPECT_EQ(f[1].kind, FaultKind::kLost);
  EXPECT_EQ(f[2].kind, FaultKind::kReorder);
  for (const char* bad : {"nan", "nan@", "nan@x", "nan@-1", "bogus@1", "nan@1,", "@1", "nan@1.5"}) {
    std::vector<FaultAt> g;
    EXPECT_NE(parse_fault_list(bad, g), "") << bad;
  }
  for (FaultKind k : kAllFaults) {
    EXPECT_EQ(parse_fault_kind(to_string(k)), k);
  }
}

TEST(Faults, ParseRate) {
  FaultRate r;
  EXPECT_EQ(parse_fault_rate("corrupt=0.25", r), "");
  EXPECT_EQ(r.kind, FaultKind::kCorrupt);
  EXPECT_EQ(r.probability, 0.25);
  for (const char* bad :
       {"corrupt", "corrupt=", "corrupt=1.5", "corrupt=-0.1", "x=0.1", "nan=0.1x"}) {
    EXPECT_NE(parse_fault_rate(bad, r), "") << bad;
  }
}

TEST(Faults, ExplicitPlacementRules) {
  FaultPlan plan;
  std::vector<FaultAt> ok{{FaultKind::kReorder, 4}, {FaultKind::kLate, 6}, {FaultKind::kNan, 7}};
  ASSERT_EQ(make_fault_plan(10, ok, {}, 1, plan), "");
  EXPECT_EQ(plan[4], FaultKind::kReorder);
  EXPECT_EQ(plan[5], FaultKind::kNone);  // taken by the reorder, but no fault of its own
  EXPECT_EQ(plan.count(FaultKind::kReorder), 1u);
  EXPECT_EQ(plan.count(FaultKind::kLate), 1u);
  EXPECT_EQ(plan.count(FaultKind::kNan), 1u);
  const std::vector<std::vector<FaultAt>> bad{
      {{FaultKind::kNan, 3}, {FaultKind::kLost, 3}},     // two on one frame
      {{FaultKind::kReorder, 3}, {FaultKind::kNan, 4}},  // 4 is taken by the reorder
      {{FaultKind::kNan, 4}, {FaultKind::kReorder, 3}},  // the reorder's next frame is taken
      {{FaultKind::kLate, 9}},                           // no next frame
      {{FaultKind::kReorder, 9}},                        // no next frame
      {{FaultKind::kNan, 10}},                           // outside the run
  };
  for (const auto& b : bad)
    EXPECT_NE(make_fault_plan(10, b, {}, 1, plan), "");
}

// The same seed gives the same plan; another seed another; the counts are near p * frames
// (binomial: within 5 standard deviations); every rule holds for every placed fault.
TEST(Faults, RatesAreReproducibleAndFollowTheRules) {
  std::vector<FaultRate> rates;
  for (FaultKind k : kAllFaults)
    rates.push_back({k, 0.03});
  FaultPlan a, b, c;
  constexpr std::int64_t kFrames = 20'000;
  ASSERT_EQ(make_fault_plan(kFrames, {}, rates, 42, a), "");
  ASSERT_EQ(make_fault_plan(kFrames, {}, rates, 42, b), "");
  ASSERT_EQ(make_fault_plan(kFrames, {}, rates, 43, c), "");
  EXPECT_EQ(a.at, b.at);
  EXPECT_NE(a.at, c.at);
  std::array<std::uint64_t, kFaultKinds> seen{};
  for (std::int64_t k = 0; k < kFrames; ++k) {
    ++seen[static_cast<std::size_t>(a[k])];
    if (a[k] == FaultKind::kReorder) {
      ASSERT_LT(k + 1, kFrames);
      EXPECT_EQ(a[k + 1], FaultKind::kNone);
    }
    if (a[k] == FaultKind::kLate) {
      EXPECT_LT(k + 1, kFrames);
    }
  }
  for (FaultKind k : kAllFaults) {
    const auto i = static_cast<std::size_t>(k);
    EXPECT_EQ(seen[i], a.injected[i]) << to_string(k);
    // Drawn hits are placed or skipped; a hit is a Bernoulli(0.03) per frame.
    const double hits = static_cast<double>(a.injected[i] + a.skipped[i]);
    const double mean = 0.03 * kFrames, sd = std::sqrt(kFrames * 0.03 * 0.97);
    EXPECT_NEAR(hits, mean, 5 * sd) << to_string(k);
    EXPECT_GT(a.injected[i], 0u) << to_string(k);
  }
}

TEST(Faults, HashIsDeterministicAndSpread) {
  EXPECT_EQ(fault_hash(1, 5), fault_hash(1, 5));
  EXPECT_NE(fault_hash(1, 5), fault_hash(1, 6));
  EXPECT_NE(fault_hash(1, 5), fault_hash(2, 5));
}

}  // namespace faults_test
