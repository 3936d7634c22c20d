// The reader's parts of hinges: one direction's behaviour, a member-end release, and hinge
// (or support) axes with their check (orthonormal and right-handed).
#pragma once

#include <toml++/toml.h>
#include <array>
#include <optional>
#include <string>

#include "source_model.hpp"
#include "toml_reader.hpp"

namespace ntn::modelc::compile {

// One hinge direction: "rigid", "free", { linear = k, dashpot = c }, { curve = "id" },
// { plastic = k, yield = F, ... } or { backbone = [B, C, D, E], rule = "...", ... }.
std::optional<BehaviourIn> read_behaviour(Reader& L, const toml::node& n, const std::string& key);

// release_start / release_end: an array of DOF names (those free, the rest rigid), or a table
// of behaviours per direction (those not named rigid).
std::optional<Release> read_release(Reader& L, const toml::node& n, const std::string& key);

// Hinge axes: rows x, y, z in global axes, orthonormal and right-handed to 1e-9.
std::optional<std::array<double, 9>> read_axes(Reader& L, const toml::node& n,
                                               const std::string& key);

}  // namespace ntn::modelc::compile
