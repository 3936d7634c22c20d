// ntn-modelc MODEL.toml -o OUT.hpp [--name NAME]: validates a model file and writes its
// constexpr header. Exit 0 on success, 1 when the model has errors (printed to stderr as
// file:line:column: error: ...), 2 on a usage error. Notes (file:line:column: note: ...) go to
// stderr and do not change the exit code.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "ntn/modelc/emit_header.hpp"
#include "ntn/modelc/load_model.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Compile an ntn-rt model file (TOML) into a C++ header of constexpr data"};
  std::string model_path, out_path, ns_name;
  app.add_option("model", model_path, "model file (.toml)")->required();
  app.add_option("-o,--output", out_path, "header to write")->required();
  app.add_option("-n,--name", ns_name,
                 "namespace: ntn::models::NAME (default: the model's [model] name)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  if (!ns_name.empty() && !ntn::modelc::is_cpp_identifier(ns_name)) {
    std::fprintf(stderr, "ntn-modelc: --name '%s' is not a C++ identifier\n", ns_name.c_str());
    return 2;
  }

  const ntn::modelc::LoadResult r = ntn::modelc::load_model(model_path);
  if (!r.ok()) {
    std::fputs(ntn::modelc::format_all(r.errors).c_str(), stderr);
    std::fprintf(stderr, "ntn-modelc: %zu error%s in %s; no header written\n", r.errors.size(),
                 r.errors.size() == 1 ? "" : "s", model_path.c_str());
    return 1;
  }
  std::fputs(ntn::modelc::format_all(r.notes).c_str(), stderr);  // mechanisms: not errors
  try {
    const std::string text = ntn::modelc::emit_header(*r.model, ns_name);
    const std::filesystem::path out(out_path);
    if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
    // Write beside the target, then rename: a reader never sees half a header.
    const std::filesystem::path tmp = out.string() + ".tmp";
    {
      std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
      f << text;
      if (!f.flush()) {
        std::fprintf(stderr, "ntn-modelc: cannot write %s\n", tmp.c_str());
        return 1;
      }
    }
    std::filesystem::rename(tmp, out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ntn-modelc: %s\n", e.what());
    return 1;
  }
  return 0;
}
