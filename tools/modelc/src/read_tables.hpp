// The reader's table readers (read_model.cpp runs them, in the order of its kTableReaders): each
// reads one table of an array of tables ([[materials]], ...) at `path`, checks its keys, types
// and values on their own, and appends what it read to the model; errors go to L.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "source_model.hpp"
#include "toml_reader.hpp"

namespace ntn::modelc::compile {

// `geometry` of [model] and [[members]], in the order of ntn::Geometry's first values.
inline const std::vector<std::string_view> kGeometries = {"linear", "p_delta", "corotational"};
inline constexpr Geometry kGeometryOf[] = {Geometry::kLinear, Geometry::kPDelta,
                                           Geometry::kCorotational};

// read_structure.cpp
void read_material(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p);
void read_section(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p);
void read_node(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p);
void read_member(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p);
void read_leaning_column(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p);
void read_support(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p);
void read_point_mass(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p);
void read_curve(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p);
void read_hinge(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p);

// read_loads.cpp
void read_time_function(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p);
void read_load(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p);
void read_member_load(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p);

// read_channels.cpp
void read_input(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p);
void read_output(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p);

}  // namespace ntn::modelc::compile
