// Kernel step cost per beam element: the kernel's on-the-fly local formulation
// (ntn::step, beam_force: f = R^T K_L R u per element) against a stored-global-matrix
// formulation written here (per element a stored 12x12 K_e = T^T K_L T, f = K_e u_e) with the
// same load, acceleration, output and update stages. Frames of ~10 to ~30 000 elements.
// The peer: a plain central-difference program written here with Eigen's
// sparse K u (the global stiffness assembled from the same element matrices, with and without
// its exact zeros pruned), lumped mass, mass-proportional damping and the same loads, on the
// same frames and on the OpenSees frame_scaling grids (6 m bays, 3.5 m storeys, one element
// per member: 1 064 and 10 101 elements).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <numeric>
#include <random>
#include <string>

#include <Eigen/SparseCore>
#include <vector>

#include "frame_models.hpp"
#include "ntn/hil/energy.hpp"
#include "ntn/hil/output_hash.hpp"
#include "ntn/hil/worker_team.hpp"
#include "ntn/runtime_storage.hpp"

// ---- Allocation counter: every operator new in this executable is counted. ----------------

namespace {
std::atomic<std::uint64_t> g_allocations{0};

void* counted_alloc(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}

void* counted_aligned_alloc(std::size_t n, std::align_val_t al) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  const auto a = static_cast<std::size_t>(al);
  const std::size_t size = ((n == 0 ? 1 : n) + a - 1) / a * a;  // aligned_alloc: multiple of a
  if (void* p = std::aligned_alloc(a, size)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t n) {
  return counted_alloc(n);
}
void* operator new[](std::size_t n) {
  return counted_alloc(n);
}
void* operator new(std::size_t n, std::align_val_t al) {
  return counted_aligned_alloc(n, al);
}
void* operator new[](std::size_t n, std::align_val_t al) {
  return counted_aligned_alloc(n, al);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}

namespace ntn::bench {
namespace {

// ---- Stored-global-matrix formulation (for comparison; not in the kernel). ------------------

// Per element its nodes and K_e = T^T K_L T (global axes, row-major, symmetric): 1160 bytes,
// against 160 bytes of BeamData for the on-the-fly formulation.
struct StoredBeam {
  std::int32_t node_i = 0, node_j = 0;
  Matrix12 K{};
};

template <Sizes S>
struct StoredBeams {
  std::array<StoredBeam, S.elements> beams{};
};

template <Sizes S>
void build_stored(const Model<S>& m, StoredBeams<S>& out) {
  for (std::size_t e = 0; e < S.elements; ++e) {
    const BeamData b = m.beam(e);
    out.beams[e].node_i = b.node_i;
    out.beams[e].node_j = b.node_j;
    out.beams[e].K = beam_global_stiffness(b);
  }
}

// F_n = sum over elements of K_e u_e, gathered and scattered exactly as the kernel does. K_e is
// symmetric, so row r of K_e is also column r: f = sum_c u_c K(:, c) reads the stored rows in
// order and vectorizes across rows without reassociating any sum.
template <Sizes S>
void stored_element_forces(const StoredBeams<S>& sb, const State<S>& s, Scratch<S>& w) {
  w.f.fill(0.0);
  for (const StoredBeam& b : sb.beams) {
    const auto i = static_cast<std::size_t>(kDofsPerNode * b.node_i);
    const auto j = static_cast<std::size_t>(kDofsPerNode * b.node_j);
    double ue[12];
    for (std::size_t d = 0; d < kDofsPerNode; ++d) {
      ue[d] = s.u[i + d];
      ue[d + 6] = s.u[j + d];
    }
    double fe[12] = {};
    for (std::size_t c = 0; c < 12; ++c) {
      const double* col = &b.K[c * 12];
      for (std::size_t r = 0; r < 12; ++r)
        fe[r] += col[r] * ue[c];
    }
    for (std::size_t d = 0; d < kDofsPerNode; ++d) {
      w.f[i + d] += fe[d];
      w.f[j + d] += fe[d + 6];
    }
  }
}

// ntn::step with the element-force stage swapped; every other stage is the kernel's own.
template <Sizes S>
StepStatus step_stored(const Model<S>& m, const StoredBeams<S>& sb, State<S>& s, Scratch<S>& w,
                       const std::array<double, S.inputs>& in) {
  const bool accepted = ntn::detail::accept_inputs(m, s, in);
  const double t = static_cast<double>(s.tick) * m.dt;
  ntn::detail::apply_loads(m, s, w, t);
  stored_element_forces(sb, s, w);
  ntn::detail::residual_stage(m, s, w);
  ntn::detail::sample_outputs(m, s, w, t);
  const bool finite = ntn::detail::update(m, s, w);
  ++s.tick;
  if (!finite) {
    s.faults |= kFaultDiverged;
    return StepStatus::kDiverged;
  }
  return accepted ? StepStatus::kOk : StepStatus::kInputHeld;
}

// ---- The peer: a plain Eigen sparse K u central-difference program. -------------------------

// Its whole state: K (row-major, CSR), u, v, F and the per-DOF load, damping and 1/mass.
struct SparsePeer {
  Eigen::SparseMatrix<double, Eigen::RowMajor> K;
  Eigen::VectorXd u, v, f, load, damping, inv_mass;
  double dt = 0;
};

// K = sum of the elements' K_e = T^T K_L T (beam_global_stiffness), exact zeros pruned or kept;
// P_j = m_j g_d (gravity and the ground acceleration, from the kernel's first step's load_g),
// C = alpha M, 1/m_j (0 on supported DOFs). The kernel's model only lends its data.
template <Sizes S>
void build_peer(const Model<S>& m, const std::array<double, kDofsPerNode>& load_g, bool prune,
                SparsePeer& p) {
  const auto n = static_cast<Eigen::Index>(Model<S>::kDofs);
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(144 * S.elements);
  for (std::size_t e = 0; e < S.elements; ++e) {
    const BeamData b = m.beam(e);
    const Matrix12 Ke = beam_global_stiffness(b);
    int dofs[12];
    for (int d = 0; d < 6; ++d) {
      dofs[d] = kDofsPerNode * b.node_i + d;
      dofs[d + 6] = kDofsPerNode * b.node_j + d;
    }
    for (std::size_t r = 0; r < 12; ++r) {
      for (std::size_t c = 0; c < 12; ++c)
        t.emplace_back(dofs[r], dofs[c], Ke[12 * r + c]);
    }
  }
  p.K.resize(n, n);
  p.K.setFromTriplets(t.begin(), t.end());
  if (prune) p.K.prune(0.0);
  p.K.makeCompressed();
  p.u = p.v = p.f = p.load = p.damping = p.inv_mass = Eigen::VectorXd::Zero(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const auto k = static_cast<std::size_t>(j);
    const bool held = (m.fixed[k / kDofsPerNode] >> (k % kDofsPerNode)) & 1U;
    p.load(j) = m.mass[k] * load_g[k % kDofsPerNode];
    p.damping(j) = m.alpha * m.mass[k];
    p.inv_mass(j) = held || !(m.mass[k] > 0) ? 0.0 : 1.0 / m.mass[k];
  }
  p.dt = m.dt;
}

// From rest, as the kernel's start: v_{-1/2} = -dt/2 a_0.
void peer_start(SparsePeer& p) {
  p.u.setZero(), p.v.setZero();
  p.f.noalias() = p.K * p.u;
  for (Eigen::Index j = 0; j < p.u.size(); ++j)
    p.v(j) = -0.5 * p.dt * (p.load(j) - p.f(j)) * p.inv_mass(j);
}

// One step: F = K u, a = (P - F - C v) / m, v += dt a, u += dt v.
void peer_step(SparsePeer& p) {
  p.f.noalias() = p.K * p.u;
  const double dt = p.dt;
  for (Eigen::Index j = 0; j < p.u.size(); ++j) {
    const double a = (p.load(j) - p.f(j) - p.damping(j) * p.v(j)) * p.inv_mass(j);
    p.v(j) += dt * a;
    p.u(j) += dt * p.v(j);
  }
}

// ---- Models, built once per grid into static storage. --------------------------------------

// kOnTheFly: the kernel's step (its SIMD element pass); kScalar: the same with the scalar
// reference element pass (element_pass.hpp: the same bits).
// kFileOrder, kFileShuffled: the kernel's step on the model with its elements in the file's own
// order (file_order_model), the grid's or a shuffled one.
enum class Formulation {
  kOnTheFly,
  kScalar,
  kStored,
  kSparse,
  kSparsePruned,
  kTeam1,
  kTeam2,
  kFileOrder,
  kFileShuffled
};

// The multi-core step's workers (hil_sim's WorkerTeam), made once before the first timed loop
// that uses them: a team of 1 (the team's phases on this thread alone) and of 2.
template <int kSize>
hil::WorkerTeam& workers() {
  static hil::WorkerTeam team({kSize, -1});
  return team;
}

constexpr int team_size(Formulation f) {
  return f == Formulation::kTeam2 ? 2 : 1;
}

// Ground acceleration held at (0.10 g, 0.05 g) plus gravity: every DOF moves from the first
// steps on, so no subnormal numbers slow the timed loop.
inline constexpr std::array<double, kInputs> kGround{0.10, 0.05};
inline constexpr int kWarmupSteps = 100;

// Set when a benchmark reports an error, so that the exit code (and the CTest entry) fails.
template <Grid G>
const Model<sizes_of(G)>& model_of() {
  static constexpr Sizes S = sizes_of(G);
  static const bool ready = [] {
    auto& spec = static_instance<ModelSpec<S>>();
    build_frame<G>(spec);
    const InitStatus st =
        init(spec, static_instance<Model<S>>(), static_instance<InitWorkspace<S>>());
    if (!st.ok()) {
      std::fprintf(stderr, "init failed: %s at %d\n", to_string(st.error), st.where);
      std::abort();
    }
    return true;
  }();
  (void)ready;
  return static_instance<Model<S>>();
}

// The grid's model with its elements taken in the file's own order, as the kernel took them
// before the model's element order (element_order.hpp): built by init(), then its blocks laid
// out again with element e at place e. kShuffle: the file's elements first put in a random order
// (seed 7), as a file written by another program may list them. For comparison only.
template <Grid G, bool kShuffle>
Model<sizes_of(G)>& file_order_model() {
  static constexpr Sizes S = sizes_of(G);
  static constexpr int kTag = kShuffle ? 2 : 1;
  static const bool ready = [] {
    auto& spec = static_instance<ModelSpec<S>, kTag>();
    build_frame<G>(spec);
    if constexpr (kShuffle) {
      std::vector<ElementSpec> elements(spec.elements.begin(), spec.elements.end());
      std::mt19937_64 rng(7);
      std::shuffle(elements.begin(), elements.end(), rng);
      std::copy(elements.begin(), elements.end(), spec.elements.begin());
    }
    Model<S>& m = static_instance<Model<S>, kTag>();
    const InitStatus st = init(spec, m, static_instance<InitWorkspace<S>>());
    if (!st.ok()) {
      std::fprintf(stderr, "init failed: %s at %d\n", to_string(st.error), st.where);
      std::abort();
    }
    // The blocks again as init() fills them (fill_beam_blocks), in the file's order.
    std::vector<std::int32_t> order(S.elements);
    std::iota(order.begin(), order.end(), 0);
    m.beams.fill(BeamBlock{});
    m.rotations.fill(BeamRotations{});
    m.stiffness.fill(BeamStiffnessBlock{});
    m.num_stiffness = fill_beam_blocks(view(spec), order, m.beams.data(), m.rotations.data(),
                                       m.stiffness.data(), m.element_slot.data());
    std::vector<std::uint8_t> touched(S.nodes);
    m.every_node_in_element = mark_first_ends(m.beams.data(), S.elements, S.nodes, touched.data());
    return true;
  }();
  (void)ready;
  return static_instance<Model<S>, kTag>();
}

template <Grid G>
const StoredBeams<sizes_of(G)>& stored_of() {
  static constexpr Sizes S = sizes_of(G);
  static const bool ready = [] {
    build_stored(model_of<G>(), static_instance<StoredBeams<S>>());
    return true;
  }();
  (void)ready;
  return static_instance<StoredBeams<S>>();
}

bool g_failed = false;

void fail(benchmark::State& bs, const char* why) {
  g_failed = true;
  bs.SkipWithError(why);
}

// The peer of grid G (pruned or not), built once, from rest; `difference` (set once) is its
// largest |u_peer - u_kernel| over the largest |u_kernel| after 500 steps from rest.
template <Grid G, bool kPrune>
SparsePeer& peer_of(double* difference = nullptr) {
  static constexpr Sizes S = sizes_of(G);
  static SparsePeer peer;
  static double diff = [] {
    const Model<S>& m = model_of<G>();
    State<S>& s = static_instance<State<S>, 3>();
    Scratch<S>& w = static_instance<Scratch<S>>();
    s.u.fill(0.0), s.v.fill(0.0), s.held_inputs.fill(0.0);
    s.tick = 0, s.inputs_held = 0, s.faults = 0;
    (void)start(m, s, w, kGround);
    (void)step(m, s, w, kGround);  // load_g of the held ground acceleration
    build_peer(m, w.load_g, kPrune, peer);
    s.u.fill(0.0), s.v.fill(0.0), s.tick = 0;
    (void)start(m, s, w, kGround);
    peer_start(peer);
    for (int k = 0; k < 500; ++k) {
      (void)step(m, s, w, kGround);
      peer_step(peer);
    }
    double d = 0, scale = 0;
    for (std::size_t j = 0; j < s.u.size(); ++j) {
      d = std::max(d, std::fabs(peer.u(static_cast<Eigen::Index>(j)) - s.u[j]));
      scale = std::max(scale, std::fabs(s.u[j]));
    }
    return scale > 0 ? d / scale : INFINITY;
  }();
  if (difference != nullptr) *difference = diff;
  return peer;
}

template <Sizes S>
void reset(State<S>& s) {
  s.u.fill(0.0), s.v.fill(0.0), s.held_inputs.fill(0.0);
  s.tick = 0, s.inputs_held = 0, s.faults = 0;
}

// One step of either formulation; `sb` is used (and must be set) by the stored one only.
template <Formulation F, Sizes S>
StepStatus advance(const Model<S>& m, const StoredBeams<S>* sb, State<S>& s, Scratch<S>& w) {
  if constexpr (F == Formulation::kOnTheFly || F == Formulation::kScalar ||
                F == Formulation::kFileOrder || F == Formulation::kFileShuffled) {
    return step(m, s, w, kGround);
  } else if constexpr (F == Formulation::kTeam1 || F == Formulation::kTeam2) {
    static const Team team = workers<team_size(F)>().team();
    return step(m, s, w, kGround, team, static_instance<TeamWork<S>>());
  } else {
    return step_stored(m, *sb, s, w, kGround);
  }
}

// Largest |u_stored - u_otf| over the largest |u_otf| after `steps` steps from rest: the two
// formulations compute the same K u in a different order, so this stays at rounding level.
template <Grid G>
double stored_vs_otf_difference(int steps) {
  static constexpr Sizes S = sizes_of(G);
  State<S>& a = static_instance<State<S>, 1>();
  State<S>& b = static_instance<State<S>, 2>();
  Scratch<S>& w = static_instance<Scratch<S>>();
  reset(a), reset(b);
  (void)start(model_of<G>(), a, w, kGround);
  (void)start(model_of<G>(), b, w, kGround);
  const Model<S>& m = model_of<G>();
  const StoredBeams<S>* sb = &stored_of<G>();
  for (int k = 0; k < steps; ++k) {
    (void)advance<Formulation::kOnTheFly>(m, sb, a, w);
    (void)advance<Formulation::kStored>(m, sb, b, w);
  }
  double diff = 0, scale = 0;
  for (std::size_t d = 0; d < a.u.size(); ++d) {
    diff = std::max(diff, std::fabs(a.u[d] - b.u[d]));
    scale = std::max(scale, std::fabs(a.u[d]));
  }
  return scale > 0 ? diff / scale : INFINITY;
}

template <Grid G, Formulation F>
void bm_step(benchmark::State& bs) {
  static constexpr Sizes S = sizes_of(G);
  State<S>& s = static_instance<State<S>>();
  Scratch<S>& w = static_instance<Scratch<S>>();
  (void)model_of<G>();
  // Built by model_of (or file_order_model); only its element pass is set here.
  Model<S>& m = F == Formulation::kFileOrder      ? file_order_model<G, false>()
                : F == Formulation::kFileShuffled ? file_order_model<G, true>()
                                                  : static_instance<Model<S>>();
  m.element_pass = F == Formulation::kScalar ? ElementPass::kScalar : ElementPass::kSimd;
  // The on-the-fly runs never build (or touch) the stored matrices.
  const StoredBeams<S>* sb = F == Formulation::kStored ? &stored_of<G>() : nullptr;

  if constexpr (F == Formulation::kTeam1 || F == Formulation::kTeam2) {
    if (!prepare_team(m, team_size(F), static_instance<TeamWork<S>>())) {
      fail(bs, "prepare_team failed");
      return;
    }
  }

  reset(s);
  (void)start(m, s, w, kGround);
  for (int k = 0; k < kWarmupSteps; ++k)
    (void)advance<F>(m, sb, s, w);

  bool diverged = false;
  const std::uint64_t allocs_before = g_allocations.load(std::memory_order_relaxed);
  for (auto _ : bs) {
    diverged |= advance<F>(m, sb, s, w) == StepStatus::kDiverged;
  }
  const std::uint64_t allocs = g_allocations.load(std::memory_order_relaxed) - allocs_before;
  if (allocs != 0) fail(bs, "heap allocation in the timed loop");
  if (diverged) fail(bs, "the step diverged");

  // Bytes the step streams through: the elements' data, and per node u, v, F, a and the model's
  // mass and 1/mass (6 doubles per DOF; P_n and C = alpha M are computed in the residual pass;
  // the kernel's SIMD DOF pass reads the masses from the shared mass table instead).
  // The kernel's element data: its blocks, the rotations of the blocks that are not aligned with
  // one map (element_pass.hpp), and the stiffness entries the blocks share.
  double element_bytes = static_cast<double>(sizeof(StoredBeam) * S.elements);
  if constexpr (F != Formulation::kStored) {
    std::size_t rotated = 0;
    for (std::size_t b = 0; b < beam_blocks(S.elements); ++b) {
      bool uniform = m.beams[b].axes[0] != kGeneralAxes;
      for (const AxisMap a : m.beams[b].axes)
        uniform = uniform && a == m.beams[b].axes[0];
      rotated += uniform ? 0 : 1;
    }
    element_bytes = static_cast<double>(beam_blocks(S.elements) * sizeof(BeamBlock) +
                                        rotated * sizeof(BeamRotations) +
                                        m.num_stiffness * sizeof(BeamStiffnessBlock));
    bs.counters["stiffness_entries"] = static_cast<double>(m.num_stiffness);
  }
  double node_bytes = 6.0 * sizeof(double) * kDofsPerNode * S.nodes;
  if constexpr (F != Formulation::kStored && F != Formulation::kScalar) {
    node_bytes = 4.0 * sizeof(double) * kDofsPerNode * S.nodes +
                 static_cast<double>(mass_groups(S.nodes) * sizeof(std::int32_t) +
                                     m.num_mass_entries * sizeof(MassBlock));
    bs.counters["mass_entries"] = static_cast<double>(m.num_mass_entries);
  }
  const double working_set = element_bytes + node_bytes;

  const double element_steps = static_cast<double>(bs.iterations()) * S.elements;
  bs.counters["elements"] = S.elements;
  bs.counters["nodes"] = S.nodes;
  bs.counters["dt_us"] = m.dt * 1e6;
  // Element-steps as an inverted rate: CPU seconds per element-step. The console prints it with
  // an SI prefix ("19.9ns"); JSON and CSV reports hold the value in seconds.
  bs.counters["ns_per_element_step"] =
      benchmark::Counter(element_steps, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  bs.counters["allocs"] = static_cast<double>(allocs);  // operator new calls in the timed loop
  bs.counters["working_set"] =
      benchmark::Counter(working_set, benchmark::Counter::kDefaults, benchmark::Counter::kIs1024);
  if constexpr (F == Formulation::kStored) {
    static const double rel_diff = stored_vs_otf_difference<G>(500);
    bs.counters["rel_diff_vs_otf"] = rel_diff;
    // Observed ~1e-15 (summation order only); a wrong entry of K_e would show as O(1e-3..1).
    if (!(rel_diff < 1e-9)) fail(bs, "stored formulation disagrees with the kernel");
  }
}

// A model given as a view in run-time storage: one block bound before init, kept for the run.
RunTimeParts* bind_runtime(const SpecView& v) {
  const Sizes z = ntn::sizes_of(v);
  const std::size_t bytes = runtime_block_bytes(z);
  auto* p = new RunTimeParts;
  auto* block =
      static_cast<std::byte*>(::operator new (bytes, std::align_val_t{kRunTimeBlockAlign}));
  if (!runtime_bind(*p, z, {}, std::span<std::byte>(block, bytes)) ||
      !init(runtime_spec(v), p->model, p->init_work).ok()) {
    std::fprintf(stderr, "run-time storage: binding or init failed\n");
    std::abort();
  }
  return p;
}

// The same frame in run-time storage: the spec of model_of<G>() given as a view,
// one block bound before init. Its state after `kCheckSteps` steps from rest equals the compiled
// model's bit for bit (else the benchmark fails).
template <Grid G>
RunTimeParts& runtime_of() {
  static constexpr Sizes S = sizes_of(G);
  static RunTimeParts* const parts = [] {
    (void)model_of<G>();  // builds the spec
    return bind_runtime(view(static_instance<ModelSpec<S>>()));
  }();
  return *parts;
}

template <Grid G, bool kBooks = false>
void bm_step_runtime(benchmark::State& bs) {
  static constexpr Sizes S = sizes_of(G);
  RunTimeParts& p = runtime_of<G>();
  p.model.books = kBooks;  // with kBooks the kernel's energy books over the DOFs (books.hpp)
  const std::span<const double> in(kGround);
  auto run_from_rest = [&](int steps) {
    p.state.u.fill(0.0), p.state.v.fill(0.0), p.state.held_inputs.fill(0.0);
    p.state.tick = 0, p.state.inputs_held = 0, p.state.faults = 0;
    (void)start(p.model, p.state, p.scratch, in);
    for (int k = 0; k < steps; ++k)
      (void)step(p.model, p.state, p.scratch, in);
  };
  // The compiled model from rest the same number of steps: the same bits.
  {
    constexpr int kCheckSteps = 200;
    State<S>& c = static_instance<State<S>, 4>();
    Scratch<S>& w = static_instance<Scratch<S>>();
    reset(c);
    (void)start(model_of<G>(), c, w, kGround);
    for (int k = 0; k < kCheckSteps; ++k)
      (void)step(model_of<G>(), c, w, kGround);
    run_from_rest(kCheckSteps);
    if (std::memcmp(c.u.data(), p.state.u.data(), sizeof c.u) != 0 ||
        std::memcmp(c.v.data(), p.state.v.data(), sizeof c.v) != 0) {
      fail(bs, "run-time storage differs from the compiled model");
      return;
    }
  }
  run_from_rest(kWarmupSteps);
  bool diverged = false;
  const std::uint64_t allocs_before = g_allocations.load(std::memory_order_relaxed);
  for (auto _ : bs) {
    diverged |= step(p.model, p.state, p.scratch, in) == StepStatus::kDiverged;
  }
  const std::uint64_t allocs = g_allocations.load(std::memory_order_relaxed) - allocs_before;
  if (allocs != 0) fail(bs, "heap allocation in the timed loop");
  if (diverged) fail(bs, "the step diverged");
  const double element_steps = static_cast<double>(bs.iterations()) * S.elements;
  bs.counters["elements"] = S.elements;
  bs.counters["ns_per_element_step"] =
      benchmark::Counter(element_steps, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  bs.counters["allocs"] = static_cast<double>(allocs);
}

// What ntn-run (and Python's run(), ntn-ida) does per kernel step on run-time storage: the step,
// then its sink's work (tools/run/run_driver.hpp, RunSink::after_step): the energy books
// (hil/energy.hpp), the output hash and the peaks. Against step/runtime_storage, the kernel's
// step alone, in the same run.
template <Grid G>
void bm_step_user(benchmark::State& bs) {
  static constexpr Sizes S = sizes_of(G);
  RunTimeParts& p = runtime_of<G>();
  const std::span<const double> in(kGround);
  p.state.u.fill(0.0), p.state.v.fill(0.0), p.state.held_inputs.fill(0.0);
  p.state.tick = 0, p.state.inputs_held = 0, p.state.faults = 0;
  (void)start(p.model, p.state, p.scratch, in);
  for (int k = 0; k < kWarmupSteps; ++k)
    (void)step(p.model, p.state, p.scratch, in);
  hil::EnergyBalance<kRunTime> books;  // from here: begin() turns the kernel's books on
  books.reserve(p.model.dofs());
  books.begin(p.model, p.state);
  hil::OutputHash hash;
  std::vector<double> peaks(p.model.sizes.outputs, 0.0);
  bool diverged = false;
  const std::uint64_t allocs_before = g_allocations.load(std::memory_order_relaxed);
  for (auto _ : bs) {
    diverged |= step(p.model, p.state, p.scratch, in) == StepStatus::kDiverged;
    books.after_step(p.model, p.state, p.scratch);
    hash.add_step(p.scratch);
    for (std::size_t c = 0; c < peaks.size(); ++c)
      peaks[c] = std::max(peaks[c], std::fabs(p.scratch.outputs[c]));
  }
  const std::uint64_t allocs = g_allocations.load(std::memory_order_relaxed) - allocs_before;
  if (allocs != 0) fail(bs, "heap allocation in the timed loop");
  if (diverged) fail(bs, "the step diverged");
  if (!(books.accounts(p.model, p.state).relative_residual() <= 1e-10))
    fail(bs, "the energy books do not close");
  const double element_steps = static_cast<double>(bs.iterations()) * S.elements;
  bs.counters["elements"] = S.elements;
  bs.counters["ns_per_element_step"] =
      benchmark::Counter(element_steps, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  bs.counters["allocs"] = static_cast<double>(allocs);
}

// The peer's step, timed like bm_step: per element-step, allocations counted, and checked
// against the kernel (the same K u in another order: rounding only).
template <Grid G, bool kPrune>
void bm_peer(benchmark::State& bs) {
  static constexpr Sizes S = sizes_of(G);
  double diff = 0;
  SparsePeer& p = peer_of<G, kPrune>(&diff);
  peer_start(p);
  for (int k = 0; k < kWarmupSteps; ++k)
    peer_step(p);
  const std::uint64_t allocs_before = g_allocations.load(std::memory_order_relaxed);
  for (auto _ : bs)
    peer_step(p);
  const std::uint64_t allocs = g_allocations.load(std::memory_order_relaxed) - allocs_before;
  if (allocs != 0) fail(bs, "heap allocation in the timed loop");
  if (!p.u.allFinite()) fail(bs, "the peer diverged");
  const double element_steps = static_cast<double>(bs.iterations()) * S.elements;
  bs.counters["elements"] = S.elements;
  bs.counters["nonzeros"] = static_cast<double>(p.K.nonZeros());
  bs.counters["ns_per_element_step"] =
      benchmark::Counter(element_steps, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  bs.counters["allocs"] = static_cast<double>(allocs);
  bs.counters["rel_diff_vs_otf"] = diff;
  // The same stiffness, loads and scheme: only the order of K u's sums differs.
  if (!(diff < 1e-9)) fail(bs, "the peer disagrees with the kernel");
}

// The same frame in run-time storage with every element's geometry set to `kGeometry`
// (geometry.hpp, corotational.hpp): linear, p_delta or corotational, in the same run, per
// element-step. One block bound before init; the frame under gravity and the held ground
// acceleration from rest.
template <Grid G, Geometry kGeometry>
RunTimeParts& geometry_runtime_of() {
  static constexpr Sizes S = sizes_of(G);
  static RunTimeParts* const parts = [] {
    (void)model_of<G>();  // builds the spec
    const ModelSpec<S>& spec = static_instance<ModelSpec<S>>();
    static std::vector<ElementSpec> elements(spec.elements.begin(), spec.elements.end());
    for (ElementSpec& e : elements)
      e.geometry = kGeometry;
    SpecView v = view(spec);
    v.elements = elements;
    return bind_runtime(v);
  }();
  return *parts;
}

template <Grid G, Geometry kGeometry>
void bm_step_geometry(benchmark::State& bs) {
  static constexpr Sizes S = sizes_of(G);
  RunTimeParts& p = geometry_runtime_of<G, kGeometry>();
  const std::span<const double> in(kGround);
  initial_state(p.model, p.state);
  (void)start(p.model, p.state, p.scratch, in);
  for (int k = 0; k < kWarmupSteps; ++k)
    (void)step(p.model, p.state, p.scratch, in);
  bool diverged = false;
  const std::uint64_t allocs_before = g_allocations.load(std::memory_order_relaxed);
  for (auto _ : bs) {
    diverged |= step(p.model, p.state, p.scratch, in) == StepStatus::kDiverged;
  }
  const std::uint64_t allocs = g_allocations.load(std::memory_order_relaxed) - allocs_before;
  if (allocs != 0) fail(bs, "heap allocation in the timed loop");
  if (diverged) fail(bs, "the step diverged");
  if (p.state.geometry_bound != 0) fail(bs, "past the geometry bound");
  const double element_steps = static_cast<double>(bs.iterations()) * S.elements;
  bs.counters["elements"] = S.elements;
  bs.counters["ns_per_element_step"] =
      benchmark::Counter(element_steps, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  bs.counters["allocs"] = static_cast<double>(allocs);
}

template <Grid G>
void register_geometry() {
  const std::string n = std::to_string(element_count(G));
  benchmark::RegisterBenchmark(("step/geometry:linear/elements:" + n).c_str(),
                               bm_step_geometry<G, Geometry::kLinear>)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark(("step/geometry:p_delta/elements:" + n).c_str(),
                               bm_step_geometry<G, Geometry::kPDelta>)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark(("step/geometry:corotational/elements:" + n).c_str(),
                               bm_step_geometry<G, Geometry::kCorotational>)
      ->Unit(benchmark::kMicrosecond);
}

// The benchmark frames: ~10, ~100, ~1 000, ~10 000, ~30 000 and ~100 000 elements.
inline constexpr Grid kFrame12{.nx = 1, .ny = 1, .storeys = 1, .col_div = 1, .beam_div = 2};
inline constexpr Grid kFrame104{.nx = 2, .ny = 1, .storeys = 4, .col_div = 2, .beam_div = 2};
inline constexpr Grid kFrame975{.nx = 4, .ny = 4, .storeys = 5, .col_div = 3, .beam_div = 3};
inline constexpr Grid kFrame9900{.nx = 8, .ny = 8, .storeys = 11, .col_div = 4, .beam_div = 4};
inline constexpr Grid kFrame30008{.nx = 10, .ny = 10, .storeys = 22, .col_div = 4, .beam_div = 4};
// Beyond the last-level cache for both formulations (32 MiB L3 on the reference machine).
inline constexpr Grid kFrame99960{.nx = 16, .ny = 16, .storeys = 30, .col_div = 4, .beam_div = 4};
// The OpenSees frame_scaling grids: one element per member, 6 x 6 bays x 8 storeys
// and 12 x 12 bays x 21 storeys; and the same geometry at ~100 000 elements (28 x 28 bays x 41
// storeys), for the cost per element-step from 1k to 100k on one kind of frame.
inline constexpr Grid kScaling1064{.nx = 6, .ny = 6, .storeys = 8, .col_div = 1, .beam_div = 1};
inline constexpr Grid kScaling10101{.nx = 12, .ny = 12, .storeys = 21, .col_div = 1, .beam_div = 1};
inline constexpr Grid kScaling101065{
    .nx = 28, .ny = 28, .storeys = 41, .col_div = 1, .beam_div = 1};

// The peer of grid G, pruned and not (its K of 144 entries per element: up to ~30 000 elements;
// `unpruned` false registers the pruned one alone).
template <Grid G>
void register_peer(bool unpruned = true) {
  const std::string n = std::to_string(element_count(G));
  if (unpruned) {
    benchmark::RegisterBenchmark(("step/sparse_peer/elements:" + n).c_str(), bm_peer<G, false>)
        ->Unit(benchmark::kMicrosecond);
  }
  benchmark::RegisterBenchmark(("step/sparse_peer_pruned/elements:" + n).c_str(), bm_peer<G, true>)
      ->Unit(benchmark::kMicrosecond);
}

template <Grid G>
void register_frame() {
  const std::string n = std::to_string(element_count(G));
  benchmark::RegisterBenchmark(("step/on_the_fly/elements:" + n).c_str(),
                               bm_step<G, Formulation::kOnTheFly>)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark(("step/on_the_fly_scalar/elements:" + n).c_str(),
                               bm_step<G, Formulation::kScalar>)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark(("step/file_order/elements:" + n).c_str(),
                               bm_step<G, Formulation::kFileOrder>)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark(("step/file_order_shuffled/elements:" + n).c_str(),
                               bm_step<G, Formulation::kFileShuffled>)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark(("step/stored_matrix/elements:" + n).c_str(),
                               bm_step<G, Formulation::kStored>)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark(("step/runtime_storage/elements:" + n).c_str(), bm_step_runtime<G>)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark(("step/runtime_storage_books/elements:" + n).c_str(),
                               bm_step_runtime<G, true>)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark(("step/user_path/elements:" + n).c_str(), bm_step_user<G>)
      ->Unit(benchmark::kMicrosecond);
  // The multi-core step: wall-clock time (the CPU time is the calling thread's alone).
  benchmark::RegisterBenchmark(("step/threads:1/elements:" + n).c_str(),
                               bm_step<G, Formulation::kTeam1>)
      ->Unit(benchmark::kMicrosecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark(("step/threads:2/elements:" + n).c_str(),
                               bm_step<G, Formulation::kTeam2>)
      ->Unit(benchmark::kMicrosecond)
      ->UseRealTime();
}

}  // namespace
}  // namespace ntn::bench

int main(int argc, char** argv) {
  using namespace ntn::bench;
  register_frame<kFrame12>();
  register_frame<kFrame104>();
  register_frame<kFrame975>();
  register_frame<kFrame9900>();
  register_frame<kFrame30008>();
  register_frame<kFrame99960>();
  register_frame<kScaling1064>();
  register_frame<kScaling10101>();
  register_frame<kScaling101065>();
  register_geometry<kFrame104>();
  register_geometry<kFrame975>();
  register_geometry<kScaling1064>();
  register_peer<kFrame975>();
  register_peer<kFrame9900>();
  register_peer<kScaling1064>();
  register_peer<kScaling10101>();
  register_peer<kScaling101065>(false);
  benchmark::AddCustomContext("element_pass", ntn::element_pass_target());
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return g_failed ? 1 : 0;
}
