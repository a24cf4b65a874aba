// Rotor-level timings for the paper's typical case (assumed modes, model "paper").
//   BM_RotorPointHsu_K50_J4: one stability point at mu = 0.7 from a built system:
//                            Phi by Hsu (K = 50, J = 4) + eigen-solve + identification, in
//                            place (_WithEigenvectors: every eigenvector computed).
//   BM_RotorSystem_Build:    harmonic matrices for one mu (generated code, both regions).
//   BM_RotorSweep151_*:      151-point sweep mu = 0..1.5 (build + Phi + identification each),
//                            with the paper's fixed Hsu K = 50, J = 4 (_Hsu_K50_J4, plus the 2K
//                            evaluation of the error estimate), with the default automatic
//                            steps (_HsuAuto) and with the reference method (_MagnusAuto).
//   BM_RotorCritical_*:      the full mu_c search of `flaplag critical`, the same two settings.
//   *_ExactReversedFlow:     the same with the exact circular reversed-flow region.
#include <benchmark/benchmark.h>

#include "fixed_kernel.h"
#include "flaplag/analysis.h"
#include "flaplag/core/constants.h"
#include "flaplag/numerics/continuation.h"

namespace {

// The default options: Hsu, J = 4, automatic steps.
flaplag::Analysis typical(const flaplag::TransitionOptions& o = {}) {
  return flaplag::Analysis(flaplag::RotorParameters{}, o);
}

// The point path of the analysis: Phi into a reused matrix, the multipliers into a reused
// FloquetResult (eigenvectors on demand), the identification (eigenvectors only when two
// candidates are close); nothing allocates in the loop.
void BM_RotorPointHsu_K50_J4(benchmark::State& state) {
  const auto an = typical();
  const auto sys = an.system(0.7);
  const auto hover = flaplag::label_hover_modes(an.hover().A0, 1, 1);
  const double tr = sys.trace_integral();
  flaplag::ExponentTracker tracker(hover);
  tracker.advance(flaplag::floquet_exponents(flaplag::transition_matrix_hsu(sys, 50, 4), tr), 0.7);
  Eigen::MatrixXd phi;
  flaplag::FloquetResult r;
  // Advancing in place at the same mu keeps the tracker state fixed from one iteration to the
  // next, without timing a copy of it.
  for (auto _ : state) {
    flaplag::transition_matrix_hsu(sys, 50, 4, &phi);
    flaplag::floquet_exponents(phi, tr, flaplag::FloquetVectors::OnDemand, &r);
    benchmark::DoNotOptimize(tracker.advance(r, 0.7));
  }
}
BENCHMARK(BM_RotorPointHsu_K50_J4);

// The same with every eigenvector computed and matched (the point path before issue 10's
// identification work), for comparison.
void BM_RotorPointHsu_K50_J4_WithEigenvectors(benchmark::State& state) {
  const auto an = typical();
  const auto sys = an.system(0.7);
  const auto hover = flaplag::label_hover_modes(an.hover().A0, 1, 1);
  const double tr = sys.trace_integral();
  flaplag::ExponentTracker tracker(hover);
  tracker.advance(flaplag::floquet_exponents(flaplag::transition_matrix_hsu(sys, 50, 4), tr), 0.7);
  for (auto _ : state) {
    const auto phi = flaplag::transition_matrix_hsu(sys, 50, 4);
    benchmark::DoNotOptimize(tracker.advance(flaplag::floquet_exponents(phi, tr), 0.7));
  }
}
BENCHMARK(BM_RotorPointHsu_K50_J4_WithEigenvectors);

// The comparison kernel (bench/fixed_kernel.h) on the same system: the arithmetic floor.
void BM_RotorPointHsu_K50_J4_FixedKernel(benchmark::State& state) {
  const auto an = typical();
  const flaplag::bench::FixedKernel k(an.system(0.7), 50);
  for (auto _ : state) benchmark::DoNotOptimize(k.eigenvalues());
}
BENCHMARK(BM_RotorPointHsu_K50_J4_FixedKernel);

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

// The 1974 program's RK4 (paper 4.2, step 2a): the equations are integrated four times, once
// per column of Phi, and A(psi) is rebuilt from its harmonics at every stage.  This is the
// RK4 of the paper's Fig 4 CPU-time comparison, kept here only to reproduce that comparison;
// flaplag's own RK4 (BM_RotorPointRK4_N50, transition_bench) advances all columns at once.
void BM_RotorPhi_RK4_N50_ColumnByColumn1974(benchmark::State& state) {
  const auto an = typical();
  const auto sys = an.system(0.7);
  const int n = sys.n, N = 50;
  const double h = flaplag::kTwoPi / N;
  for (auto _ : state) {
    Eigen::MatrixXd phi(n, n);
    for (int col = 0; col < n; ++col) {
      Eigen::VectorXd y = Eigen::VectorXd::Unit(n, col);
      for (int k = 0; k < N; ++k) {
        const double psi = k * h;
        const Eigen::VectorXd k1 = sys.A(psi) * y;
        const Eigen::VectorXd k2 = sys.A(psi + 0.5 * h) * (y + 0.5 * h * k1);
        const Eigen::VectorXd k3 = sys.A(psi + 0.5 * h) * (y + 0.5 * h * k2);
        const Eigen::VectorXd k4 = sys.A(psi + h) * (y + h * k3);
        y += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
      }
      phi.col(col) = y;
    }
    benchmark::DoNotOptimize(phi);
  }
}
BENCHMARK(BM_RotorPhi_RK4_N50_ColumnByColumn1974);

void BM_RotorPhi_Hsu_K50_J4(benchmark::State& state) {
  const auto an = typical();
  const auto sys = an.system(0.7);
  for (auto _ : state) benchmark::DoNotOptimize(flaplag::transition_matrix_hsu(sys, 50, 4));
}
BENCHMARK(BM_RotorPhi_Hsu_K50_J4);

// The automatic rule's first pair, K = 100 and K / 2 = 50: in one pass (the coarse intervals
// take the sums of the fine ones) and as the two separate products it replaces.
void BM_RotorPhi_HsuPair_K100_K50(benchmark::State& state) {
  const auto an = typical();
  const auto sys = an.system(0.7);
  Eigen::MatrixXd phi, half;
  for (auto _ : state) {
    flaplag::transition_matrix_hsu_pair(sys, 100, 4, &phi, &half);
    benchmark::DoNotOptimize(phi.data());
    benchmark::DoNotOptimize(half.data());
  }
}
BENCHMARK(BM_RotorPhi_HsuPair_K100_K50);

void BM_RotorPhi_Hsu_K100_Then_K50(benchmark::State& state) {
  const auto an = typical();
  const auto sys = an.system(0.7);
  Eigen::MatrixXd phi, half;
  for (auto _ : state) {
    flaplag::transition_matrix_hsu(sys, 100, 4, &phi);
    flaplag::transition_matrix_hsu(sys, 50, 4, &half);
    benchmark::DoNotOptimize(phi.data());
    benchmark::DoNotOptimize(half.data());
  }
}
BENCHMARK(BM_RotorPhi_Hsu_K100_Then_K50);

// The periodic forced response of the typical case at mu = 0.8 (RK4 monodromy with its step
// doubling, then the samples): the kernel of every trim and response.
void BM_RotorResponse_Mu08(benchmark::State& state) {
  const auto an = typical();
  for (auto _ : state) benchmark::DoNotOptimize(an.response(0.8));
}
BENCHMARK(BM_RotorResponse_Mu08)->Unit(benchmark::kMicrosecond);

void BM_RotorSystem_Build(benchmark::State& state) {
  const auto an = typical();
  for (auto _ : state) benchmark::DoNotOptimize(an.system(0.7));
}
BENCHMARK(BM_RotorSystem_Build);

void BM_RotorSweep151_Hsu_K50_J4(benchmark::State& state) {
  const auto an = typical(flaplag::TransitionOptions::Paper());
  for (auto _ : state) benchmark::DoNotOptimize(an.sweep(0.0, 1.5, 0.01));
}
BENCHMARK(BM_RotorSweep151_Hsu_K50_J4)->Unit(benchmark::kMicrosecond);

// The argument is the number of threads (the stretches of the sweep: Analysis::sweep); wall time.
void BM_RotorSweep151_HsuAuto(benchmark::State& state) {
  const auto an = typical();
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(an.sweep(0.0, 1.5, 0.01, threads));
}
BENCHMARK(BM_RotorSweep151_HsuAuto)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);

// The same sweep with the reference method (Magnus4 + Richardson, sixth order).
void BM_RotorSweep151_MagnusAuto(benchmark::State& state) {
  flaplag::TransitionOptions o;
  o.method = flaplag::TransitionMethod::Magnus4;
  const auto an = typical(o);
  for (auto _ : state) benchmark::DoNotOptimize(an.sweep(0.0, 1.5, 0.01));
}
BENCHMARK(BM_RotorSweep151_MagnusAuto)->Unit(benchmark::kMicrosecond);

void BM_RotorCritical_Hsu_K50_J4(benchmark::State& state) {
  const auto an = typical(flaplag::TransitionOptions::Paper());
  for (auto _ : state) benchmark::DoNotOptimize(an.critical({}));
}
BENCHMARK(BM_RotorCritical_Hsu_K50_J4)->Unit(benchmark::kMicrosecond);

void BM_RotorCritical_HsuAuto(benchmark::State& state) {
  const auto an = typical();
  for (auto _ : state) benchmark::DoNotOptimize(an.critical({}));
}
BENCHMARK(BM_RotorCritical_HsuAuto)->Unit(benchmark::kMicrosecond);

// The reference method (Magnus4 + Richardson, sixth order) with automatic steps.
void BM_RotorCritical_MagnusAuto(benchmark::State& state) {
  flaplag::TransitionOptions o;
  o.method = flaplag::TransitionMethod::Magnus4;
  const auto an = typical(o);
  for (auto _ : state) benchmark::DoNotOptimize(an.critical({}));
}
BENCHMARK(BM_RotorCritical_MagnusAuto)->Unit(benchmark::kMicrosecond);

// One point with the reference method (`flaplag --method magnus point --mu 0.8`): the
// continuation from hover in the CLI's steps of 0.01 and the point at the analysis's tolerance.
void BM_RotorPoint_MagnusAuto_Mu08(benchmark::State& state) {
  flaplag::TransitionOptions o;
  o.method = flaplag::TransitionMethod::Magnus4;
  const auto an = typical(o);
  for (auto _ : state) benchmark::DoNotOptimize(an.point(0.8, 0.01));
}
BENCHMARK(BM_RotorPoint_MagnusAuto_Mu08)->Unit(benchmark::kMicrosecond);

void BM_RotorAnalysis_Setup(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(typical());
}
BENCHMARK(BM_RotorAnalysis_Setup)->Unit(benchmark::kMicrosecond);

// The exact circular reversed-flow region (exact_reversed_flow, docs/validation.md): one system
// build (the Chebyshev table of the region) and the mu_c search, against the sector's
// BM_RotorSystem_Build and BM_RotorCritical_HsuAuto.
flaplag::Analysis typical_exact_region() {
  flaplag::RotorParameters p;
  p.exact_reversed_flow = true;
  return flaplag::Analysis(p, {});
}

void BM_RotorSystem_Build_ExactReversedFlow(benchmark::State& state) {
  const auto an = typical_exact_region();
  for (auto _ : state) benchmark::DoNotOptimize(an.system(0.7));
}
BENCHMARK(BM_RotorSystem_Build_ExactReversedFlow)->Unit(benchmark::kMicrosecond);

void BM_RotorCritical_HsuAuto_ExactReversedFlow(benchmark::State& state) {
  const auto an = typical_exact_region();
  for (auto _ : state) benchmark::DoNotOptimize(an.critical({}));
}
BENCHMARK(BM_RotorCritical_HsuAuto_ExactReversedFlow)->Unit(benchmark::kMicrosecond);

}  // namespace
