// How ntn-ida writes numbers: exactly (%.17g, which reads back as the same double: the result
// files and the journal) and rounded for people (messages, legends).
#pragma once

#include <cstdio>
#include <string>

namespace ntn::ida::detail {

inline std::string exact(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

inline std::string rounded(double v, int digits) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

}  // namespace ntn::ida::detail
