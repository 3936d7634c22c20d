// The reader, the compiler's first layer: model text -> SourceModel, the model as the file
// describes it with the place of every value (source_model.hpp). Size and nesting limits first
// (ntn/modelc/limits.hpp), then the TOML parser, then every table's keys, types and values.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "diagnostic_sink.hpp"
#include "source_model.hpp"

namespace ntn::modelc::compile {

// The model read from `text` (`file` names it in messages), or nullopt when the sink has errors
// (every problem of every table is reported, not only the first).
std::optional<SourceModel> read_model_text(DiagnosticSink& sink, std::string_view text,
                                           const std::string& file);

}  // namespace ntn::modelc::compile
