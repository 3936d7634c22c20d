// ntn-run MODEL.toml: runs a model file on recorded inputs, with no compile step. The model
// compiler's checks run when the file is loaded (errors as file:line:column, exit 1); the model
// goes into run-time storage (one block, allocated before init) and runs the compiled runners'
// code (run_driver.hpp) on the same kernel code: ntn-run config/frame3d.toml and ntn-run-frame3d
// give the same bits for the same options.
#include <cstdio>
#include <string>

#include "ntn/hil/loaded_model.hpp"
#include "run_driver.hpp"

int main(int argc, char** argv) {
  ntn::cli::App app{"Run a model file (TOML) on recorded inputs, without compiling it"};
  std::string model_path;
  app.add_option("model", model_path, "model file (.toml)")->required();
  ntn::run::RunOptions options;
  ntn::run::add_options(app, options);
  if (const auto code = ntn::cli::parse(app, argc, argv)) return *code;
  int code = 0;
  const auto m = ntn::hil::load_or_report(model_path, {.team = options.threads > 1}, "ntn-run",
                                          options.quiet, code);
  if (!m) return code;
  // run_model() runs init() into the bound storage, as the compiled runners do.
  return ntn::run::run_model<ntn::kRunTime>(
      options, m->info(), m->spec(),
      {m->model(), m->init_work(), m->state(), m->scratch(), m->team_work(), &m->loop_buffers()});
}
