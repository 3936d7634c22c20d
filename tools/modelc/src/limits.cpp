#include "ntn/modelc/limits.hpp"

#include <vector>

#include "ntn/modelc/memory.hpp"

namespace ntn::modelc {
namespace {

// A TOML scanner that only follows structure: statements (table headers, key = value), keys
// (bare, quoted, dotted), values (strings, scalars, arrays, inline tables) and comments.
class Scanner {
 public:
  Scanner(std::string_view text, int limit) : t_(text), limit_(limit) {}

  NestingScan run() {
    while (!done()) {
      const char c = peek();
      if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
        advance();
      } else if (c == '#') {
        skip_comment();
      } else if (c == '[') {
        const int parts = header();
        if (parts >= 0) base_ = parts;
        skip_line();
      } else {
        const int parts = key(base_);
        if (parts < 0) {
          skip_line();
        } else {
          value(base_ + parts);
        }
      }
    }
    return result_;
  }

 private:
  bool done() const { return i_ >= t_.size() || result_.line > 0; }
  char peek(std::size_t k = 0) const { return i_ + k < t_.size() ? t_[i_ + k] : '\0'; }
  void advance() {
    if (t_[i_] == '\n') ++line_, line_start_ = i_ + 1;
    ++i_;
  }
  // Records a level at the current position; false once past the limit.
  bool level(int depth) {
    ++result_.values;
    if (depth > result_.depth) result_.depth = depth;
    if (depth > limit_ && result_.line == 0) {
      result_.line = line_;
      result_.column = static_cast<int>(i_ - line_start_) + 1;
    }
    return result_.line == 0;
  }
  void skip_comment() {
    while (i_ < t_.size() && t_[i_] != '\n')
      ++i_;
  }
  void skip_line() {
    while (i_ < t_.size() && t_[i_] != '\n') {
      if (t_[i_] == '"' || t_[i_] == '\'') {
        string();
      } else {
        ++i_;
      }
    }
  }
  // A string at i_ (basic "...", literal '...', or their multi-line forms """ and ''').
  void string() {
    const char q = peek();
    const bool basic = q == '"';
    if (peek(1) == q && peek(2) == q) {
      i_ += 3;
      while (i_ < t_.size()) {
        if (basic && t_[i_] == '\\') {
          advance();
          if (i_ < t_.size()) advance();
        } else if (t_[i_] == q && peek(1) == q && peek(2) == q) {
          i_ += 3;
          while (i_ < t_.size() && t_[i_] == q)  // up to two quotes end the content
            ++i_;
          return;
        } else {
          advance();
        }
      }
      return;
    }
    ++i_;
    while (i_ < t_.size() && t_[i_] != '\n') {
      if (basic && t_[i_] == '\\') {
        ++i_;
        if (i_ < t_.size() && t_[i_] != '\n') ++i_;
      } else if (t_[i_] == q) {
        ++i_;
        return;
      } else {
        ++i_;
      }
    }
  }
  // A table header at i_ ('[' or '[['): its depth (parts, + 1 for an array of tables), or -1.
  int header() {
    const bool array = peek(1) == '[';
    i_ += array ? 2 : 1;
    int depth = array ? 2 : 1;
    if (!level(depth)) return -1;
    while (i_ < t_.size()) {
      const char c = t_[i_];
      if (c == '"' || c == '\'') {
        string();
      } else if (c == '.') {
        if (!level(++depth)) return -1;
        ++i_;
      } else if (c == ']') {
        ++i_;
        if (array && peek() == ']') ++i_;
        return depth;
      } else if (c == '\n') {
        return -1;
      } else {
        ++i_;
      }
    }
    return -1;
  }
  // A key at i_ up to and including its '=': the number of its parts, or -1 (no '=' before the
  // end of the line, a ',' or a '}', or past the limit). `base`: the depth of its table.
  int key(int base) {
    int parts = 1;
    if (!level(base + parts)) return -1;
    while (i_ < t_.size()) {
      const char c = t_[i_];
      if (c == '"' || c == '\'') {
        string();
      } else if (c == '.') {
        if (!level(base + ++parts)) return -1;
        ++i_;
      } else if (c == '=') {
        ++i_;
        return parts;
      } else if (c == '\n' || c == '#' || c == ',' || c == '}' || c == '{' || c == '[' ||
                 c == ']') {
        return -1;
      } else {
        ++i_;
      }
    }
    return -1;
  }
  // The value of a key-value statement at depth `depth`: scalars, strings, and arrays and inline
  // tables to any depth, with an explicit stack. Returns at the end of the value (the end of the
  // line for a scalar, after the closing bracket for a container) or at something malformed.
  void value(int depth) {
    struct Open {
      char kind;  // '[' or '{'
      int depth;  // the container's own level
    };
    std::vector<Open> open;  // at most limit_ + 1 entries: each push passed level()
    int next = depth;        // level of the next value
    bool expect_key = false;
    while (!done()) {
      const char c = peek();
      if (expect_key) {
        if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
          advance();
          continue;
        }
        if (c == '#') {
          skip_comment();
          continue;
        }
        if (c != '}') {
          const int parts = key(open.back().depth);
          if (parts < 0) return;
          next = open.back().depth + parts;
          expect_key = false;
          continue;
        }
      }
      switch (c) {
        case '"':
        case '\'':
          string();
          if (open.empty()) return;
          break;
        case '#':
          skip_comment();
          break;
        case '[':
        case '{':
          open.push_back({c, next});
          if (c == '{') ++result_.values;
          ++i_;
          if (c == '[') {
            if (!level(++next)) return;
          } else {
            expect_key = true;
          }
          break;
        case ',':
          ++i_;
          if (open.empty()) return;
          if (open.back().kind == '{') {
            expect_key = true;
          } else {
            ++result_.values;
            next = open.back().depth + 1;
          }
          break;
        case ']':
        case '}':
          ++i_;
          if (open.empty()) return;
          open.pop_back();
          expect_key = false;
          if (open.empty()) return;
          break;
        case '\n':
          if (open.empty()) return;
          advance();
          break;
        default:
          ++i_;
      }
    }
  }

  std::string_view t_;
  int limit_;
  std::size_t i_ = 0;
  int line_ = 1;
  std::size_t line_start_ = 0;
  int base_ = 0;  // depth of the table that the current header opened
  NestingScan result_;
};

}  // namespace

NestingScan scan_nesting(std::string_view text, int limit) {
  return Scanner(text, limit).run();
}

std::optional<Diagnostic> check_model_text_limits(std::string_view text, const std::string& file) {
  if (text.size() > kMaxModelFileBytes) {
    return Diagnostic{file, 1, 1, "",
                      "the file has " + std::to_string(text.size()) +
                          " bytes; a model file may have at most " +
                          std::to_string(kMaxModelFileBytes) +
                          " (64 MiB: the parser needs up to 55 bytes of memory per byte of "
                          "text)"};
  }
  const NestingScan s = scan_nesting(text, kMaxNesting);
  if (s.line > 0) {
    return Diagnostic{file, s.line, s.column, "",
                      "nested deeper than " + std::to_string(kMaxNesting) +
                          " levels (tables, arrays and inline tables one inside another; each "
                          "part of a dotted key or table header is a table); a model needs at "
                          "most 5. Refused before parsing: the TOML parser recurses once per "
                          "level"};
  }
  if (auto refused = memory_refusal(
          "reading the file", s.values * kParseBytesPerValue,
          std::to_string(s.values) + " TOML values in " + format_bytes(text.size()))) {
    return Diagnostic{file, 1, 1, "", std::move(*refused)};
  }
  return std::nullopt;
}

}  // namespace ntn::modelc
