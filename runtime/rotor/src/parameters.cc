// Rotor parameters: the name table, validation and the hover inflow (eq 2.24).
#include "flaplag/rotor/parameters.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "flaplag/blade/blade.h"
#include "flaplag/blade/rotating_modes.h"
#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/rotor/parameter_table.h"

namespace flaplag {

namespace {

ParameterSpec real_row(const char* field, const char* symbol, const char* units,
                       const char* description, double RotorParameters::*member, Interval range,
                       const char* requirement) {
  return ParameterSpec{field,       symbol, units, description, ParameterType::Real,
                       requirement, member, range, nullptr,     nullptr,
                       nullptr};
}

// An int field with the closed range [lo, hi].
ParameterSpec integer_row(const char* field, const char* symbol, const char* description,
                          int RotorParameters::*member, int lo, int hi, const char* requirement) {
  return ParameterSpec{field,
                       symbol,
                       "-",
                       description,
                       ParameterType::Integer,
                       requirement,
                       nullptr,
                       Interval{static_cast<double>(lo), static_cast<double>(hi), false, false},
                       nullptr,
                       nullptr,
                       member};
}

ParameterSpec flag_row(const char* field, const char* description, bool RotorParameters::*member) {
  return ParameterSpec{field,
                       "",
                       "-",
                       description,
                       ParameterType::Flag,
                       "",
                       nullptr,
                       Interval{0, 0, false, false},
                       member,
                       nullptr,
                       nullptr};
}

// The upper bounds are far outside any rotor (the paper's typical case is gamma = 10,
// sigma = 0.05, a = 2 pi, omega ~ 1.2 per rev) but keep every admissible value a blade whose
// periodic system is finite in double precision up to mu = kMaxAdvanceRatio: A(psi) grows like
// gamma a mu^2 and omega^2, so without bounds a value such as gamma = 1e308 overflows the
// coefficients and the front end could only report a derived quantity it never saw.
std::vector<ParameterSpec> build_table() {
  // The strip theory and the small-angle ordering (Appendix C.1) break down long before pi/2;
  // the bound only rejects angles for which tan/cos of the geometry are meaningless.
  const Interval angle{-kHalfPi, kHalfPi, true, true};
  const Interval frequency{0.0, 1000.0, true, false};
  const Interval damping{0.0, 10.0, false, false};
  std::vector<ParameterSpec> t;
  t.push_back(ParameterSpec{"model", "", "-", "compiled ordering model (the list: flaplag models)",
                            ParameterType::Text, "the name of a compiled model", nullptr,
                            Interval{0, 0, false, false}, nullptr, nullptr, nullptr});
  t.push_back(real_row("gamma", "gamma", "-", "Lock number, based on normal flow",
                       &RotorParameters::gamma, Interval{0.0, 1e4, true, false}, "in (0, 1e4]"));
  t.push_back(real_row("sigma", "sigma", "-", "rotor solidity, for the inflow of eq 2.24",
                       &RotorParameters::sigma, Interval{0.0, 1.0, true, false}, "in (0, 1]"));
  t.push_back(real_row("lift_slope", "a", "1/rad", "lift-curve slope", &RotorParameters::lift_slope,
                       Interval{0.0, 100.0, true, false}, "in (0, 100]"));
  t.push_back(real_row("cdo", "C_Do", "-", "profile drag coefficient", &RotorParameters::cdo,
                       Interval{0.0, 1.0, false, false}, "in [0, 1]"));
  t.push_back(real_row("theta", "theta", "rad", "collective pitch", &RotorParameters::theta, angle,
                       "in (-pi/2, pi/2)"));
  t.push_back(real_row("theta1c", "theta_1c", "rad", "cyclic pitch, cos psi part",
                       &RotorParameters::theta1c, angle, "in (-pi/2, pi/2)"));
  t.push_back(real_row("theta1s", "theta_1s", "rad", "cyclic pitch, sin psi part",
                       &RotorParameters::theta1s, angle, "in (-pi/2, pi/2)"));
  t.push_back(real_row("precone", "beta_P", "rad", "precone angle", &RotorParameters::precone,
                       angle, "in (-pi/2, pi/2)"));
  t.push_back(real_row("droop", "beta_D", "rad", "droop angle", &RotorParameters::droop, angle,
                       "in (-pi/2, pi/2)"));
  t.push_back(real_row("omega_flap", "omega_F1", "per rev",
                       "first rotating flap frequency by Omega", &RotorParameters::omega_flap,
                       frequency, "in (0, 1000]"));
  t.push_back(real_row("omega_lag", "omega_L1", "per rev", "first rotating lag frequency by Omega",
                       &RotorParameters::omega_lag, frequency, "in (0, 1000]"));
  t.push_back(real_row("damping_flap", "eta_SF", "-", "flap structural damping ratio",
                       &RotorParameters::damping_flap, damping, "in [0, 10]"));
  t.push_back(real_row("damping_lag", "eta_SL", "-", "lag structural damping ratio",
                       &RotorParameters::damping_lag, damping, "in [0, 10]"));
  t.push_back(real_row("length_ratio", "l/R", "-", "elastic blade length by rotor radius",
                       &RotorParameters::length_ratio, Interval{0.0, 1.0, true, false},
                       "in (0, 1]"));
  t.push_back(real_row("tip_loss_a", "A", "-", "inner limit of the aerodynamic span, in x0 = r/l",
                       &RotorParameters::tip_loss_a, Interval{0.0, 1.0, false, true}, "in [0, 1)"));
  t.push_back(real_row("tip_loss_b", "B", "-",
                       "outer limit of the aerodynamic span (tip loss), in x0 = r/l",
                       &RotorParameters::tip_loss_b, Interval{0.0, 1.0, true, false}, "in (0, 1]"));
  // A root at or beyond the rotor radius is no blade.
  t.push_back(real_row("root_offset", "e1", "-", "root offset of the elastic blade by R",
                       &RotorParameters::root_offset, Interval{0.0, 1.0, false, true},
                       "in [0, 1)"));
  t.push_back(flag_row("reversed_flow", "the reversed-flow sector (Appendix D)",
                       &RotorParameters::reversed_flow));
  t.push_back(flag_row("exact_reversed_flow",
                       "the exact circular reversed-flow region (x < -mu sin psi) instead of the "
                       "Appendix D sector",
                       &RotorParameters::exact_reversed_flow));
  t.push_back(ParameterSpec{"modes", "", "-",
                            "blade mode shapes: assumed (eq 4.1) or exact rotating modes",
                            ParameterType::Choice, "assumed or exact", nullptr,
                            Interval{0, 0, false, false}, nullptr, "assumed|exact", nullptr});
  // Paper 4.1(b): five functions (`paper`).  A lag frequency near the k -> 0 limit of the basis
  // (0.207 with five, Fig 15's left end omega_L1 = 0.2) needs more (rotating_modes.h).
  static_assert(kMaxBasisFunctions == 12, "update the requirement text");
  static_assert(kPaperBasis == 5 && kConvergedBasis == 0 && kElementBasis == -1,
                "update the names");
  ParameterSpec basis = integer_row(
      "basis", "",
      "exact modes: nonrotating cantilever functions per direction (Galerkin basis of the "
      "rotating modes; at least the model's mode counts); converged: the largest, 12, with its "
      "error estimated against 11 (a blade table's against finite elements) and included in the "
      "results' error estimates; paper: the paper's 5; elements: cubic finite elements on the "
      "blade's stations instead, checked against 12 functions",
      &RotorParameters::basis, 1, kMaxBasisFunctions, "converged, paper, elements or 1..12");
  basis.names = "converged=0|paper=5|elements=-1";
  t.push_back(basis);
  t.push_back(flag_row("elastic_coupling", "the elastic coupling of Appendix E (exact modes only)",
                       &RotorParameters::elastic_coupling));
  t.push_back(flag_row("paper_1974_shapes",
                       "exact modes rebuilt with the 1974 sign slip (reproduces Figs 10-17)",
                       &RotorParameters::paper_1974_shapes));
  return t;
}

const ParameterSpec& row(std::string_view field) {
  const ParameterSpec* s = find_parameter(field);
  // Only reachable if the table and this file disagree: a programming error, not bad input.
  if (s == nullptr) throw std::logic_error("parameter table has no row " + std::string(field));
  return *s;
}

}  // namespace

const std::vector<ParameterSpec>& parameter_table() {
  static const std::vector<ParameterSpec> table = build_table();
  return table;
}

const ParameterSpec* find_parameter(std::string_view field) {
  for (const ParameterSpec& s : parameter_table()) {
    if (field == s.field) return &s;
  }
  return nullptr;
}

bool in_range(const ParameterSpec& spec, double v) { return spec.range.Contains(v); }

namespace {

// Calls f(name, value) for each named value of an Integer row until it returns true.
template <class F>
bool for_each_name(const ParameterSpec& spec, F f) {
  if (spec.type != ParameterType::Integer || spec.names == nullptr) return false;
  const std::string_view all = spec.names;
  for (std::size_t start = 0; start < all.size();) {
    std::size_t bar = all.find('|', start);
    if (bar == std::string_view::npos) bar = all.size();
    const std::string_view item = all.substr(start, bar - start);
    const std::size_t eq = item.find('=');
    if (f(item.substr(0, eq), std::stoi(std::string(item.substr(eq + 1))))) return true;
    start = bar + 1;
  }
  return false;
}

}  // namespace

bool integer_from_name(const ParameterSpec& spec, std::string_view name, int* value) {
  return for_each_name(spec, [&](std::string_view n, int v) {
    if (n != name) return false;
    *value = v;
    return true;
  });
}

std::string integer_name(const ParameterSpec& spec, int value) {
  if (spec.type != ParameterType::Integer || in_range(spec, value)) return "";
  std::string out;
  for_each_name(spec, [&](std::string_view n, int v) {
    if (v != value) return false;
    out = std::string(n);
    return true;
  });
  return out;
}

bool integer_admissible(const ParameterSpec& spec, int value) {
  return in_range(spec, value) || !integer_name(spec, value).empty();
}

int galerkin_basis(const RotorParameters& p) {
  if (p.basis == kElementBasis) return 0;
  return p.basis == kConvergedBasis ? kMaxBasisFunctions : p.basis;
}

int reference_basis(const RotorParameters& p, int flap_modes, int lag_modes) {
  if (p.basis == kElementBasis) return kMaxBasisFunctions;
  if (p.blade) return kElementBasis;
  const int b = galerkin_basis(p);
  const int r = b < kMaxBasisFunctions ? b + 1 : b - 1;
  return r >= std::max(flap_modes, lag_modes) && r >= 1 ? r : 0;
}

std::string basis_description(int basis) {
  if (basis == kElementBasis) return "cubic finite elements";
  const int n = basis == kConvergedBasis ? kMaxBasisFunctions : basis;
  return std::to_string(n) + " cantilever functions";
}

const char* mode_kind_name(ModeKind k) { return k == ModeKind::Exact ? "exact" : "assumed"; }

bool mode_kind_from_name(std::string_view name, ModeKind* kind) {
  for (ModeKind k : {ModeKind::Assumed, ModeKind::Exact}) {
    if (name == mode_kind_name(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

std::string parameter_text(const RotorParameters& p, const ParameterSpec& spec) {
  switch (spec.type) {
    case ParameterType::Real:
      return round_trip_text(p.*spec.real);
    case ParameterType::Integer: {
      const std::string name = integer_name(spec, p.*spec.integer);
      return name.empty() ? std::to_string(p.*spec.integer) : name;
    }
    case ParameterType::Flag:
      return p.*spec.flag ? "true" : "false";
    case ParameterType::Choice:
      return mode_kind_name(p.modes);
    case ParameterType::Text:
      return p.model;
  }
  return "";
}

void validate(const RotorParameters& p) {
  validate_except_inflow(p);
  // Every other check is per field; this one keeps hover_inflow() defined for valid input.
  hover_inflow(p);
}

void validate_except_inflow(const RotorParameters& p) {
  for (const ParameterSpec& s : parameter_table()) {
    if (s.type == ParameterType::Integer) {
      const int v = p.*s.integer;
      if (!integer_admissible(s, v))
        throw InvalidInput(s.field, std::to_string(v), std::string("must be ") + s.requirement);
      continue;
    }
    if (s.type != ParameterType::Real) continue;
    const double v = p.*s.real;
    if (!std::isfinite(v))
      throw InvalidInput(s.field, round_trip_text(v), "must be a finite number");
    if (!in_range(s, v)) {
      throw InvalidInput(s.field, round_trip_text(v), std::string("must be ") + s.requirement);
    }
  }
  if (p.model.empty()) throw InvalidInput("model", "\"\"", "must name a compiled model");
  // Each limit is in range on its own; an aerodynamic span needs them ordered as well.
  if (!(p.tip_loss_a < p.tip_loss_b)) {
    throw InvalidInput(row("tip_loss_a").field, round_trip_text(p.tip_loss_a),
                       "must be below `tip_loss_b` = " + round_trip_text(p.tip_loss_b));
  }
  // The aerodynamic loads carry C_Do / a: a lift slope near the bottom of double's range would
  // overflow them (first seen near 1e307) and the failure would name a derived matrix.  A real
  // blade has C_Do / a of about 0.002.
  if (!(p.cdo / p.lift_slope <= kMaxDragOverLiftSlope)) {
    throw InvalidInput(row("lift_slope").field, round_trip_text(p.lift_slope),
                       "too small for `cdo` = " + round_trip_text(p.cdo) +
                           ": C_Do / a must be at most 1e300 (the aerodynamic loads overflow)");
  }
  if (p.mode_shapes && p.paper_1974_shapes) {
    throw InvalidInput(row("paper_1974_shapes").field, "true",
                       "the 1974 shapes are computed ones; imported mode shapes are used as given");
  }
  if (p.blade) {
    validate(*p.blade);
    if (p.modes != ModeKind::Exact) {
      throw InvalidInput(row("modes").field, mode_kind_name(p.modes),
                         "a blade table needs the exact modes of that blade (`modes` = exact)");
    }
    if (p.paper_1974_shapes) {
      throw InvalidInput(row("paper_1974_shapes").field, "true",
                         "the 1974 shapes are the uniform blade's (no blade table)");
    }
  }
  // The exact region is a way of modelling the reversed flow, not a second switch for it.
  if (p.exact_reversed_flow && !p.reversed_flow) {
    throw InvalidInput(row("exact_reversed_flow").field, "true",
                       "needs the reversed flow switched on (the exact region replaces its "
                       "Appendix D sector)");
  }
}

namespace {

// A blade table's thrust-weighted chord and twist over the disc, x = r/R in [0, 1] (stations
// x = e1 + (l/R) x0, the root values held inboard of e1 as eq 2.24 integrates from the
// centre): chord = 3 int c/c_ref x^2 dx, twist = 3 int (c/c_ref) theta_tw x^2 dx / chord.
struct ThrustWeights {
  double chord = 1.0, twist = 0.0;
};
ThrustWeights thrust_weights(const RotorParameters& p) {
  ThrustWeights w;
  if (!p.blade) return w;
  const BladeProperties& b = *p.blade;
  std::vector<double> corners;
  for (double c : b.x0) corners.push_back(p.root_offset + p.length_ratio * c);
  const SpanRule rule = span_rule(0.0, 1.0, corners);
  double chord = 0.0, twist = 0.0;
  for (std::size_t q = 0; q < rule.x0.size(); ++q) {
    const double x = rule.x0[q];
    const double x0 = (x - p.root_offset) / p.length_ratio;
    const double c = b.chord_at(x0);
    chord += rule.weight[q] * 3.0 * c * x * x;
    twist += rule.weight[q] * 3.0 * c * b.twist_at(x0) * x * x;
  }
  w.chord = chord;
  w.twist = twist / chord;
  return w;
}

}  // namespace

double hover_inflow(const RotorParameters& p) {
  // A blade table: eq 2.24 with its thrust-weighted solidity and the collective plus its
  // thrust-weighted twist (for a linear twist and uniform chord, theta at x = 0.75).
  const ThrustWeights tw = thrust_weights(p);
  const double sa = p.sigma * p.lift_slope * tw.chord;
  const double theta = p.theta + tw.twist;
  // Written as 24 theta / (16 (sqrt(1 + 24 theta/(sigma a)) + 1)), which equals eq 2.24 exactly
  // but does not lose digits to cancellation when 24 theta << sigma a.  Negative theta below
  // -sigma a / 24 makes the square root imaginary: eq 2.24 has no hover inflow there.
  const double r = 1.0 + 24.0 * theta / sa;
  if (r < 0.0) {
    throw InvalidInput(row("theta").field, round_trip_text(p.theta),
                       "eq 2.24 has no real inflow for theta < -sigma a / 24 = " +
                           round_trip_text(-sa / 24.0 - tw.twist) +
                           (p.blade ? " (with the blade's thrust-weighted twist and chord)" : ""));
  }
  return 24.0 * theta / (16.0 * (std::sqrt(r) + 1.0));
}

}  // namespace flaplag
