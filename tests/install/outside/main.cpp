// The outside project's program (and, built in the ntn-rt tree, install_inside): the model of
// NTN_MODEL_HEADER from its initial state, 4 000 steps with its inputs at zero, every output
// channel written every 400 steps as hexadecimal floats, so that two builds print the same text
// only if they compute the same bits.
#include <array>
#include <cstdio>

#include NTN_MODEL_HEADER
#include "ntn/kernel.hpp"

namespace {

namespace model_file = NTN_MODEL_NS;
constexpr ntn::Sizes kSizes = model_file::kSizes;
ntn::Model<kSizes> model;  // static: the kernel's arrays are too large for a stack
ntn::InitWorkspace<kSizes> workspace;
ntn::State<kSizes> state;
ntn::Scratch<kSizes> scratch;

}  // namespace

int main() {
  const ntn::InitStatus init = ntn::init(model_file::kSpec, model, workspace);
  if (!init.ok()) {
    std::printf("init failed: %s at %d\n", ntn::to_string(init.error), init.where);
    return 1;
  }
  ntn::initial_state(model, state);  // u0, v0 of the model file (the cantilever: at rest)
  const std::array<double, kSizes.inputs> inputs{};
  if (ntn::start(model, state, scratch, inputs) != ntn::StepStatus::kOk) return 1;
  std::printf("model %s, dt %a s, channels", model_file::kName.data(),
              model_file::kSpec.settings.dt);
  for (const auto& name : model_file::kOutputNames)
    std::printf(" %.*s", static_cast<int>(name.size()), name.data());
  std::printf("\n");
  for (int n = 1; n <= 4000; ++n) {
    if (ntn::step(model, state, scratch, inputs) != ntn::StepStatus::kOk) {
      std::printf("step %d failed\n", n);
      return 1;
    }
    if (n % 400 == 0) {
      std::printf("%d", n);
      for (const double y : scratch.outputs)
        std::printf(" %a", y);
      std::printf("\n");
    }
  }
  return 0;
}
