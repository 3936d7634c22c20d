// The kernel compiles and runs with -fno-exceptions -fno-rtti (DESIGN §2). Plain main(): the
// GoogleTest library is built with exceptions and RTTI. Returns non-zero on failure.
#if defined(__cpp_exceptions) || defined(__EXCEPTIONS)
#error "this target must be compiled with -fno-exceptions"
#endif
#if defined(__GXX_RTTI) || defined(__cpp_rtti)
#error "this target must be compiled with -fno-rtti"
#endif

#include <cmath>
#include <cstdio>

#include "ntn/kernel.hpp"
#include "support/builders.hpp"
#include "support/frames.hpp"
#include "support/no_heap.hpp"
#include "support/relaxation.hpp"

namespace {

int failures = 0;

void check(bool ok, const char* what) {
  std::printf("%s: %s\n", ok ? "ok  " : "FAIL", what);
  if (!ok) ++failures;
}

// A 4-element steel cantilever under a tip load, relaxed to rest: P L^3 / (3 E I), exact for
// cubic elements; tolerance 1e-6 (relaxation converged to 1e-10).
constexpr ntn::Sizes kBeam{.nodes = 5, .elements = 4, .loads = 1};
ntn::ModelSpec<kBeam> beam_spec;
ntn::Model<kBeam> beam_model;
ntn::InitWorkspace<kBeam> beam_init;
ntn::State<kBeam> beam_state;
ntn::Scratch<kBeam> beam_scratch;

// The portal frame with every load, input and output kind, for 5000 steps.
constexpr ntn::Sizes kFrame = ntn_test::kFeatureSizes;
ntn::ModelSpec<kFrame> frame_spec;
ntn::Model<kFrame> frame_model;
ntn::InitWorkspace<kFrame> frame_init;
ntn::State<kFrame> frame_state;
ntn::Scratch<kFrame> frame_scratch;

}  // namespace

int main() {
  const ntn_test::EigenNoMalloc guard;
  constexpr ntn_test::Section sec = ntn_test::rectangle(0.05, 0.02);
  const double L = 2.0, P = 100.0;
  ntn_test::straight_beam(beam_spec, L, ntn_test::kSteel, sec);
  beam_spec.loads[0] = {4, ntn::kUz, P, ntn::kConstant};
  beam_spec.settings.alpha = 2 * 26.2;  // ~ critical for the first mode (omega_1 = 26.2 rad/s)
  beam_spec.settings.dt = 0.9 * ntn::stable_time_step(ntn::view(beam_spec)).dt_stable;
  check(ntn::init(beam_spec, beam_model, beam_init).ok(), "cantilever init");
  const ntn_test::RelaxationResult r =
      ntn_test::relax(beam_model, beam_state, beam_scratch, 1e-10, 1'000'000);
  check(r.converged, "cantilever relaxation converged");
  const double expected = P * L * L * L / (3 * ntn_test::kSteel.E * sec.Iy);
  const double tip = beam_state.u[ntn_test::dof(4, ntn::kUz)];
  std::printf("tip deflection %.9e m, P L^3 / 3EI %.9e m\n", tip, expected);
  check(std::abs(tip / expected - 1) < 1e-6, "tip deflection = P L^3 / 3EI");

  check(ntn_test::feature_frame(frame_spec), "frame built");
  check(ntn::init(frame_spec, frame_model, frame_init).ok(), "frame init");
  check(ntn::start(frame_model, frame_state, frame_scratch, {0, 0, 0}) == ntn::StepStatus::kOk,
        "frame start");
  bool all_ok = true;
  for (long n = 0; n < 5000; ++n) {
    const std::array<double, kFrame.inputs> in = {ntn_test::input_sample(0, n),
                                                  ntn_test::input_sample(1, n), 1.0};
    all_ok &= ntn::step(frame_model, frame_state, frame_scratch, in) == ntn::StepStatus::kOk;
  }
  check(all_ok && frame_state.tick == 5000 && frame_state.faults == 0, "frame 5000 steps");
  return failures == 0 ? 0 : 1;
}
