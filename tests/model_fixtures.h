// Shared test fixtures: hand-built integral lists and model descriptors for the blade tests.
#pragma once

#include <vector>

#include "flaplag/model_api.h"

namespace flaplag::testing::fixtures {

using model::AeroIntegral;
using model::Factor;
using model::FactorRef;
using model::StructuralIntegral;

inline constexpr FactorRef kEta{Factor::Eta, 0};
inline constexpr FactorRef kEtaP{Factor::EtaPrime, 0};
inline constexpr FactorRef kGamma{Factor::Gamma, 0};
inline constexpr FactorRef kGammaP{Factor::GammaPrime, 0};
inline constexpr FactorRef kArm{Factor::Arm, 0};
inline constexpr FactorRef kNone{Factor::X0, 0};

inline AeroIntegral aero(const char* name, int p, std::vector<FactorRef> f) {
  AeroIntegral a{name, name, p, static_cast<int>(f.size()), {kNone, kNone, kNone, kNone}, ""};
  for (std::size_t i = 0; i < f.size(); ++i) a.factors[i] = f[i];
  return a;
}

// A 1 x 1 descriptor over the given lists (no coefficient functions).
inline model::ModelDescriptor descriptor(const std::vector<AeroIntegral>& a,
                                  const std::vector<StructuralIntegral>& s) {
  model::ModelDescriptor d{};
  d.name = "test";
  d.flap_modes = 1;
  d.lag_modes = 1;
  d.n_aero = static_cast<int>(a.size());
  d.aero = a.data();
  d.n_structural = static_cast<int>(s.size());
  d.structural = s.data();
  return d;
}

}  // namespace flaplag::testing::fixtures
