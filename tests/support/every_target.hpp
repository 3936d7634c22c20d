// Highway's instruction sets for the SIMD-path tests (element_pass_test, dof_pass_test): every set
// this CPU runs that Highway compiled the kernel's passes for (the dispatch picks the widest; the
// others are what other machines get), and a fixture that puts the dispatch back afterwards.
#pragma once

#if defined(NTN_SIMD)

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include <hwy/highway.h>
#include <hwy/targets.h>

#include "ntn/element_pass.hpp"

namespace ntn_test {

inline std::vector<std::int64_t> targets_here() {
  std::vector<std::int64_t> out;
  const std::int64_t here = hwy::SupportedTargets() & HWY_TARGETS;
  for (std::int64_t t = 1; t != 0 && t <= here; t <<= 1) {
    if ((here & t) != 0) out.push_back(t);
  }
  return out;
}

// Makes target t the one the dispatch takes (as if the CPU had no wider set).
inline void use_target(std::int64_t t) {
  hwy::SetSupportedTargetsForTest(t);
  hwy::GetChosenTarget().Update(hwy::SupportedTargets());
}

class EveryTarget : public ::testing::Test {
 protected:
  // Runs body(t) with the dispatch on each target t here in turn (checking that it takes it).
  template <class Body>
  static void each_target(Body body) {
    const std::vector<std::int64_t> targets = targets_here();
    ASSERT_FALSE(targets.empty());
    for (const std::int64_t t : targets) {
      use_target(t);
      ASSERT_STREQ(ntn::element_pass_target(), hwy::TargetName(t)) << "the dispatch must take it";
      body(t);
    }
  }

  void TearDown() override {
    hwy::SetSupportedTargetsForTest(0);  // back to what the CPU has
    hwy::GetChosenTarget().Update(hwy::SupportedTargets());
  }
};

}  // namespace ntn_test

#endif  // NTN_SIMD
