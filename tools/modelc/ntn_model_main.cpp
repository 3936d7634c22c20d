// ntn-model: validates and inspects a model file.
//   ntn-model check MODEL.toml   errors as file:line:column (exit 1), or "ok" (exit 0)
//   ntn-model info MODEL.toml    sizes, masses, hinges, time step (and with penalty), CFL, memory
//   ntn-model modes MODEL.toml [-n N] [--json]
//                                the N lowest modes with supports and rigid hinge directions tied
//                                exactly: Hz, period, effective mass % in x, y, z (and cumulative),
//                                each hinge direction as tied, spring or free (README.md)
// Notes (mechanisms: DOFs without mass or stiffness, held at zero) go to stderr with exit 0.
// Exit 1: the model has errors (modes: or its modal analysis fails). Exit 2 on a usage error
// (also a model file that cannot be read: missing, a directory; a bad -n).
#include <cstdio>
#include <limits>
#include <string>

#include "cli.hpp"  // tools/io: validators that refuse 1.5, nan and out-of-range counts
#include "ntn/modelc/load_model.hpp"
#include "ntn/modelc/model_report.hpp"
#include "ntn/modelc/modes_report.hpp"

namespace {

// Above this many DOFs (ntn::modal's dense limit) the sparse eigensolver keeps 2 N + 1 vectors of
// the model's length: `modes` then asks for at most kMaxSparseModes modes.
constexpr int kDenseDofs = 3000;
constexpr int kMaxSparseModes = 500;

}  // namespace

int main(int argc, char** argv) {
  ntn::cli::App app{"Validate and inspect an ntn-rt model file (TOML)"};
  app.require_subcommand(1);
  std::string check_path, info_path, modes_path;
  int modes_count = 12;
  bool modes_json = false;
  ntn::cli::App* check = app.add_subcommand("check", "validate a model; print its errors");
  check->add_option("model", check_path, "model file (.toml)")->required();
  ntn::cli::App* info = app.add_subcommand("info", "print sizes, masses, time step and memory");
  info->add_option("model", info_path, "model file (.toml)")->required();
  ntn::cli::App* modes = app.add_subcommand(
      "modes",
      "print the lowest modes with the hinges applied exactly (Hz, period, effective mass)");
  modes->add_option("model", modes_path, "model file (.toml)")->required();
  modes
      ->add_option("-n,--modes", modes_count,
                   "number of lowest modes (all when the model has fewer)")
      ->check(ntn::cli::Integer(1, std::numeric_limits<int>::max()))
      ->capture_default_str();
  modes->add_flag("--json", modes_json,
                  "print JSON (schema ntn-model-modes/2) instead of the table");
  // A first word that is neither an option nor a command: say so (CLI11 would speak of an
  // extra argument).
  if (argc > 1 && argv[1][0] != '-' && std::string(argv[1]) != "check" &&
      std::string(argv[1]) != "info" && std::string(argv[1]) != "modes") {
    std::fprintf(stderr, "ntn-model: unknown command '%s' (give check, info or modes)\n", argv[1]);
    return 2;
  }
  if (const auto code = ntn::cli::parse(app, argc, argv)) return *code;

  const std::string& path =
      check->parsed() ? check_path : (info->parsed() ? info_path : modes_path);
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
  } else if (info->parsed()) {
    std::fputs(ntn::modelc::info_text(*r.model).c_str(), stdout);
  } else {
    const std::size_t dofs = 6 * r.model->nodes.size();
    if (dofs > kDenseDofs && modes_count > kMaxSparseModes) {
      std::fprintf(stderr,
                   "ntn-model modes: -n %d: a model of %zu DOFs gives at most %d modes (above %d "
                   "DOFs the sparse eigensolver keeps 2 N + 1 vectors of that length)\n",
                   modes_count, dofs, kMaxSparseModes, kDenseDofs);
      return 2;
    }
    const ntn::modelc::ModesReport rep = ntn::modelc::modes_report(*r.model, modes_count);
    if (!rep.result.ok()) {
      std::fprintf(stderr, "ntn-model modes: %s: modal analysis failed: %s\n", path.c_str(),
                   rep.result.error.c_str());
      return 1;
    }
    const std::string out =
        modes_json ? ntn::modelc::modes_json(rep) : ntn::modelc::modes_text(rep);
    std::fputs(out.c_str(), stdout);
  }
  return 0;
}
