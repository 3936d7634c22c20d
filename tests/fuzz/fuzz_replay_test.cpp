// Replays the fuzz seeds (corpus/<target>/) and every input a fuzzer once crashed on
// (regressions/<target>/) through the fuzz target bodies, in the ordinary test build. Passing
// means: every input returns (an error or a result) without a crash; under the asan preset, also
// without an AddressSanitizer or UBSan report. No tolerance: the outcome is pass/abort.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_bodies.hpp"

namespace {

namespace fs = std::filesystem;
using Body = void (*)(const std::uint8_t*, std::size_t);

std::vector<fs::path> inputs(const std::string& target) {
  std::vector<fs::path> files;
  for (const char* kind : {"corpus", "regressions"}) {
    const fs::path dir = fs::path(NTN_FUZZ_DIR) / kind / target;
    if (!fs::is_directory(dir)) continue;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file()) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Runs every input of `target`; returns how many there were.
std::size_t replay(const std::string& target, Body body) {
  const auto files = inputs(target);
  for (const auto& f : files) {
    SCOPED_TRACE(f.string());
    std::ifstream in(f, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
    body(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  }
  return files.size();
}

TEST(FuzzReplay, Modelc) {
  EXPECT_GT(replay("modelc", ntn_fuzz::modelc), 0U);
}
TEST(FuzzReplay, At2) {
  EXPECT_GT(replay("at2", ntn_fuzz::at2), 0U);
}
TEST(FuzzReplay, Csv) {
  EXPECT_GT(replay("csv", ntn_fuzz::csv), 0U);
}
TEST(FuzzReplay, Packet) {
  EXPECT_GT(replay("packet", ntn_fuzz::packet), 0U);
}

}  // namespace
