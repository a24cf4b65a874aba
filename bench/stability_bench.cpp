// Rotor-level timings for the paper's typical case (assumed modes, model "paper").
//   BM_RotorPointHsu_K50_J4: one stability point at mu = 0.7 from a built system:
//                            Phi by Hsu (K = 50, J = 4) + eigen-solve + identification.
//   BM_RotorSystem_Build:    harmonic matrices for one mu (generated code, both regions).
//   BM_RotorSweep151_Hsu:    151-point sweep mu = 0..1.5 (build + Phi + identification each).
//   BM_RotorCritical_Hsu:    the full mu_c search of `flaplag critical`.
#include <benchmark/benchmark.h>

#include "flaplag/analysis.h"
#include "flaplag/continuation.h"

namespace {

flaplag::Analysis typical(flaplag::TransitionMethod m = flaplag::TransitionMethod::Hsu) {
  flaplag::TransitionOptions o;
  o.method = m;
  return flaplag::Analysis(flaplag::RotorParameters{}, o);
}

void BM_RotorPointHsu_K50_J4(benchmark::State& state) {
  const auto an = typical();
  const auto sys = an.system(0.7);
  const auto hover = flaplag::label_hover_modes(an.hover().A0, 1, 1);
  const double tr = sys.trace_integral();
  flaplag::ExponentTracker tracker(hover);
  tracker.advance(flaplag::floquet_exponents(flaplag::transition_matrix_hsu(sys, 50, 4), tr));
  for (auto _ : state) {
    flaplag::ExponentTracker t = tracker;
    const auto phi = flaplag::transition_matrix_hsu(sys, 50, 4);
    benchmark::DoNotOptimize(t.advance(flaplag::floquet_exponents(phi, tr)));
  }
}
BENCHMARK(BM_RotorPointHsu_K50_J4);

void BM_RotorPointRK4_N50(benchmark::State& state) {
  const auto an = typical();
  const auto sys = an.system(0.7);
  const double tr = sys.trace_integral();
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        flaplag::floquet_exponents(flaplag::transition_matrix_rk4(sys, 50), tr));
  }
}
BENCHMARK(BM_RotorPointRK4_N50);

void BM_RotorSystem_Build(benchmark::State& state) {
  const auto an = typical();
  for (auto _ : state) benchmark::DoNotOptimize(an.system(0.7));
}
BENCHMARK(BM_RotorSystem_Build);

void BM_RotorSweep151_Hsu(benchmark::State& state) {
  const auto an = typical();
  for (auto _ : state) benchmark::DoNotOptimize(an.sweep(0.0, 1.5, 0.01));
}
BENCHMARK(BM_RotorSweep151_Hsu)->Unit(benchmark::kMicrosecond);

void BM_RotorCritical_Hsu(benchmark::State& state) {
  const auto an = typical();
  for (auto _ : state) benchmark::DoNotOptimize(an.critical({}));
}
BENCHMARK(BM_RotorCritical_Hsu)->Unit(benchmark::kMicrosecond);

void BM_RotorAnalysis_Setup(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(typical());
}
BENCHMARK(BM_RotorAnalysis_Setup)->Unit(benchmark::kMicrosecond);

}  // namespace
