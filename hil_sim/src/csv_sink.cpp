#include "ntn/hil/csv_sink.hpp"

#include <cerrno>
#include <cstring>

namespace ntn::hil {

CsvWriter::~CsvWriter() {
  if (file_ != nullptr) (void)close();
}

bool CsvWriter::open(const std::string& path) {
  error_.clear();
  errno = 0;
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) {
    error_ = std::strerror(errno != 0 ? errno : EIO);
    return false;
  }
  buffer_.resize(std::size_t{1} << 20);
  std::setvbuf(file_, buffer_.data(), _IOFBF, buffer_.size());
  return true;
}

void CsvWriter::fail(int err) {
  if (error_.empty()) error_ = std::strerror(err != 0 ? err : EIO);
}

void CsvWriter::put(const char* text) {
  if (file_ == nullptr || !error_.empty()) return;
  errno = 0;
  if (std::fputs(text, file_) < 0) fail(errno);
}

void CsvWriter::header(std::span<const std::string_view> names,
                       std::span<const std::string_view> units, bool flags) {
  std::string head = "time[s]";
  for (std::size_t c = 0; c < names.size(); ++c) {
    head += ',';
    head += names[c];
    head += '[';
    head += c < units.size() ? units[c] : std::string_view();
    head += ']';
  }
  head += flags ? ",flags\n" : "\n";
  put(head.c_str());
  flush();  // on disk at once: a run killed before its first flush still leaves the header
}

void CsvWriter::flush() {
  if (file_ == nullptr || !error_.empty()) return;
  errno = 0;
  if (std::fflush(file_) != 0) fail(errno);
}

void CsvWriter::row(double time, std::span<const double> values) {
  char text[64];
  std::snprintf(text, sizeof text, "%.9g", time);
  put(text);
  for (const double v : values) {
    std::snprintf(text, sizeof text, ",%.17g", v);
    put(text);
  }
  put("\n");
}

void CsvWriter::row(double time, std::span<const double> values, std::uint16_t flags) {
  char text[64];
  std::snprintf(text, sizeof text, "%.9g", time);
  put(text);
  for (const double v : values) {
    std::snprintf(text, sizeof text, ",%.17g", v);
    put(text);
  }
  std::snprintf(text, sizeof text, ",%u\n", static_cast<unsigned>(flags));
  put(text);
}

bool CsvWriter::close() {
  if (file_ == nullptr) return error_.empty();
  errno = 0;
  if (std::fflush(file_) != 0 || std::ferror(file_) != 0) fail(errno);
  errno = 0;
  if (std::fclose(file_) != 0) fail(errno);
  file_ = nullptr;
  return error_.empty();
}

}  // namespace ntn::hil
