// Writes a ModelDescription as a C++ header of constexpr data (ntn::ModelSpec<kSizes> kSpec).
#pragma once

#include <string>

#include "ntn/modelc/model_description.hpp"

namespace ntn::modelc {

// The header text. Namespace ntn::models::<ns_name> (default: the model's own name). Doubles
// are printed with %.17g so that they read back bit for bit. Throws std::invalid_argument for a
// non-finite number or a namespace name that is not a C++ identifier (load_model never produces
// either).
std::string emit_header(const ModelDescription& model, const std::string& ns_name = {});

// True for [A-Za-z_][A-Za-z0-9_]* that is not a C++ keyword.
bool is_cpp_identifier(const std::string& s);

}  // namespace ntn::modelc
