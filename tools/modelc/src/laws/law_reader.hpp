// The model compiler's companions of the kernel's hysteretic laws (ntn/laws/): each reads the
// TOML form of its law in a hinge direction's table and words the kernel's rule for it at the
// key that breaks it. One table lists them (law_readers.cpp); read_behaviour
// (read_hinge_parts.cpp) takes their keys and hands a direction to the one whose key it has.
#pragma once

#include <toml++/toml.h>
#include <array>
#include <optional>
#include <span>
#include <string_view>

#include "../source_model.hpp"
#include "../toml_reader.hpp"

namespace ntn::modelc::compile {

struct LawReader {
  std::string_view key;                      // the key that selects the law ("backbone", "imk")
  std::span<const std::string_view> own;     // the other keys only it takes
  std::span<const std::string_view> shared;  // keys it shares with `plastic` (yield, ...)
  // The direction's behaviour and law, or nullopt (reported).
  std::optional<BehaviourIn> (*read)(Reader& L, Table& tb, const toml::table& t, BehaviourIn b);
  const char* form;  // its form in the list of a direction's forms
};

// The readers, in the order read_behaviour tries them.
std::span<const LawReader> law_readers();

// Acceptance criteria io, ls, cp on the peak plastic deformation: all three or none,
// io <= ls <= cp. False (reported) when they are not.
bool read_limits(Reader& L, Table& tb, const toml::table& t, std::array<double, 3>& limits);

// A direction of this kind ("a friction direction") takes no dashpot, for `why`: false
// (reported at the dashpot) when it has one.
bool no_dashpot(Reader& L, Table& tb, std::string_view what, std::string_view why);

// The readers (one file each).
std::optional<BehaviourIn> read_backbone(Reader& L, Table& tb, const toml::table& t, BehaviourIn b);
std::optional<BehaviourIn> read_imk(Reader& L, Table& tb, const toml::table& t, BehaviourIn b);
extern const std::array<std::string_view, 2> kBackboneKeys;
extern const std::array<std::string_view, 8> kImkKeys;
extern const std::array<std::string_view, 2> kImkSharedKeys;

}  // namespace ntn::modelc::compile
