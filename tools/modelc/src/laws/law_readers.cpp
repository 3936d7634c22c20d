// The table of the hysteretic laws' readers, and what they share.
#include <string>

#include "../messages.hpp"
#include "law_reader.hpp"

namespace ntn::modelc::compile {

std::span<const LawReader> law_readers() {
  static const LawReader kReaders[] = {
      {"backbone",
       kBackboneKeys,
       {},
       read_backbone,
       "{ backbone = [B, C, D, E], rule = \"kinematic\" }"},
      {"imk", kImkKeys, kImkSharedKeys, read_imk,
       "{ imk = k, yield = F, pre_capping = theta_p, post_capping = theta_pc, ultimate = "
       "theta_u, capping_ratio = Fc/Fy, ... }"},
  };
  return kReaders;
}

bool no_dashpot(Reader& L, Table& tb, std::string_view what, std::string_view why) {
  if (!tb.has("dashpot")) return true;
  L.error(tb.where("dashpot"),
          std::string(what) + " direction takes no dashpot: " + std::string(why));
  return false;
}

// Acceptance criteria io, ls, cp on the peak plastic deformation: all three or none,
// io <= ls <= cp. False (reported) when they are not.
bool read_limits(Reader& L, Table& tb, const toml::table& t, std::array<double, 3>& limits) {
  const char* const kLimit[3] = {"io", "ls", "cp"};
  const int given = static_cast<int>(tb.has("io")) + static_cast<int>(tb.has("ls")) +
                    static_cast<int>(tb.has("cp"));
  limits = {};
  bool ok = true;
  if (given > 0 && given < 3) {
    for (const char* l : kLimit) {
      if (!tb.has(l)) {
        L.error(t.source(), tb.key(l),
                "missing: give all three acceptance limits io, ls and cp, or none");
        ok = false;
      }
    }
  } else if (given == 3) {
    for (std::size_t i = 0; i < 3; ++i) {
      const auto v = tb.positive(kLimit[i], Need::kRequired);
      if (!v) {
        ok = false;
      } else {
        limits[i] = *v;
      }
    }
    for (std::size_t i = 1; i < 3 && ok; ++i) {
      if (limits[i] < limits[i - 1]) {
        L.error(tb.where(kLimit[i]), std::string(kLimit[i]) + " = " + num(limits[i]) +
                                         " is below " + kLimit[i - 1] + " = " + num(limits[i - 1]) +
                                         ": the limits must not decrease (io <= ls <= cp)");
        ok = false;
      }
    }
  }
  return ok;
}

}  // namespace ntn::modelc::compile
