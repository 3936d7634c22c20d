// The stable step's bound of second-order geometry in a run, for the run and loop summaries: the
// step holds while every p_delta, leaning and corotational element's Q = N+ + k l (phi + phi^2)
// stays under its bound (ntn/geometry.hpp); past it the kernel counts the element evaluations
// (State::geometry_bound) and sets kFaultGeometryBound, and the loop says in which frame it was
// first passed (LoopResult::geometry_bound_frame).
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

#include "ntn/model.hpp"
#include "ntn/state.hpp"
#include "ntn/status.hpp"

namespace ntn::hil {

// What the summaries say after a run past the bound.
inline constexpr const char* kGeometryBoundMeaning =
    "the step left its stable bound for the axial forces and chord rotations reached: results "
    "past it are not valid";

// The names of State::faults' bits, in bit order.
struct FaultName {
  std::uint32_t bit;
  const char* name;
};
inline constexpr FaultName kFaultNames[] = {{kFaultInputHeld, "input_held"},
                                            {kFaultDiverged, "diverged"},
                                            {kFaultInputRange, "input_range"},
                                            {kFaultGeometryBound, "geometry_bound"}};

// The names of State::faults' bits, as a JSON array: ["diverged", "geometry_bound"].
inline std::string fault_names_json(std::uint32_t faults) {
  std::string out = "[";
  for (const FaultName& f : kFaultNames) {
    if ((faults & f.bit) == 0) continue;
    out += std::string(out.size() > 1 ? ", " : "") + "\"" + f.name + "\"";
  }
  return out + "]";
}

// The elements the bound is checked in: p_delta, leaning and corotational.
template <Sizes S>
std::size_t bounded_elements(const Model<S>& m) {
  return static_cast<std::size_t>(m.sizes.geometric + m.sizes.corotational);
}

// The summary's line for the bound, after its label: empty for a model without second-order
// geometry; else whether it held, or from when it did not and how many evaluations were past it.
template <Sizes S>
std::string geometry_bound_text(const Model<S>& m, const State<S>& s, std::int64_t first_frame,
                                double period) {
  const std::size_t n = bounded_elements(m);
  if (n == 0) return {};
  char text[320];
  if (first_frame < 0 && s.geometry_bound == 0) {
    std::snprintf(text, sizeof text,
                  "the stable step's bound held in the %zu element%s with second-order geometry", n,
                  n == 1 ? "" : "s");
  } else {
    std::snprintf(text, sizeof text,
                  "PAST the stable step's bound from the frame at t = %.3f s (%llu element "
                  "evaluations past it); %s",
                  static_cast<double>(first_frame < 0 ? 0 : first_frame) * period,
                  static_cast<unsigned long long>(s.geometry_bound), kGeometryBoundMeaning);
  }
  return text;
}

// The bound as a JSON object: {"elements", "evaluations", "first_frame", "first_time_s"}
// (first_frame -1 and first_time_s null when it held).
template <Sizes S>
std::string geometry_bound_json(const Model<S>& m, const State<S>& s, std::int64_t first_frame,
                                double period) {
  char t[40] = "null";
  if (first_frame >= 0)
    std::snprintf(t, sizeof t, "%.9g", static_cast<double>(first_frame) * period);
  return "{\"elements\": " + std::to_string(bounded_elements(m)) +
         ", \"evaluations\": " + std::to_string(s.geometry_bound) +
         ", \"first_frame\": " + std::to_string(first_frame) + ", \"first_time_s\": " + t + "}";
}

}  // namespace ntn::hil
