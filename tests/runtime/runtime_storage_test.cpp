// One kernel, two storages: a model in run-time storage (ntn-run's
// LoadedModel: the model file loaded when the program runs, one block bound before init)
// computes the same bits as the same model compiled (the model compiler's header, std::arrays),
// step by step, over a real record (El Centro 1940, config/ground-motions): every output channel
// at every step and the whole state at the end (u, v, the hinges' history). Exact equality: the
// same kernel lines on the same numbers in the same order; any difference is a defect.
//
// Both storages start from the model's initial state plus the same small velocity at every DOF
// (so that a model without inputs moves too). The models: every model in config/, the model
// compiler's hinged test models (a pinned joint, backbone hinges, the slip connections), the
// every-key model, and benchmark frames (merged, pinned, mixed and plastic joints;
// tests/bench/frame_models.hpp) given to both storages as the same spec. The run-time side is also
// checked for zero heap allocations after init, in start() and step() (the allocation counter
// replaces malloc and operator new).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "backbone_portal_model.hpp"
#include "bench/frame_models.hpp"
#include "cantilever_model.hpp"
#include "every_key_model.hpp"
#include "frame3d_model.hpp"
#include "hinged_beam_model.hpp"
#include "mast_model.hpp"
#include "ntn/hil/clock.hpp"
#include "ntn/hil/energy.hpp"
#include "ntn/hil/gate.hpp"
#include "ntn/hil/loaded_model.hpp"
#include "ntn/hil/loop.hpp"
#include "ntn/hil/output_hash.hpp"
#include "ntn/hil/record_source.hpp"
#include "ntn/kernel.hpp"
#include "ntn/modelc/load_model.hpp"
#include "ntn/modelc/model_report.hpp"
#include "pinned_joint_model.hpp"
#include "portal_plastic_model.hpp"
#include "portal_slip_model.hpp"
#include "sdof_model.hpp"
#include "slip_connections_model.hpp"
#include "support/alloc_counter.hpp"

namespace runtime_storage_test {

const std::string kElCentro = NTN_CONFIG_DIR "/ground-motions/elCentro.AT2";

// The compiled storage of one model (on the heap: large models do not fit the stack).
template <ntn::Sizes S>
struct Compiled {
  ntn::Model<S> model;
  ntn::State<S> state;
  ntn::Scratch<S> scratch;
  ntn::InitWorkspace<S> work;
};

// Every input channel's step inputs: ground accelerations from El Centro (in the channel's unit,
// as ntn-run reads it), other channels a 2 Hz sine of 1 kN or kN m.
class Inputs {
 public:
  Inputs(std::span<const ntn::InputSpec> specs, double period, double dt)
      : records_(specs.size()), gate_(specs) {
    for (std::size_t k = 0; k < specs.size(); ++k) {
      if (specs[k].kind == ntn::InputKind::kGroundAcceleration) {
        const auto e =
            ntn::hil::load_input_record(specs[k], "in", kElCentro, "", false, records_[k]);
        EXPECT_FALSE(e.has_value()) << *e;
      } else {
        records_[k].dt = 1e-3;
        records_[k].units = "N";
        for (int n = 0; n < 40000; ++n)
          records_[k].values.push_back(1e3 * std::sin(2 * M_PI * 2.0 * n * 1e-3));
      }
    }
    source_ = std::make_unique<ntn::hil::RecordSource>(records_, gate_, period, dt);
  }
  void at(std::int64_t n, std::span<double> v) const { source_->step_inputs(n, v); }

 private:
  std::vector<ntn::io::Record> records_;
  ntn::hil::InputGate gate_;
  std::unique_ptr<ntn::hil::RecordSource> source_;
};

bool same_bits(const double* a, const double* b, std::size_t n) {
  return n == 0 || std::memcmp(a, b, n * sizeof(double)) == 0;
}

template <class A, class B>
bool same(const A& a, const B& b) {
  return a.size() == b.size() &&
         (a.size() == 0 || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

// Runs `steps` steps of both storages from the model's initial state and compares. `rt` was
// bound and init()ed from the same model.
template <ntn::Sizes S>
void expect_same_run(const ntn::ModelSpec<S>& spec, ntn::hil::LoadedModel& rt, std::int64_t steps) {
  auto c = std::make_unique<Compiled<S>>();
  ASSERT_TRUE(ntn::init(spec, c->model, c->work).ok());
  const ntn::InitStatus st = rt.init();
  ASSERT_TRUE(st.ok()) << ntn::to_string(st.error) << " at " << st.where;
  auto& m = rt.model();
  auto& s = rt.state();
  auto& w = rt.scratch();
  ASSERT_EQ(m.dt, c->model.dt);
  ASSERT_EQ(m.sizes, S);

  const Inputs feed(std::span<const ntn::InputSpec>(spec.inputs), spec.settings.frame_period,
                    c->model.dt);
  std::array<double, S.inputs> in_c{};
  std::vector<double> in_r(S.inputs);
  feed.at(0, in_c);
  std::copy(in_c.begin(), in_c.end(), in_r.begin());
  ntn::initial_state(c->model, c->state);
  ntn::initial_state(m, s);
  // Both start moving (a model without inputs or loads too): the same small initial velocity at
  // every DOF, which start() projects onto the hinges' constraints.
  for (std::size_t j = 0; j < s.v.size(); ++j) {
    const double v0 = 1e-3 * std::sin(0.7 * static_cast<double>(j));
    c->state.v[j] += v0;
    s.v[j] += v0;
  }

  const ntn_test::AllocationScope heap;  // from here on the run-time side allocates nothing
  EXPECT_EQ(ntn::start(c->model, c->state, c->scratch, in_c),
            ntn::start(m, s, w, std::span<const double>(in_r)));
  std::uint64_t allocations_rt = heap.counts().allocations;
  std::int64_t first_difference = -1;
  for (std::int64_t n = 0; n < steps && first_difference < 0; ++n) {
    feed.at(n, in_c);  // the compiled side's inputs (RecordSource allocates nothing here)
    std::copy(in_c.begin(), in_c.end(), in_r.begin());
    const auto before = heap.counts().allocations;
    const ntn::StepStatus b = ntn::step(m, s, w, std::span<const double>(in_r));
    allocations_rt += heap.counts().allocations - before;
    const ntn::StepStatus a = ntn::step(c->model, c->state, c->scratch, in_c);
    if (a != b || !same_bits(c->scratch.outputs.data(), w.outputs.data(), S.outputs))
      first_difference = n;
  }
  EXPECT_EQ(first_difference, -1) << "the storages' outputs differ from step " << first_difference;
  EXPECT_EQ(allocations_rt, 0U) << "run-time storage allocated in start() or step()";
  EXPECT_TRUE(same(c->state.u, s.u));
  EXPECT_TRUE(same(c->state.v, s.v));
  EXPECT_TRUE(same(c->state.plastic, s.plastic));
  EXPECT_TRUE(same(c->state.dissipated, s.dissipated));
  EXPECT_TRUE(same(c->state.plastic_peak, s.plastic_peak));
  EXPECT_TRUE(same(c->state.first_slip, s.first_slip));
  EXPECT_TRUE(same(c->state.slip_state, s.slip_state));
  EXPECT_EQ(c->state.tick, s.tick);
  EXPECT_EQ(c->state.faults, s.faults);
  EXPECT_EQ(c->state.inputs_held, s.inputs_held);
  // The record moved the model: not a comparison of two states at rest.
  double peak = 0;
  for (double u : s.u)
    peak = std::max(peak, std::fabs(u));
  EXPECT_GT(peak, 0.0);
}

// A model file: the compiled header's spec against the file loaded as ntn-run loads it.
template <ntn::Sizes S>
void expect_file_same(const ntn::ModelSpec<S>& spec, const std::string& file, double seconds) {
  ntn::modelc::LoadResult r = ntn::modelc::load_model(file);
  ASSERT_TRUE(r.ok()) << ntn::modelc::format_all(r.errors);
  ntn::hil::LoadedModel rt(std::move(*r.model), {});
  ASSERT_TRUE(rt.bound());
  const auto steps = static_cast<std::int64_t>(seconds / spec.settings.dt);
  expect_same_run(spec, rt, steps);
}

// A benchmark frame: the same spec, given to run-time storage as a view.
template <ntn::bench::Grid G, ntn::bench::Joints J>
void expect_frame_same(std::int64_t steps) {
  constexpr ntn::Sizes S = ntn::bench::sizes_of(G, J);
  auto spec = std::make_unique<ntn::ModelSpec<S>>();
  ntn::bench::build_frame<G, J>(*spec);
  ntn::modelc::ModelDescription d;  // the spec's arrays, as a loaded file would hold them
  const ntn::SpecView v = ntn::view(*spec);
  d.nodes.assign(v.nodes.begin(), v.nodes.end());
  d.elements.assign(v.elements.begin(), v.elements.end());
  d.time_points.assign(v.time_points.begin(), v.time_points.end());
  d.time_functions.assign(v.time_functions.begin(), v.time_functions.end());
  d.loads.assign(v.loads.begin(), v.loads.end());
  d.inputs.assign(v.inputs.begin(), v.inputs.end());
  d.outputs.assign(v.outputs.begin(), v.outputs.end());
  d.hinges.assign(v.hinges.begin(), v.hinges.end());
  d.curves.assign(v.curves.begin(), v.curves.end());
  d.curve_points.assign(v.curve_points.begin(), v.curve_points.end());
  d.element_loads.assign(v.element_loads.begin(), v.element_loads.end());
  d.hystereses.assign(v.hystereses.begin(), v.hystereses.end());
  d.settings = v.settings;
  ntn::hil::LoadedModel rt(std::move(d), {});
  ASSERT_TRUE(rt.bound());
  expect_same_run(*spec, rt, steps);
}

// `ntn-model info` reports the stiffness entries the blocks share as init() fills them (the
// kernel's fill_beam_blocks, run by both): the same count as the model in run-time storage, and
// frame3d's 26 blocks (members of 4 elements, four kinds of member) share a few.
TEST(RuntimeStorage, InfoCountsTheStiffnessEntriesInitShares) {
  for (const char* name : {"frame3d.toml", "cantilever.toml", "hinged_beam.toml",
                           "portal_plastic.toml", "portal_slip.toml", "mast.toml"}) {
    ntn::modelc::LoadResult r = ntn::modelc::load_model(NTN_CONFIG_DIR "/" + std::string(name));
    ASSERT_TRUE(r.ok()) << name;
    const std::string info = ntn::modelc::info_text(*r.model);
    ntn::hil::LoadedModel rt(std::move(*r.model), {});
    ASSERT_TRUE(rt.init().ok()) << name;
    const ntn::Model<ntn::kRunTime>& m = rt.model();
    const std::size_t blocks = ntn::beam_blocks(m.sizes.elements);
    EXPECT_GE(m.num_stiffness, 1U) << name;
    EXPECT_LE(m.num_stiffness, blocks) << name;
    EXPECT_NE(info.find(", " + std::to_string(m.num_stiffness) + " distinct stiffness blocks;"),
              std::string::npos)
        << name << "\n"
        << info;
    for (std::size_t b = 0; b < blocks; ++b)
      ASSERT_LT(static_cast<std::size_t>(m.beams[b].stiffness), m.num_stiffness) << name;
    if (std::string(name) == "frame3d.toml") {
      EXPECT_LE(m.num_stiffness, blocks / 2);
    }
  }
}

// Of El Centro: its strong motion (peak at 2.1 s) and after; under the sanitizers (~10x slower)
// its first second, where every model already moves (the initial velocity). The sanitizers' build
// keeps the models that between them take every path of the step (frame3d: SIMD pass and NTN
// hinges; the portals: yield and slip; the every-key model; the loop): each model is one more
// instantiation of the kernel, and all thirteen cost 100 CPU-s to compile under ASan.
#ifdef NTN_SANITIZE
constexpr double kSeconds = 1.0;
#else
constexpr double kSeconds = 8.0;
#endif

TEST(RuntimeStorage, Frame3dConfig) {
  expect_file_same(ntn::models::frame3d::kSpec, NTN_CONFIG_DIR "/frame3d.toml", kSeconds);
}
#ifndef NTN_SANITIZE
TEST(RuntimeStorage, CantileverConfig) {
  expect_file_same(ntn::models::cantilever::kSpec, NTN_CONFIG_DIR "/cantilever.toml", kSeconds);
}
TEST(RuntimeStorage, HingedBeamConfig) {
  expect_file_same(ntn::models::hinged_beam::kSpec, NTN_CONFIG_DIR "/hinged_beam.toml", kSeconds);
}
#endif
TEST(RuntimeStorage, PortalPlasticConfig) {
  expect_file_same(ntn::models::portal_plastic::kSpec, NTN_CONFIG_DIR "/portal_plastic.toml",
                   kSeconds);
}
TEST(RuntimeStorage, PortalSlipConfig) {
  expect_file_same(ntn::models::portal_slip::kSpec, NTN_CONFIG_DIR "/portal_slip.toml", kSeconds);
}
// Corotational members: the nodes' rotations in State, the corotational stage.
TEST(RuntimeStorage, MastConfig) {
  expect_file_same(ntn::models::mast::kSpec, NTN_CONFIG_DIR "/mast.toml", kSeconds);
}
#ifndef NTN_SANITIZE
// No members: one node, a point mass and a hinge (no element blocks in either storage).
TEST(RuntimeStorage, SdofConfig) {
  expect_file_same(ntn::models::sdof::kSpec, NTN_CONFIG_DIR "/sdof.toml", kSeconds);
}
#endif
#ifndef NTN_SANITIZE
TEST(RuntimeStorage, PinnedJoint) {
  expect_file_same(ntn::models::pinned_joint::kSpec, NTN_MODELC_GOOD_DIR "/pinned_joint.toml",
                   kSeconds);
}
TEST(RuntimeStorage, BackbonePortal) {
  expect_file_same(ntn::models::backbone_portal::kSpec, NTN_MODELC_GOOD_DIR "/backbone_portal.toml",
                   kSeconds);
}
TEST(RuntimeStorage, SlipConnections) {
  expect_file_same(ntn::models::slip_connections::kSpec,
                   NTN_MODELC_GOOD_DIR "/slip_connections.toml", kSeconds);
}
#endif
TEST(RuntimeStorage, EveryKey) {
  expect_file_same(ntn::models::every_key::kSpec, NTN_KERNEL_TESTS_DIR "/every_key.toml", kSeconds);
}

// The frame loop (hil_sim's run_loop, as ntn-hil runs it) over run-time storage: with the
// storage's channel buffers and checkpoint, made when the model was loaded, it allocates nothing
// (the gate, the record source and the frame times made before it), and its output hash (every
// step's outputs, the final state) is the compiled model's in the same loop.
struct HashSink {
  ntn::hil::OutputHash* hash;
  template <class State, class Scratch>
  void after_step(const State&, const Scratch& w) {
    hash->add_step(w);
  }
  void frame_outputs(std::int64_t, std::span<const double>, std::uint16_t) {}
};

template <ntn::Sizes S>
std::uint64_t loop_hash(const ntn::ModelSpec<S>& spec, ntn::Model<S>& model, ntn::State<S>& state,
                        ntn::Scratch<S>& scratch, ntn::State<S>& checkpoint,
                        ntn::hil::LoopBuffers<S>* buffers, std::uint64_t& allocations) {
  std::vector<ntn::io::Record> records(1);
  EXPECT_FALSE(
      ntn::hil::load_input_record(spec.inputs[0], "ag_x", kElCentro, "", false, records[0]));
  ntn::hil::InputGate gate{std::span<const ntn::InputSpec>(spec.inputs)};
  ntn::hil::RecordSource source(records, gate, spec.settings.frame_period, model.dt);
  ntn::hil::OutputHash hash;
  HashSink sink{&hash};
  ntn::hil::LoopConfig config;
  config.period = spec.settings.frame_period;
  config.substeps = static_cast<int>(model.substeps.count);
  config.frames = 3000;  // 3 s of El Centro, held over each 1 ms frame (ntn-hil's default)
  std::vector<ntn::hil::Alarm> alarms(model.sizes.outputs);
  ntn::hil::VirtualClock clock;
  ntn::hil::FrameTimes times;
  times.reserve(config.frames);
  const ntn_test::AllocationScope heap;
  (void)ntn::hil::run_loop(model, state, scratch, clock, source, sink, nullptr, config, alarms,
                           times, &checkpoint, nullptr, static_cast<ntn::TeamWork<S>*>(nullptr),
                           buffers);
  allocations = heap.counts().allocations;
  return hash.finish(state);
}

TEST(RuntimeStorage, LoopAllocatesNothingAndHashesAsCompiled) {
  namespace mdl = ntn::models::portal_plastic;  // a yielding frame: the hinges' history too
  constexpr ntn::Sizes S = mdl::kSizes;
  auto c = std::make_unique<Compiled<S>>();
  auto checkpoint = std::make_unique<ntn::State<S>>();
  ASSERT_TRUE(ntn::init(mdl::kSpec, c->model, c->work).ok());
  std::uint64_t compiled_allocations = 1, runtime_allocations = 1;
  const std::uint64_t compiled =
      loop_hash(mdl::kSpec, c->model, c->state, c->scratch, *checkpoint,
                static_cast<ntn::hil::LoopBuffers<S>*>(nullptr), compiled_allocations);

  ntn::modelc::LoadResult r = ntn::modelc::load_model(NTN_CONFIG_DIR "/portal_plastic.toml");
  ASSERT_TRUE(r.ok());
  ntn::hil::LoadedModel rt(std::move(*r.model), {.checkpoint = true});
  ASSERT_TRUE(rt.init().ok());
  const std::uint64_t runtime = loop_hash(rt.spec(), rt.model(), rt.state(), rt.scratch(),
                                          rt.checkpoint(), &rt.loop_buffers(), runtime_allocations);
  EXPECT_EQ(runtime, compiled);
  EXPECT_EQ(compiled_allocations, 0U);
  EXPECT_EQ(runtime_allocations, 0U) << "run_loop allocated over run-time storage";
  EXPECT_GT(ntn::hil::hysteretic_energy(rt.state()), 0.0);  // the connections yielded
}

#ifndef NTN_SANITIZE
using ntn::bench::Grid;
using ntn::bench::Joints;
constexpr Grid kFrame104{.nx = 2, .ny = 1, .storeys = 4, .col_div = 2, .beam_div = 2};
constexpr Grid kScaling1064{.nx = 6, .ny = 6, .storeys = 8, .col_div = 1, .beam_div = 1};

TEST(RuntimeStorage, BenchFrameMerged) {
  expect_frame_same<kScaling1064, Joints::kMerged>(3000);
}
TEST(RuntimeStorage, BenchFramePinned) {
  expect_frame_same<kFrame104, Joints::kPinned>(3000);
}
TEST(RuntimeStorage, BenchFrameMixed) {
  expect_frame_same<kFrame104, Joints::kMixed>(3000);
}
TEST(RuntimeStorage, BenchFramePlastic) {
  expect_frame_same<kFrame104, Joints::kPlastic>(3000);
}

#endif

}  // namespace runtime_storage_test
