// Transition-matrix benchmarks on the rotor-like 4x4 periodic system of tests/periodic_fixtures.h
// (paper Fig. 4: Hsu vs RK4), the same system on which transition_test checks the accuracy.
//
// The system has the shape of the flap-lag equations, y = [g', g, h', h]: a flap mode at about
// 1.17/rev and a lightly damped lag mode at about 1.28/rev, harmonics 0..4 (H = 9 coefficient
// matrices) and a reversed-flow sector [5 pi/4, 7 pi/4) with its own harmonics.
#include <benchmark/benchmark.h>

#include <cmath>

#include "fixed_kernel.h"
#include "flaplag/core/constants.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/numerics/floquet.h"
#include "flaplag/rotor/hover.h"
#include "periodic_fixtures.h"

namespace {

using flaplag::fixtures::rotor_hover_matrix;
using flaplag::fixtures::rotor_like;

void BM_Phi_RK4_N50(benchmark::State& state) {
  const flaplag::PeriodicSystem s = rotor_like();
  for (auto _ : state) benchmark::DoNotOptimize(flaplag::transition_matrix_rk4(s, 50));
}
BENCHMARK(BM_Phi_RK4_N50);

void BM_Phi_Hsu_K50_J4(benchmark::State& state) {
  const flaplag::PeriodicSystem s = rotor_like();
  for (auto _ : state) benchmark::DoNotOptimize(flaplag::transition_matrix_hsu(s, 50, 4));
}
BENCHMARK(BM_Phi_Hsu_K50_J4);

void BM_Phi_Magnus_50(benchmark::State& state) {
  const flaplag::PeriodicSystem s = rotor_like();
  for (auto _ : state) benchmark::DoNotOptimize(flaplag::transition_matrix_magnus4(s, 50));
}
BENCHMARK(BM_Phi_Magnus_50);

// One stability point as the continuation does it: Phi by Hsu, multipliers and exponents,
// and the tracker's identification step.
void BM_PointHsu_K50_J4(benchmark::State& state) {
  const flaplag::PeriodicSystem s = rotor_like();
  const double tr = s.trace_integral();
  flaplag::ExponentTracker tracker(flaplag::label_hover_modes(rotor_hover_matrix(), 1, 1));
  Eigen::MatrixXd phi;
  flaplag::FloquetResult r;
  for (auto _ : state) {  // in place, eigenvectors on demand, as the analysis does
    flaplag::transition_matrix_hsu(s, 50, 4, &phi);
    flaplag::floquet_exponents(phi, tr, flaplag::FloquetVectors::OnDemand, &r);
    benchmark::DoNotOptimize(tracker.advance(r));
  }
}
BENCHMARK(BM_PointHsu_K50_J4);

void BM_Phi_Hsu_K50_J4_FixedKernel(benchmark::State& state) {
  const flaplag::bench::FixedKernel k(rotor_like(), 50);
  for (auto _ : state) benchmark::DoNotOptimize(k.phi());
}
BENCHMARK(BM_Phi_Hsu_K50_J4_FixedKernel);

void BM_PointHsu_K50_J4_FixedKernel(benchmark::State& state) {
  const flaplag::bench::FixedKernel k(rotor_like(), 50);
  for (auto _ : state) benchmark::DoNotOptimize(k.eigenvalues());
}
BENCHMARK(BM_PointHsu_K50_J4_FixedKernel);

}  // namespace
