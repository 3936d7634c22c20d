// Runs the model compiler's layers one at a time (tools/modelc/src/compile.hpp): the reader on
// a text, then the stages a test names, so that each stage's test sees what it makes and
// reports, not the whole compiler's verdict.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "compile.hpp"
#include "diagnostic_sink.hpp"
#include "read_model.hpp"

namespace ntn::modelc::compile::testing {

// A small valid model: a 3 m column of 3 elements, fixed at its base (node 1 at the origin,
// node 2 at z = 3). Tests append tables to it.
inline constexpr std::string_view kColumn = R"([model]
name = "m"

[[materials]]
id = "steel"
E = 2.1e11
nu = 0.3
rho = 7850

[[sections]]
id = "s"
A = 1e-2
Iy = 1e-5
Iz = 2e-5
J = 1e-5

[[nodes]]
id = 1
xyz = [0, 0, 0]

[[nodes]]
id = 2
xyz = [0, 0, 3]

[[members]]
id = "C"
nodes = [1, 2]
material = "steel"
section = "s"
divisions = 3

[[supports]]
node = 1
fix = "all"
)";

class Staged {
 public:
  explicit Staged(std::string text) : text_(std::move(text)), sink_("m.toml") {
    source_ = read_model_text(sink_, text_, "m.toml");
    if (source_) {
      comp_ = std::make_unique<Compilation>(sink_, *source_);
      start_description(*comp_, "m.toml");
    }
  }
  bool read() const { return source_.has_value(); }
  const SourceModel& source() const { return *source_; }
  Compilation& comp() { return *comp_; }
  ModelDescription& d() { return comp_->d; }
  DiagnosticSink& sink() { return sink_; }
  // The stages that make the description (everything before the checks).
  void describe() {
    resolve_ids(*comp_);
    collect_member_points(*comp_);
    mesh_members(*comp_);
    add_hinges(*comp_);
    add_supports(*comp_);
    add_point_masses(*comp_);
    hold_out_of_plane(*comp_);
    add_loads(*comp_);
    add_member_loads(*comp_);
    add_channels(*comp_);
    add_initial_values(*comp_);
  }
  // Every error so far, one formatted line each ("m.toml:L:C: error: key 'K': message").
  std::string errors() { return format_all(sink_.take_errors()); }
  std::string notes() { return format_all(sink_.take_notes()); }

 private:
  std::string text_;
  DiagnosticSink sink_;
  std::optional<SourceModel> source_;
  std::unique_ptr<Compilation> comp_;
};

inline std::string column(std::string_view more) {
  return std::string(kColumn) + "\n" + std::string(more);
}

}  // namespace ntn::modelc::compile::testing
