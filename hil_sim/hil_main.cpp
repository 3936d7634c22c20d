// ntn-hil-<model>: the model compiled in (NTN_MODEL_HEADER, static storage) in the fixed-rate
// frame loop (DESIGN §8): hil_driver.hpp, the program ntn-hil MODEL.toml runs too.
#include <string>

#include "hil_driver.hpp"
#include NTN_MODEL_HEADER

#include "ntn/hil/compiled_model_info.hpp"  // after the model header

namespace {

namespace mdl = NTN_MODEL_NS;
constexpr ntn::Sizes kS = mdl::kSizes;

ntn::Model<kS> g_model;
ntn::InitWorkspace<kS> g_init_work;  // what init() works in (static: no heap, little stack)
ntn::State<kS> g_state;
ntn::Scratch<kS> g_scratch;
ntn::State<kS> g_checkpoint;    // the end of the last good frame (the loop's safe state)
ntn::TeamWork<kS> g_team_work;  // the multi-core step's partition and end forces (--threads)

int hil_main(int argc, char** argv) {
  ntn::hil::program::HilOptions options;
  if (const auto code = ntn::hil::program::parse_args(
          argc, argv, "Run the model '" + std::string(mdl::kName) + "' in the real-time frame loop",
          false, options))
    return *code;
  return ntn::hil::program::hil_execute<kS>(
      options, compiled_model_info(), mdl::kSpec,
      {g_model, g_init_work, g_state, g_scratch, g_checkpoint, g_team_work});
}

}  // namespace

int main(int argc, char** argv) {
  return ntn::cli::guarded_main(hil_main, argc, argv);
}
