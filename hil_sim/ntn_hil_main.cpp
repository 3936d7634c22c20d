// ntn-hil run MODEL.toml ... / ntn-hil replay MODEL.toml LOG: a model file in the fixed-rate
// frame loop without a compile step. The file is loaded (the model compiler's checks, errors as
// file:line:column, exit 1) into run-time storage: one block, allocated and bound before init,
// so that nothing is allocated in the loop. The program is ntn-hil-<model>'s (hil_driver.hpp): for
// the same options the two give the same bits.
#include "hil_driver.hpp"
#include "ntn/hil/loaded_model.hpp"

namespace {

int hil_main(int argc, char** argv) {
  ntn::hil::program::HilOptions options;
  if (const auto code = ntn::hil::program::parse_args(
          argc, argv, "Run a model file (TOML) in the real-time frame loop", true, options))
    return *code;
  int code = 0;
  const auto m = ntn::hil::load_or_report(options.model_path,
                                          {.team = options.threads > 1, .checkpoint = true},
                                          "ntn-hil", options.quiet, code);
  if (!m) return code;
  return ntn::hil::program::hil_execute<ntn::kRunTime>(
      options, m->info(), m->spec(),
      {m->model(), m->init_work(), m->state(), m->scratch(), m->checkpoint(), m->team_work(),
       &m->loop_buffers()});
}

}  // namespace

// No exception may end the program unreported (as ntn-hil-<model>): exit 2.
int main(int argc, char** argv) {
  return ntn::cli::guarded_main(hil_main, argc, argv);
}
