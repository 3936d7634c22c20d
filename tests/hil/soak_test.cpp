// Soak: the default model config/frame3d.toml (pinned beam ends through
// member-end releases, ntn_exact) in the frame loop on the virtual clock, fed El Centro over and
// over through the input gate, for 10^7 kernel steps (label soak) or 10^5 (default check).
// Checked over every step of the run:
// - no allocation once the loop runs (tests/support's counter of malloc and operator new);
// - the relative displacement in every rigid hinge direction (d = B u, DESIGN §7) stays at
//   rounding level;
// - the discrete energy balance of central difference holds to rounding: with
//   E_{n+1/2} = 1/2 v_{n+1/2}^T M v_{n+1/2} + 1/2 u_n^T K u_{n+1}, the scheme (DESIGN §5) gives
//   exactly E_{n+1/2} - E_{n-1/2} = dt vbar^T p_n - dt vbar^T C v_{n-1/2},
//   vbar = (v_{n+1/2} + v_{n-1/2}) / 2 (constraint forces do no work on the admissible vbar);
// - the energy stays below the a-priori bound of the damped model under inputs in their range
//   (ntn::hil::response_energy_bound) and the loop's divergence check never fires;
// - with a periodic input the response settles to its periodic steady state: the peak energy of
//   each repetition of the record converges at the rate the damping predicts (no drift);
// - a second run gives the same hash of every frame's outputs and flags, and the same state.
#include <gtest/gtest.h>
#include <xxhash.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "ntn/hil/gate.hpp"
#include "ntn/hil/loop.hpp"
#include "ntn/kernel.hpp"
#include "record.hpp"
#include "support/alloc_counter.hpp"
#include "support/init_model.hpp"
#include NTN_MODEL_HEADER

namespace {

namespace mdl = NTN_MODEL_NS;
constexpr ntn::Sizes kS = mdl::kSizes;
constexpr std::size_t kDofs = ntn::Model<kS>::kDofs;
constexpr double kEps = std::numeric_limits<double>::epsilon();

ntn::Model<kS> model;
ntn::State<kS> state, checkpoint;
ntn::Scratch<kS> scratch;

// El Centro sampled at the frame times (as ntn-hil's file source does), repeated.
struct CyclicSource {
  const std::vector<double>* samples;
  ntn::hil::InputGate* gate;
  void frame_inputs(std::int64_t k, std::span<double> v, std::uint16_t& flags) {
    const std::array<double, 1> x{(*samples)[static_cast<std::size_t>(k) % samples->size()]};
    gate->begin_frame(k);
    (void)gate->accept_values(k, x);
    gate->end_frame(v, flags);
  }
};

// Hashes every frame's outputs and flags; optionally measures energy and constraints per step.
struct SoakSink {
  bool measure = false;
  int substeps = 1;
  std::int64_t cycle_frames = 1;
  XXH3_state_t* hash = XXH3_createState();
  std::uint16_t flags_or = 0;
  // energy
  std::int64_t steps = 0;
  long double e_start = 0, work_in = 0, work_damp = 0;  // J; long double: the sums of 10^7 terms
  double energy_max = 0;                                // J
  double balance_max = 0;                               // J, max |E_n - E_start - W_in + W_d|
  long double rounding = 0;  // J: eps x every term the balance sums, over all steps so far
  double rounding_at_balance_max = 0;
  double balance_ratio_max = 0;      // max over steps of |balance| / rounding
  std::vector<double>* cycle_peaks;  // peak E per repetition of the record (reserved)
  // constraints: the largest |d| of a rigid direction, absolute and in units of eps x scale
  double d_trans_max = 0, d_rot_max = 0, d_ratio_max = 0;
  std::array<double, kDofs> v_prev{};

  explicit SoakSink(std::vector<double>* peaks) : cycle_peaks(peaks) { XXH3_64bits_reset(hash); }
  ~SoakSink() { XXH3_freeState(hash); }
  SoakSink(const SoakSink&) = delete;
  SoakSink& operator=(const SoakSink&) = delete;

  void frame_outputs(std::int64_t, std::span<const double> v, std::uint16_t flags) {
    XXH3_64bits_update(hash, v.data(), v.size_bytes());
    XXH3_64bits_update(hash, &flags, sizeof flags);
    flags_or |= flags;
  }

  // After step n: s.u = u_{n+1}, s.v = v_{n+1/2}, w.a = a_n, w.f = K u_n (frame3d has no hinge
  // springs, so F_n is the elements' K u_n), P_n = external_load; v_{n-1/2} = v_{n+1/2} - dt a_n.
  void after_step(const ntn::State<kS>& s, const ntn::Scratch<kS>& w) {
    if (!measure) return;
    const double dt = model.dt;
    double kin = 0, strain = 0, in = 0, damp = 0, magnitude = 0;
    // The damping's velocity: v_n = vbar (damping_velocity = "central"), else v_{n-1/2}.
    const bool central = model.damping_velocity == ntn::DampingVelocity::kCentral;
    for (std::size_t j = 0; j < kDofs; ++j) {
      const double vp = s.v[j] - dt * w.a[j];
      const double vbar = 0.5 * (s.v[j] + vp);
      const double vd = central ? vbar : vp;
      const double m = model.mass[j];
      const double p = ntn::external_load(model, w, j);
      kin += m * s.v[j] * s.v[j];
      strain += w.f[j] * s.u[j];
      in += vbar * p;
      damp += vbar * model.damping[j] * vd;
      magnitude += m * s.v[j] * s.v[j] + std::abs(w.f[j] * s.u[j]) +
                   dt * (std::abs(vbar * p) + std::abs(vbar * model.damping[j] * vd)) +
                   (steps == 0 ? m * vp * vp : 0.0);
      if (steps == 0) v_prev[j] = vp;
    }
    if (steps == 0) {
      // E_{-1/2} = 1/2 v_{-1/2}^T M v_{-1/2}: the run starts from rest, u_0 = 0.
      double e = 0;
      for (std::size_t j = 0; j < kDofs; ++j)
        e += model.mass[j] * v_prev[j] * v_prev[j];
      e_start = 0.5L * e;
    }
    const double energy = 0.5 * (kin + strain);
    work_in += static_cast<long double>(dt * in);
    work_damp += static_cast<long double>(dt * damp);
    rounding += static_cast<long double>(kEps * magnitude);
    const double balance = static_cast<double>(energy - e_start - work_in + work_damp);
    if (std::abs(balance) > balance_max) {
      balance_max = std::abs(balance);
      rounding_at_balance_max = static_cast<double>(rounding);
    }
    balance_ratio_max =
        std::max(balance_ratio_max, std::abs(balance) / static_cast<double>(rounding));
    energy_max = std::max(energy_max, energy);
    const auto cycle = static_cast<std::size_t>(steps / substeps / cycle_frames);
    if (cycle < cycle_peaks->size())
      (*cycle_peaks)[cycle] = std::max((*cycle_peaks)[cycle], energy);
    // Rigid hinge directions: d = B u_{n+1} after the step's projection.
    for (std::size_t h = 0; h < kS.hinges; ++h) {
      const ntn::HingeData& hd = model.hinges[h];
      const auto i1 = static_cast<std::size_t>(6 * hd.node1);
      const bool ground = hd.node2 == ntn::kGround;
      const auto i2 = ground ? 0 : static_cast<std::size_t>(6 * hd.node2);
      double d[6];
      ntn::hinge_relative(hd, &s.u[i1], ground ? nullptr : &s.u[i2], d);
      double trans = 0, rot = 0;  // the size of what d is computed from
      for (std::size_t c = 0; c < 3; ++c) {
        trans = std::max({trans, std::abs(s.u[i1 + c]), ground ? 0.0 : std::abs(s.u[i2 + c])});
        rot = std::max({rot, std::abs(s.u[i1 + 3 + c]), ground ? 0.0 : std::abs(s.u[i2 + 3 + c])});
      }
      const double lever = std::abs(hd.eccentricity[0]) + std::abs(hd.eccentricity[1]) +
                           std::abs(hd.eccentricity[2]);
      trans += lever * rot;
      for (int k = 0; k < 6; ++k) {
        if (!((hd.rigid >> k) & 1U)) continue;
        const double a = std::abs(d[k]);
        const double scale = k < 3 ? trans : rot;
        (k < 3 ? d_trans_max : d_rot_max) = std::max(k < 3 ? d_trans_max : d_rot_max, a);
        if (scale > 0) d_ratio_max = std::max(d_ratio_max, a / (kEps * scale));
        if (scale == 0 && a > 0) d_ratio_max = std::numeric_limits<double>::infinity();
      }
    }
    ++steps;
  }
};

struct SoakRun {
  std::uint64_t output_hash = 0;
  std::uint64_t state_hash = 0;
  std::uint64_t allocations = 1;
  ntn::hil::LoopResult result;
  double wall_s = 0;
};

struct Soak : ::testing::Test {
  static std::vector<double> samples;  // El Centro per frame
  static void SetUpTestSuite() {
    ASSERT_TRUE(ntn_test::init_model(mdl::kSpec, model).ok());
    const ntn::io::ReadResult r = ntn::io::read_record(NTN_EL_CENTRO);
    ASSERT_FALSE(r.error) << r.error->format();
    const double period = mdl::kSpec.settings.frame_period;
    const auto frames = static_cast<std::int64_t>(std::ceil(r.record->duration() / period - 1e-9));
    samples.resize(static_cast<std::size_t>(frames));
    for (std::int64_t k = 0; k < frames; ++k)
      samples[static_cast<std::size_t>(k)] = r.record->at(static_cast<double>(k) * period);
  }

  static int substeps() {
    return static_cast<int>(model.substeps.count);  // N, stored once by init
  }

  static SoakRun run(std::int64_t frames, SoakSink& sink) {
    SoakRun out;
    state = {};
    ntn::hil::InputGate gate(std::span<const ntn::InputSpec>(mdl::kSpec.inputs));
    CyclicSource source{&samples, &gate};
    ntn::hil::LoopConfig config;
    config.frames = frames;
    config.period = mdl::kSpec.settings.frame_period;
    config.substeps = substeps();
    sink.substeps = config.substeps;
    sink.cycle_frames = static_cast<std::int64_t>(samples.size());
    ntn::hil::VirtualClock clock;
    ntn::hil::FrameTimes times;
    times.reserve(frames);
    std::vector<ntn::hil::Alarm> alarms(kS.outputs);  // the model file's alarms, as ntn-hil
    for (std::size_t c = 0; c < alarms.size(); ++c) {
      alarms[c].enabled = mdl::kAlarmLimits[c] > 0;
      alarms[c].limit = mdl::kAlarmLimits[c];
      alarms[c].hysteresis = mdl::kAlarmHysteresis[c];
    }
    const auto t0 = std::chrono::steady_clock::now();
    {
      const ntn_test::AllocationScope scope;
      out.result = ntn::hil::run_loop(model, state, scratch, clock, source, sink, nullptr, config,
                                      alarms, times, &checkpoint);
      out.allocations = scope.counts().allocations;
    }
    out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    out.output_hash = XXH3_64bits_digest(sink.hash);
    XXH3_state_t* h = XXH3_createState();
    XXH3_64bits_reset(h);
    XXH3_64bits_update(h, state.u.data(), sizeof state.u);
    XXH3_64bits_update(h, state.v.data(), sizeof state.v);
    out.state_hash = XXH3_64bits_digest(h);
    XXH3_freeState(h);
    return out;
  }

  // `steps` kernel steps (rounded up to whole frames), measured; then once more, unmeasured.
  static void soak(std::int64_t steps) {
    const int n = substeps();
    const std::int64_t frames = (steps + n - 1) / n;
    const auto cycles =
        static_cast<std::size_t>(frames / static_cast<std::int64_t>(samples.size()));
    std::vector<double> peaks(cycles + 1, 0.0);
    SoakSink measured(&peaks);
    measured.measure = true;
    const SoakRun a = run(frames, measured);
    std::vector<double> unused;
    SoakSink plain(&unused);
    const SoakRun b = run(frames, plain);

    const double bound = ntn::hil::response_energy_bound(model);
    const double alpha = mdl::kSpec.settings.alpha;  // 1/s, C = alpha M
    std::printf(
        "soak frame3d: %lld frames x %d substeps = %lld steps (dt %.6g s), El Centro x %.2f\n"
        "  run 1 (measured) %.2f s wall; run 2 %.2f s wall = %.0f steps/s (%.1fx real time)\n"
        "  allocations %llu / %llu; output hash %016llx / %016llx; state hash %016llx / %016llx\n"
        "  rigid hinge directions: max |d| %.3g m, %.3g rad; max |d| / (eps x scale) %.3g\n"
        "  energy: peak %.6g J; a-priori bound %.6g J (peak / bound %.3g); W_in %.6g J, W_damp "
        "%.6g J\n"
        "  balance: max |E - E0 - W_in + W_damp| %.3g J (%.3g of the peak energy; %.3g of the "
        "rounding envelope then, max ratio %.3g)\n"
        "  loop: kinetic limit %.6g J, peak kinetic %.6g J, diverged frame %lld\n",
        static_cast<long long>(frames), n, static_cast<long long>(frames * n), model.dt,
        static_cast<double>(frames) / static_cast<double>(samples.size()), a.wall_s, b.wall_s,
        static_cast<double>(frames * n) / b.wall_s,
        static_cast<double>(frames) * mdl::kSpec.settings.frame_period / b.wall_s,
        static_cast<unsigned long long>(a.allocations),
        static_cast<unsigned long long>(b.allocations),
        static_cast<unsigned long long>(a.output_hash),
        static_cast<unsigned long long>(b.output_hash),
        static_cast<unsigned long long>(a.state_hash),
        static_cast<unsigned long long>(b.state_hash), measured.d_trans_max, measured.d_rot_max,
        measured.d_ratio_max, measured.energy_max, bound, measured.energy_max / bound,
        static_cast<double>(measured.work_in), static_cast<double>(measured.work_damp),
        measured.balance_max, measured.balance_max / measured.energy_max,
        measured.balance_max / measured.rounding_at_balance_max, measured.balance_ratio_max,
        a.result.kinetic_limit, a.result.peak_kinetic,
        static_cast<long long>(a.result.diverged_frame));
    for (std::size_t c = 0; c < cycles; ++c)
      std::printf("  repetition %zu: peak energy %.17g J\n", c, peaks[c]);

    EXPECT_EQ(measured.steps, frames * n);
    EXPECT_EQ(a.allocations, 0U);
    EXPECT_EQ(b.allocations, 0U);
    // Repeatable: the same bits from the same inputs, and measuring changes nothing.
    EXPECT_EQ(a.output_hash, b.output_hash);
    EXPECT_EQ(a.state_hash, b.state_hash);
    // No false alarm of the divergence check on the stable model.
    EXPECT_EQ(a.result.diverged_frame, -1);
    EXPECT_EQ(measured.flags_or & ntn::hil::flag::kDiverged, 0);
    // Rigid directions at rounding level: d = T (u2 - u1 - phi1 x e) is a few products and sums
    // of the nodes' values, each rounded once (a few eps of their size), and the projection
    // restores it every step, so no error can accumulate: 16 eps x the size of the values.
    EXPECT_LE(measured.d_ratio_max, 16.0);
    // The balance holds to rounding: each term of each step's sums (m v^2, f u, dt vbar p,
    // dt vbar c v) passes through a few roundings (the kernel's force sums and its v and u
    // updates, the products and sums here), so |residual| stays below 16 eps x the sum of their
    // magnitudes over the run so far (the rounding envelope: a worst case, errors mostly cancel).
    EXPECT_LE(measured.balance_ratio_max, 16.0);
    // Bounded: below what no stable run from rest under inputs within their range can exceed
    // (divergence.hpp: 8 P^2 / alpha^2 from the modal impulse responses).
    EXPECT_LT(measured.energy_max, bound);
    // Periodic steady state: a solution started from rest differs from the periodic one by a
    // free vibration, which mass-proportional damping makes decay by |lambda| = sqrt(1 - alpha
    // dt) per step in every mode (lagged; central: sqrt((1 - alpha dt/2) / (1 + alpha dt/2))); the
    // peak energies of repetitions c and the last then differ by at most 2 r + r^2 of the peak, r =
    // sqrt(2) |lambda|^(steps before c) (sqrt 2: energy vs mode amplitude within 1/sqrt(2) of
    // critical damping), plus rounding: a relative eps per step, decaying by alpha dt / 2 per step,
    // sums to at most 2 eps / (alpha dt); 16 x that.
    const double noise = 16 * 2 * kEps / (alpha * model.dt);
    std::printf("  periodic steady state: rounding allowance %.3g of the peak\n", noise);
    if (cycles >= 3) {
      const double last = peaks[cycles - 1];
      for (std::size_t c = 1; c + 1 < cycles; ++c) {
        const double before = static_cast<double>(c) * static_cast<double>(samples.size() * n);
        const double x = 0.5 * alpha * model.dt;
        const double lambda2 = model.damping_velocity == ntn::DampingVelocity::kCentral
                                   ? (1.0 - x) / (1.0 + x)
                                   : 1.0 - alpha * model.dt;
        const double r = std::sqrt(2.0) * std::pow(lambda2, before / 2);
        EXPECT_LE(std::abs(peaks[c] - last), (2 * r + r * r + noise) * last) << "repetition " << c;
      }
    }
  }
};

std::vector<double> Soak::samples;

// The same code path, 10^5 steps (a few seconds): in the default check.
TEST_F(Soak, HundredThousandSteps) {
  soak(100'000);
}

// 10^7 steps (label soak; a few minutes in Release).
TEST_F(Soak, TenMillionSteps) {
  soak(10'000'000);
}

}  // namespace
