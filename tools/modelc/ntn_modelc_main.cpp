// ntn-modelc MODEL.toml -o OUT.hpp [--name NAME]: validates a model file and writes its
// constexpr header. Exit 0 on success, 1 when the model has errors (printed to stderr as
// file:line:column: error: ...), 2 on a usage error (also a model file that cannot be read, or
// an output that cannot be written, checked before the model is read). Notes (file:line:column:
// note: ...) go to stderr and do not change the exit code.
#include <cstdio>
#include <string>

#include "cli.hpp"  // tools/io: output_path_problem
#include "ntn/modelc/emit_header.hpp"
#include "ntn/modelc/load_model.hpp"

int main(int argc, char** argv) {
  ntn::cli::App app{"Compile an ntn-rt model file (TOML) into a C++ header of constexpr data"};
  std::string model_path, out_path, ns_name;
  app.add_option("model", model_path, "model file (.toml)")->required();
  app.add_option("-o,--output", out_path, "header to write")->required();
  app.add_option("-n,--name", ns_name,
                 "namespace: ntn::models::NAME (default: the model's [model] name)");
  if (const auto code = ntn::cli::parse(app, argc, argv)) return *code;
  if (app.count("--name") > 0 && !ntn::modelc::is_cpp_identifier(ns_name)) {
    std::fprintf(stderr, "ntn-modelc: --name '%s' is not a C++ identifier\n", ns_name.c_str());
    return 2;
  }
  // The output before any work: not a directory, its directory made (a build step writes into
  // the build tree) and the file writable.
  if (const auto problem = ntn::cli::output_path_problem(out_path, "--output", true)) {
    std::fprintf(stderr, "ntn-modelc: %s\n", problem->c_str());
    return 2;
  }

  const ntn::modelc::LoadResult r = ntn::modelc::load_model(model_path);
  if (!r.ok()) {
    std::fputs(ntn::modelc::format_all(r.errors).c_str(), stderr);
    if (r.unreadable) return 2;  // a usage error: no model to judge
    std::fprintf(stderr, "ntn-modelc: %zu error%s in %s; no header written\n", r.error_count,
                 r.error_count == 1 ? "" : "s", model_path.c_str());
    return 1;
  }
  std::fputs(ntn::modelc::format_all(r.notes).c_str(), stderr);  // mechanisms: not errors
  std::string text;
  try {
    text = ntn::modelc::emit_header(*r.model, ns_name);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ntn-modelc: %s\n", e.what());
    return 1;
  }
  // Beside the target, then renamed (a reader never sees half a header); a device is written
  // into, never replaced.
  if (const auto problem = ntn::cli::write_output_file(out_path, text, "--output")) {
    std::fprintf(stderr, "ntn-modelc: %s\n", problem->c_str());
    return 2;
  }
  return 0;
}
