// The words of a model file that messages and the reader share (DOF names), the distance below
// which two nodes are at the same place, and how numbers and lists print in messages.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace ntn::modelc::compile {

inline const std::vector<std::string_view> kDofNames = {"ux", "uy", "uz", "rx", "ry", "rz"};
inline constexpr double kCoincident = 1e-9;  // m: hinge nodes closer than this coincide

// A number in a message: %.6g.
std::string num(double v);
// "a", "b", "c" (each quoted) / a, b, c.
std::string quoted_list(const std::vector<std::string_view>& items);
std::string plain_list(const std::vector<std::string_view>& items);

}  // namespace ntn::modelc::compile
