// Model file (TOML) -> ModelDescription, in layers (tools/modelc/README.md):
//   1. the reader (read_model.cpp): text -> SourceModel, every value with its place: the size
//      and nesting limits, the TOML parser, then keys, types and values of every table;
//   2. the compile stages (compile.hpp, one file each): resolve ids, mesh the members, hinges and
//      supports, loads, channels; then the checks with the kernel's own functions (rigid
//      cycles, numbers beyond double, mass and mechanisms, hinge stiffness and curves) and the
//      time step.
// Every problem is collected in one DiagnosticSink (diagnostic_sink.hpp), each at its
// file:line:column; a layer runs only when the ones before it found nothing.
#include "ntn/modelc/load_model.hpp"

#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <new>
#include <optional>
#include <utility>

#include "compile.hpp"
#include "diagnostic_sink.hpp"
#include "ntn/modelc/limits.hpp"
#include "ntn/modelc/memory.hpp"
#include "read_model.hpp"

namespace ntn::modelc {
namespace {

// The compile stages' memory (memory.hpp), from the members' divisions: refused before the
// mesh is made. A member of 10^6 divisions is a few bytes of text.
std::optional<std::string> compile_memory_refusal(const compile::SourceModel& source) {
  std::uint64_t elements = 0;
  for (const compile::Member& m : source.members)
    elements += static_cast<std::uint64_t>(m.divisions);
  const std::uint64_t nodes = source.nodes.size(), members = source.members.size();
  const std::uint64_t needed = nodes * kCompileBytesPerNode + members * kCompileBytesPerMember +
                               elements * kCompileBytesPerElement;
  return memory_refusal("compiling the model", needed,
                        std::to_string(nodes) + " nodes, " + std::to_string(members) +
                            " members meshed into " + std::to_string(elements) + " elements");
}

LoadResult load_text(std::string_view text, const std::string& file) {
  compile::DiagnosticSink sink(file);
  LoadResult r;
  try {
    if (const auto source = compile::read_model_text(sink, text, file)) {
      if (auto refused = compile_memory_refusal(*source)) {
        sink.error_at_start("", std::move(*refused));
      } else {
        r.model = compile::compile_model(sink, *source, file);
      }
    }
  } catch (const std::bad_alloc&) {
    r.model.reset();
    sink.error_at_start("", "out of memory (" + format_bytes(available_memory().bytes) +
                                " was available when it ran out): the model is too large for "
                                "this machine or its memory limit");
  } catch (const std::exception& e) {
    r.model.reset();
    sink.error_at_start("", std::string("internal error: ") + e.what());
  }
  r.error_count = sink.error_count();
  r.errors = sink.take_errors();
  if (!r.errors.empty()) {
    r.model.reset();
  } else {
    r.notes = sink.take_notes();
  }
  return r;
}

}  // namespace

LoadResult load_model(const std::string& path) {
  auto unreadable = [&](const std::string& why) {
    LoadResult r;
    r.unreadable = true;
    r.errors.push_back({path, 1, 1, "", "cannot read the model file: " + why});
    r.error_count = 1;
    return r;
  };
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return unreadable("it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return unreadable(std::filesystem::exists(path, ec) ? "permission denied"
                                                        : "no such file (or a path through a "
                                                          "file that is not a directory)");
  }
  // At most one byte more than the limit: a huge file is refused without reading it all.
  std::string text;
  char buf[1 << 16];
  while (text.size() <= kMaxModelFileBytes && in.read(buf, sizeof buf).gcount() > 0)
    text.append(buf, static_cast<std::size_t>(in.gcount()));
  if (in.bad()) return unreadable("read error");
  return load_text(text, path);
}

LoadResult load_model_from_string(std::string_view toml_text, const std::string& source_name) {
  return load_text(toml_text, source_name);
}

}  // namespace ntn::modelc
