// Real-time capacity: the largest frame (elements, at its stable step) that
// holds a 1 kHz frame rate in the real-time loop (ntn::hil::run_loop on the RealClock) with zero
// overruns over 60 s and compute time <= 50 % of the period at p99.9. Frames of ~1 000 to ~10 000
// elements from frame_models.hpp, run one after the other, each with N = ceil(period / (0.9
// dt_stable)) substeps per frame (dt = period / N) and a synthetic ground motion (or held inputs):
// no UDP, since the criterion is about the loop's compute and deadlines. SCHED_FIFO and mlockall
// where permitted. A plain program, not Google Benchmark: each size is one long real-time run on
// absolute deadlines, not a repeated timed loop. README.md "Real-time capacity".
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <numbers>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "cli.hpp"  // tools/io
#include "frame_models.hpp"
#include "ntn/hil/clock.hpp"
#include "ntn/hil/loop.hpp"
#include "ntn/hil/worker_team.hpp"
#include "ntn/runtime_storage.hpp"

namespace ntn::bench {
namespace {

struct Options {
  double duration = 60.0;  // s of real time per size
  double period = 1e-3;    // s
  bool held = false;       // inputs held constant instead of the synthetic ground motion
  bool fifo = true, mlock = true;
  int priority = 80;
  int cpu = -1;
  int max_elements = 1 << 30;
  bool screen = true;  // skip the real-time run when a short virtual-clock trial cannot hold
  int threads = 1;     // workers of the multi-core step (the loop's thread is one)
  int spin = 1 << 10;  // pauses a waiting worker spins before it yields and sleeps
  // Every element's geometry: linear runs the compiled frames; p_delta and corotational run them
  // in run-time storage (one block bound before init, as ntn-hil run does).
  Geometry geometry = Geometry::kLinear;
};

struct Row {
  int elements = 0, nodes = 0;
  double dt_stable = 0, dt = 0;
  int substeps = 0;
  std::int64_t frames = 0;
  double cmp[4] = {};  // compute / period: p50, p99, p99.9, max
  double lat[4] = {};  // wake-up latency, us: p50, p99, p99.9, max
  std::int64_t overruns = 0, longest_late = 0;
  bool ran = false;     // false: skipped by the virtual-clock screen
  double screen50 = 0;  // virtual-clock trial: compute / period, p50
  bool diverged = false;
  bool holds() const { return ran && !diverged && overruns == 0 && cmp[2] <= 0.5; }
};

// Ground acceleration in g on (x, y): held at (0.10, 0.05), or two sines of 0.10 g at 1.0 Hz and
// 0.05 g at 1.7 Hz (a few storey periods), computed per frame from its time.
struct GroundSource {
  double period = 1e-3;
  bool held = false;
  void frame_inputs(std::int64_t k, std::span<double> v, std::uint16_t& flags) {
    flags = 0;
    if (held) {
      v[0] = 0.10, v[1] = 0.05;
      return;
    }
    const double t = static_cast<double>(k) * period;
    v[0] = 0.10 * std::sin(2 * std::numbers::pi * 1.0 * t);
    v[1] = 0.05 * std::sin(2 * std::numbers::pi * 1.7 * t);
  }
};

struct NullSink {
  double last = 0;
  void frame_outputs(std::int64_t, std::span<const double> v, std::uint16_t) {
    if (!v.empty()) last = v[0];
  }
};

double frac(std::int64_t ns, double period) {
  return static_cast<double>(ns) / (period * 1e9);
}

// The loop over one model at row.substeps per frame: the virtual-clock screen, then the real-time
// run; `fresh` puts the state back at rest.
template <Sizes S, class Fresh>
void run_model(const Options& o, hil::WorkerTeam& workers, Model<S>& model, State<S>& state,
               Scratch<S>& scratch, TeamWork<S>& work, Fresh fresh, Row& row);

template <Grid G>
Row run_size(const Options& o, hil::WorkerTeam& workers) {
  constexpr Sizes S = sizes_of(G);
  Row row;
  row.elements = S.elements, row.nodes = S.nodes;
  if (std::cmp_greater(S.elements, o.max_elements)) return row;
  auto& spec = static_instance<ModelSpec<S>>();
  build_frame<G>(spec);
  row.dt_stable = stable_time_step(view(spec)).dt_stable;
  // DESIGN §8 / hil_main: dt must divide the period; the largest such dt <= 0.9 dt_stable.
  row.substeps = static_cast<int>(std::ceil(o.period / (kDtFraction * row.dt_stable) - 1e-12));
  row.dt = o.period / row.substeps;
  spec.settings.dt = row.dt;
  if (o.geometry != Geometry::kLinear) {
    // The same frame in run-time storage with every element's geometry set (the corotational
    // nodes' isotropic rotary inertia can only lengthen the stable step).
    std::vector<ElementSpec> elements(spec.elements.begin(), spec.elements.end());
    for (ElementSpec& e : elements)
      e.geometry = o.geometry;
    SpecView v = view(spec);
    v.elements = elements;
    const Sizes z = ntn::sizes_of(v);
    static RunTimeParts parts;
    std::vector<std::byte> block(runtime_block_bytes(z) + kRunTimeBlockAlign);
    void* at = block.data();
    std::size_t space = block.size();
    std::align(kRunTimeBlockAlign, runtime_block_bytes(z), at, space);
    if (!runtime_bind(parts, z, {.team = o.threads > 1},
                      std::span<std::byte>(static_cast<std::byte*>(at), runtime_block_bytes(z))) ||
        !init(runtime_spec(v), parts.model, parts.init_work).ok()) {
      std::fprintf(stderr, "run-time storage with geometry: binding or init failed\n");
      std::exit(2);
    }
    run_model(
        o, workers, parts.model, parts.state, parts.scratch, parts.team_work,
        [&] { initial_state(parts.model, parts.state); }, row);
    return row;
  }
  auto& model = static_instance<Model<S>>();
  const InitStatus st = init(spec, model, static_instance<InitWorkspace<S>>());
  if (!st.ok()) {
    std::fprintf(stderr, "init failed (%zu elements): %s at %d\n", S.elements, to_string(st.error),
                 st.where);
    std::exit(2);
  }
  auto& state = static_instance<State<S>>();
  run_model(
      o, workers, model, state, static_instance<Scratch<S>>(), static_instance<TeamWork<S>>(),
      [&] { state = State<S>{}; }, row);
  return row;
}

template <Sizes S, class Fresh>
void run_model(const Options& o, hil::WorkerTeam& workers, Model<S>& model, State<S>& state,
               Scratch<S>& scratch, TeamWork<S>& work, Fresh fresh, Row& row) {
  // The multi-core step: the workers were made before the first size, the partition is this
  // model's (none with one thread: the single-core step).
  const Team team = workers.team();
  const Team* team_ptr = o.threads > 1 && prepare_team(model, o.threads, work) ? &team : nullptr;
  hil::LoopConfig config;
  config.period = o.period;
  config.substeps = row.substeps;
  GroundSource source{o.period, o.held};
  NullSink sink;
  std::vector<hil::Alarm> no_alarms;

  if (o.screen) {  // 1 s of frames on the virtual clock: compute only, no deadlines
    hil::VirtualClock vclock;
    hil::FrameTimes vt;
    hil::LoopConfig vc = config;
    vc.frames = static_cast<std::int64_t>(std::llround(1.0 / o.period));
    vt.reserve(vc.frames);
    fresh();
    (void)hil::run_loop(model, state, scratch, vclock, source, sink, nullptr, vc, no_alarms, vt,
                        static_cast<State<S>*>(nullptr), team_ptr, &work);
    row.screen50 = frac(hil::percentile(vt.compute_ns, 50), o.period);
    if (row.screen50 > 0.5) return;  // p50 > 0.5 already: p99.9 <= 0.5 cannot hold
  }

  config.frames = static_cast<std::int64_t>(std::llround(o.duration / o.period));
  hil::FrameTimes times;
  times.reserve(config.frames);
  fresh();
  hil::RealClock clock;
  const hil::LoopResult r =
      hil::run_loop(model, state, scratch, clock, source, sink, nullptr, config, no_alarms, times,
                    static_cast<State<S>*>(nullptr), team_ptr, &work);
  row.ran = true;
  row.frames = r.frames;
  row.diverged = r.diverged_frame >= 0;
  const double ps[4] = {50, 99, 99.9, 100};
  for (int i = 0; i < 4; ++i) {
    row.cmp[i] = frac(hil::percentile(times.compute_ns, ps[i]), o.period);
    row.lat[i] = static_cast<double>(hil::percentile(times.latency_ns, ps[i])) / 1e3;
  }
  row.overruns = times.overruns;
  row.longest_late = times.max_late_frames;
}

std::string loadavg() {
  std::ifstream f("/proc/loadavg");
  std::string a, b, c;
  f >> a >> b >> c;
  return a + " " + b + " " + c;
}

void print_header() {
  std::printf(
      "| elements | nodes | dt (us) | substeps | compute/period p50 | p99 | p99.9 | max | "
      "wake-up latency p50 (us) | p99 | p99.9 | max | overruns | holds |\n"
      "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
}

void print_row(const Row& r) {
  if (r.dt == 0) {
    std::printf("| %d | %d | | | | | | | | | | | | not run (--max-elements) |\n", r.elements,
                r.nodes);
  } else if (!r.ran) {
    std::printf(
        "| %d | %d | %.1f | %d | | | | | | | | | | no: virtual-clock trial p50 = %.2f > 0.5, "
        "not run |\n",
        r.elements, r.nodes, r.dt * 1e6, r.substeps, r.screen50);
  } else {
    std::printf(
        "| %d | %d | %.1f | %d | %.3f | %.3f | %.3f | %.3f | %.1f | %.1f | %.1f | %.1f | %lld | "
        "%s |\n",
        r.elements, r.nodes, r.dt * 1e6, r.substeps, r.cmp[0], r.cmp[1], r.cmp[2], r.cmp[3],
        r.lat[0], r.lat[1], r.lat[2], r.lat[3], static_cast<long long>(r.overruns),
        r.diverged ? "no (diverged)" : (r.holds() ? "yes" : "no"));
  }
  std::fflush(stdout);
}

// Column and beam members in 3 elements (dt ~ 160 us, 7 substeps): two small frames (1 x 1 bay,
// 2 storeys; 2 x 2 bays, 4 storeys) that separate the platform's stalls from compute, a growing
// 4 x 4 grid, then 5 x 5 to 7 x 7 (up to 8 976 elements, where a fast core still holds 1 kHz);
// the 9 900-element frame of bench_kernel (4 elements per member, 12 substeps).
constexpr Grid kG48{1, 1, 2, 3, 3};
constexpr Grid kG252{2, 2, 4, 3, 3};
constexpr Grid kG975{4, 4, 5, 3, 3};
constexpr Grid kG1950{4, 4, 10, 3, 3};
constexpr Grid kG2535{4, 4, 13, 3, 3};
constexpr Grid kG2925{4, 4, 15, 3, 3};
constexpr Grid kG3315{4, 4, 17, 3, 3};
constexpr Grid kG3900{4, 4, 20, 3, 3};
constexpr Grid kG4896{5, 5, 17, 3, 3};
constexpr Grid kG5586{6, 6, 14, 3, 3};
constexpr Grid kG6783{6, 6, 17, 3, 3};
constexpr Grid kG8976{7, 7, 17, 3, 3};
constexpr Grid kG9900{8, 8, 11, 4, 4};

}  // namespace
}  // namespace ntn::bench

int main(int argc, char** argv) {
  using namespace ntn::bench;
  Options o;
  ntn::cli::App app{"Real-time capacity of the frame loop at 1 kHz"};
  app.add_option("--duration", o.duration, "real-time seconds per size")
      ->check(ntn::cli::Positive());
  app.add_option("--period", o.period, "frame period, s")->check(ntn::cli::Positive());
  app.add_flag("--held", o.held, "inputs held at (0.10 g, 0.05 g) instead of two sines");
  app.add_option("--cpu", o.cpu, "pin to this CPU (and worker k to the k-th next one)");
  app.add_option("--threads", o.threads, "workers of the multi-core step (1: single-core)")
      ->check(ntn::cli::Integer(1, ntn::kMaxTeam));
  app.add_option("--spin", o.spin,
                 "pauses a waiting worker spins before it sleeps (large: never sleeps in a run)")
      ->check(ntn::cli::NonNegative());
  app.add_option("--max-elements", o.max_elements, "skip larger frames");
  std::string geometry = "linear";
  app.add_option("--geometry", geometry,
                 "every element's geometry: linear (compiled), p_delta or corotational (run-time "
                 "storage)")
      ->check(ntn::cli::IsMember({"linear", "p_delta", "corotational"}));
  bool no_fifo = false, no_mlock = false, no_screen = false;
  app.add_flag("--no-fifo", no_fifo, "do not ask for SCHED_FIFO");
  app.add_flag("--no-mlock", no_mlock, "do not mlockall");
  app.add_flag("--no-screen", no_screen,
               "run every size in real time, even when a 1 s virtual-clock trial has p50 > 0.5");
  if (const auto code = ntn::cli::parse(app, argc, argv)) return *code;
  o.fifo = !no_fifo, o.mlock = !no_mlock, o.screen = !no_screen;
  o.geometry = geometry == "p_delta"        ? ntn::Geometry::kPDelta
               : geometry == "corotational" ? ntn::Geometry::kCorotational
                                            : ntn::Geometry::kLinear;

  for (const std::string& w :
       ntn::hil::apply_real_time({o.fifo, o.priority, o.mlock, o.cpu, 1, 0}).warnings)
    std::fprintf(stderr, "warning: %s\n", w.c_str());
  // Made (and pinned after the loop's CPU) before any run: no thread is made in the loop.
  ntn::hil::WorkerTeam workers({o.threads, o.cpu, o.spin});
  for (const std::string& w : workers.warnings())
    std::fprintf(stderr, "warning: %s\n", w.c_str());
  std::printf(
      "# period %g ms, %g s per size, %s inputs, SCHED_FIFO %s, mlockall %s, %d thread%s, "
      "geometry %s\n",
      o.period * 1e3, o.duration, o.held ? "held" : "sine ground-motion", o.fifo ? "asked" : "off",
      o.mlock ? "asked" : "off", o.threads, o.threads == 1 ? "" : "s", geometry.c_str());
  std::printf("# load average before: %s\n", loadavg().c_str());
  print_header();
  std::vector<Row> rows;
  auto go = [&](Row r) {
    print_row(r);
    rows.push_back(r);
  };
  go(run_size<kG48>(o, workers));
  go(run_size<kG252>(o, workers));
  go(run_size<kG975>(o, workers));
  go(run_size<kG1950>(o, workers));
  go(run_size<kG2535>(o, workers));
  go(run_size<kG2925>(o, workers));
  go(run_size<kG3315>(o, workers));
  go(run_size<kG3900>(o, workers));
  go(run_size<kG4896>(o, workers));
  go(run_size<kG5586>(o, workers));
  go(run_size<kG6783>(o, workers));
  go(run_size<kG8976>(o, workers));
  go(run_size<kG9900>(o, workers));
  std::printf("# load average after: %s\n", loadavg().c_str());
  int best = -1;
  bool diverged = false;
  for (const Row& r : rows) {
    if (r.holds() && r.elements > best) best = r.elements;
    diverged = diverged || r.diverged;
  }
  if (best > 0) {
    std::printf("# largest that holds: %d elements\n", best);
  } else {
    std::printf("# no size held\n");
  }
  return diverged ? 1 : 0;
}
