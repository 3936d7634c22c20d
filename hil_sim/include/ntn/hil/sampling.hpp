// How a run feeds its inputs to the kernel: one option, `--sampling`, shared by ntn-run-<model>
// and ntn-hil-<model> (hil_sim/README.md "Input sampling"). A frame is N kernel steps of dt
// (period T = N dt); outputs are per frame in every mode.
//   step         the record at every kernel step, t_n = n dt (linear between its samples): the
//                finest reading of a record; only a file source can do it (a packet carries one
//                value per frame). ntn-run's default.
//   hold         the input at frame times t_k = k T, held over the frame's N steps: what a DAQ
//                sending one value per frame gives. ntn-hil's default.
//   interpolate  linear from frame k-1's value to frame k's over frame k's steps (one frame of
//                delay, since the next value is not known yet).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace ntn::hil {

enum class InputSampling : std::uint8_t { kStep, kFrameHeld, kFrameInterpolated };

// The option's words: "step", "hold", "interpolate".
constexpr const char* to_string(InputSampling s) {
  switch (s) {
    case InputSampling::kStep:
      return "step";
    case InputSampling::kFrameHeld:
      return "hold";
    case InputSampling::kFrameInterpolated:
      return "interpolate";
  }
  return "?";
}

constexpr std::optional<InputSampling> parse_sampling(std::string_view word) {
  for (const InputSampling s :
       {InputSampling::kStep, InputSampling::kFrameHeld, InputSampling::kFrameInterpolated}) {
    if (word == to_string(s)) return s;
  }
  return std::nullopt;
}

}  // namespace ntn::hil
