// The audit report's section on the nonlinear generalized loads (spec [emit] nonlinear): every
// term of every monomial of the full state, with the columns of the linear blocks (report.cc).
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "flaplag_derive/emit.h"
#include "flaplag_derive/operating_point.h"

namespace flaplag::derive {

namespace {

std::string value_text(double v) {
  if (std::isnan(v)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  const std::string s = buf;
  return s == "-0" ? "0" : s;
}

std::string integral_name(const DerivedModel& m, const Term& t) {
  if (t.ref == IntegralRef::Aero) return "int " + m.aero[t.integral].name;
  if (t.ref == IntegralRef::Structural) return "int " + m.structural[t.integral].name;
  return "-";
}

}  // namespace

std::string nonlinear_report_section(const DerivedModel& m) {
  if (!m.spec.nonlinear) return "";
  const PointValues pv = typical_case_values(m);
  std::ostringstream os;
  os << "\n## Nonlinear generalized loads\n\n"
     << "`mass q'' = sum_h phi_h(psi) sum_monomials coefficient * monomial`, in the *full* "
        "coordinates g, h and rates g', h' (not perturbations about hover): the same "
        "derivation and eps_D truncation of every product as above, without the degree-1 cut "
        "in the perturbation. The linear blocks above are this polynomial linearized about "
        "(g0, h0); the products of degree >= 2 are what the periodic equilibrium adds. "
        "Aerodynamic factors with (gamma/2)(l/R)^2 removed; value = the full term's "
        "coefficient of the monomial at the operating point (not divided by the mass), "
        "normal flow.\n\n";
  std::map<int, int> per_degree;
  for (const auto& s : m.nonlinear) per_degree[s.degree()] += static_cast<int>(s.slot.terms.size());
  os << "Terms by degree in the state:";
  for (const auto& [d, count] : per_degree) os << " degree " << d << ": " << count << ";";
  os << " harmonics H_nl = " << m.H_nonlinear << ".\n";
  for (int eq = 0; eq < m.n(); ++eq) {
    os << "\n### " << m.equation_name(eq) << " equation, nonlinear loads\n\n"
       << "| monomial | harmonic | factor | integral | paper | eps | origin | radial | value |\n"
       << "|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& s : m.nonlinear) {
      if (s.equation != eq) continue;
      for (const auto& t : s.slot.terms) {
        os << "| " << monomial_text(m, s.powers) << " | " << DerivedModel::harmonic_name(s.harmonic)
           << " | " << factor_text(m, t, true) << " | " << integral_name(m, t) << " | "
           << (t.paper_name.empty() ? "-" : t.paper_name) << " | " << t.eps_order << " | "
           << t.origin << " | " << (t.radial_flow ? "radial" : "") << " | "
           << value_text(pv.available ? pv.value(t) : NAN) << " |\n";
      }
    }
  }
  if (!m.nonlinear_thrust.empty()) {
    os << "\n### Rotor thrust, nonlinear\n\n"
       << "The rotor thrust of one blade (section \"Rotor thrust\" above) at the full state: "
          "the trim about the periodic equilibrium averages it along q°(psi). Factors as in that "
          "section (nothing removed).\n\n"
       << "| monomial | harmonic | factor | integral | paper | eps | origin | radial | value |\n"
       << "|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& s : m.nonlinear_thrust) {
      for (const auto& t : s.slot.terms) {
        os << "| " << monomial_text(m, s.powers) << " | " << DerivedModel::harmonic_name(s.harmonic)
           << " | " << factor_text(m, t, false) << " | " << integral_name(m, t) << " | "
           << (t.paper_name.empty() ? "-" : t.paper_name) << " | " << t.eps_order << " | "
           << t.origin << " | " << (t.radial_flow ? "radial" : "") << " | "
           << value_text(pv.available ? pv.value(t) : NAN) << " |\n";
      }
    }
  }
  return os.str();
}

}  // namespace flaplag::derive
