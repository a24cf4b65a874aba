// Studies and maps of issue 9 ("Speed"), through the analysis library (study.h) with the
// default transition options (Hsu, J = 4, automatic error-controlled steps), assumed modes:
//   BM_Study_OmegaLag_47:     `flaplag study --vary omega-lag=0.2:2.5:0.05` (47 rows: mu_c and
//                             every instability interval up to mu_max = 2), 2 threads;
//                             goal <= 0.5 s wall.
//   BM_Map_OmegaLag_Mu_200x200: a 200 x 200 map, omega_lag = 0.3 + 0.011 i (0.3 .. 2.489) by
//                             mu = 0.01 j (0 .. 1.99), largest zeta per cell, 2 threads;
//                             goal <= 1 s wall.
//   BM_Map_..._Paper:         the same map with the paper's fixed Hsu K = 50, J = 4.
//   BM_Map_OmegaLag_Mu_1000x1000: issue 10's map of 10^6 points, omega_lag = 0.3 + 0.0022 i
//                             (0.3 .. 2.4978) by mu = 0.002 j (0 .. 1.998), 2 threads, one
//                             iteration (about ten seconds); goal <= 5 s wall.
//   BM_Map_OmegaLag_Mu_100x1000: every tenth omega_lag line of that map (10^5 points, the same
//                             mu grid): each line is an independent continuation in mu on the
//                             pool, so the full map costs ten times this (the repeatable
//                             measurement; the full one checks the extrapolation).
// Wall-clock times (UseRealTime): the work runs on a pool of threads.
#include <benchmark/benchmark.h>

#include "flaplag/analysis.h"
#include "flaplag/study.h"

namespace {

void BM_Study_OmegaLag_47(benchmark::State& state) {
  flaplag::StudyOptions o;
  o.parameter = "omega_lag";
  for (int i = 0; i <= 46; ++i) o.values.push_back(0.2 + 0.05 * i);
  o.threads = 2;
  for (auto _ : state)
    benchmark::DoNotOptimize(flaplag::run_study(flaplag::RotorParameters{}, {}, o));
}
BENCHMARK(BM_Study_OmegaLag_47)->Unit(benchmark::kMillisecond)->UseRealTime();

flaplag::MapOptions map_200x200() {
  flaplag::MapOptions o;
  o.x.parameter = "omega_lag";
  o.y.parameter = "mu";
  for (int i = 0; i < 200; ++i) {
    o.x.values.push_back(0.3 + 0.011 * i);
    o.y.values.push_back(0.01 * i);
  }
  o.threads = 2;
  return o;
}

void BM_Map_OmegaLag_Mu_200x200(benchmark::State& state) {
  const flaplag::MapOptions o = map_200x200();
  for (auto _ : state)
    benchmark::DoNotOptimize(flaplag::run_map(flaplag::RotorParameters{}, {}, o));
}
BENCHMARK(BM_Map_OmegaLag_Mu_200x200)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Map_OmegaLag_Mu_200x200_Paper(benchmark::State& state) {
  const flaplag::MapOptions o = map_200x200();
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        flaplag::run_map(flaplag::RotorParameters{}, flaplag::TransitionOptions::Paper(), o));
  }
}
BENCHMARK(BM_Map_OmegaLag_Mu_200x200_Paper)->Unit(benchmark::kMillisecond)->UseRealTime();

flaplag::MapOptions map_million(int stride) {
  flaplag::MapOptions o;
  o.x.parameter = "omega_lag";
  o.y.parameter = "mu";
  for (int i = 0; i < 1000; i += stride) o.x.values.push_back(0.3 + 0.0022 * i);
  for (int j = 0; j < 1000; ++j) o.y.values.push_back(0.002 * j);
  o.threads = 2;
  return o;
}

void BM_Map_OmegaLag_Mu_1000x1000(benchmark::State& state) {
  const flaplag::MapOptions o = map_million(1);
  for (auto _ : state)
    benchmark::DoNotOptimize(flaplag::run_map(flaplag::RotorParameters{}, {}, o));
}
BENCHMARK(BM_Map_OmegaLag_Mu_1000x1000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

void BM_Map_OmegaLag_Mu_100x1000(benchmark::State& state) {
  const flaplag::MapOptions o = map_million(10);
  for (auto _ : state)
    benchmark::DoNotOptimize(flaplag::run_map(flaplag::RotorParameters{}, {}, o));
}
BENCHMARK(BM_Map_OmegaLag_Mu_100x1000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
