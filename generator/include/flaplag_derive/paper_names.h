// flaplag-derive — the paper's names for what the derivation produces: the Appendix B names of
// the spanwise integrals (F1..F24, L1..L24, M_F, B1.., P, S, M_eta, M_gamma).
#pragma once

#include <string>
#include <vector>

#include "flaplag_derive/derive.h"

namespace flaplag::derive {

// Appendix B name of an aerodynamic integral in the flap (flap_eq) or lag equation of mode
// eq_mode (0-based), e.g. "F6_11"; "" when the paper has no name for it.
std::string paper_aero_name(bool flap_eq, int eq_mode, const AeroIntegralKey& key);
// The Appendix B names the derivation can give an aerodynamic term, without mode subscripts
// ("F1", ..., "L24"), flap first, in the paper's order: what a spec's [exclude] terms accepts.
const std::vector<std::string>& paper_aero_names();
// "F23" of "F23_112" (or of "F23_ijk"): the name without its mode subscripts.
std::string paper_base_name(const std::string& indexed);

// Appendix B name of a structural integral (generalized mass), e.g. "B3_11", "P_111"; "".
std::string paper_structural_name(bool flap_eq, int eq_mode, const StructuralIntegralKey& k);

// Appendix C names of the first-order form y' = A(psi) y + f(psi) (eqs 2.36-2.37), generalised
// to M flap and N lag modes: the equation of coordinate j feeds row i = (state column of q_j') + 1
// of A and f, state column c feeds column c + 1.  For M = N = 1 these are exactly Appendix C.2's
// A11..A14 (flap equation) and A31..A34 (lag equation) and C.3's f1 and f3.  Indices above 9 are
// written A(i,j), so that the name stays unambiguous.
std::string a_entry_name(int eq, int col, int M, int N);
std::string f_entry_name(int eq, int M, int N);

}  // namespace flaplag::derive
