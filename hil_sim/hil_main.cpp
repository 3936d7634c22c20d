// ntn-hil-<model>: the model compiled in (NTN_MODEL_HEADER, static storage) in the fixed-rate
// frame loop (DESIGN §8): hil_driver.hpp, the program ntn-hil MODEL.toml runs too.
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include "hil_driver.hpp"
#include NTN_MODEL_HEADER

namespace {

namespace mdl = NTN_MODEL_NS;
constexpr ntn::Sizes kS = mdl::kSizes;

ntn::Model<kS> g_model;
ntn::InitWorkspace<kS> g_init_work;  // what init() works in (static: no heap, little stack)
ntn::State<kS> g_state;
ntn::Scratch<kS> g_scratch;
ntn::State<kS> g_checkpoint;    // the end of the last good frame (the loop's safe state)
ntn::TeamWork<kS> g_team_work;  // the multi-core step's partition and end forces (--threads)

template <class A>
std::vector<std::string_view> names(const A& a) {
  return {a.begin(), a.end()};
}

int hil_main(int argc, char** argv) {
  ntn::hil::program::HilOptions options;
  if (const auto code = ntn::hil::program::parse_args(
          argc, argv, "Run the model '" + std::string(mdl::kName) + "' in the real-time frame loop",
          false, options))
    return *code;
  const ntn::hil::ModelInfo info{mdl::kName,
                                 mdl::kSourceFile,
                                 names(mdl::kInputNames),
                                 names(mdl::kOutputNames),
                                 names(mdl::kOutputUnits),
                                 {mdl::kAlarmLimits.begin(), mdl::kAlarmLimits.end()},
                                 {mdl::kAlarmHysteresis.begin(), mdl::kAlarmHysteresis.end()},
                                 names(mdl::kMemberNames),
                                 names(mdl::kHingeNames)};
  return ntn::hil::program::hil_execute<kS>(
      options, info, mdl::kSpec,
      {g_model, g_init_work, g_state, g_scratch, g_checkpoint, g_team_work});
}

}  // namespace

// No exception may end the program unreported: whatever is left (a std::bad_alloc, a
// filesystem error) is an error with exit 2. A backstop: the checks come first.
int main(int argc, char** argv) {
  try {
    return hil_main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}
