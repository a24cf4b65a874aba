// Blade-setup costs: exact rotating modes (target <= 1 ms per blade) and the spanwise integrals
// evaluated from them.
#include <benchmark/benchmark.h>

#include "flaplag/blade/blade.h"
#include "flaplag/blade/rotating_modes.h"

namespace {

using flaplag::model::Factor;
using flaplag::model::FactorRef;
using flaplag::model::Inner;

// The paper's typical blade: wbar_F1 = 1.175, wbar_L1 = 1.28303, five cantilever functions.
void BM_ExactModes_Typical(benchmark::State& state) {
  for (auto _ : state) {
    flaplag::ModeSet m = flaplag::exact_modes(1.175, 1.28303);
    benchmark::DoNotOptimize(m);
  }
}
BENCHMARK(BM_ExactModes_Typical)->Unit(benchmark::kMicrosecond);

// All five modes per direction from an eight-function basis.
void BM_ExactModes_EightBasisFiveModes(benchmark::State& state) {
  flaplag::ExactModeOptions o;
  o.n_basis = 8;
  o.flap_modes = 5;
  o.lag_modes = 5;
  for (auto _ : state) {
    flaplag::ModeSet m = flaplag::exact_modes(1.175, 1.28303, o);
    benchmark::DoNotOptimize(m);
  }
}
BENCHMARK(BM_ExactModes_EightBasisFiveModes)->Unit(benchmark::kMicrosecond);

// A nested generalized mass (P_111 form) on exact modes.
void BM_StructuralIntegral_ExactNested(benchmark::State& state) {
  const flaplag::ModeSet m = flaplag::exact_modes(1.175, 1.28303);
  const FactorRef none{Factor::X0, 0};
  const flaplag::model::StructuralIntegral p{
      "P_111",
      "P_111",
      0,
      2,
      {{Factor::EtaPrime, 0}, {Factor::EtaPrime, 0}, none, none},
      Inner::Tail,
      1,
      2,
      {{Factor::Gamma, 0}, {Factor::X0, 0}, none, none},
      "P_111"};
  for (auto _ : state) {
    benchmark::DoNotOptimize(flaplag::structural_integral(p, m, 0.0));
  }
}
BENCHMARK(BM_StructuralIntegral_ExactNested)->Unit(benchmark::kMicrosecond);

// One aerodynamic integral with four exact-mode factors over the span.
void BM_AeroIntegral_ExactFourFactors(benchmark::State& state) {
  const flaplag::ModeSet m = flaplag::exact_modes(1.175, 1.28303);
  const flaplag::model::AeroIntegral a{
      "x eta eta' gamma gamma'",
      "x_eta_deta_gamma_dgamma",
      1,
      4,
      {{Factor::Eta, 0}, {Factor::EtaPrime, 0}, {Factor::Gamma, 0}, {Factor::GammaPrime, 0}},
      ""};
  const flaplag::SpanGeometry g;
  for (auto _ : state) {
    benchmark::DoNotOptimize(flaplag::aero_integral(a, m, g, 0.0, 1.0));
  }
}
BENCHMARK(BM_AeroIntegral_ExactFourFactors)->Unit(benchmark::kMicrosecond);

}  // namespace
