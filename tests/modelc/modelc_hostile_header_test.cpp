// Headers generated from hostile strings (hostile_strings.hpp, made by make_hostile_headers at
// build time) compile, carry every string back byte for byte, and their comment lines hold
// printable ASCII only (a title with a newline once injected C++ into the header).
// That this file compiles is half the test: an escaped string that got out would have put
// static_assert(false) or a stray declaration into the header.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <string_view>

#include "hostile_0.hpp"
#include "hostile_1.hpp"
#include "hostile_2.hpp"
#include "hostile_3.hpp"
#include "hostile_4.hpp"
#include "hostile_5.hpp"
#include "hostile_6.hpp"
#include "hostile_7.hpp"
#include "hostile_8.hpp"
#include "hostile_9.hpp"
#include "hostile_strings.hpp"

namespace {

static_assert(hostile::kCount == 10);  // one include above per string

template <class Strings>
void all_equal(const Strings& names, std::string_view want, const char* what, std::size_t i) {
  for (std::string_view n : names)
    EXPECT_EQ(n, want) << what << " of hostile_" << i;
}

// One header's strings against hostile string i; its data must still be the model's (the
// strings did not eat any of it).
#define NTN_CHECK_HOSTILE(i)                                                  \
  do {                                                                        \
    namespace h = ntn::models::hostile_##i;                                   \
    const std::string_view want = hostile::kStrings[i];                       \
    EXPECT_EQ(h::kTitle, want) << (i);                                        \
    EXPECT_EQ(h::kTitle.size(), want.size()) << (i); /* NUL bytes included */ \
    EXPECT_EQ(h::kSourceFile, want) << (i);                                   \
    EXPECT_EQ(h::kName, "hinged_beam") << (i);                                \
    all_equal(h::kInputNames, want, "input name", i);                         \
    all_equal(h::kOutputNames, want, "output name", i);                       \
    all_equal(h::kOutputUnits, want, "unit", i);                              \
    all_equal(h::kMemberNames, want, "member name", i);                       \
    all_equal(h::kHingeNames, want, "hinge name", i);                         \
    EXPECT_EQ(h::kSizes.hinges, 5U);                                          \
    EXPECT_EQ(h::kSpec.settings.limit_stiffness, 1.0e12);                     \
  } while (false)

TEST(HostileStrings, EveryStringReadsBackByteForByte) {
  NTN_CHECK_HOSTILE(0);
  NTN_CHECK_HOSTILE(1);
  NTN_CHECK_HOSTILE(2);
  NTN_CHECK_HOSTILE(3);
  NTN_CHECK_HOSTILE(4);
  NTN_CHECK_HOSTILE(5);
  NTN_CHECK_HOSTILE(6);
  NTN_CHECK_HOSTILE(7);
  NTN_CHECK_HOSTILE(8);
  NTN_CHECK_HOSTILE(9);
}
#undef NTN_CHECK_HOSTILE

// Each header's text: every line is printable ASCII (no byte that could end or splice a line
// inside a comment or a literal: the strings' bytes are all escapes), no line ends in a
// backslash, and no "??" (trigraphs).
TEST(HostileStrings, HeaderTextIsPrintableAsciiLineByLine) {
  for (std::size_t i = 0; i < hostile::kCount; ++i) {
    const std::string path =
        std::string(NTN_HOSTILE_DIR) + "/hostile_" + std::to_string(i) + ".hpp";
    std::ifstream in(path, std::ios::binary);
    ASSERT_TRUE(in) << path;
    std::stringstream text;
    text << in.rdbuf();
    const std::string h = text.str();
    EXPECT_EQ(h.find("??"), std::string::npos) << path;
    std::size_t start = 0;
    int line = 0;
    while (start < h.size()) {
      const std::size_t end = h.find('\n', start);
      const std::string_view l(h.data() + start, (end == h.npos ? h.size() : end) - start);
      ++line;
      for (const char c : l) {
        EXPECT_TRUE(c >= 0x20 && c < 0x7F) << path << ":" << line << ": byte " << int(c);
      }
      EXPECT_FALSE(!l.empty() && l.back() == '\\') << path << ":" << line;
      start = end == h.npos ? h.size() : end + 1;
    }
  }
}

}  // namespace
