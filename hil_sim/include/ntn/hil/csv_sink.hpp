// The response CSV of a run, as ntn-run-<model> and ntn-hil-<model> both write it (tools/run
// and hil_sim READMEs): a header `time[s],NAME[UNIT],...` (and `,flags`), then one row per
// frame: the frame time k T (%.9g), every output (%.17g) and, with flags, the frame's flag::
// bits (%u). Written as the run goes through a 1 MiB buffer, so a long run needs no memory for
// its whole response; every write is checked, and the first error is kept for close().
#pragma once

#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace ntn::hil {

class CsvWriter {
 public:
  CsvWriter() = default;
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;
  ~CsvWriter();

  // Creates (truncates) `path`; false: error() says why (strerror).
  bool open(const std::string& path);
  bool is_open() const { return file_ != nullptr; }
  // The header line; `flags` adds the flags column (then every row must give flags).
  void header(std::span<const std::string_view> names, std::span<const std::string_view> units,
              bool flags);
  // Hands the buffered rows to the file (the header does so itself): a run killed later loses
  // only what came after.
  void flush();
  void row(double time, std::span<const double> values);
  void row(double time, std::span<const double> values, std::uint16_t flags);
  // Flushes and closes; false: a write or the close failed, error() says how (strerror). The
  // file is closed either way.
  bool close();
  const std::string& error() const { return error_; }

 private:
  void put(const char* text);
  void fail(int err);
  std::FILE* file_ = nullptr;
  std::vector<char> buffer_;
  std::string error_;
};

}  // namespace ntn::hil
