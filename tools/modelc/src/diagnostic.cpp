#include "ntn/modelc/diagnostic.hpp"

namespace ntn::modelc {

std::string Diagnostic::format() const {
  std::string s = file + ":" + std::to_string(line) + ":" + std::to_string(column) +
                  (severity == Severity::kNote ? ": note: " : ": error: ");
  if (!key.empty()) s += "key '" + key + "': ";
  s += message;
  return s;
}

std::string format_all(const std::vector<Diagnostic>& diagnostics) {
  std::string s;
  for (const Diagnostic& d : diagnostics)
    s += d.format() + "\n";
  return s;
}

}  // namespace ntn::modelc
