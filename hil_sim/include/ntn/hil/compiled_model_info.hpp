// The ModelInfo (model_info.hpp) of the model compiled into a program: include it after
// NTN_MODEL_HEADER, whose namespace NTN_MODEL_NS holds the names. For ntn-run-<model> and
// ntn-hil-<model>; internal linkage, since each program has its own model.
#pragma once

#include <string_view>
#include <vector>

#include "ntn/hil/model_info.hpp"

namespace {

template <class A>
std::vector<std::string_view> compiled_names(const A& a) {
  return {a.begin(), a.end()};
}

ntn::hil::ModelInfo compiled_model_info() {
  namespace mdl = NTN_MODEL_NS;
  return {mdl::kName,
          mdl::kSourceFile,
          compiled_names(mdl::kInputNames),
          compiled_names(mdl::kOutputNames),
          compiled_names(mdl::kOutputUnits),
          {mdl::kAlarmLimits.begin(), mdl::kAlarmLimits.end()},
          {mdl::kAlarmHysteresis.begin(), mdl::kAlarmHysteresis.end()},
          compiled_names(mdl::kMemberNames),
          compiled_names(mdl::kHingeNames)};
}

}  // namespace
