// JSON text pieces every tool writes its JSON output with (header-only): a string literal with
// RFC 8259 escapes, and a number (null where JSON has no number: NaN and infinities).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

namespace ntn::json {

// `s` as a JSON string literal: quotes, backslash and the control characters escaped (\n, \t and
// \u00XX); every other byte is copied as it is (UTF-8 passes through).
inline std::string quoted(std::string_view s) {
  std::string o = "\"";
  for (const char c : s) {
    switch (c) {
      case '"':
        o += "\\\"";
        break;
      case '\\':
        o += "\\\\";
        break;
      case '\n':
        o += "\\n";
        break;
      case '\t':
        o += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char u[8];
          std::snprintf(u, sizeof u, "\\u%04x",
                        static_cast<unsigned>(static_cast<unsigned char>(c)));
          o += u;
        } else {
          o += c;
        }
    }
  }
  return o + "\"";
}

// `v` printed with `format` (a printf conversion for one double); `null` when v is NaN or
// infinite, which JSON cannot write. "%.17g" reads back as the same double.
inline std::string number(double v, const char* format = "%.17g") {
  if (!std::isfinite(v)) return "null";
  char b[48];
  std::snprintf(b, sizeof b, format, v);
  return b;
}

}  // namespace ntn::json
