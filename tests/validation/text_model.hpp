// A model from its TOML text, compiled and initialized in run-time storage, for the validation
// tests that vary a model file's text: nullptr (with the compiler's errors or init's status as a
// test failure) when it does not load.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>

#include "ntn/hil/loaded_model.hpp"
#include "ntn/kernel.hpp"
#include "ntn/modelc/load_model.hpp"

namespace ntn_test {

inline std::unique_ptr<ntn::hil::LoadedModel> load_text_model(const std::string& text,
                                                              const std::string& name) {
  ntn::modelc::LoadResult r = ntn::modelc::load_model_from_string(text, name);
  EXPECT_TRUE(r.ok()) << ntn::modelc::format_all(r.errors);
  if (!r.ok()) return nullptr;
  auto rt = std::make_unique<ntn::hil::LoadedModel>(std::move(*r.model), ntn::RunTimeOptions{});
  const ntn::InitStatus st = rt->init();
  EXPECT_TRUE(st.ok()) << ntn::to_string(st.error) << " at " << st.where;
  return st.ok() ? std::move(rt) : nullptr;
}

// A number as model text, to the last bit (%.17g).
inline std::string num(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// The slender steel bar of the corotational tests: E I = 2.1e5 N m^2 about both axes, G J =
// 1.6e5 N m^2, E A = 2.1e9 N (radius of gyration 1 cm), material "steel", section "bar".
inline const char* const kSlenderBar = R"(
[[materials]]
id = "steel"
E = 210e9
nu = 0.3
rho = 7850.0

[[sections]]
id = "bar"
A = 1e-2
Iy = 1e-6
Iz = 1e-6
J = 2e-6
)";

}  // namespace ntn_test
