// A problem found in a model file, with the place it was found (file:line:column).
#pragma once

#include <string>
#include <vector>

namespace ntn::modelc {

struct Diagnostic {
  std::string file;
  int line = 0;     // 1-based
  int column = 0;   // 1-based
  std::string key;  // TOML path of the offending key, e.g. "materials[1].E"; empty for syntax
  std::string message;

  // "file:line:column: error: key 'KEY': MESSAGE" (the key part is left out when key is empty).
  std::string format() const;
};

// One diagnostic per line, in the order given.
std::string format_all(const std::vector<Diagnostic>& diagnostics);

}  // namespace ntn::modelc
