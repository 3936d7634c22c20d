// What the plot tests read back: a temporary directory, the PNG header, the SVG's text (parsed by
// expat, so "well-formed" means what an XML parser says), and running ntn-plot.
#pragma once

#include <expat.h>
#include <sys/wait.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

namespace ntn::plot::test {

namespace fs = std::filesystem;

// A fresh directory under the system's temporary directory, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "ntn-plot-test-XXXXXX").string();
    if (::mkdtemp(pattern.data()) != nullptr) path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    if (!path_.empty()) fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_file(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Width and height from a PNG's IHDR chunk (PNG spec §5.2, §11.2.2: the 8-byte signature, then
// the first chunk, IHDR: length 13, type, width and height as big-endian 32-bit integers).
struct PngSize {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};
inline std::optional<PngSize> png_size(const std::string& path) {
  const std::string b = read_file(path);
  static constexpr std::array<unsigned char, 8> kSignature = {0x89, 'P',  'N',  'G',
                                                              '\r', '\n', 0x1a, '\n'};
  if (b.size() < 24) return std::nullopt;
  for (std::size_t i = 0; i < 8; ++i)
    if (static_cast<unsigned char>(b[i]) != kSignature[i]) return std::nullopt;
  if (b.compare(12, 4, "IHDR") != 0) return std::nullopt;
  const auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i)
      v = (v << 8) | static_cast<unsigned char>(b[at + i]);
    return v;
  };
  return PngSize{be32(16), be32(20)};
}

// An SVG parsed by expat: the error (empty when well-formed), the root's name and attributes,
// and the character data of every <text> element (its tspans joined).
struct Svg {
  std::string error;
  std::string root;
  std::string width, height;  // root attributes
  std::vector<std::string> texts;

  bool has_text(const std::string& s) const {
    for (const std::string& t : texts)
      if (t.find(s) != std::string::npos) return true;
    return false;
  }
};

inline Svg parse_svg(const std::string& path) {
  struct State {
    Svg svg;
    int depth = 0;
    int text_depth = 0;  // > 0 inside <text>
  } st;
  XML_Parser p = XML_ParserCreate(nullptr);
  XML_SetUserData(p, &st);
  XML_SetElementHandler(
      p,
      [](void* u, const XML_Char* name, const XML_Char** attrs) {
        auto& s = *static_cast<State*>(u);
        if (s.depth++ == 0) {
          s.svg.root = name;
          for (int i = 0; attrs[i] != nullptr; i += 2) {
            if (std::string(attrs[i]) == "width") s.svg.width = attrs[i + 1];
            if (std::string(attrs[i]) == "height") s.svg.height = attrs[i + 1];
          }
        }
        if (std::string(name) == "text" && s.text_depth++ == 0)
          s.svg.texts.emplace_back();
        else if (s.text_depth > 0)
          ++s.text_depth;
      },
      [](void* u, const XML_Char*) {
        auto& s = *static_cast<State*>(u);
        --s.depth;
        if (s.text_depth > 0) --s.text_depth;
      });
  XML_SetCharacterDataHandler(p, [](void* u, const XML_Char* text, int len) {
    auto& s = *static_cast<State*>(u);
    if (s.text_depth > 0) s.svg.texts.back().append(text, static_cast<std::size_t>(len));
  });
  const std::string doc = read_file(path);
  if (doc.empty()) {
    st.svg.error = "empty file";
  } else if (XML_Parse(p, doc.data(), static_cast<int>(doc.size()), 1) == XML_STATUS_ERROR) {
    st.svg.error = std::string(XML_ErrorString(XML_GetErrorCode(p))) + " at line " +
                   std::to_string(XML_GetCurrentLineNumber(p));
  }
  XML_ParserFree(p);
  return st.svg;
}

// Runs a command line through /bin/sh with stdout and stderr captured in files under `dir`.
struct Run {
  int status = -1;
  std::string out;
  std::string err;
};
inline Run run(const std::string& command, const TempDir& dir) {
  const std::string out = dir / "cmd.out";
  const std::string err = dir / "cmd.err";
  const int rc = std::system((command + " >" + out + " 2>" + err).c_str());
  Run r;
  r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  std::error_code ec;
  fs::remove(out, ec);
  fs::remove(err, ec);
  return r;
}

}  // namespace ntn::plot::test
