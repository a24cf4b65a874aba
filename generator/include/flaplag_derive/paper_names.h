// flaplag-derive — the paper's names for what the derivation produces: the Appendix B names of
// the spanwise integrals (F1..F24, L1..L24, M_F, B1.., P, S, M_eta, M_gamma).
#pragma once

#include <string>

#include "flaplag_derive/derive.h"

namespace flaplag::derive {

// Appendix B name of an aerodynamic integral in the flap (flap_eq) or lag equation of mode
// eq_mode (0-based), e.g. "F6_11"; "" when the paper has no name for it.
std::string paper_aero_name(bool flap_eq, int eq_mode, const AeroIntegralKey& key);

// Appendix B name of a structural integral (generalized mass), e.g. "B3_11", "P_111"; "".
std::string paper_structural_name(bool flap_eq, int eq_mode, const StructuralIntegralKey& k);

}  // namespace flaplag::derive
