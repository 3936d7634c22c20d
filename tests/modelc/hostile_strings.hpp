// Strings that try to get out of where the header generator puts them: a
// newline, CR or NUL ending a // comment early, a backslash at the end of a comment splicing
// the next line into it, a trigraph (?? and /: a backslash where trigraphs are on), the end of a
// block comment, a quote ending a string literal, non-ASCII and invalid UTF-8, control characters.
// Each that got out would put static_assert(false) or a stray line into the header: the header
// would not compile, or its strings would not read back.
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

namespace hostile {

using namespace std::string_view_literals;

inline constexpr std::size_t kCount = 10;  // tests/modelc/CMakeLists.txt makes as many headers

inline constexpr std::array<std::string_view, kCount> kStrings{
    "newline\nstatic_assert(false, \"newline injected\");\nint injected_newline = 1;"sv,
    "carriage return\rstatic_assert(false, \"CR injected\");"sv,
    "nul\0static_assert(false, \"NUL injected\");\0"sv,
    "backslash at the end \\"sv,
    "trigraph ?\?/\nstatic_assert(false, \"trigraph injected\");"sv,
    "*/ static_assert(false, \"comment closed\"); /*"sv,
    "quote \"); static_assert(false, \"quote\"); (\" and '\\''"sv,
    "non-ASCII: Z\xc3\xbcrich \xe2\x80\x93 \xe6\x9d\xb1\xe4\xba\xac, invalid UTF-8 \xff\xfe\xc3"sv,
    "percent %0A and control characters \t\v\f\x1b\x7f\x01"sv,
    "backslash-newline \\\nstatic_assert(false, \"spliced\");"sv,
};

}  // namespace hostile
