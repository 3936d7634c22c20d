// ntn-model: validates and inspects a model file.
//   ntn-model check MODEL.toml   errors as file:line:column (exit 1), or "ok" (exit 0)
//   ntn-model info MODEL.toml    sizes, masses, hinges, time step (and with penalty), CFL, memory
// Notes (mechanisms: DOFs without mass or stiffness, held at zero) go to stderr with exit 0.
// Exit 2 on a usage error (also a model file that cannot be read: missing, a directory).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

#include "ntn/modelc/load_model.hpp"
#include "ntn/modelc/model_report.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Validate and inspect an ntn-rt model file (TOML)"};
  app.require_subcommand(1);
  std::string check_path, info_path;
  CLI::App* check = app.add_subcommand("check", "validate a model; print its errors");
  check->add_option("model", check_path, "model file (.toml)")->required();
  CLI::App* info = app.add_subcommand("info", "print sizes, masses, time step and memory");
  info->add_option("model", info_path, "model file (.toml)")->required();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (argc > 1 && argv[1][0] != '-' && std::string(argv[1]) != "check" &&
        std::string(argv[1]) != "info") {
      std::fprintf(stderr, "ntn-model: unknown command '%s' (give check or info)\n", argv[1]);
      return 2;
    }
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  const std::string& path = check->parsed() ? check_path : info_path;
  const ntn::modelc::LoadResult r = ntn::modelc::load_model(path);
  if (!r.ok()) {
    std::fputs(ntn::modelc::format_all(r.errors).c_str(), stderr);
    if (r.unreadable) return 2;  // a usage error: no model to judge
    std::fprintf(stderr, "%zu error%s\n", r.error_count, r.error_count == 1 ? "" : "s");
    return 1;
  }
  // Notes (mechanisms held at zero) go to stderr, like a compiler's; `info` lists them too.
  std::fputs(ntn::modelc::format_all(r.notes).c_str(), stderr);
  if (check->parsed()) {
    std::printf("%s: ok (%zu nodes, %zu elements, dt = %.6g s)\n", path.c_str(),
                r.model->nodes.size(), r.model->elements.size(), r.model->settings.dt);
  } else {
    std::fputs(ntn::modelc::info_text(*r.model).c_str(), stdout);
  }
  return 0;
}
