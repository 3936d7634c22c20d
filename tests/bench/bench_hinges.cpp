// Hinge cost per step: a ~1 000-element frame whose ~500 beam ends are pinned
// to the columns through NTN hinges (rigid in ux, uy, uz, rx of the beam's axes, free in ry, rz),
// stepped with ntn_exact, ntn_paper and penalty, against the same frame with merged nodes and no
// hinges. Also the time to simulate 1 s with penalty (at a penalty stiffness that keeps the
// hinges' relative displacement below 1e-6 of the peak displacement) against ntn_exact, and a
// frame with every hinge kind (rigid, free, curve with rigid stops, linear with a dashpot).
//
// Besides the benchmarks, three modes (each replaces the benchmark run):
//   --calibrate        penalty stiffness from runs of 1 s (README "Hinges")
//   --penalty-sweep    penalty / ntn_exact time for 1 s under 10 and 100 times stricter criteria
//   --slip-accuracy    rigid_plastic: the penalty stiffness that matches the exact peak slip
//                      within 1 % over 1 s, and the time ratio to simulate 1 s there
//   --stages[=N]       manual timing of each stage of step() over N steps (default 4000)
//   --dump-state=FILE  u, v after 1000 steps of every variant, raw bytes (to compare builds)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "frame_models.hpp"
#include "support/alloc_counter.hpp"

namespace ntn::bench {
namespace {

// ---- The frames. ----------------------------------------------------------------------------

// 4 x 4 bays, 6 storeys; columns in 2 elements, beams in 3: 1 020 elements, 240 beams, so 480
// hinged beam ends. Merged: 805 nodes; hinged: 1 285 nodes.
inline constexpr Grid kFrame{.nx = 4, .ny = 4, .storeys = 6, .col_div = 2, .beam_div = 3};

// Penalty stiffness of the rigid directions: the smallest value of the 1-2-5 series for which
// the hinges' relative displacement stays below 1e-6 of the peak displacement over 1 s of the
// benchmark's load (translations against translations, the torsion rotation against rotations).
// Found with --calibrate; README "Hinges" has its output.
inline constexpr double kPenaltyStiffness = 2e10;    // N/m
inline constexpr double kPenaltyRotStiffness = 5e9;  // N m/rad
inline constexpr double kPenaltyTolerance = 1e-6;

enum class Variant : std::uint8_t { kMerged, kExact, kPaper, kPenalty };

constexpr const char* name_of(Variant v) {
  switch (v) {
    case Variant::kMerged:
      return "merged";
    case Variant::kExact:
      return "ntn_exact";
    case Variant::kPaper:
      return "ntn_paper";
    case Variant::kPenalty:
      return "penalty";
  }
  return "?";
}

constexpr HingeMethod method_of(Variant v) {
  return v == Variant::kPaper     ? HingeMethod::kNtnPaper
         : v == Variant::kPenalty ? HingeMethod::kPenalty
                                  : HingeMethod::kNtnExact;
}

constexpr Joints joints_of(Variant v, bool mixed) {
  return v == Variant::kMerged ? Joints::kMerged : mixed ? Joints::kMixed : Joints::kPinned;
}

// Static storage per (joints, variant, tag): spec, model, state, scratch.
constexpr int slot(Joints j, Variant v, int tag = 0) {
  return 100 * static_cast<int>(j) + 10 * static_cast<int>(v) + tag;
}

template <Joints J>
constexpr Sizes kSizes = sizes_of(kFrame, J);

// The frame with `v`'s hinge method, the given penalty stiffness and dt = 0.9 dt_stable. One
// storage for every call: the result is valid until the next call.
template <Joints J>
const ModelSpec<kSizes<J>>& spec_of(Variant v, double kt = kPenaltyStiffness,
                                    double kr = kPenaltyRotStiffness) {
  static ModelSpec<kSizes<J>>& base = []() -> ModelSpec<kSizes<J>>& {
    auto& s = static_instance<ModelSpec<kSizes<J>>, slot(J, Variant::kMerged, 9)>();
    build_frame<kFrame, J>(s);
    return s;
  }();
  auto& s = static_instance<ModelSpec<kSizes<J>>, slot(J, Variant::kMerged, 8)>();
  s = base;
  if constexpr (J != Joints::kMerged) {
    s.settings.hinge_method = method_of(v);
    s.settings.penalty_stiffness = kt;
    s.settings.penalty_rotational_stiffness = kr;
    s.settings.dt = kDtFraction * stable_step_with_hinges(view(s)).dt_stable;
  }
  return s;
}

template <Joints J>
void init_or_die(const ModelSpec<kSizes<J>>& spec, Model<kSizes<J>>& m) {
  const InitStatus st = init(spec, m, static_instance<InitWorkspace<kSizes<J>>>());
  if (!st.ok()) {
    std::fprintf(stderr, "init failed: %s at %d\n", to_string(st.error), st.where);
    std::abort();
  }
}

template <Joints J, Variant V>
const Model<kSizes<J>>& model_of() {
  static const Model<kSizes<J>>& m = []() -> const Model<kSizes<J>>& {
    auto& model = static_instance<Model<kSizes<J>>, slot(J, V)>();
    init_or_die<J>(spec_of<J>(V), model);
    return model;
  }();
  return m;
}

// ---- Runs. ----------------------------------------------------------------------------------

// Ground acceleration held at (0.10 g, 0.05 g) plus gravity, as in bench_kernel: every DOF moves
// from the first steps on.
inline constexpr std::array<double, kInputs> kGround{0.10, 0.05};
inline constexpr int kWarmupSteps = 100;
inline constexpr int kRepeatSteps = 1000;  // steps of each of the two repeat runs

bool g_failed = false;

void fail(benchmark::State& bs, const char* why) {
  g_failed = true;
  bs.SkipWithError(why);
}

std::uint64_t allocations() {
  return ntn_test::allocation_counts().allocations;
}

template <Sizes S>
void reset(State<S>& s) {
  s.u.fill(0.0), s.v.fill(0.0), s.held_inputs.fill(0.0);
  s.tick = 0, s.inputs_held = 0, s.faults = 0;
  s.plastic.fill(0.0), s.dissipated.fill(0.0), s.plastic_peak.fill(0.0);
}

// From rest, `steps` steps; false if a step diverged.
template <Sizes S>
bool run_from_rest(const Model<S>& m, State<S>& s, Scratch<S>& w, int steps) {
  reset(s);
  bool ok = start(m, s, w, kGround) == StepStatus::kOk;
  for (int k = 0; k < steps; ++k)
    ok &= step(m, s, w, kGround) == StepStatus::kOk;
  return ok;
}

// Two runs of kRepeatSteps from rest give the same State, byte for byte (u, v and counters).
template <Joints J, Variant V>
bool repeat_identical() {
  constexpr Sizes S = kSizes<J>;
  State<S>& a = static_instance<State<S>, slot(J, V, 1)>();
  State<S>& b = static_instance<State<S>, slot(J, V, 2)>();
  Scratch<S>& w = static_instance<Scratch<S>, slot(J, V, 1)>();
  const bool ok = run_from_rest(model_of<J, V>(), a, w, kRepeatSteps) &
                  run_from_rest(model_of<J, V>(), b, w, kRepeatSteps);
  return ok && std::memcmp(a.u.data(), b.u.data(), sizeof(a.u)) == 0 &&
         std::memcmp(a.v.data(), b.v.data(), sizeof(a.v)) == 0 && a.tick == b.tick &&
         a.faults == b.faults && a.inputs_held == b.inputs_held;
}

template <Joints J, Variant V>
void bm_step(benchmark::State& bs) {
  constexpr Sizes S = kSizes<J>;
  State<S>& s = static_instance<State<S>, slot(J, V)>();
  Scratch<S>& w = static_instance<Scratch<S>, slot(J, V)>();
  const Model<S>& m = model_of<J, V>();
  static const bool identical = repeat_identical<J, V>();

  bool diverged = !run_from_rest(m, s, w, kWarmupSteps);
  const std::uint64_t allocs_before = allocations();
  for (auto _ : bs) {
    diverged |= step(m, s, w, kGround) == StepStatus::kDiverged;
  }
  const std::uint64_t allocs = allocations() - allocs_before;
  if (allocs != 0) fail(bs, "heap allocation in the timed loop");
  if (diverged) fail(bs, "the step diverged");
  if (!identical) fail(bs, "two runs from rest differ");

  const auto iters = static_cast<double>(bs.iterations());
  bs.counters["elements"] = S.elements;
  bs.counters["nodes"] = S.nodes;
  bs.counters["hinges"] = S.hinges;
  bs.counters["dt_us"] = m.dt * 1e6;
  // CPU seconds per step, and per simulated second (inverted rates: the console prints them
  // with SI prefixes; JSON and CSV hold seconds).
  bs.counters["cpu_per_step"] =
      benchmark::Counter(iters, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  bs.counters["cpu_per_sim_s"] =
      benchmark::Counter(iters * m.dt, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  bs.counters["sim_s_per_cpu_s"] = benchmark::Counter(iters * m.dt, benchmark::Counter::kIsRate);
  bs.counters["allocs"] = static_cast<double>(allocs);  // malloc / new calls in the timed loop
  // Largest |u| at the end (m or rad): shows a run that grows without bound (ntn_paper here).
  double max_u = 0;
  for (double x : s.u)
    max_u = std::max(max_u, std::fabs(x));
  bs.counters["max_abs_u"] = max_u;
  bs.counters["repeat_identical"] = identical ? 1 : 0;
  if constexpr (S.hystereses > 0) {  // plastic directions that have yielded by the end
    double yielded = 0;
    for (double p : s.plastic_peak)
      yielded += p > 0 ? 1 : 0;
    bs.counters["yielded"] = yielded;
  }
}

// ---- Summary after the run: ratios from the medians (or the single runs). -------------------

struct Figures {
  double cpu_per_step = 0;   // s
  double cpu_per_sim_s = 0;  // s
  double dt = 0;             // s
  double max_abs_u = 0;      // m or rad, at the end of the timed loop
};

// |u| above this (m or rad) is not a response of this frame but a run growing without bound.
inline constexpr double kUnbounded = 1e3;

class SummaryReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& reports) override {
    for (const Run& r : reports) {
      if (r.error_occurred) continue;
      const bool aggregate = r.run_type == Run::RT_Aggregate;
      if (aggregate && r.aggregate_name != "median") continue;
      const std::string name = r.run_name.str();
      if (!aggregate && medians_.count(name) != 0) continue;  // a median already arrived
      auto get = [&](const char* c) {
        const auto it = r.counters.find(c);
        return it == r.counters.end() ? 0.0 : it->second.value;
      };
      Figures f{get("cpu_per_step"), get("cpu_per_sim_s"), get("dt_us") * 1e-6, get("max_abs_u")};
      if (aggregate) medians_.insert(name);
      figures_[name] = f;
    }
    ConsoleReporter::ReportRuns(reports);
  }

  const Figures* find(const std::string& prefix) const {
    for (const auto& [name, f] : figures_) {
      if (name.rfind(prefix, 0) == 0) return &f;
    }
    return nullptr;
  }

 private:
  std::map<std::string, Figures> figures_;
  std::set<std::string> medians_;
};

void print_summary(const SummaryReporter& rep) {
  const Figures* merged = rep.find("step/merged/");
  std::printf("\nSummary (CPU time; medians when run with repetitions)\n");
  if (merged != nullptr) {
    std::printf("  %-22s %9.2f us/step  dt %6.1f us  %8.3f s CPU per simulated s\n", "merged",
                merged->cpu_per_step * 1e6, merged->dt * 1e6, merged->cpu_per_sim_s);
  }
  for (const char* kind : {"pinned", "mixed", "semirigid", "plastic", "rigid_plastic"}) {
    for (Variant v : {Variant::kExact, Variant::kPaper, Variant::kPenalty}) {
      const std::string label = std::string(kind) + "/" + name_of(v);
      const Figures* f = rep.find("step/" + label + "/");
      if (f == nullptr) continue;
      std::printf("  %-22s %9.2f us/step  dt %6.3f us  %8.3f s CPU per simulated s", label.c_str(),
                  f->cpu_per_step * 1e6, f->dt * 1e6, f->cpu_per_sim_s);
      if (merged != nullptr && merged->cpu_per_step > 0) {
        std::printf("  x%.2f per step vs merged", f->cpu_per_step / merged->cpu_per_step);
      }
      // This frame's response stays within a few metres over the timed runs (README "Hinges").
      if (f->max_abs_u > kUnbounded) std::printf("  UNSTABLE: |u| reached %.1e", f->max_abs_u);
      std::printf("\n");
    }
  }
  const Figures* semi = rep.find("step/semirigid/ntn_exact/");
  const Figures* plastic = rep.find("step/plastic/ntn_exact/");
  if (semi != nullptr && plastic != nullptr && semi->cpu_per_step > 0) {
    const double r = plastic->cpu_per_step / semi->cpu_per_step;
    std::printf("  plastic / linear hinge directions per step: %.2f (target <= 1.3: %s)\n", r,
                r <= 1.3 ? "met" : "missed");
  }
  const Figures* rp = rep.find("step/rigid_plastic/ntn_exact/");
  const Figures* rp_penalty = rep.find("step/rigid_plastic/penalty/");
  if (rp != nullptr && merged != nullptr && merged->cpu_per_step > 0) {
    const double r = rp->cpu_per_step / merged->cpu_per_step;
    std::printf("  rigid_plastic / merged per step: %.2f (target <= 2: %s)\n", r,
                r <= 2 ? "met" : "missed");
  }
  if (rp != nullptr && rp_penalty != nullptr && rp->cpu_per_sim_s > 0) {
    std::printf(
        "  time to simulate 1 s, rigid_plastic penalty (the calibrated k) / ntn_exact: %.0f\n",
        rp_penalty->cpu_per_sim_s / rp->cpu_per_sim_s);
  }
  const Figures* exact = rep.find("step/pinned/ntn_exact/");
  const Figures* penalty = rep.find("step/pinned/penalty/");
  if (exact != nullptr && merged != nullptr && merged->cpu_per_step > 0) {
    const double r = exact->cpu_per_step / merged->cpu_per_step;
    std::printf("  ntn_exact / merged per step: %.2f (target <= 1.3: %s)\n", r,
                r <= 1.3 ? "met" : "missed");
  }
  if (exact != nullptr && penalty != nullptr && exact->cpu_per_sim_s > 0) {
    const double r = penalty->cpu_per_sim_s / exact->cpu_per_sim_s;
    std::printf("  time to simulate 1 s, penalty / ntn_exact: %.0f (target >= 100: %s)\n", r,
                r >= 100 ? "met" : "missed");
  }
}

// ---- --calibrate: the penalty stiffness. ----------------------------------------------------

struct Drift {
  double dt = 0;           // s
  std::int64_t steps = 0;  // steps run
  double peak_u = 0;       // m, max |u| of any translation
  double peak_phi = 0;     // rad, max |phi| of any rotation
  double max_d = 0;        // m, max |d_L| of any hinge in a rigid translation direction
  double max_d_phi = 0;    // rad, the same in a rigid rotation direction
  int worst_hinge = -1;    // hinge of max_d
  bool diverged = false;   //
  double wall = 0;         // s of wall time
  double ratio() const { return max_d / peak_u; }
  double ratio_phi() const { return max_d_phi / peak_phi; }
};

// Runs `seconds` of simulated time from rest (whole steps), measuring after every step the peak
// displacement and the largest relative displacement of the hinges in their rigid directions.
template <Joints J>
Drift drift(Variant v, double kt, double kr, double seconds) {
  constexpr Sizes S = kSizes<J>;
  const ModelSpec<S>& spec = spec_of<J>(v, kt, kr);
  Model<S>& m = static_instance<Model<S>, slot(J, Variant::kMerged, 5)>();
  State<S>& s = static_instance<State<S>, slot(J, Variant::kMerged, 5)>();
  Scratch<S>& w = static_instance<Scratch<S>, slot(J, Variant::kMerged, 5)>();
  init_or_die<J>(spec, m);
  Drift out;
  out.dt = m.dt;
  out.steps = static_cast<std::int64_t>(std::ceil(seconds / m.dt));
  const auto t0 = std::chrono::steady_clock::now();
  reset(s);
  out.diverged = start(m, s, w, kGround) != StepStatus::kOk;
  for (std::int64_t n = 0; n < out.steps && !out.diverged; ++n) {
    out.diverged = step(m, s, w, kGround) != StepStatus::kOk;
    for (std::size_t j = 0; j < s.u.size(); ++j) {
      double& peak = j % kDofsPerNode < 3 ? out.peak_u : out.peak_phi;
      peak = std::max(peak, std::fabs(s.u[j]));
    }
    for (std::size_t h = 0; h < S.hinges; ++h) {
      const HingeData& hd = m.hinges[h];
      const HingeSpec& hs = spec.hinges[h];
      double d[6];
      hinge_relative(hd, &s.u[static_cast<std::size_t>(kDofsPerNode * hd.node1)],
                     &s.u[static_cast<std::size_t>(kDofsPerNode * hd.node2)], d);
      for (std::size_t k = 0; k < kDofsPerNode; ++k) {
        if (hs.behaviour[k] != HingeBehaviour::kRigid) continue;
        if (k < 3 && std::fabs(d[k]) > out.max_d)
          out.max_d = std::fabs(d[k]), out.worst_hinge = static_cast<int>(h);
        if (k >= 3) out.max_d_phi = std::max(out.max_d_phi, std::fabs(d[k]));
      }
    }
  }
  out.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

void print_drift(const char* what, double kt, double kr, const Drift& d) {
  std::printf(
      "  %-34s k_t %8.2e  k_r %8.2e  dt %9.4f us  steps %8lld  peak |u| %.4e m  peak |phi| "
      "%.4e rad\n"
      "  %-34s max |d| %.3e m = %.2e of peak  max |d_rx| %.3e rad = %.2e of peak%s  (%.1f s "
      "wall)\n",
      what, kt, kr, d.dt * 1e6, static_cast<long long>(d.steps), d.peak_u, d.peak_phi, "", d.max_d,
      d.ratio(), d.max_d_phi, d.ratio_phi(), d.diverged ? "  DIVERGED" : "", d.wall);
}

// Smallest value of the 1-2-5 series at least x.
double series_125_at_least(double x) {
  double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (;;) {
    for (double f : {1.0, 2.0, 5.0}) {
      if (f * decade >= x * (1 - 1e-12)) return f * decade;
    }
    decade *= 10;
  }
}

// The value of the 1-2-5 series just below x (x itself on the series).
double series_125_below(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x) + 1e-9));
  const double f = x / decade;
  return f > 4.5 ? 2 * decade : f > 1.5 ? decade : 0.5 * decade;
}

int calibrate() {
  constexpr double kSeconds = 1.0;
  constexpr double kTrial = 1e9;  // N/m and N m/rad: stiff, yet the elements keep the step
  std::printf("Penalty calibration: %zu hinges, %.1f s of the benchmark load from rest\n",
              kSizes<Joints::kPinned>.hinges, kSeconds);
  const Drift exact = drift<Joints::kPinned>(Variant::kExact, kTrial, kTrial, kSeconds);
  print_drift("ntn_exact", 0, 0, exact);
  const Drift paper = drift<Joints::kPinned>(Variant::kPaper, kTrial, kTrial, kSeconds);
  print_drift("ntn_paper", 0, 0, paper);
  const Drift trial = drift<Joints::kPinned>(Variant::kPenalty, kTrial, kTrial, kSeconds);
  print_drift("penalty, trial", kTrial, kTrial, trial);
  // The relative displacement of a penalty spring is its force over k; the forces barely depend
  // on k once k is far above the members' stiffness, so the ratio scales as 1 / k.
  const double kt = series_125_at_least(kTrial * trial.ratio() / kPenaltyTolerance);
  const double kr = series_125_at_least(kTrial * trial.ratio_phi() / kPenaltyTolerance);
  std::printf("  suggested (1-2-5 series, ratio <= %.0e): k_t %.0e N/m, k_r %.0e N m/rad\n",
              kPenaltyTolerance, kt, kr);
  const auto& spec =
      spec_of<Joints::kPinned>(Variant::kPenalty, kPenaltyStiffness, kPenaltyRotStiffness);
  const StableStepReport st = stable_step_with_hinges(view(spec));
  std::printf(
      "  compiled in: k_t %.0e N/m, k_r %.0e N m/rad: dt_stable %.4f us (hinge %d, direction "
      "%d; elements alone %.2f us)\n",
      kPenaltyStiffness, kPenaltyRotStiffness, st.dt_stable * 1e6, st.governing_hinge,
      st.hinge_direction, st.dt_elements * 1e6);
  const Drift check =
      drift<Joints::kPinned>(Variant::kPenalty, kPenaltyStiffness, kPenaltyRotStiffness, kSeconds);
  print_drift("penalty, compiled in", kPenaltyStiffness, kPenaltyRotStiffness, check);
  const bool meets = !check.diverged && check.ratio() <= kPenaltyTolerance &&
                     check.ratio_phi() <= kPenaltyTolerance;
  std::printf("  compiled-in stiffness %s the criterion\n", meets ? "meets" : "FAILS");
  // The previous values of the series must each fail it, else the compiled-in ones are not the
  // smallest (one run with both lowered: the translations' ratio depends on k_t, the torsion's
  // on k_r, hardly on the other).
  const double kt_below = series_125_below(kPenaltyStiffness);
  const double kr_below = series_125_below(kPenaltyRotStiffness);
  const Drift below = drift<Joints::kPinned>(Variant::kPenalty, kt_below, kr_below, kSeconds);
  print_drift("penalty, one value lower", kt_below, kr_below, below);
  const bool smallest = below.ratio() > kPenaltyTolerance && below.ratio_phi() > kPenaltyTolerance;
  std::printf("  compiled-in stiffness %s the smallest of the series that meets it\n",
              smallest ? "is" : "is NOT");
  return meets && smallest && !exact.diverged ? 0 : 1;
}

// ---- --penalty-sweep: the time ratio under stricter criteria. ------------------------------

// Wall-clock time per step: the smallest of three timings of `steps` steps after the warm-up
// (the smallest is the one least disturbed by other processes).
template <Joints J, Variant V>
double seconds_per_step(int steps) {
  constexpr Sizes S = kSizes<J>;
  const Model<S>& m = model_of<J, V>();
  State<S>& s = static_instance<State<S>, slot(J, V, 6)>();
  Scratch<S>& w = static_instance<Scratch<S>, slot(J, V, 6)>();
  double best = 0;
  for (int run = 0; run < 3; ++run) {
    (void)run_from_rest(m, s, w, kWarmupSteps);
    const auto t0 = std::chrono::steady_clock::now();
    for (int n = 0; n < steps; ++n)
      (void)step(m, s, w, kGround);
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (run == 0 || t < best) best = t;
  }
  return best / steps;
}

// For the criterion of --calibrate (relative displacement <= tol x peak over 1 s) made 10 and
// 100 times stricter: the penalty stiffness the 1/k scaling of the trial run predicts (1-2-5
// series), a 1 s run that checks the criterion there, the strict stable step it allows, and the
// time to simulate 1 s against ntn_exact (a penalty step costs the same whatever k).
int penalty_sweep() {
  constexpr double kTrial = 1e9;
  constexpr Joints J = Joints::kPinned;
  std::printf("Penalty / ntn_exact, time to simulate 1 s, under stricter criteria\n");
  const double exact_step = seconds_per_step<J, Variant::kExact>(3000);
  const double penalty_step = seconds_per_step<J, Variant::kPenalty>(3000);
  const double exact_dt = model_of<J, Variant::kExact>().dt;
  std::printf("  per step: ntn_exact %.2f us (dt %.2f us), penalty %.2f us\n", exact_step * 1e6,
              exact_dt * 1e6, penalty_step * 1e6);
  const Drift trial = drift<J>(Variant::kPenalty, kTrial, kTrial, 1.0);
  bool ok = !trial.diverged;
  std::printf("  %-10s %10s %10s %10s %12s %12s %8s\n", "criterion", "k_t N/m", "k_r Nm/rad",
              "dt us", "max|d|/peak", "max|d_rx|/pk", "ratio");
  for (double tol : {kPenaltyTolerance, kPenaltyTolerance / 10, kPenaltyTolerance / 100}) {
    const double kt = series_125_at_least(kTrial * trial.ratio() / tol);
    const double kr = series_125_at_least(kTrial * trial.ratio_phi() / tol);
    const Drift d = drift<J>(Variant::kPenalty, kt, kr, 1.0);
    const bool meets = !d.diverged && d.ratio() <= tol && d.ratio_phi() <= tol;
    ok = ok && meets;
    const double ratio = (penalty_step / d.dt) / (exact_step / exact_dt);
    std::printf("  %-10.0e %10.0e %10.0e %10.3f %12.2e %12.2e %8.0f%s\n", tol, kt, kr, d.dt * 1e6,
                d.ratio(), d.ratio_phi(), ratio, meets ? "" : "  (criterion NOT met)");
  }
  return ok ? 0 : 1;
}

// ---- --slip-accuracy: rigid_plastic against its penalty equivalent at equal accuracy. -------

// The largest plastic deformation (slip) of any rigid-plastic direction over `seconds` of
// simulated time from rest, and the run's dt and steps.
struct PeakSlip {
  double dt = 0, peak = 0;
  std::int64_t steps = 0;
  bool diverged = false;
};

PeakSlip peak_slip(Variant v, double kr, double seconds) {
  constexpr Joints J = Joints::kRigidPlastic;
  constexpr Sizes S = kSizes<J>;
  Model<S>& m = static_instance<Model<S>, slot(J, Variant::kMerged, 4)>();
  State<S>& s = static_instance<State<S>, slot(J, Variant::kMerged, 4)>();
  Scratch<S>& w = static_instance<Scratch<S>, slot(J, Variant::kMerged, 4)>();
  init_or_die<J>(spec_of<J>(v, kPenaltyStiffness, kr), m);
  PeakSlip out;
  out.dt = m.dt;
  out.steps = static_cast<std::int64_t>(std::ceil(seconds / m.dt));
  reset(s);
  out.diverged = start(m, s, w, kGround) != StepStatus::kOk;
  for (std::int64_t n = 0; n < out.steps && !out.diverged; ++n)
    out.diverged = step(m, s, w, kGround) != StepStatus::kOk;
  for (const double p : s.plastic_peak)
    out.peak = std::max(out.peak, p);
  return out;
}

// The comparison: the exact rigid-plastic frame's peak slip over 1 s, then the penalty
// frame (its rotational penalty stiffness k_r in a 1-2-5 series from the calibrated value, each
// at 0.9 of its own stable step) until its peak slip is within 1 %; the time to simulate 1 s of
// each from its measured time per step.
int slip_accuracy() {
  constexpr Joints J = Joints::kRigidPlastic;
  constexpr double kTolerance = 0.01;
  std::printf("rigid_plastic frame, peak slip over 1 s: ntn_exact against penalty springs\n");
  const double exact_step = seconds_per_step<J, Variant::kExact>(2000);
  const double penalty_step = seconds_per_step<J, Variant::kPenalty>(2000);
  const PeakSlip exact = peak_slip(Variant::kExact, kPenaltyRotStiffness, 1.0);
  std::printf("  per step: ntn_exact %.2f us (dt %.2f us), penalty %.2f us\n", exact_step * 1e6,
              exact.dt * 1e6, penalty_step * 1e6);
  std::printf("  ntn_exact: peak slip %.6e rad, %lld steps\n", exact.peak,
              static_cast<long long>(exact.steps));
  if (exact.diverged || !(exact.peak > 0)) {
    std::printf("  the exact frame did not yield (or diverged): no comparison\n");
    return 1;
  }
  std::printf("  %10s %10s %10s %12s %10s\n", "k_r Nm/rad", "dt us", "steps", "slip error",
              "ratio");
  for (double kr = kPenaltyRotStiffness; kr <= 1e4 * kPenaltyRotStiffness;
       kr = series_125_at_least(kr * 1.5)) {
    const PeakSlip p = peak_slip(Variant::kPenalty, kr, 1.0);
    const double error = std::fabs(p.peak - exact.peak) / exact.peak;
    const double ratio = (penalty_step / p.dt) / (exact_step / exact.dt);
    std::printf("  %10.0e %10.4f %10lld %12.3e %10.1f%s\n", kr, p.dt * 1e6,
                static_cast<long long>(p.steps), error, ratio, p.diverged ? "  DIVERGED" : "");
    if (!p.diverged && error <= kTolerance) {
      std::printf(
          "  within 1 %% at k_r = %.0e N m/rad: penalty takes %.1f x the time of "
          "ntn_exact to simulate 1 s (target >= 30)\n",
          kr, ratio);
      return 0;
    }
  }
  std::printf("  no penalty stiffness in the series came within 1 %%\n");
  return 1;
}

// ---- --stages: manual timing of each stage of step(). ---------------------------------------

enum Stage : std::uint8_t {
  kInputsLoads,
  kElements,
  kHingeSprings,
  kResidual,  // R_n - C v: into w.r (ntn_paper), into w.a scaled (ntn_exact)
  kCoupleUp,  // paper_forces (S 17-21) / forest_up
  kDivide,    // a = r / m (with the residual in one pass: no hinges, penalty)
  kForest,    // the roots and forest_down (DESIGN 7.1)
  kOutputs,
  kUpdate,
  kClamps,   // momentum_clamp / paper_after_update
  kProject,  // forest_project
  kStages
};
constexpr const char* kStageNames[kStages] = {
    "inputs+loads", "element forces", "hinge springs", "residual R-Cv", "couple up (S17-21/up)",
    "a = r/m",      "forest down",    "outputs",       "update",        "clamps (+S27-37)",
    "projection"};

using Clock = std::chrono::steady_clock;

// step() stage by stage, with the kernel's own functions in the kernel's order, timing each
// (accelerations() is spelled out here to time its parts; print_stages checks it is the same).
template <Sizes S>
StepStatus timed_step(const Model<S>& m, State<S>& s, Scratch<S>& w,
                      std::array<double, kStages>& ns) {
  auto t = Clock::now();
  auto lap = [&](Stage st) {
    const auto now = Clock::now();
    ns[st] += std::chrono::duration<double, std::nano>(now - t).count();
    t = now;
  };
  const bool accepted = ntn::detail::accept_inputs(m, s, kGround);
  const double time = static_cast<double>(s.tick) * m.dt;
  ntn::detail::apply_loads(m, s, w, time);
  lap(kInputsLoads);
  ntn::detail::element_forces(m, s, w);
  lap(kElements);
  constexpr std::size_t kDofs = Model<S>::kDofs;
  if constexpr (S.hinges == 0) {
    ntn::detail::residual(m, s, w, m.inv_mass.data(), w.a.data());
    lap(kDivide);
  } else {
    ntn::detail::hinge_springs(m, s, w);
    lap(kHingeSprings);
    if (m.hinge_method == HingeMethod::kNtnPaper) {
      ntn::detail::residual<S, false>(m, s, w, nullptr, w.r.data());
      lap(kResidual);
      paper_forces(m.hinges, w.r.data());
      lap(kCoupleUp);
      for (std::size_t j = 0; j < kDofs; ++j)
        w.a[j] = w.r[j] * m.inv_mass[j];
      lap(kDivide);
    } else if (m.hinge_method == HingeMethod::kNtnExact) {
      ntn::detail::residual(m, s, w, m.residual_scale.data(), w.a.data());
      lap(kResidual);
      forest_up(m.edges, m.edge_matrices, m.num_edges, w.a.data());
      lap(kCoupleUp);
      forest_down(m.roots, m.num_roots, m.edges, m.edge_matrices, m.num_edges, w.a.data(),
                  w.a.data());
      lap(kForest);
    } else {
      ntn::detail::residual(m, s, w, m.inv_mass.data(), w.a.data());
      lap(kDivide);
    }
  }
  ntn::detail::sample_outputs(m, s, w, time);
  lap(kOutputs);
  const bool finite = ntn::detail::update(m, s, w);
  lap(kUpdate);
  if constexpr (S.hinges > 0) {
    const bool paper = m.hinge_method == HingeMethod::kNtnPaper;
    if (!paper && m.clamp == ClampRule::kMomentum) {
      ntn::detail::step_weights(m, w);
      ntn::detail::momentum_clamp(m, s, w);
    } else {
      paper_after_update(m.hinges, m.fixed, s.u.data(), s.v.data(), w.a.data(), m.inv_dt, paper);
    }
    lap(kClamps);
    if (m.hinge_method == HingeMethod::kNtnExact) {
      forest_project(m.edges, m.edge_matrices, m.project_edges, m.num_project_edges, s.u.data(),
                     s.v.data(), w.a.data(), m.inv_dt);
    }
    lap(kProject);
  }
  ++s.tick;
  if (!finite) return StepStatus::kDiverged;
  return accepted ? StepStatus::kOk : StepStatus::kInputHeld;
}

// Times the stages over `steps` steps after the warm-up (the median of each stage over the steps,
// so that a step interrupted by another process does not count), and checks that the staged step
// gives the State of step() bit for bit (so what is timed is what step() does).
template <Joints J, Variant V>
bool print_stages(int steps) {
  constexpr Sizes S = kSizes<J>;
  const Model<S>& m = model_of<J, V>();
  State<S>& s = static_instance<State<S>, slot(J, V, 3)>();
  State<S>& ref = static_instance<State<S>, slot(J, V, 4)>();
  Scratch<S>& w = static_instance<Scratch<S>, slot(J, V, 3)>();
  std::vector<std::array<double, kStages>> ns(static_cast<std::size_t>(steps));
  (void)run_from_rest(m, s, w, kWarmupSteps);
  std::vector<double> total(static_cast<std::size_t>(steps));
  for (std::size_t k = 0; k < ns.size(); ++k) {
    ns[k].fill(0.0);
    const auto t0 = Clock::now();
    (void)timed_step(m, s, w, ns[k]);
    total[k] = std::chrono::duration<double, std::nano>(Clock::now() - t0).count();
  }
  auto median = [](std::vector<double> x) {
    std::sort(x.begin(), x.end());
    return x[x.size() / 2];
  };
  (void)run_from_rest(m, ref, w, kWarmupSteps + steps);
  const bool same = std::memcmp(s.u.data(), ref.u.data(), sizeof(s.u)) == 0 &&
                    std::memcmp(s.v.data(), ref.v.data(), sizeof(s.v)) == 0;
  std::printf("%s/%s: median %.2f us per step (with clock reads), staged == step(): %s\n",
              J == Joints::kMixed    ? "mixed"
              : J == Joints::kPinned ? "pinned"
                                     : "merged",
              name_of(V), median(total) * 1e-3, same ? "yes" : "NO");
  double sum = 0;
  for (std::size_t st = 0; st < kStages; ++st) {
    std::vector<double> x(ns.size());
    for (std::size_t k = 0; k < ns.size(); ++k)
      x[k] = ns[k][st];
    const double med = median(x);
    sum += med;
    if (med > 0) std::printf("  %-22s %8.2f us\n", kStageNames[st], med * 1e-3);
  }
  std::printf("  %-22s %8.2f us\n", "sum of medians", sum * 1e-3);
  return same;
}

int stages(int steps) {
  bool ok = print_stages<Joints::kMerged, Variant::kMerged>(steps);
  ok &= print_stages<Joints::kPinned, Variant::kExact>(steps);
  ok &= print_stages<Joints::kPinned, Variant::kPaper>(steps);
  ok &= print_stages<Joints::kPinned, Variant::kPenalty>(steps);
  return ok ? 0 : 1;
}

// ---- --dump-state: u, v after kRepeatSteps of every variant. --------------------------------

template <Joints J, Variant V>
bool dump_one(std::FILE* f) {
  constexpr Sizes S = kSizes<J>;
  State<S>& s = static_instance<State<S>, slot(J, V, 1)>();
  Scratch<S>& w = static_instance<Scratch<S>, slot(J, V, 1)>();
  (void)run_from_rest(model_of<J, V>(), s, w, kRepeatSteps);
  return std::fwrite(s.u.data(), sizeof(s.u), 1, f) == 1 &&
         std::fwrite(s.v.data(), sizeof(s.v), 1, f) == 1;
}

int dump_state(const char* path) {
  std::FILE* f = std::fopen(path, "wb");
  if (f == nullptr) return 1;
  bool ok = dump_one<Joints::kMerged, Variant::kMerged>(f);
  ok &= dump_one<Joints::kPinned, Variant::kExact>(f);
  ok &= dump_one<Joints::kPinned, Variant::kPaper>(f);
  ok &= dump_one<Joints::kPinned, Variant::kPenalty>(f);
  ok &= dump_one<Joints::kMixed, Variant::kExact>(f);
  ok &= dump_one<Joints::kMixed, Variant::kPaper>(f);
  ok &= dump_one<Joints::kMixed, Variant::kPenalty>(f);
  ok &= dump_one<Joints::kSemiRigid, Variant::kExact>(f);
  ok &= dump_one<Joints::kPlastic, Variant::kExact>(f);
  ok &= dump_one<Joints::kRigidPlastic, Variant::kExact>(f);
  ok &= dump_one<Joints::kRigidPlastic, Variant::kPenalty>(f);
  ok &= std::fclose(f) == 0;
  return ok ? 0 : 1;
}

// ---- Registration. --------------------------------------------------------------------------

template <Joints J, Variant V>
void register_step(const char* kind) {
  const std::string n = V == Variant::kMerged
                            ? "step/merged/elements:" + std::to_string(kSizes<J>.elements)
                            : std::string("step/") + kind + "/" + name_of(V) +
                                  "/hinges:" + std::to_string(kSizes<J>.hinges);
  benchmark::RegisterBenchmark(n.c_str(), bm_step<J, V>)->Unit(benchmark::kMicrosecond);
}

}  // namespace
}  // namespace ntn::bench

int main(int argc, char** argv) {
  using namespace ntn::bench;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--calibrate") return calibrate();
    if (a == "--penalty-sweep") return penalty_sweep();
    if (a == "--slip-accuracy") return slip_accuracy();
    if (a.rfind("--stages", 0) == 0) {
      return stages(a.size() > 9 ? std::atoi(a.c_str() + 9) : 4000);
    }
    if (a.rfind("--dump-state=", 0) == 0) return dump_state(a.c_str() + 13);
  }
  register_step<Joints::kMerged, Variant::kMerged>("merged");
  register_step<Joints::kPinned, Variant::kExact>("pinned");
  register_step<Joints::kPinned, Variant::kPaper>("pinned");
  register_step<Joints::kPinned, Variant::kPenalty>("pinned");
  register_step<Joints::kMixed, Variant::kExact>("mixed");
  register_step<Joints::kMixed, Variant::kPaper>("mixed");
  register_step<Joints::kMixed, Variant::kPenalty>("mixed");
  register_step<Joints::kSemiRigid, Variant::kExact>("semirigid");
  register_step<Joints::kPlastic, Variant::kExact>("plastic");
  register_step<Joints::kRigidPlastic, Variant::kExact>("rigid_plastic");
  register_step<Joints::kRigidPlastic, Variant::kPenalty>("rigid_plastic");
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  SummaryReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  print_summary(reporter);
  return g_failed ? 1 : 0;
}
