// Reads and validates a model file (TOML) into a ModelDescription. Never throws: every problem
// comes back as a Diagnostic with its file:line:column.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ntn/modelc/diagnostic.hpp"
#include "ntn/modelc/model_description.hpp"

namespace ntn::modelc {

struct LoadResult {
  std::optional<ModelDescription> model;  // set exactly when `errors` is empty
  // Sorted by line, then column. At most 50 of each kind (severity and key, any array index):
  // the rest are counted, and one note per capped kind says how many were left out.
  std::vector<Diagnostic> errors;
  std::vector<Diagnostic> notes;  // severity kNote (mechanisms), when the model loads; capped
  std::size_t error_count = 0;    // every error found, listed or not
  bool unreadable = false;        // load_model could not read the file (missing, a directory, no
                                  // permission): the one error says why; programs exit 2 (usage)
  bool ok() const { return model.has_value(); }
};

// Reads the file (at most kMaxModelFileBytes, ntn/modelc/limits.hpp) and loads it.
LoadResult load_model(const std::string& path);

// The same from text in memory; `source_name` stands for the file name in diagnostics. Text over
// the size or nesting limits (ntn/modelc/limits.hpp) is refused before it is parsed.
LoadResult load_model_from_string(std::string_view toml_text, const std::string& source_name);

}  // namespace ntn::modelc
