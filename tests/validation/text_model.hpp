// A model from its TOML text, compiled and initialized in run-time storage, for the validation
// tests that vary a model file's text: nullptr (with the compiler's errors or init's status as a
// test failure) when it does not load.
#pragma once

#include <gtest/gtest.h>

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

}  // namespace ntn_test
