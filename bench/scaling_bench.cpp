// Cost against the state size: the paper family on exact rotating modes, k flap x k lag modes
// (models paper, paper-2x2 .. paper-5x5: 4k = 4, 8, 12, 16, 20 states), typical case.  The
// benchmark argument is k.
//   BM_ScalingPointHsu_K50_J4:   one stability point at mu = 0.8 from a built system: Phi by
//                                Hsu (K = 50, J = 4) + eigen-solve + identification (the
//                                arithmetic of BM_RotorPointHsu_K50_J4; NOT resolved from 3 x 3 on:
//                                see bench/README.md).
//   BM_ScalingFloquet_K50_J4:    Analysis::floquet(0.8) with TransitionOptions::Paper(): system
//                                build, Phi at K = 50 and at 2K for the error estimate.
//   BM_ScalingFloquet_Auto:      Analysis::floquet(0.8) with the default automatic steps
//                                (counter K: the intervals it settled on).
//   BM_ScalingCritical_Auto:     the converged mu_c search of `flaplag critical` (the default
//                                method; the search with six functions for basis_error runs
//                                beside it on the second core: wall time, CPU of all threads).
//   BM_ScalingCritical_Auto_OneThread: the same on one thread (the two searches in turn).
//   BM_ScalingCritical_HsuAuto:  the same search with Hsu asked for explicitly (one thread).
//   BM_ScalingCritical_MagnusAuto: the same search with Magnus4 asked for explicitly (one thread).
//   BM_ScalingAnalysis_Setup:    exact modes, spanwise integrals, hover (once per blade).
//   BM_RotorPointHsu_K50_J4_FixedKernel: the comparison kernel of stability_bench (one 1 x 1
//                                point's arithmetic, bench/fixed_kernel.h), measured in the same
//                                run so that the figures above can be compared across runs.
#include <benchmark/benchmark.h>

#include "fixed_kernel.h"
#include "flaplag/analysis.h"
#include "flaplag/numerics/continuation.h"

namespace {

constexpr double kMu = 0.8;

flaplag::Analysis exact(int k, const flaplag::TransitionOptions& o = {}) {
  flaplag::RotorParameters p;
  p.modes = flaplag::ModeKind::Exact;
  // The paper's five cantilever functions, the basis of these benchmarks before the converged
  // basis (12) became the default, so that the timings compare with earlier runs.  A critical
  // search now also runs again with six functions for its basis_error (about twice the time of
  // one search); the Floquet evaluations, the setup and the transition matrices do not.
  p.basis = flaplag::kPaperBasis;
  p.model = flaplag::find_model("paper", k, k).name;
  return flaplag::Analysis(p, o);
}

int size_of(const benchmark::State& state) { return static_cast<int>(state.range(0)); }

void label(benchmark::State& state) { state.counters["states"] = 4.0 * size_of(state); }

void BM_ScalingPointHsu_K50_J4(benchmark::State& state) {
  const int k = size_of(state);
  const auto an = exact(k);
  const auto sys = an.system(kMu);
  const double tr = sys.trace_integral();
  flaplag::ExponentTracker tracker(flaplag::label_hover_modes(an.hover().A0, k, k));
  tracker.advance(flaplag::floquet_exponents(flaplag::transition_matrix_hsu(sys, 50, 4), tr), kMu);
  // Advancing in place at the same mu keeps the tracker state fixed from one iteration to the
  // next, without timing a copy of it.
  Eigen::MatrixXd phi;
  flaplag::FloquetResult r;
  for (auto _ : state) {  // in place, eigenvectors on demand, as the analysis does
    flaplag::transition_matrix_hsu(sys, 50, 4, &phi);
    flaplag::floquet_exponents(phi, tr, flaplag::FloquetVectors::OnDemand, &r);
    benchmark::DoNotOptimize(tracker.advance(r, kMu));
  }
  label(state);
}
BENCHMARK(BM_ScalingPointHsu_K50_J4)->DenseRange(1, 5)->Unit(benchmark::kMicrosecond);

void BM_ScalingFloquet_K50_J4(benchmark::State& state) {
  const auto an = exact(size_of(state), flaplag::TransitionOptions::Paper());
  for (auto _ : state) benchmark::DoNotOptimize(an.floquet(kMu, 1e-5));
  label(state);
}
BENCHMARK(BM_ScalingFloquet_K50_J4)->DenseRange(1, 5)->Unit(benchmark::kMicrosecond);

void BM_ScalingFloquet_Auto(benchmark::State& state) {
  const auto an = exact(size_of(state));
  int steps = 0;
  for (auto _ : state) {
    const auto s = an.floquet(kMu, 1e-5);
    steps = s.steps;
    benchmark::DoNotOptimize(s);
  }
  label(state);
  state.counters["K"] = steps;
}
BENCHMARK(BM_ScalingFloquet_Auto)->DenseRange(1, 5)->Unit(benchmark::kMillisecond);

void critical(benchmark::State& state, const flaplag::TransitionOptions& o, int threads = 0) {
  const auto an = exact(size_of(state), o);
  flaplag::CriticalResult r;
  for (auto _ : state) {
    r = an.critical({}, threads);
    benchmark::DoNotOptimize(r);
  }
  label(state);
  state.counters["evaluations"] = r.evaluations;
  state.counters["mu_c"] = r.mu_c.value_or(0.0);
  state.counters["mu_c_error"] = r.mu_c_error.value_or(-1.0);
}

flaplag::TransitionOptions with_method(flaplag::TransitionMethod m) {
  flaplag::TransitionOptions o;
  o.method = m;
  return o;
}

// The converged mu_c of `flaplag critical` on 1 x 1 to 5 x 5 exact modes, with the default
// method and with each of Hsu and Magnus4 asked for.  One search takes a few ms (1 x 1) to
// seconds (5 x 5 with Hsu): one iteration per repetition from 3 x 3.
// Wall time (the answer's wait) with the CPU time of every thread beside it.
void BM_ScalingCritical_Auto(benchmark::State& state) { critical(state, {}); }
BENCHMARK(BM_ScalingCritical_Auto)
    ->DenseRange(1, 2)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ScalingCritical_Auto)
    ->DenseRange(3, 5)
    ->Iterations(1)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_ScalingCritical_Auto_OneThread(benchmark::State& state) { critical(state, {}, 1); }
BENCHMARK(BM_ScalingCritical_Auto_OneThread)->DenseRange(1, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ScalingCritical_Auto_OneThread)
    ->DenseRange(3, 5)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

void BM_ScalingCritical_HsuAuto(benchmark::State& state) {
  critical(state, with_method(flaplag::TransitionMethod::Hsu), 1);
}
BENCHMARK(BM_ScalingCritical_HsuAuto)->DenseRange(1, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ScalingCritical_HsuAuto)
    ->DenseRange(3, 5)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

void BM_ScalingCritical_MagnusAuto(benchmark::State& state) {
  critical(state, with_method(flaplag::TransitionMethod::Magnus4), 1);
}
BENCHMARK(BM_ScalingCritical_MagnusAuto)->DenseRange(1, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ScalingCritical_MagnusAuto)
    ->DenseRange(3, 5)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

void BM_ScalingAnalysis_Setup(benchmark::State& state) {
  const int k = size_of(state);
  for (auto _ : state) benchmark::DoNotOptimize(exact(k));
  label(state);
}
BENCHMARK(BM_ScalingAnalysis_Setup)->DenseRange(1, 5)->Unit(benchmark::kMillisecond);

// The comparison kernel (bench/README.md): the typical case's 1 x 1 point at mu = 0.7.
void BM_RotorPointHsu_K50_J4_FixedKernel(benchmark::State& state) {
  const flaplag::Analysis an(flaplag::RotorParameters{}, flaplag::TransitionOptions::Paper());
  const flaplag::bench::FixedKernel k(an.system(0.7), 50);
  for (auto _ : state) benchmark::DoNotOptimize(k.eigenvalues());
}
BENCHMARK(BM_RotorPointHsu_K50_J4_FixedKernel);

}  // namespace
