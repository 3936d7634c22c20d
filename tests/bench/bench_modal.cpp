// Modal analysis of large frames: the first 20 modes of the benchmark frames
// of frame_models.hpp by ntn::modal (sparse path: Spectra shift-invert Lanczos with a sparse
// LDL^T), with merged joints and with a pinned NTN hinge at every beam end. Figures:
// README.md, "Modal analysis".
//
// One analysis is one iteration (seconds each at 10 000 elements). Counters: the stage times of
// ModalResult::seconds, the sizes, f1 and f20, and for merged frames the largest relative
// residual |K phi - omega^2 M phi| / |K phi| over the 20 modes on the unsupported DOFs, with K and
// M assembled here from the kernel's element functions (hinged frames are left out: there the
// constraint forces make the plain residual nonzero). The program exits non-zero when an analysis
// fails or a residual exceeds 1e-6.
#include <benchmark/benchmark.h>

#include <Eigen/SparseCore>
#include <cmath>
#include <cstdio>
#include <vector>

#include "frame_models.hpp"
#include "ntn/modal/assembly.hpp"
#include "ntn/modal/modal.hpp"

namespace {

namespace nb = ntn::bench;

bool g_failed = false;

// max over modes of |K phi - omega^2 M phi| / |K phi| on the unsupported DOFs (no hinges).
double residual(const ntn::SpecView& v, const ntn::modal::ModalResult& r) {
  const auto n = static_cast<Eigen::Index>(6 * v.nodes.size());
  std::vector<Eigen::Triplet<double>> t;
  ntn::modal::for_each_element_stiffness(v,
                                         [&t](int i, int j, double x) { t.emplace_back(i, j, x); });
  Eigen::SparseMatrix<double> K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  const std::vector<double> m = ntn::modal::lumped_mass(v);
  double worst = 0;
  for (int i = 0; i < r.modes(); ++i) {
    const Eigen::VectorXd kphi = K * r.shapes.col(i);
    Eigen::VectorXd res = kphi;
    for (Eigen::Index j = 0; j < n; ++j)
      res(j) -= r.omega(i) * r.omega(i) * m[static_cast<std::size_t>(j)] * r.shapes(j, i);
    double num = 0, den = 0;
    for (Eigen::Index j = 0; j < n; ++j) {
      if ((v.nodes[static_cast<std::size_t>(j / 6)].fixed >> (j % 6)) & 1U) continue;
      num += res(j) * res(j), den += kphi(j) * kphi(j);
    }
    worst = std::max(worst, std::sqrt(num / den));
  }
  return worst;
}

template <nb::Grid G, nb::Joints J>
void BM_Modal(benchmark::State& state) {
  auto& spec = nb::static_instance<ntn::ModelSpec<nb::sizes_of(G, J)>>();
  nb::build_frame<G, J>(spec);
  const ntn::SpecView v = ntn::view(spec);
  ntn::modal::ModalOptions o;
  o.modes = 20;
  ntn::modal::ModalResult r;
  for (auto _ : state) {
    r = ntn::modal::modal_analysis(v, o);
    benchmark::DoNotOptimize(r.omega.data());
  }
  if (!r.ok()) {
    g_failed = true;
    state.SkipWithError(r.error.c_str());
    return;
  }
  state.counters["elements"] = static_cast<double>(v.elements.size());
  state.counters["hinges"] = static_cast<double>(v.hinges.size());
  state.counters["dofs"] = r.dofs;
  state.counters["reduced"] = r.reduced;
  state.counters["assembly_s"] = r.seconds.assembly;
  state.counters["reduction_s"] = r.seconds.reduction;
  state.counters["eigen_s"] = r.seconds.eigensolver;
  state.counters["results_s"] = r.seconds.results;
  state.counters["solves"] = r.operations;
  state.counters["f1_Hz"] = r.frequency(0);
  state.counters["f20_Hz"] = r.frequency(r.modes() - 1);
  if (J == nb::Joints::kMerged) {
    const double res = residual(v, r);
    state.counters["residual"] = res;
    if (!(res < 1e-6)) {
      g_failed = true;
      state.SkipWithError("residual above 1e-6");
    }
  }
}

// ~1 000 elements (4 x 4 bays, 5 storeys) and ~10 000 elements (8 x 8 bays, 11 storeys), the
// frames of the kernel benchmark (README.md "The frames").
constexpr nb::Grid k1k{.nx = 4, .ny = 4, .storeys = 5, .col_div = 3, .beam_div = 3};
constexpr nb::Grid k10k{.nx = 8, .ny = 8, .storeys = 11, .col_div = 4, .beam_div = 4};

BENCHMARK(BM_Modal<k1k, nb::Joints::kMerged>)
    ->Name("modal/975_elements/merged")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Modal<k1k, nb::Joints::kPinned>)
    ->Name("modal/975_elements/pinned")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Modal<k10k, nb::Joints::kMerged>)
    ->Name("modal/9900_elements/merged")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);
BENCHMARK(BM_Modal<k10k, nb::Joints::kPinned>)
    ->Name("modal/9900_elements/pinned")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return g_failed ? 1 : 0;
}
