// Fault injection plans for the feeder (ntn-feeder --fault / --fault-rate). Not real-time code:
// a plan is built once, before the first frame.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace ntn::hil {

// What the feeder does to frame k's input packet. Expected effect on an InputGate whose frame k
// is processed after everything sent for k (lock-step, or real time with the loop's frame k half
// a period after the feeder's deadline k):
//   kNan, kInf  one value NaN / +-Inf               -> nonfinite +1 (held), packet accepted
//   kRange      one value = the range value (1e308)  -> out_of_range +1 (held), packet accepted
//   kLate       sent at frame k+1, before k+1's      -> missing +1, late +1 (late_for_missing +1)
//   kLost       never sent                           -> missing +1 (lost +1)
//   kDuplicate  sent twice                           -> duplicate +1
//   kReorder    k+1's packet sent first, then k's    -> early +1 (k+1), reordered +1 (k)
//               (frame k+1 then sends nothing more and carries no fault of its own)
//   kCorrupt    one byte flipped after the checksum  -> corrupt +1, missing +1 (lost +1)
// The value faults hit channel (k mod channels).
enum class FaultKind : std::uint8_t {
  kNone,
  kNan,
  kInf,
  kRange,
  kLate,
  kLost,
  kDuplicate,
  kReorder,
  kCorrupt,
};
inline constexpr int kFaultKinds = 9;
inline constexpr std::array<FaultKind, 8> kAllFaults{
    FaultKind::kNan,  FaultKind::kInf,       FaultKind::kRange,   FaultKind::kLate,
    FaultKind::kLost, FaultKind::kDuplicate, FaultKind::kReorder, FaultKind::kCorrupt};

const char* to_string(FaultKind kind);  // "nan", "inf", ... ("none")
std::optional<FaultKind> parse_fault_kind(std::string_view name);

struct FaultAt {
  FaultKind kind = FaultKind::kNone;
  std::int64_t frame = 0;
};
struct FaultRate {
  FaultKind kind = FaultKind::kNone;
  double probability = 0;  // per frame, in [0, 1]
};

// "nan@10,lost@20,..." (appends to out). "" on success, else the error message.
std::string parse_fault_list(std::string_view text, std::vector<FaultAt>& out);
// "late=0.01". "" on success, else the error message.
std::string parse_fault_rate(std::string_view text, FaultRate& out);

struct FaultPlan {
  std::vector<FaultKind> at;                          // per frame
  std::array<std::uint64_t, kFaultKinds> injected{};  // by FaultKind
  std::array<std::uint64_t, kFaultKinds> skipped{};   // rate draws that hit a taken frame

  FaultKind operator[](std::int64_t frame) const {
    return frame >= 0 && frame < static_cast<std::int64_t>(at.size())
               ? at[static_cast<std::size_t>(frame)]
               : FaultKind::kNone;
  }
  std::uint64_t count(FaultKind k) const { return injected[static_cast<std::size_t>(k)]; }
};

// At most one fault per frame; kLate and kReorder need a frame k+1, and kReorder takes frame k+1
// too. Explicit faults are placed first: a conflict among them (or a frame outside [0, frames))
// is an error. Then, frame by frame, each rate draws once per kind in kAllFaults order from an
// mt19937_64 seeded with `seed` (so the draws do not depend on what was placed); a hit on a taken
// frame is counted in `skipped`. "" on success, else the error message.
std::string make_fault_plan(std::int64_t frames, std::span<const FaultAt> faults,
                            std::span<const FaultRate> rates, std::uint64_t seed, FaultPlan& out);

// A deterministic 64-bit hash of (seed, frame) (splitmix64), for per-frame choices such as the
// corrupted byte.
std::uint64_t fault_hash(std::uint64_t seed, std::int64_t frame);

}  // namespace ntn::hil
