#include "ntn/hil/faults.hpp"

#include <charconv>
#include <random>

namespace ntn::hil {
namespace {

constexpr std::array<const char*, kFaultKinds> kNames{
    "none", "nan", "inf", "range", "late", "lost", "duplicate", "reorder", "corrupt"};

bool needs_next(FaultKind k) {
  return k == FaultKind::kLate || k == FaultKind::kReorder;
}

// Whether `kind` fits at `frame` given what is taken; marks it if so.
bool place(std::vector<FaultKind>& at, std::vector<bool>& taken, FaultKind kind,
           std::int64_t frame) {
  const auto n = static_cast<std::int64_t>(at.size());
  const auto k = static_cast<std::size_t>(frame);
  if (frame < 0 || frame >= n || taken[k]) return false;
  if (needs_next(kind) && frame + 1 >= n) return false;
  if (kind == FaultKind::kReorder && taken[k + 1]) return false;
  at[k] = kind;
  taken[k] = true;
  if (kind == FaultKind::kReorder) taken[k + 1] = true;
  return true;
}

}  // namespace

const char* to_string(FaultKind kind) {
  return kNames[static_cast<std::size_t>(kind)];
}

std::optional<FaultKind> parse_fault_kind(std::string_view name) {
  for (FaultKind k : kAllFaults) {
    if (name == kNames[static_cast<std::size_t>(k)]) return k;
  }
  return std::nullopt;
}

std::string parse_fault_list(std::string_view text, std::vector<FaultAt>& out) {
  for (bool more = !text.empty(); more;) {
    const std::size_t comma = text.find(',');
    const std::string_view item = text.substr(0, comma);
    more = comma != std::string_view::npos;  // "a," has an empty (bad) second item
    text = more ? text.substr(comma + 1) : std::string_view{};
    const std::size_t at = item.find('@');
    if (at == std::string_view::npos) {
      return "fault '" + std::string(item) + "': expected KIND@FRAME";
    }
    const auto kind = parse_fault_kind(item.substr(0, at));
    if (!kind) {
      return "fault '" + std::string(item) +
             "': unknown kind (nan, inf, range, late, lost, duplicate, reorder, corrupt)";
    }
    const std::string_view num = item.substr(at + 1);
    std::int64_t frame = 0;
    const auto [end, ec] = std::from_chars(num.data(), num.data() + num.size(), frame);
    if (ec != std::errc{} || end != num.data() + num.size() || frame < 0) {
      return "fault '" + std::string(item) + "': FRAME must be a frame index >= 0";
    }
    out.push_back({*kind, frame});
  }
  return {};
}

std::string parse_fault_rate(std::string_view text, FaultRate& out) {
  const std::size_t eq = text.find('=');
  if (eq == std::string_view::npos) {
    return "fault rate '" + std::string(text) + "': expected KIND=P";
  }
  const auto kind = parse_fault_kind(text.substr(0, eq));
  if (!kind) return "fault rate '" + std::string(text) + "': unknown kind";
  const std::string_view num = text.substr(eq + 1);
  double p = -1;
  const auto [end, ec] = std::from_chars(num.data(), num.data() + num.size(), p);
  if (ec != std::errc{} || end != num.data() + num.size() || !(p >= 0 && p <= 1)) {
    return "fault rate '" + std::string(text) + "': P must be a probability in [0, 1]";
  }
  out = {*kind, p};
  return {};
}

std::string make_fault_plan(std::int64_t frames, std::span<const FaultAt> faults,
                            std::span<const FaultRate> rates, std::uint64_t seed, FaultPlan& out) {
  out = {};
  if (frames < 0) return "negative frame count";
  out.at.assign(static_cast<std::size_t>(frames), FaultKind::kNone);
  std::vector<bool> taken(static_cast<std::size_t>(frames), false);
  for (const FaultAt& f : faults) {
    if (!place(out.at, taken, f.kind, f.frame)) {
      return std::string("fault ") + to_string(f.kind) + "@" + std::to_string(f.frame) +
             ": frame outside the run, already has a fault" +
             (needs_next(f.kind) ? ", or has no next frame / a taken next frame" : "");
    }
    ++out.injected[static_cast<std::size_t>(f.kind)];
  }
  if (rates.empty()) return {};
  std::array<double, kFaultKinds> p{};
  for (const FaultRate& r : rates)
    p[static_cast<std::size_t>(r.kind)] = r.probability;
  std::mt19937_64 rng(seed);
  for (std::int64_t k = 0; k < frames; ++k) {
    for (FaultKind kind : kAllFaults) {
      const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;  // [0, 1), same everywhere
      if (u >= p[static_cast<std::size_t>(kind)]) continue;
      if (place(out.at, taken, kind, k)) {
        ++out.injected[static_cast<std::size_t>(kind)];
      } else {
        ++out.skipped[static_cast<std::size_t>(kind)];
      }
    }
  }
  return {};
}

std::uint64_t fault_hash(std::uint64_t seed, std::int64_t frame) {
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (static_cast<std::uint64_t>(frame) + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace ntn::hil
