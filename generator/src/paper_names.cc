// The paper's names (Appendix B) of the spanwise integrals the derivation produces, as a
// function of the equation (the Galerkin weight eta_i or gamma_i) and the integral's key.
#include "flaplag_derive/paper_names.h"

#include <algorithm>
#include <sstream>

namespace flaplag::derive {

namespace {

// Paper coefficient names (Appendix B), with the definitions the derivation produces.  Kinds
// are listed in the order of the paper's indices after the equation index i.
struct PaperAero {
  const char* name;
  bool flap;  // weight eta_i (flap) or gamma_i (lag)
  int x_power;
  std::vector<FactorKind> kinds;
};

const std::vector<PaperAero>& paper_aero_table() {
  using K = FactorKind;
  static const std::vector<PaperAero> t = {
      {"F1", true, 2, {}},
      {"F2", true, 1, {}},
      {"F3", true, 0, {}},
      {"F6", true, 1, {K::EtaPrime}},
      {"F7", true, 0, {K::EtaPrime}},
      {"F8", true, 1, {K::Eta}},
      {"F9", true, 0, {K::Eta}},
      {"F10", true, 1, {K::Gamma}},
      {"F11", true, 0, {K::Gamma}},
      {"F14", true, 0, {K::EtaPrime, K::Gamma}},
      {"F15", true, 0, {K::Eta, K::Gamma}},
      {"F21", true, 1, {K::GammaPrime}},
      {"F22", true, 0, {K::GammaPrime}},
      {"F23", true, 0, {K::EtaPrime, K::GammaPrime}},
      {"F24", true, 0, {K::Eta, K::GammaPrime}},
      {"L1", false, 1, {}},
      {"L2", false, 0, {}},
      {"L4", false, 2, {}},
      {"L7", false, 1, {K::Eta}},
      {"L8", false, 0, {K::Eta}},
      {"L10", false, 1, {K::EtaPrime}},
      {"L11", false, 0, {K::EtaPrime}},
      {"L13", false, 0, {K::Gamma}},
      {"L14", false, 1, {K::Gamma}},
      {"L16", false, 0, {K::EtaPrime, K::Gamma}},
      {"L17", false, 0, {K::EtaPrime, K::Eta}},
      {"L18", false, 0, {K::Eta, K::Eta}},
      {"L20", false, 0, {K::GammaPrime}},
      {"L21", false, 0, {K::EtaPrime, K::GammaPrime}},
      {"L22", false, 0, {K::Eta, K::GammaPrime}},
      {"L23", false, 1, {K::GammaPrime}},
      {"L24", false, 0, {K::EtaPrime, K::EtaPrime}},
  };
  return t;
}

// Assigns modes of `rest` to the kinds in paper order; "" when no entry matches.
std::string indexed_name(const char* base, int eq_mode, const std::vector<FactorKind>& kinds,
                         std::vector<ShapeFactor> rest) {
  std::ostringstream os;
  os << base << "_" << eq_mode + 1;
  for (FactorKind k : kinds) {
    auto it =
        std::find_if(rest.begin(), rest.end(), [k](const ShapeFactor& f) { return f.kind == k; });
    if (it == rest.end()) return "";
    os << it->mode + 1;
    rest.erase(it);
  }
  return rest.empty() ? os.str() : "";
}

}  // namespace

const std::vector<std::string>& paper_aero_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const auto& e : paper_aero_table()) v.emplace_back(e.name);
    return v;
  }();
  return names;
}

std::string paper_base_name(const std::string& indexed) {
  return indexed.substr(0, indexed.find('_'));
}

std::string paper_aero_name(bool flap_eq, int eq_mode, const AeroIntegralKey& key) {
  const ShapeFactor weight{flap_eq ? FactorKind::Eta : FactorKind::Gamma, eq_mode};
  std::vector<ShapeFactor> rest = key.factors;
  auto w = std::find(rest.begin(), rest.end(), weight);
  if (w == rest.end()) return "";
  rest.erase(w);
  for (const auto& e : paper_aero_table()) {
    if (e.flap != flap_eq || e.x_power != key.x_power || e.kinds.size() != rest.size()) continue;
    std::vector<FactorKind> a = e.kinds, b;
    for (const auto& f : rest) b.push_back(f.kind);
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    if (a == b) return indexed_name(e.name, eq_mode, e.kinds, rest);
  }
  return "";
}

// Structural generalized masses (Appendix B) as derived.  Signature: weight-free outer kinds |
// inner kind | inner kinds, with mass flags.
std::string paper_structural_name(bool flap_eq, int eq_mode, const StructuralIntegralKey& k) {
  using K = FactorKind;
  std::vector<ShapeFactor> outer = k.outer;
  // The Galerkin weight is eta_i / gamma_i (local terms) or its slope (tension terms).
  const ShapeFactor w0{flap_eq ? K::Eta : K::Gamma, eq_mode};
  const ShapeFactor w1{flap_eq ? K::EtaPrime : K::GammaPrime, eq_mode};
  bool slope_weight = false;
  auto it = std::find(outer.begin(), outer.end(), w0);
  if (k.inner == InnerKind::Tail) {
    it = std::find(outer.begin(), outer.end(), w1);
    slope_weight = true;
  }
  if (it == outer.end()) return "";
  outer.erase(it);
  const std::string i = std::to_string(eq_mode + 1);
  auto kinds_are = [](const std::vector<ShapeFactor>& v, std::vector<K> want) {
    if (v.size() != want.size()) return false;
    for (size_t j = 0; j < v.size(); ++j) {
      if (v[j].kind != want[j]) return false;
    }
    return true;
  };
  auto idx = [](const std::vector<ShapeFactor>& v) {
    std::string s;
    for (const auto& f : v) s += std::to_string(f.mode + 1);
    return s;
  };
  if (k.inner == InnerKind::None && k.outer_mass == 1) {
    if (flap_eq && kinds_are(outer, {K::Eta})) return "M_F" + i + idx(outer);
    if (!flap_eq && kinds_are(outer, {K::Gamma})) return "M_L" + i + idx(outer);
    if (!flap_eq && kinds_are(outer, {K::Eta})) return "B7_" + i + idx(outer);
    if (!flap_eq && kinds_are(outer, {K::X0})) return "B11_" + i;
  }
  if (k.inner == InnerKind::Tail && slope_weight && k.inner_mass == 1) {
    const bool arm = kinds_are(k.inner_factors, {K::Arm});
    if (flap_eq && outer.empty() && arm) return "B1_" + i;
    if (!flap_eq && outer.empty() && arm) return "B10_" + i;
    if (flap_eq && outer.empty() && kinds_are(k.inner_factors, {K::Gamma}))
      return "B3_" + i + idx(k.inner_factors);
    if (!flap_eq && outer.empty() && kinds_are(k.inner_factors, {K::Gamma}))
      return "B8_" + i + idx(k.inner_factors);
    if (flap_eq && kinds_are(outer, {K::EtaPrime}) && kinds_are(k.inner_factors, {K::Gamma}))
      return "P_" + i + idx(outer) + idx(k.inner_factors);
    if (!flap_eq && kinds_are(outer, {K::GammaPrime}) && kinds_are(k.inner_factors, {K::Gamma}))
      return "S_" + i + idx(outer) + idx(k.inner_factors);
  }
  if (k.inner == InnerKind::Head && k.outer_mass == 1 && outer.empty() && !flap_eq) {
    if (kinds_are(k.inner_factors, {K::EtaPrime, K::EtaPrime}))
      return "Meta_" + i + idx(k.inner_factors);
    if (kinds_are(k.inner_factors, {K::GammaPrime, K::GammaPrime}))
      return "Mgamma_" + i + idx(k.inner_factors);
  }
  return "";
}

std::string a_entry_name(int eq, int col, int M, int N) {
  const int i = model::rate_index(eq, M, N) + 1, j = col + 1;
  if (i <= 9 && j <= 9) return "A" + std::to_string(i) + std::to_string(j);
  return "A(" + std::to_string(i) + "," + std::to_string(j) + ")";
}

std::string f_entry_name(int eq, int M, int N) {
  return "f" + std::to_string(model::rate_index(eq, M, N) + 1);
}

}  // namespace flaplag::derive
