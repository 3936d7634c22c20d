// A problem found in a model file, with the place it was found (file:line:column).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ntn::modelc {

// An error stops the model; a note reports something the model does on purpose or that the
// kernel handles (a mechanism held at zero) and does not.
enum class Severity : std::uint8_t { kError, kNote };

struct Diagnostic {
  std::string file;
  int line = 0;     // 1-based
  int column = 0;   // 1-based
  std::string key;  // TOML path of the offending key, e.g. "materials[1].E"; empty for syntax
  std::string message;
  Severity severity = Severity::kError;

  // "file:line:column: error: key 'KEY': MESSAGE" ("note:" for a note; the key part is left out
  // when key is empty).
  std::string format() const;
};

// One diagnostic per line, in the order given.
std::string format_all(const std::vector<Diagnostic>& diagnostics);

}  // namespace ntn::modelc
