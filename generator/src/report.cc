// The audit report (<model>.md), laid out like the paper's Appendix C so that an auditor can
// hold one block of the report against one printed entry: A11 against the A11 block, f3 against
// the f3 block.  Within a block the structural terms come first, then the aerodynamic ones in
// the order of their Appendix B coefficient (F8 before F9 before F24), as Appendix C.2 prints
// them; terms that differ only by beta_P versus beta_D are printed as the paper's sum.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "flaplag_derive/emit.h"
#include "flaplag_derive/operating_point.h"
#include "flaplag_derive/paper_names.h"
#include "flaplag_derive/paper_print.h"

namespace flaplag::derive {

namespace {

constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

int scalar_index(const DerivedModel& m, const std::string& name) {
  for (size_t j = 0; j < m.scalars.size(); ++j) {
    if (m.scalars[j].name == name) return static_cast<int>(j);
  }
  return -1;
}

int power_of(const Term& t, int scalar) {
  for (const auto& [idx, p] : t.scalars) {
    if (idx == scalar) return p;
  }
  return 0;
}

int binomial(int k, int i) {
  int b = 1;
  for (int j = 1; j <= i; ++j) b = b * (k - i + j) / j;
  return b;
}

std::string num(double v) {
  if (std::isnan(v)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  std::string s = buf;
  return s == "-0" ? "0" : s;
}

// One printed row: a term, or the terms c precone^a droop^(k-a) C(k,a) printed as
// c (precone + droop)^k.
struct Row {
  int harmonic = 0;
  Term term;           // for a combined row: precone and droop removed from the scalars
  int beta_power = 0;  // k of (precone + droop)^k; 0 = a plain term
  std::vector<Term> members;
};

std::vector<Row> rows_of(const DerivedModel& m, const std::vector<Term>& terms, int harmonic) {
  const int ip = scalar_index(m, "precone"), id = scalar_index(m, "droop");
  auto strip = [&](const Term& t) {
    Term u = t;
    u.scalars.erase(std::remove_if(u.scalars.begin(), u.scalars.end(),
                                   [&](const auto& s) { return s.first == ip || s.first == id; }),
                    u.scalars.end());
    return u;
  };
  auto key_of = [&](const Term& t) -> std::string {
    const int k = power_of(t, ip) + power_of(t, id);
    if (k == 0) return "";
    const Term u = strip(t);
    std::ostringstream os;
    os << k << "|" << static_cast<int>(u.ref) << ":" << u.integral << "|" << u.origin << "|"
       << u.radial_flow << "|" << u.eps_order << "|" << u.paper_name;
    for (const auto& [idx, p] : u.scalars) os << "|" << idx << "^" << p;
    return os.str();
  };
  std::map<std::string, std::vector<const Term*>> groups;
  for (const auto& t : terms) {
    const std::string k = key_of(t);
    if (!k.empty()) groups[k].push_back(&t);
  }
  // A group is the expansion of c (precone + droop)^k when it has the k + 1 terms
  // c C(k, a) precone^a droop^(k - a), a = 0..k.
  auto combinable = [&](const std::vector<const Term*>& g, int k) {
    if (static_cast<int>(g.size()) != k + 1) return false;
    GiNaC::numeric c = 0;
    for (const Term* t : g) {
      if (power_of(*t, ip) == k) c = t->coef;
    }
    if (c == 0) return false;
    std::set<int> seen;
    for (const Term* t : g) {
      const int a = power_of(*t, ip);
      if (!seen.insert(a).second || t->coef != c * binomial(k, a)) return false;
    }
    return true;
  };
  std::vector<Row> rows;
  std::set<std::string> done;
  for (const auto& t : terms) {
    const std::string k = key_of(t);
    const int power = power_of(t, ip) + power_of(t, id);
    if (!k.empty() && power > 0 && combinable(groups[k], power)) {
      if (!done.insert(k).second) continue;
      Row r;
      r.harmonic = harmonic;
      r.term = strip(t);
      r.term.coef = t.coef / binomial(power, power_of(t, ip));
      r.beta_power = power;
      for (const Term* g : groups[k]) r.members.push_back(*g);
      rows.push_back(r);
      continue;
    }
    rows.push_back({harmonic, t, 0, {t}});
  }
  return rows;
}

// Appendix C order: structural and input terms first, then the aerodynamic ones by the number
// of their F / L coefficient, then by harmonic.
int coefficient_number(const Row& r) {
  if (r.term.ref != IntegralRef::Aero) return -1;
  const std::string& p = r.term.paper_name;
  if (p.size() < 2 || (p[0] != 'F' && p[0] != 'L') ||
      !std::isdigit(static_cast<unsigned char>(p[1])))
    return 999;
  return std::stoi(p.substr(1));
}

void sort_rows(std::vector<Row>& rows) {
  std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) {
    const int na = coefficient_number(a), nb = coefficient_number(b);
    if (na != nb) return na < nb;
    return a.harmonic < b.harmonic;
  });
}

std::string integral_text(const DerivedModel& m, const Term& t) {
  if (t.ref == IntegralRef::Aero) return "int " + m.aero[t.integral].name;
  if (t.ref == IntegralRef::Structural) return "int " + m.structural[t.integral].name;
  return "-";
}

// A row as a piece of the block's formula: "- lr mu sin psi F9_11".  `harmonic` is the text of
// the psi dependence ("" for const).
std::string piece(const DerivedModel& m, const Row& r, const std::string& harmonic, bool first) {
  std::string f = factor_text(m, r.term, true, r.beta_power);
  const bool neg = !f.empty() && f[0] == '-';
  if (neg) f = f.substr(1);
  std::vector<std::string> parts;
  if (f != "1") parts.push_back(f);
  if (!harmonic.empty()) parts.push_back(harmonic);
  if (!r.term.paper_name.empty()) {
    parts.push_back(r.term.paper_name);
  } else if (r.term.ref != IntegralRef::None) {
    parts.push_back("[" + integral_text(m, r.term) + "]");
  }
  if (parts.empty()) parts.push_back("1");
  std::string s = first ? (neg ? "-" : "") : (neg ? " - " : " + ");
  for (size_t j = 0; j < parts.size(); ++j) s += (j ? " " : "") + parts[j];
  return s;
}

bool same_but_harmonic(const Row& a, const Row& b) {
  return a.beta_power == b.beta_power && a.term.ref == b.term.ref &&
         a.term.integral == b.term.integral && a.term.scalars == b.term.scalars &&
         a.term.origin == b.term.origin && a.term.radial_flow == b.term.radial_flow;
}

// "{ structural + (lock/2) lr^2 [ aerodynamic ] }".  A constant and a cos 2psi term with equal
// or opposite factors are written c (1 + cos 2psi) or c (1 - cos 2psi), as the paper does.
std::string formula(const DerivedModel& m, const std::vector<Row>& rows) {
  constexpr int kCos2 = 3;  // harmonic index of cos 2psi
  std::string structural, aero;
  std::vector<bool> used(rows.size(), false);
  for (size_t j = 0; j < rows.size(); ++j) {
    if (used[j]) continue;
    const Row& r = rows[j];
    std::string harmonic = r.harmonic == 0 ? "" : DerivedModel::harmonic_name(r.harmonic);
    if (r.harmonic == 0) {
      for (size_t k = j + 1; k < rows.size(); ++k) {
        if (used[k] || rows[k].harmonic != kCos2 || !same_but_harmonic(r, rows[k])) continue;
        if (rows[k].term.coef == r.term.coef || rows[k].term.coef == -r.term.coef) {
          harmonic = rows[k].term.coef == r.term.coef ? "(1 + cos 2psi)" : "(1 - cos 2psi)";
          used[k] = true;
          break;
        }
      }
    }
    std::string& s = r.term.ref == IntegralRef::Aero ? aero : structural;
    s += piece(m, r, harmonic, s.empty());
  }
  std::string f = structural;
  if (!aero.empty()) {
    f += (f.empty() ? "" : " + ") + std::string("(lock/2) lr^2 [ ") + aero + " ]";
  }
  return "{ " + f + " }";
}

struct Block {
  std::string name;  // A11, f3
  std::string what;  // "coefficient of dg1'"
  std::vector<Row> rows;
};

class Report {
 public:
  explicit Report(const DerivedModel& m) : m_(m), n_(m.n()), pv_(typical_case_values(m)) {}
  std::string text();

 private:
  double value(const Row& r, double divisor) const {
    if (!pv_.available) return kNoValue;
    double v = 0.0;
    for (const auto& t : r.members) v += pv_.value(t);
    return v / divisor;
  }
  // The generalized mass an entry of row eq is divided by: only for M = N = 1 (diagonal mass).
  std::string divisor_name(int eq) const {
    const Slot& s = m_.mass[eq * n_ + eq];
    return s.terms.size() == 1 && !s.terms[0].paper_name.empty() ? s.terms[0].paper_name
                                                                 : "M_" + std::to_string(eq + 1);
  }
  double divisor(int eq) const {
    return pv_.available ? pv_.value(m_.mass[eq * n_ + eq]) : kNoValue;
  }
  bool single() const { return m_.M == 1 && m_.N == 1; }

  void conventions(std::ostringstream& os) const;
  void operating_point(std::ostringstream& os) const;
  void integrals(std::ostringstream& os) const;
  void mass(std::ostringstream& os) const;
  void equation(std::ostringstream& os, int eq) const;
  void block(std::ostringstream& os, int eq, const Block& b, bool forcing) const;
  void absorbed(std::ostringstream& os) const;
  void dropped(std::ostringstream& os) const;
  void equilibrium(std::ostringstream& os) const;
  void cyclic(std::ostringstream& os) const;
  void twist(std::ostringstream& os) const;
  void thrust(std::ostringstream& os) const;

  const DerivedModel& m_;
  const int n_;
  const PointValues pv_;
};

const char* const kTermHeader =
    "| entry | harmonic | factor | integral | paper | eps | origin | radial | value |\n"
    "|---|---|---|---|---|---|---|---|---|\n";

std::string Report::text() {
  std::ostringstream os;
  os << "<!--\n" << generated_header(m_, "") << "-->\n\n";
  os << "# Audit report: model `" << m_.spec.name << "`\n\n";
  os << "Generated by `flaplag-derive` from `generator/orderings/" << m_.spec.file
     << "` -- do not edit. " << m_.spec.description << ".\n\n";
  os << "## Ordering spec\n\n";
  if (!m_.spec.base.empty()) {
    os << "Inherits from `generator/orderings/" << m_.spec.base
       << ".toml` (the values below are resolved); model family `" << m_.spec.family << "`.\n\n";
  }
  os << "```toml\n" << m_.spec.canonical_text() << "```\n\n";
  conventions(os);
  operating_point(os);
  integrals(os);
  mass(os);
  for (int eq = 0; eq < n_; ++eq) equation(os, eq);
  absorbed(os);
  if (!m_.dropped.empty()) dropped(os);
  equilibrium(os);
  if (m_.spec.cyclic_pitch) {
    cyclic(os);
    twist(os);
    thrust(os);
  }
  os << nonlinear_report_section(m_);
  os << "\n" << paper_differences_section(m_);
  return os.str();
}

void Report::conventions(std::ostringstream& os) const {
  os << "## Conventions\n\n"
     << "- Equations of motion: `mass * q'' = sum_h phi_h(psi) (force[h] y + forcing[h])`, "
        "q = [g_1..g_M, h_1..h_N] (perturbations about the hover equilibrium), "
        "state y = [dg', dg, dh', dh] (eq 2.36), harmonics phi = const, cos psi, sin psi, "
        "cos 2psi, sin 2psi. As first-order system y' = A(psi) y + f(psi) (eq 2.37): "
        "A = mass^-1 force, f = mass^-1 (forcing - hover balance) in the rows of the rates.\n"
     << "- Entry names: the coefficient of state column j in the equation of coordinate q_k "
        "feeds A_ij, where i is the state row of q_k' and j the state column (1-based); its "
        "forcing feeds f_i. For one flap and one lag mode these are Appendix C.2's A11..A14 "
        "(flap), A31..A34 (lag) and C.3's f1, f3, and A_ij = (generalized-force coefficient) / "
        "M_F1 or / M_L1. For more modes the same rule generalises the names (flap k -> row k, "
        "lag m -> row 2M+m; indices above 9 are written A(i,j)) and A = mass^-1 force mixes the "
        "rows of one direction when the generalized mass is not diagonal.\n"
     << "- The displacement rows of A are the identity on the rates and have no forcing: for "
        "M = N = 1, A21 = A43 = 1, the other entries of rows 2 and 4 are 0 and f2 = f4 = 0 "
        "(Appendix C.2, C.3); in general rows M+1..2M and 2M+N+1..2M+2N.\n"
     << "- Aerodynamic factors are printed with the common factor (gamma/2)(l/R)^2 removed, as "
        "the paper writes them; the names are those of the generated code: `lock` = gamma "
        "(Lock number), `lr` = l/R, `theta`, `inflow` = lambda, `precone` = beta_P, `droop` = "
        "beta_D, `cdo_a` = C_Do/a, `mu`, `g0_k`, `h0_m` = hover static amplitudes, "
        "`omega_flap_k`, `damping_flap_k` = omega_Fk, eta_SFk (and lag), `es_*`, `ecs_*` = "
        "Ebar^s, Ebar^cs (Appendix E). `(precone + droop)` is printed where the derivation "
        "produces the beta_P and beta_D terms with equal factors (the paper's "
        "(beta_P + beta_D)).\n"
     << "- Spanwise aerodynamic integrals run over x0 from A to B with x = e1 + (l/R) x0, `tw` "
        "in an integral is the built-in twist theta_tw(x0) (rad; 0 for the paper's untwisted "
        "blade); structural integrals over 0..1 with m = m l^3/I_b.\n"
     << "- eps = the eps_D order of the term (Appendix C.1); `radial` marks terms produced by "
        "the radial-flow term mu cos(psi) dv/dx0 of U_T (eq 2.23).\n"
     << "- value = the term's contribution to the entry (full term, including (gamma/2)(l/R)^2, "
        "divided by the generalized mass of its row) at the operating point below, in normal "
        "flow (inside the reversed-flow sector of Appendix D the aerodynamic integrals take "
        "other values).\n\n";
}

void Report::operating_point(std::ostringstream& os) const {
  os << "## Operating point of the value column\n\n";
  if (!pv_.available) {
    os << "Values are not given: " << pv_.reason << ".\n\n";
    return;
  }
  const OperatingPoint& p = pv_.point;
  auto scalar = [&](const char* name) { return num(pv_.scalar[scalar_index(m_, name)]); };
  os << "The paper's typical case (Sec. 4.1; Figs 3-5 and 13): gamma = " << num(p.lock)
     << ", theta = " << num(p.theta) << ", mu = " << num(p.mu)
     << ", omega_F1 = " << num(p.omega_flap) << ", omega_L1 = " << num(p.omega_lag)
     << "; lambda = " << scalar("inflow") << " from eq 2.24 with sigma = " << num(p.solidity)
     << ", a = 2 pi; C_Do = " << num(p.cdo) << " (C_Do/a = " << scalar("cdo_a")
     << "); beta_P = beta_D = 0 and eta_SF = eta_SL = 0 (the paper's defaults); l/R = 1, "
        "A = 0, B = 1, e1 = 0 (Sec. 4.1); uniform blade, mbar = 3; the assumed mode of eq 4.1, "
        "eta1 = gamma1 = -(1/3)[1 - 4 x0 - (1 - x0)^4], for flap and lag, so Ebar^s = "
        "Ebar^cs = 0 (Sec. 4.1(a)). The spanwise integrals of the assumed-mode polynomials are "
        "exact (rational arithmetic in GiNaC). The hover equilibrium solves the derived "
        "S q0 = c (below) at that point: g0_1 = "
     << scalar("g0_1") << ", h0_1 = " << scalar("h0_1") << ".\n\n";
}

void Report::integrals(std::ostringstream& os) const {
  os << "## Spanwise aerodynamic integrals\n\n| # | integral | paper | value |\n"
        "|---|---|---|---|\n";
  for (size_t j = 0; j < m_.aero.size(); ++j) {
    os << "| " << j << " | int " << m_.aero[j].name << " dx0 | " << m_.aero[j].paper_name << " | "
       << (pv_.available ? num(pv_.aero[j].to_double()) : "-") << " |\n";
  }
  os << "\n## Structural generalized masses\n\n| # | integral | paper | value |\n"
        "|---|---|---|---|\n";
  for (size_t j = 0; j < m_.structural.size(); ++j) {
    os << "| " << j << " | int " << m_.structural[j].name << " dx0 | "
       << m_.structural[j].paper_name << " | "
       << (pv_.available ? num(pv_.structural[j].to_double()) : "-") << " |\n";
  }
}

void Report::mass(std::ostringstream& os) const {
  os << "\n## Generalized mass\n\nCoefficient of the acceleration q_j'' in equation i (the "
        "generated function `mass`); value = the term at the operating point.\n\n"
     << "| entry | factor | integral | paper | eps | origin | value |\n"
     << "|---|---|---|---|---|---|---|\n";
  for (int i = 0; i < n_; ++i) {
    for (int j = 0; j < n_; ++j) {
      for (const auto& t : m_.mass[i * n_ + j].terms) {
        os << "| " << m_.equation_name(i) << " / "
           << m_.state_name(model::displacement_index(j, m_.M, m_.N)) << "'' | "
           << factor_text(m_, t, false) << " | " << integral_text(m_, t) << " | "
           << (t.paper_name.empty() ? "-" : t.paper_name) << " | " << t.eps_order << " | "
           << t.origin << " | " << (pv_.available ? num(pv_.value(t)) : "-") << " |\n";
      }
    }
  }
}

void Report::equation(std::ostringstream& os, int eq) const {
  const int row = model::rate_index(eq, m_.M, m_.N) + 1;
  os << "\n## " << m_.equation_name(eq) << " equation: row " << row << " of A and f";
  if (single())
    os << (eq == 0 ? " (Appendix C.2 A11-A14, C.3 f1)" : " (Appendix C.2 A31-A34, C.3 f3)");
  os << "\n";
  for (int col = 0; col < 2 * n_; ++col) {
    Block b{a_entry_name(eq, col, m_.M, m_.N), "coefficient of " + m_.state_name(col), {}};
    for (int h = 0; h < m_.H; ++h) {
      const auto r = rows_of(m_, m_.force[(h * n_ + eq) * 2 * n_ + col].terms, h);
      b.rows.insert(b.rows.end(), r.begin(), r.end());
    }
    if (!b.rows.empty()) block(os, eq, b, false);
  }
  Block f{f_entry_name(eq, m_.M, m_.N), "state-independent terms", {}};
  for (int h = 0; h < m_.H; ++h) {
    const auto r = rows_of(m_, m_.forcing[h * n_ + eq].terms, h);
    f.rows.insert(f.rows.end(), r.begin(), r.end());
  }
  if (!f.rows.empty()) block(os, eq, f, true);
}

void Report::block(std::ostringstream& os, int eq, const Block& b, bool forcing) const {
  std::vector<Row> rows = b.rows, hover;
  if (forcing) {
    // The mu-free constant terms are the hover balance c - S q0, zero at the equilibrium; the
    // runtime subtracts them (f = forcing - forcing at hover).  Listed apart, as C.3 omits them.
    const int mu = scalar_index(m_, "mu");
    std::vector<Row> rest;
    for (const auto& r : rows)
      (r.harmonic == 0 && power_of(r.term, mu) == 0 ? hover : rest).push_back(r);
    rows = rest;
  }
  sort_rows(rows);
  sort_rows(hover);
  const std::string mass = divisor_name(eq);
  os << "\n### " << b.name << ": " << m_.equation_name(eq) << " equation, " << b.what << "\n\n";
  if (single()) {
    os << "`" << b.name << " = (1/" << mass << ") " << formula(m_, rows) << "`\n\n";
  } else {
    os << "Generalized-force coefficient F (A = mass^-1 F; with orthogonal modes the mass is "
          "diagonal and "
       << b.name << " = F / " << mass << "): `" << formula(m_, rows) << "`\n\n";
  }
  os << kTermHeader;
  const double div = divisor(eq);
  std::map<int, double> total;
  for (const auto& r : rows) {
    const double v = value(r, div);
    total[r.harmonic] += v;
    os << "| " << b.name << " | " << DerivedModel::harmonic_name(r.harmonic) << " | "
       << factor_text(m_, r.term, true, r.beta_power) << " | " << integral_text(m_, r.term) << " | "
       << (r.term.paper_name.empty() ? "-" : r.term.paper_name) << " | " << r.term.eps_order
       << " | " << r.term.origin << " | " << (r.term.radial_flow ? "radial" : "") << " | " << num(v)
       << " |\n";
  }
  if (pv_.available && !rows.empty()) {
    os << "\nAt the operating point: " << b.name << " =";
    bool first = true;
    for (const auto& [h, v] : total) {
      const std::string t = num(std::abs(v));
      os << (first ? (v < 0 ? " -" : " ") : (v < 0 ? " - " : " + ")) << t
         << (h == 0 ? "" : " " + DerivedModel::harmonic_name(h));
      first = false;
    }
    os << ".\n";
  }
  if (!hover.empty()) {
    os << "\nHover balance in the forcing of this equation (mu-free, not part of " << b.name
       << "; the runtime subtracts the forcing at the hover equilibrium):\n\n"
       << kTermHeader;
    double sum = 0.0;
    for (const auto& r : hover) {
      const double v = value(r, div);
      sum += v;
      os << "| (hover) | " << DerivedModel::harmonic_name(r.harmonic) << " | "
         << factor_text(m_, r.term, true, r.beta_power) << " | " << integral_text(m_, r.term)
         << " | " << (r.term.paper_name.empty() ? "-" : r.term.paper_name) << " | "
         << r.term.eps_order << " | " << r.term.origin << " | "
         << (r.term.radial_flow ? "radial" : "") << " | " << num(v) << " |\n";
    }
    if (pv_.available) {
      os << "\nSum at the hover equilibrium: " << num(sum) << " (zero up to rounding).\n";
    }
  }
}

// Specs with per-equation term classes or exclusions: every aerodynamic term they dropped.
void Report::dropped(std::ostringstream& os) const {
  os << "\n## Terms dropped by the spec\n\n"
     << "Aerodynamic terms the derivation produced and the spec's `[terms.flap]`, `[terms.lag]` "
        "or `[exclude]` keys removed (they are in no entry above). Factors with "
        "(gamma/2)(l/R)^2 removed.\n\n"
     << "| entry | harmonic | factor | integral | paper | eps | origin | radial | reason |\n"
     << "|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& d : m_.dropped) {
    const std::string entry = d.equation == n_ ? "thrust"
                              : d.state < 0    ? f_entry_name(d.equation, m_.M, m_.N)
                                               : a_entry_name(d.equation, d.state, m_.M, m_.N);
    os << "| " << entry << " | " << DerivedModel::harmonic_name(d.harmonic) << " | "
       << factor_text(m_, d.term, true) << " | int " << d.integral << " | " << d.term.paper_name
       << " | " << d.term.eps_order << " | " << d.term.origin << " | "
       << (d.term.radial_flow ? "radial" : "") << " | " << d.reason << " |\n";
  }
}

void Report::absorbed(std::ostringstream& os) const {
  os << "\n## Terms absorbed into the modal stiffness\n\n"
     << "The linear centrifugal stiffness terms below, together with the bending stiffness, are "
        "replaced by M w^2 through the orthogonality relations of the rotating modes (A.2, A.4); "
        "they are listed so that nothing derived disappears silently.\n\n"
     << "| equation | state | factor | integral | origin |\n|---|---|---|---|---|\n";
  for (const auto& a : m_.absorbed) {
    os << "| " << m_.equation_name(a.equation) << " | " << m_.state_name(a.state) << " | "
       << factor_text(m_, a.term, false) << " | " << integral_text(m_, a.term) << " | "
       << a.term.origin << " |\n";
  }
}

// Cyclic-pitch models: every term that theta1c or theta1s brings in, gathered from the entry
// blocks above (where they also appear) so that the new terms can be audited at a glance.
void Report::cyclic(std::ostringstream& os) const {
  const int c1 = scalar_index(m_, "theta1c"), s1 = scalar_index(m_, "theta1s");
  os << "\n## Terms of the cyclic pitch\n\n"
     << "theta(psi) = theta + theta1c cos psi + theta1s sin psi in the section pitch of eqs "
        "2.20-2.21 (theta1c, theta1s of the same eps order as theta); the droop slope "
        "-beta_D theta and the elastic coupling keep the collective theta. The terms below are "
        "part of the entries above; at the operating point of the value column theta1c = "
        "theta1s = 0. Factors with (gamma/2)(l/R)^2 removed.\n\n"
     << "| entry | harmonic | factor | integral | eps | origin | radial |\n"
     << "|---|---|---|---|---|---|---|\n";
  auto list = [&](const std::string& entry, int h, const Slot& slot) {
    for (const auto& t : slot.terms) {
      if (power_of(t, c1) == 0 && power_of(t, s1) == 0) continue;
      os << "| " << entry << " | " << DerivedModel::harmonic_name(h) << " | "
         << factor_text(m_, t, true) << " | " << integral_text(m_, t) << " | " << t.eps_order
         << " | " << t.origin << " | " << (t.radial_flow ? "radial" : "") << " |\n";
    }
  };
  for (int eq = 0; eq < n_; ++eq) {
    for (int col = 0; col < 2 * n_; ++col) {
      for (int h = 0; h < m_.H; ++h) {
        list(a_entry_name(eq, col, m_.M, m_.N), h, m_.force[(h * n_ + eq) * 2 * n_ + col]);
      }
    }
    for (int h = 0; h < m_.H; ++h) list(f_entry_name(eq, m_.M, m_.N), h, m_.forcing[h * n_ + eq]);
  }
}

// Every term of the built-in twist theta_tw(x0) (an integral with the factor tw), gathered from
// the entry blocks, the hover equilibrium and the thrust, where they also appear.
void Report::twist(std::ostringstream& os) const {
  auto twisted = [&](const Term& t) {
    if (t.ref != IntegralRef::Aero) return false;
    for (const auto& f : m_.aero_keys[t.integral].factors)
      if (f.kind == FactorKind::Twist) return true;
    return false;
  };
  os << "\n## Terms of the built-in twist\n\n"
     << "The section pitch of eqs 2.20-2.21 is theta + theta_tw(x0) (+ the cyclic pitch), the "
        "built-in twist theta_tw of the same eps order as theta: each theta term of L_z and L_y "
        "has a twin with theta replaced by the factor tw in its integral. The droop slope "
        "-beta_D theta and the elastic coupling keep the collective theta. The terms below are "
        "part of the entries above (and of S q0 = c and the thrust); for the paper's untwisted "
        "blade every tw integral is 0. Factors with (gamma/2)(l/R)^2 removed (thrust: as "
        "derived).\n\n"
     << "| entry | harmonic | factor | integral | eps | origin | radial |\n"
     << "|---|---|---|---|---|---|---|\n";
  auto list = [&](const std::string& entry, int h, const Slot& slot, bool strip) {
    for (const auto& t : slot.terms) {
      if (!twisted(t)) continue;
      os << "| " << entry << " | " << DerivedModel::harmonic_name(h) << " | "
         << factor_text(m_, t, strip) << " | " << integral_text(m_, t) << " | " << t.eps_order
         << " | " << t.origin << " | " << (t.radial_flow ? "radial" : "") << " |\n";
    }
  };
  for (int eq = 0; eq < n_; ++eq) {
    for (int col = 0; col < 2 * n_; ++col) {
      for (int h = 0; h < m_.H; ++h) {
        list(a_entry_name(eq, col, m_.M, m_.N), h, m_.force[(h * n_ + eq) * 2 * n_ + col], true);
      }
    }
    for (int h = 0; h < m_.H; ++h)
      list(f_entry_name(eq, m_.M, m_.N), h, m_.forcing[h * n_ + eq], true);
  }
  for (int i = 0; i < n_; ++i) list("c[" + std::to_string(i + 1) + "]", 0, m_.c[i], true);
  for (int h = 0; h < m_.H; ++h) list("thrust", h, m_.thrust_forcing[h], false);
  for (int col = 0; col < 2 * n_; ++col) {
    for (int h = 0; h < m_.H; ++h) {
      list("thrust " + m_.state_name(col), h, m_.thrust_force[h * 2 * n_ + col], false);
    }
  }
}

// Cyclic-pitch models: the rotor thrust T(psi) = (l/R) int L_z dx0 of ModelDescriptor::thrust.
void Report::thrust(std::ostringstream& os) const {
  os << "\n## Rotor thrust (for the trim)\n\n"
     << "T(psi) = (l/R) int L_z dx0 over the aerodynamic span, with the flap load L_z of eq 2.20 "
        "exactly as derived for the flap equation (truncated at O(eps^"
     << m_.spec.kept_flap
     << "), linear in the perturbation state) but not Galerkin-weighted; C_T = (sigma a / 2) "
        "times its azimuth average (the runtime averages it over the normal and the reversed-flow "
        "regions). Terms by state column (`-`: state-independent).\n\n"
     << "| state | harmonic | factor | integral | eps | origin | radial |\n"
     << "|---|---|---|---|---|---|---|\n";
  auto list = [&](const std::string& state, int h, const Slot& slot) {
    for (const auto& t : slot.terms) {
      os << "| " << state << " | " << DerivedModel::harmonic_name(h) << " | "
         << factor_text(m_, t, false) << " | " << integral_text(m_, t) << " | " << t.eps_order
         << " | " << t.origin << " | " << (t.radial_flow ? "radial" : "") << " |\n";
    }
  };
  for (int h = 0; h < m_.H; ++h) list("-", h, m_.thrust_forcing[h]);
  for (int col = 0; col < 2 * n_; ++col) {
    for (int h = 0; h < m_.H; ++h) list(m_.state_name(col), h, m_.thrust_force[h * 2 * n_ + col]);
  }
}

void Report::equilibrium(std::ostringstream& os) const {
  os << "\n## Hover static equilibrium (eqs 2.27-2.32)\n\n`S q0 = c`; aerodynamic factors with "
        "(gamma/2)(l/R)^2 removed; value = the full term at the operating point.\n\n"
     << "| entry | factor | integral | paper | eps | origin | radial | value |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  auto line = [&](const std::string& entry, const Row& r) {
    double v = pv_.available ? 0.0 : kNoValue;
    for (const auto& t : r.members) v += pv_.available ? pv_.value(t) : 0.0;
    os << "| " << entry << " | " << factor_text(m_, r.term, true, r.beta_power) << " | "
       << integral_text(m_, r.term) << " | "
       << (r.term.paper_name.empty() ? "-" : r.term.paper_name) << " | " << r.term.eps_order
       << " | " << r.term.origin << " | " << (r.term.radial_flow ? "radial" : "") << " | " << num(v)
       << " |\n";
  };
  for (int i = 0; i < n_; ++i) {
    for (int j = 0; j < n_; ++j) {
      for (const auto& r : rows_of(m_, m_.S[i * n_ + j].terms, 0)) {
        line("S[" + std::to_string(i + 1) + "," + std::to_string(j + 1) + "]", r);
      }
    }
    for (const auto& r : rows_of(m_, m_.c[i].terms, 0)) line("c[" + std::to_string(i + 1) + "]", r);
  }
}

}  // namespace

std::string factor_text(const DerivedModel& m, const Term& t, bool strip_aero_scale,
                        int beta_power) {
  GiNaC::numeric c = t.coef;
  std::vector<std::pair<int, int>> sc = t.scalars;
  if (strip_aero_scale && t.ref == IntegralRef::Aero) {
    // remove (gamma/2)(l/R)^2
    c = c * 2;
    for (auto& [idx, p] : sc) {
      if (m.scalars[idx].name == "lock") p -= 1;
      if (m.scalars[idx].name == "lr") p -= 2;
    }
  }
  std::vector<std::string> parts;
  const int precone = scalar_index(m, "precone");
  const std::string beta =
      beta_power == 0
          ? ""
          : "(precone + droop)" + (beta_power > 1 ? "^" + std::to_string(beta_power) : "");
  bool beta_done = beta.empty();
  for (const auto& [idx, p] : sc) {
    if (!beta_done && idx > precone) {
      parts.push_back(beta);
      beta_done = true;
    }
    if (p == 0) continue;
    parts.push_back(m.scalars[idx].name + (p > 1 ? "^" + std::to_string(p) : ""));
  }
  if (!beta_done) parts.push_back(beta);
  std::ostringstream os;
  if (c == -1 && !parts.empty()) {
    os << "-";
  } else if (c != 1 || parts.empty()) {
    os << c << (parts.empty() ? "" : " ");
  }
  for (size_t j = 0; j < parts.size(); ++j) os << (j ? " " : "") << parts[j];
  return os.str();
}

std::string emit_report(const DerivedModel& m) { return Report(m).text(); }

}  // namespace flaplag::derive
