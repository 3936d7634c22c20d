// No heap in the kernel (DESIGN §2): init, start and 1e5 steps of a model with every
// load, input and output kind make zero heap allocations, counted by replacing malloc & co. and
// every global operator new (tests/support/alloc_counter.cpp); Eigen's own no-malloc guard is on
// around them too. The counter is first shown to count.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <vector>

#include "ntn/kernel.hpp"
#include "support/alloc_counter.hpp"
#include "support/frames.hpp"
#include "support/no_heap.hpp"

namespace allocation_test {

// Keeps the compiler from proving an allocation unused and removing it.
void escape(const void* p) {
  asm volatile("" : : "g"(p) : "memory");
}

TEST(AllocationCounter, CountsVectorGrowth) {
  ntn_test::AllocationCounts c;
  {
    const ntn_test::AllocationScope scope;
    std::vector<int> v;
    v.push_back(1);
    escape(v.data());
    v.push_back(2);
    escape(v.data());
    std::vector<int>().swap(v);  // releases the storage
    c = scope.counts();
  }
  EXPECT_GE(c.allocations, 2U);
  EXPECT_GE(c.deallocations, 2U);
}

TEST(AllocationCounter, CountsCAllocatorsAndEveryNewForm) {
  const ntn_test::AllocationScope scope;
  void* p = std::malloc(16);
  escape(p);
  p = std::realloc(p, 64);
  escape(p);
  std::free(p);
  void* q = std::calloc(4, 8);
  escape(q);
  std::free(q);
  void* r = std::aligned_alloc(64, 128);
  escape(r);
  std::free(r);
  void* s = nullptr;
  ASSERT_EQ(posix_memalign(&s, 64, 128), 0);
  escape(s);
  std::free(s);
  auto* a = new double[3];
  escape(a);
  delete[] a;
  struct alignas(64) Wide {
    double x[8];
  };
  auto* w = new Wide;
  escape(w);
  delete w;
  auto* n = new (std::nothrow) int(3);
  escape(n);
  delete n;
  const ntn_test::AllocationCounts c = scope.counts();
  EXPECT_EQ(c.allocations, 8U);  // malloc, realloc, calloc, aligned, posix, new[], new(al), nothrow
#if defined(NTN_SANITIZE)
  // Under ASan the counts come from its allocator hooks, and ASan's realloc always moves the
  // block: it releases the old one, which its free hook counts.
  EXPECT_EQ(c.deallocations, 8U);
#else
  EXPECT_EQ(c.deallocations, 7U);  // realloc released nothing separately
#endif
}

// Allocations made inside shared libraries are counted too (strdup allocates inside glibc).
TEST(AllocationCounter, CountsAllocationsInsideSharedLibraries) {
  ntn_test::AllocationCounts c;
  {
    const ntn_test::AllocationScope scope;
    char* d = strdup("counted");
    escape(d);
    std::free(d);
    c = scope.counts();
  }
  EXPECT_EQ(c.allocations, 1U);
  EXPECT_EQ(c.deallocations, 1U);
}

TEST(AllocationCounter, CountsEigenDynamicMatrices) {
  ntn_test::AllocationCounts c;
  {
    const ntn_test::AllocationScope scope;
    Eigen::MatrixXd m = Eigen::MatrixXd::Identity(20, 20);
    escape(m.data());
    c = scope.counts();
  }
  EXPECT_GE(c.allocations, 1U);
}

// The Eigen guard is live in this build type (eigen_guard.hpp): a dynamic allocation under
// EigenNoMalloc aborts.
TEST(EigenNoMallocDeathTest, DynamicMatrixAborts) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH(
      {
        const ntn_test::EigenNoMalloc guard;
        Eigen::MatrixXd m(30, 30);
        escape(m.data());
      },
      "heap allocation is forbidden");
}

constexpr ntn::Sizes kS = ntn_test::kFeatureSizes;
ntn::ModelSpec<kS> spec;
ntn::Model<kS> model;
ntn::InitWorkspace<kS> init_work;  // static: init() is inside the allocation count
ntn::State<kS> state;
ntn::Scratch<kS> scratch;

// Every kernel entry point, counted: zero allocations and zero frees, including the steps that
// hold a NaN input and the stable-step eigen solves inside init.
void expect_no_allocations(double beta_ratio);

TEST(KernelAllocations, NoneInInitStartAnd1e5Steps) {
  expect_no_allocations(0.0);
}

// The same with stiffness-proportional damping (beta K_el in the element pass: its own loop),
// beta = 2 x 0.2 / omega_max (20 % of critical at the elements' highest frequency).
TEST(KernelAllocations, NoneWithStiffnessProportionalDamping) {
  expect_no_allocations(0.2);
}

void expect_no_allocations(double beta_ratio) {
  ASSERT_TRUE(ntn_test::feature_frame(spec));
  // An initial state ([initial], a static preload) on a free node: initial_state() copies it.
  spec.nodes[1].u0 = {1e-4, -2e-4, 0, 0, 1e-5, 0};
  spec.nodes[1].v0 = {0, 0.01, 0, 0, 0, 0};
  if (beta_ratio > 0) {
    spec.settings.beta = 2 * beta_ratio / ntn::stable_time_step(ntn::view(spec)).omega_max;
    spec.settings.dt = 0.9 * ntn::stable_time_step(ntn::view(spec)).dt_stable;
  }
  constexpr long kSteps = 100'000;
  ntn::InitStatus st;
  ntn::StepStatus first = ntn::StepStatus::kDiverged;
  long ok_steps = 0, held_steps = 0;
  ntn_test::AllocationCounts c;
  {
    const ntn_test::AllocationScope scope;
    const ntn_test::EigenNoMalloc guard;
    st = ntn::init(spec, model, init_work);
    ntn::initial_state(model, state);
    first = ntn::start(model, state, scratch, {0.01, 0.0, 1.0});
    std::array<double, kS.inputs> in{};
    for (long n = 0; n < kSteps; ++n) {
      in = {ntn_test::input_sample(0, n), ntn_test::input_sample(1, n),
            n % 1000 == 7 ? std::numeric_limits<double>::quiet_NaN() : 1.0};
      const ntn::StepStatus s = ntn::step(model, state, scratch, in);
      ok_steps += s == ntn::StepStatus::kOk;
      held_steps += s == ntn::StepStatus::kInputHeld;
    }
    c = scope.counts();
  }
  ASSERT_TRUE(st.ok());
  EXPECT_EQ(first, ntn::StepStatus::kOk);
  EXPECT_EQ(held_steps, kSteps / 1000);
  EXPECT_EQ(ok_steps + held_steps, kSteps);
  EXPECT_EQ(c.allocations, 0U);
  EXPECT_EQ(c.deallocations, 0U);
  // The stable-step report a model tool would print is also heap-free.
  {
    const ntn_test::AllocationScope scope;
    const ntn_test::EigenNoMalloc guard;
    const ntn::StableStepReport r = ntn::stable_time_step(ntn::view(spec));
    escape(&r);
    EXPECT_EQ(scope.counts().allocations, 0U);
  }
}

}  // namespace allocation_test
