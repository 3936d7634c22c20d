#include "messages.hpp"

#include <cstdio>

namespace ntn::modelc::compile {

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string quoted_list(const std::vector<std::string_view>& items) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) s += ", ";
    s += '"';  // appended piecewise: GCC 12 -Wrestrict misfires on "\"" + string + "\""
    s += items[i];
    s += '"';
  }
  return s;
}

std::string plain_list(const std::vector<std::string_view>& items) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) s += ", ";
    s += std::string(items[i]);
  }
  return s;
}

}  // namespace ntn::modelc::compile
