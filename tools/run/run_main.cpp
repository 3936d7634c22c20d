// ntn-run-<model>: runs one compiled model on recorded inputs as fast as possible and writes
// the response as CSV with a one-screen summary. The model comes from the header that
// ntn_add_model() generated (NTN_MODEL_HEADER, namespace NTN_MODEL_NS).
//
// The run is the real-time loop's (hil_sim: ntn::hil::run_loop on the virtual clock, the record
// source, the CSV sink and the output hash), so that for the same --sampling this program and
// `ntn-hil-<model> run --clock virtual` compute the same steps, hash and CSV. What differs from
// ntn-hil: the length is ceil(duration / dt) kernel steps (the last frame may be cut short), the
// inputs are fed at every kernel step by default (--sampling step), every record sample is
// checked against the input's range before the run, no kinetic energy limit (a run is diverged
// when its state is no longer finite) and the run ends at the frame that diverged.
#include <string>

#include "run_driver.hpp"
#include NTN_MODEL_HEADER

#include "ntn/hil/compiled_model_info.hpp"  // after the model header

namespace {

namespace mdl = NTN_MODEL_NS;
constexpr ntn::Sizes kS = mdl::kSizes;

// Static storage: the kernel never allocates, and large models do not fit on the stack.
ntn::Model<kS> g_model;
ntn::InitWorkspace<kS> g_init_work;  // what init() works in (static: no heap, little stack)
ntn::State<kS> g_state;
ntn::Scratch<kS> g_scratch;
ntn::TeamWork<kS> g_team_work;  // the multi-core step's partition and end forces (--threads)

}  // namespace

int main(int argc, char** argv) {
  ntn::cli::App app{"Run the model '" + std::string(mdl::kName) + "' (" +
                    std::string(mdl::kSourceFile) + ") on recorded inputs"};
  ntn::run::RunOptions options;
  ntn::run::add_options(app, options);
  if (const auto code = ntn::cli::parse(app, argc, argv)) return *code;
  return ntn::run::run_model<kS>(options, compiled_model_info(), mdl::kSpec,
                                 {g_model, g_init_work, g_state, g_scratch, g_team_work});
}
