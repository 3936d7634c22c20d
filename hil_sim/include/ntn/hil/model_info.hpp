// What a program's summary names of a model: the names the model file gave it and its channels.
// The compiled programs take them from the model's header, ntn-run and ntn-hil from the loaded
// model file (ntn::modelc::ModelDescription); the strings outlive the run.
#pragma once

#include <string_view>
#include <vector>

namespace ntn::hil {

struct ModelInfo {
  std::string_view name;
  std::string_view source_file;
  std::vector<std::string_view> input_names;
  std::vector<std::string_view> output_names;
  std::vector<std::string_view> output_units;
  std::vector<double> alarm_limits;            // per output ([[outputs]] alarm; 0: none)
  std::vector<double> alarm_hysteresis;        // per output
  std::vector<std::string_view> member_names;  // by ElementSpec::member
  std::vector<std::string_view> hinge_names;   // by hinge
};

}  // namespace ntn::hil
