// Transition-matrix benchmarks on a rotor-like 4x4 periodic system (paper Fig. 4: Hsu vs RK4).
//
// The system has the shape of the flap-lag equations, y = [g', g, h', h]: a flap mode at about
// 1.17/rev and a lightly damped lag mode at about 1.28/rev, harmonics 0..4 (H = 9 coefficient
// matrices) and a reversed-flow sector [5 pi/4, 7 pi/4) with its own harmonics.
#include <benchmark/benchmark.h>

#include <cmath>

#include "flaplag/core/constants.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/numerics/floquet.h"
#include "flaplag/rotor/hover.h"

namespace {


Eigen::MatrixXd hover_matrix() {
  Eigen::MatrixXd A(4, 4);
  A << -0.3, -1.3914, -0.1, -0.3,  //
      1.0, 0.0, 0.0, 0.0,          //
      0.05, 0.2, -0.04, -1.6388,   //
      0.0, 0.0, 1.0, 0.0;
  return A;
}

flaplag::PeriodicSystem rotor_like() {
  flaplag::PeriodicSystem s;
  s.n = 4;
  auto fill = [](flaplag::HarmonicSet& set, double sign) {
    set.A.assign(9, Eigen::MatrixXd::Zero(4, 4));
    set.A[0] = hover_matrix();
    for (int h = 1; h < 9; ++h) {
      const double w = 0.3 / ((h + 1) / 2);
      set.A[h](0, 0) = sign * 0.4 * w * std::cos(h);
      set.A[h](0, 1) = 1.2 * w * std::sin(1.3 * h);
      set.A[h](0, 3) = 0.5 * w * std::cos(0.7 * h);
      set.A[h](2, 0) = 0.2 * w * std::sin(2.1 * h);
      set.A[h](2, 1) = sign * 0.8 * w * std::cos(1.9 * h);
      set.A[h](2, 2) = 0.1 * w * std::sin(0.4 * h);
      set.A[h](2, 3) = 0.5 * w * std::cos(2.9 * h);
    }
    set.A[1](0, 1) = 1.0;
  };
  fill(s.normal, 1.0);
  fill(s.reversed, -1.0);
  s.has_sector = true;
  s.sector_begin = 1.25 * flaplag::kPi;
  s.sector_end = 1.75 * flaplag::kPi;
  return s;
}

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
  flaplag::ExponentTracker tracker(flaplag::label_hover_modes(hover_matrix(), 1, 1));
  for (auto _ : state) {
    const Eigen::MatrixXd phi = flaplag::transition_matrix_hsu(s, 50, 4);
    const flaplag::FloquetResult r = flaplag::floquet_exponents(phi, tr);
    benchmark::DoNotOptimize(tracker.advance(r));
  }
}
BENCHMARK(BM_PointHsu_K50_J4);

}  // namespace
