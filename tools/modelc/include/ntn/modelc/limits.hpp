// Limits on a model file, checked on its text before the TOML parser sees it (config/README.md,
// "Limits of a model file"). toml++ builds one nested table per part of a dotted key or table
// header and recurses once per level (parsing, building and destroying the tree), without a
// limit for dotted keys: `a.a.a.…` 50 000 levels deep (a 200 KB file) overflows the stack.
// Arrays and inline tables it limits to 256 levels itself; this scan refuses all of them far
// earlier, with the place where the limit is passed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "ntn/modelc/diagnostic.hpp"

namespace ntn::modelc {

// Largest model file: toml++ keeps the whole document as a tree of 13 to 55 bytes of memory per
// byte of text (the most for `[[0]], [[0]], ...`; a model file of 10^5 members is about 13), so
// 64 MiB bounds the parse at 3.6 GB, and is 50 times the largest model the kernel is meant for
// (10^5 elements, about 1.2 MB). Within it, the tree's own estimate (NestingScan::values x
// kParseBytesPerValue, memory.hpp) is checked against the memory available before parsing.
inline constexpr std::size_t kMaxModelFileBytes = std::size_t{64} << 20;

// Deepest nesting: tables, arrays and inline tables one inside another, each part of a dotted
// key or table header counting as a table, the value itself one more (`a = 1` is 1, `[m.d]`
// then `x = [[1]]` is 5). A valid model reaches 7 (`[[members]]` with
// `release_start = { ry = { backbone = [[d, f], ...] } }`); deeper input can only be an error, so
// the limit leaves room
// and stays far below toml++'s stack needs (it crashed between 20 000 and 50 000 levels).
inline constexpr int kMaxNesting = 32;

struct NestingScan {
  int depth = 0;             // the deepest level seen (up to the first level past the limit)
  int line = 0, column = 0;  // 1-based, where `depth` first passed `limit` (0: it did not)
  // Keys (each part of a dotted one), table headers, arrays and inline tables, and array
  // elements after the first: about one per node of the parser's tree.
  std::uint64_t values = 0;
};

// Scans TOML text for its nesting depth without building anything: linear time, constant stack,
// memory bounded by `limit`. Strings (all four kinds) and comments are skipped; malformed text
// is scanned on as far as it can be and left to the parser to report.
NestingScan scan_nesting(std::string_view text, int limit = kMaxNesting);

// The error for text over kMaxModelFileBytes, nested deeper than kMaxNesting (at its place;
// file:1:1 for the size) or whose parse needs more memory than is available (file:1:1), or
// nullopt.
std::optional<Diagnostic> check_model_text_limits(std::string_view text, const std::string& file);

}  // namespace ntn::modelc
