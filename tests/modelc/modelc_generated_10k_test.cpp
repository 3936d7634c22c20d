// A 10 000-element model compiles into a constexpr header and initializes the kernel.
#include <gtest/gtest.h>

#include "chain10k_model.hpp"
#include "ntn/kernel.hpp"
#include "ntn/modelc/load_model.hpp"
#include "spec_compare.hpp"
#include "support/init_model.hpp"

namespace {

namespace chain = ntn::models::chain10k;
static_assert(chain::kSizes.elements == 10000 && chain::kSizes.nodes == 10001);
static_assert(chain::kSizes.loads == 0 && chain::kSizes.inputs == 0);

ntn::Model<chain::kSizes> g_chain;

TEST(GeneratedHeader, TenThousandElements) {
  const auto r = ntn::modelc::load_model(std::string(chain::kSourceFile));
  ASSERT_TRUE(r.ok()) << ntn::modelc::format_all(r.errors);
  ntn::test::expect_same_spec(chain::kSpec, *r.model);
  const ntn::InitStatus st = ntn_test::init_model(chain::kSpec, g_chain);
  ASSERT_TRUE(st.ok()) << ntn::to_string(st.error) << " at " << st.where;
}

}  // namespace
