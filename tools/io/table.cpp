#include "table.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>

namespace ntn::io {

namespace {

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\"");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\"");
  return std::string(s.substr(b, e - b + 1));
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool blank(const std::string& line) {
  return line.find_first_not_of(" \t") == std::string::npos;
}

}  // namespace

std::pair<std::string, std::string> split_unit(const std::string& header) {
  const auto b = header.find('[');
  if (b == std::string::npos) return {header, {}};
  const auto e = header.find(']', b);
  return {trim(header.substr(0, b)),
          header.substr(b + 1, e == std::string::npos ? std::string::npos : e - b - 1)};
}

std::optional<std::size_t> find_channel(const std::vector<std::string>& names,
                                        const std::vector<std::string>& units,
                                        std::string_view name) {
  for (std::size_t c = 0; c < names.size(); ++c) {
    if (names[c] == name || names[c] + "[" + units[c] + "]" == name) return c;
  }
  return std::nullopt;
}

std::string channel_list(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& n : names)
    list += (list.empty() ? "" : ", ") + n;
  return list;
}

ReadError TableReader::error(std::size_t line, std::size_t column, std::string message) const {
  return {path_, static_cast<int>(line), static_cast<int>(column), std::move(message)};
}

bool TableReader::next_line() {
  if (!std::getline(in_, line_)) return false;
  ++line_number_;
  if (!line_.empty() && line_.back() == '\r') line_.pop_back();
  return true;
}

std::optional<ReadError> TableReader::open(const std::string& path,
                                           std::string_view expected_header) {
  path_ = path;
  header_.clear();
  line_number_ = 0;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return error(0, 0, "cannot open: it is a directory");
  errno = 0;
  in_.open(path, std::ios::binary);
  if (!in_) {
    const int e = errno;
    return error(0, 0, std::string("cannot open: ") + (e != 0 ? std::strerror(e) : "unreadable"));
  }
  bool found = false;
  while (next_line()) {
    if (!blank(line_)) {
      found = true;
      break;
    }
  }
  if (!found)
    return error(1, 1,
                 "the file is empty; expected a header row '" + std::string(expected_header) + "'");
  for (std::size_t i = 0;;) {
    const std::size_t e = std::min(line_.find(',', i), line_.size());
    header_.push_back(trim(std::string_view(line_).substr(i, e - i)));
    if (e >= line_.size()) break;
    i = e + 1;
  }
  header_line_ = line_number_;
  return std::nullopt;
}

std::optional<ReadError> TableReader::channels(std::vector<std::string>& names,
                                               std::vector<std::string>& units,
                                               std::vector<std::size_t>& columns,
                                               std::string_view first_column) const {
  names.clear();
  units.clear();
  columns.clear();
  for (std::size_t c = 1; c < header_.size(); ++c) {
    if (lower(header_[c]) == "flags") continue;
    auto [name, unit] = split_unit(header_[c]);
    if (name.empty())
      return error(header_line_, 1, "column " + std::to_string(c + 1) + " has no name");
    names.push_back(std::move(name));
    units.push_back(std::move(unit));
    columns.push_back(c);
  }
  if (columns.empty())
    return error(header_line_, 1,
                 "the header needs " + std::string(first_column) + " and at least one channel");
  return std::nullopt;
}

bool TableReader::next_row(std::vector<TableField>& fields) {
  do {
    if (!next_line()) return false;
  } while (blank(line_));
  fields.clear();
  const std::string_view row = line_;
  for (std::size_t i = 0;;) {
    const std::size_t end = std::min(row.find(',', i), row.size());
    std::size_t b = i;
    while (b < end && (row[b] == ' ' || row[b] == '\t'))
      ++b;
    std::size_t e = end;
    while (e > b && (row[e - 1] == ' ' || row[e - 1] == '\t'))
      --e;
    if (b < e && row[b] == '+') ++b;  // from_chars takes no leading '+'
    TableField f;
    f.column = b + 1;
    f.length = e - b;
    const auto r = std::from_chars(row.data() + b, row.data() + e, f.value);
    f.ok = b < e && r.ec == std::errc() && r.ptr == row.data() + e;
    fields.push_back(f);
    if (end >= row.size()) break;
    i = end + 1;
  }
  return true;
}

std::optional<ReadError> TableReader::row_length_error(
    const std::vector<TableField>& fields) const {
  if (fields.size() == header_.size()) return std::nullopt;
  return error(line_number_, 1,
               "expected " + std::to_string(header_.size()) + " values, found " +
                   std::to_string(fields.size()));
}

}  // namespace ntn::io
