// The plastic hinge directions that yielded in a run, for the run and loop summaries:
// from the final State (its history: plastic deformation now and at its peak, energy dissipated)
// and the model's acceptance limits (the performance level, ntn::performance_level).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ntn/hysteresis.hpp"
#include "ntn/model.hpp"
#include "ntn/state.hpp"

namespace ntn::hil {

struct YieldedDirection {
  int hinge = 0;
  int direction = 0;        // local 0..5 (ux .. rz)
  double peak = 0;          // m or rad, the largest |d_p|
  double residual = 0;      // m or rad, d_p at the end (the permanent deformation)
  double dissipated = 0;    // J
  int level = 0;            // 0..4 (performance_level)
  bool has_limits = false;  // the law has IO, LS, CP limits
  double first_slip = -1;   // s: when a rigid-plastic direction first slid (-1: never)
  bool failed = false;      // a brittle (`failure`) direction that broke (at first_slip)
};

// "ux" ... "rz": a hinge direction's name.
inline const char* direction_name(int direction) {
  static const char* const kNames[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  return direction >= 0 && direction < 6 ? kNames[direction] : "?";
}

// Every plastic direction whose plastic deformation is not zero (a rigid-plastic one: that has
// slid), in hinge then direction order.
template <Sizes S>
std::vector<YieldedDirection> yielded_directions(const Model<S>& m, const State<S>& s) {
  std::vector<YieldedDirection> out;
  if constexpr (kMayHaveHystereses<S>) {
    for (std::size_t h = 0; h < m.sizes.hinges; ++h) {
      const HingeData& hd = m.hinges[h];
      for (std::size_t k = 0; k < kDofsPerNode; ++k) {
        if (!(((hd.plastic | hd.slip) >> k) & 1U)) continue;
        const auto slot = static_cast<std::size_t>(hd.history[k]);
        if (!(s.plastic_peak[slot] > 0)) continue;
        const std::int64_t first = s.first_slip[slot];
        out.push_back({static_cast<int>(h), static_cast<int>(k), s.plastic_peak[slot],
                       s.plastic[slot], s.dissipated[slot],
                       performance_level(m.hystereses[slot].limits, s.plastic_peak[slot]),
                       m.hystereses[slot].limits[0] > 0,
                       first > 0 ? static_cast<double>(first - 1) * m.dt : -1.0,
                       first > 0 && law_breaks(m.hystereses[slot].rule)});
      }
    }
  }
  return out;
}

// "elastic", "IO", "LS", "CP", "beyond CP" (no limits: "yielded" for level 1).
inline const char* level_name(int level, bool has_limits) {
  static const char* const kNames[5] = {"elastic", "IO", "LS", "CP", "beyond CP"};
  if (level == 1 && !has_limits) return "yielded";
  return level >= 0 && level <= 4 ? kNames[level] : "?";
}

template <Sizes S>
int plastic_directions(const Model<S>& m) {
  int n = 0;
  if constexpr (kMayHaveHinges<S>) {
    for (const HingeData& h : m.hinges) {
      for (std::size_t k = 0; k < kDofsPerNode; ++k)
        n += ((h.plastic | h.slip) >> k) & 1U;
    }
  }
  return n;
}

}  // namespace ntn::hil
