// Reads and validates a model file (TOML) into a ModelDescription. Never throws: every problem
// comes back as a Diagnostic with its file:line:column.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ntn/modelc/diagnostic.hpp"
#include "ntn/modelc/model_description.hpp"

namespace ntn::modelc {

struct LoadResult {
  std::optional<ModelDescription> model;  // set exactly when `errors` is empty
  std::vector<Diagnostic> errors;         // sorted by line, then column
  std::vector<Diagnostic> notes;          // severity kNote (mechanisms), when the model loads
  bool ok() const { return model.has_value(); }
};

LoadResult load_model(const std::string& path);

// The same from text in memory; `source_name` stands for the file name in diagnostics.
LoadResult load_model_from_string(std::string_view toml_text, const std::string& source_name);

}  // namespace ntn::modelc
