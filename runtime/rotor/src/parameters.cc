// Rotor parameters: the name table, validation and the hover inflow (eq 2.24).
#include "flaplag/rotor/parameters.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <system_error>

#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/rotor/parameter_table.h"

namespace flaplag {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kHalfPi = 1.5707963267948966;

ParameterSpec real_row(const char* field, const char* option, const char* symbol, const char* units,
                       const char* help, double RotorParameters::*member, Interval range,
                       const char* requirement) {
  return ParameterSpec{field,       option, symbol, units,   help,  ParameterType::Real,
                       requirement, member, range,  nullptr, false, nullptr};
}

ParameterSpec flag_row(const char* field, const char* option, const char* help,
                       bool RotorParameters::*member, bool value) {
  return ParameterSpec{field,  option,  "",
                       "-",    help,    ParameterType::Flag,
                       "",     nullptr, Interval{0, 0, false, false},
                       member, value,   nullptr};
}

std::vector<ParameterSpec> build_table() {
  const Interval positive{0.0, kInf, true, true};
  const Interval non_negative{0.0, kInf, false, true};
  // The strip theory and the small-angle ordering (Appendix C.1) break down long before pi/2;
  // the bound only rejects angles for which tan/cos of the geometry are meaningless.
  const Interval angle{-kHalfPi, kHalfPi, true, true};
  std::vector<ParameterSpec> t;
  t.push_back(ParameterSpec{"model", "--model", "", "-",
                            "compiled ordering model (list: flaplag models)", ParameterType::Text,
                            "the name of a compiled model", nullptr, Interval{0, 0, false, false},
                            nullptr, false, nullptr});
  t.push_back(real_row("lock", "--gamma", "gamma", "-", "Lock number, based on normal flow",
                       &RotorParameters::gamma, positive, "> 0"));
  t.push_back(real_row("solidity", "--sigma", "sigma", "-",
                       "rotor solidity, for the inflow of eq 2.24", &RotorParameters::sigma,
                       positive, "> 0"));
  t.push_back(real_row("lift_slope", "--lift-slope", "a", "1/rad", "lift-curve slope",
                       &RotorParameters::lift_slope, positive, "> 0"));
  t.push_back(real_row("cdo", "--cdo", "C_Do", "-", "profile drag coefficient",
                       &RotorParameters::cdo, non_negative, ">= 0"));
  t.push_back(real_row("theta", "--theta", "theta", "rad", "collective pitch",
                       &RotorParameters::theta, angle, "in (-pi/2, pi/2)"));
  t.push_back(real_row("precone", "--precone", "beta_P", "rad", "precone angle",
                       &RotorParameters::precone, angle, "in (-pi/2, pi/2)"));
  t.push_back(real_row("droop", "--droop", "beta_D", "rad", "droop angle", &RotorParameters::droop,
                       angle, "in (-pi/2, pi/2)"));
  t.push_back(real_row("omega_flap", "--omega-flap", "omega_F1", "per rev",
                       "first rotating flap frequency by Omega", &RotorParameters::omega_flap,
                       positive, "> 0"));
  t.push_back(real_row("omega_lag", "--omega-lag", "omega_L1", "per rev",
                       "first rotating lag frequency by Omega", &RotorParameters::omega_lag,
                       positive, "> 0"));
  t.push_back(real_row("damping_flap", "--damping-flap", "eta_SF", "-",
                       "flap structural damping ratio", &RotorParameters::damping_flap,
                       non_negative, ">= 0"));
  t.push_back(real_row("damping_lag", "--damping-lag", "eta_SL", "-",
                       "lag structural damping ratio", &RotorParameters::damping_lag, non_negative,
                       ">= 0"));
  t.push_back(real_row("length_ratio", "--length-ratio", "l/R", "-",
                       "elastic blade length by rotor radius", &RotorParameters::length_ratio,
                       Interval{0.0, 1.0, true, false}, "in (0, 1]"));
  t.push_back(real_row("tip_loss_a", "--tip-loss-a", "A", "-",
                       "inner limit of the aerodynamic span, in x0 = r/l",
                       &RotorParameters::tip_loss_a, Interval{0.0, 1.0, false, true}, "in [0, 1)"));
  t.push_back(real_row("tip_loss_b", "--tip-loss-b", "B", "-",
                       "outer limit of the aerodynamic span (tip loss), in x0 = r/l",
                       &RotorParameters::tip_loss_b, Interval{0.0, 1.0, true, false}, "in (0, 1]"));
  t.push_back(real_row("e1", "--root-offset", "e1", "-", "root offset of the elastic blade by R",
                       &RotorParameters::root_offset, non_negative, ">= 0"));
  t.push_back(flag_row("reversed_flow", "--no-reversed-flow",
                       "leave out the reversed-flow sector (Appendix D)",
                       &RotorParameters::reversed_flow, false));
  t.push_back(ParameterSpec{"modes", "--modes", "", "-",
                            "blade mode shapes: assumed (eq 4.1) or exact rotating modes",
                            ParameterType::Choice, "assumed or exact", nullptr,
                            Interval{0, 0, false, false}, nullptr, false, "assumed|exact"});
  t.push_back(flag_row("elastic_coupling", "--no-elastic-coupling",
                       "leave out the elastic coupling of Appendix E (exact modes only)",
                       &RotorParameters::elastic_coupling, false));
  t.push_back(flag_row("paper_1974_shapes", "--paper-1974-shapes",
                       "rebuild exact modes with the 1974 sign slip, to reproduce Figs 10-17",
                       &RotorParameters::paper_1974_shapes, true));
  return t;
}

bool in_interval(double v, const Interval& r) {
  const bool lo_ok = r.lo_open ? v > r.lo : v >= r.lo;
  const bool hi_ok = r.hi_open ? v < r.hi : v <= r.hi;
  return lo_ok && hi_ok;
}

const ParameterSpec& row(std::string_view field) {
  const ParameterSpec* s = find_parameter(field);
  // Only reachable if the table and this file disagree: a programming error, not bad input.
  if (s == nullptr) throw std::logic_error("parameter table has no row " + std::string(field));
  return *s;
}

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

}  // namespace

const std::vector<ParameterSpec>& parameter_table() {
  static const std::vector<ParameterSpec> table = build_table();
  return table;
}

const ParameterSpec* find_parameter(std::string_view name) {
  for (const ParameterSpec& s : parameter_table()) {
    if (name == s.field || name == s.option) return &s;
  }
  return nullptr;
}

std::string option_for(std::string_view name) {
  const ParameterSpec* s = find_parameter(name);
  return s != nullptr ? std::string(s->option) : std::string(name);
}

const char* mode_kind_name(ModeKind k) { return k == ModeKind::Exact ? "exact" : "assumed"; }

std::string parameter_text(const RotorParameters& p, const ParameterSpec& spec) {
  switch (spec.type) {
    case ParameterType::Real:
      return round_trip_text(p.*spec.real);
    case ParameterType::Flag:
      return p.*spec.flag ? "true" : "false";
    case ParameterType::Choice:
      return mode_kind_name(p.modes);
    case ParameterType::Text:
      return p.model;
  }
  return "";
}

double parse_real(const std::string& option, const std::string& text) {
  if (text.empty() || is_blank(text.front()) || is_blank(text.back())) {
    throw InvalidInput(option, "\"" + text + "\"", "not a number");
  }
  // strtod also accepts "nan", "inf" and hexadecimal; the first two are rejected below with a
  // clearer reason than "not a number".  errno distinguishes overflow (1e999) from a valid 0.
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if (end == begin || *end != '\0') throw InvalidInput(option, text, "not a number");
  if (!std::isfinite(v)) throw InvalidInput(option, text, "must be a finite number");
  if (errno == ERANGE && std::abs(v) > 1.0) {
    throw InvalidInput(option, text, "out of the range of double");
  }
  return v;
}

int parse_int(const std::string& option, const std::string& text, int lo, int hi) {
  long long v = 0;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+') ++first;  // from_chars takes no '+', users do type it
  const auto res = std::from_chars(first, last, v);
  if (text.empty() || res.ec == std::errc::invalid_argument || res.ptr != last) {
    throw InvalidInput(option, text.empty() ? "\"\"" : text, "not a whole number");
  }
  if (res.ec == std::errc::result_out_of_range || v < lo || v > hi) {
    throw InvalidInput(option, text,
                       "must be between " + std::to_string(lo) + " and " + std::to_string(hi));
  }
  return static_cast<int>(v);
}

void set_parameter(RotorParameters& p, const ParameterSpec& spec, const std::string& text) {
  switch (spec.type) {
    case ParameterType::Real:
      p.*spec.real = parse_real(spec.option, text);
      return;
    case ParameterType::Flag:
      p.*spec.flag = spec.flag_value;
      return;
    case ParameterType::Choice:
      if (text == "assumed") {
        p.modes = ModeKind::Assumed;
      } else if (text == "exact") {
        p.modes = ModeKind::Exact;
      } else {
        throw InvalidInput(spec.option, text.empty() ? "\"\"" : text,
                           "must be one of assumed, exact");
      }
      return;
    case ParameterType::Text:
      p.model = text;
      return;
  }
}

void validate(const RotorParameters& p) {
  for (const ParameterSpec& s : parameter_table()) {
    if (s.type != ParameterType::Real) continue;
    const double v = p.*s.real;
    if (!std::isfinite(v)) throw InvalidInput(s.option, round_trip_text(v), "must be a finite number");
    if (!in_interval(v, s.range)) {
      throw InvalidInput(s.option, round_trip_text(v), std::string("must be ") + s.requirement);
    }
  }
  if (p.model.empty()) {
    throw InvalidInput(row("model").option, "\"\"", "must name a compiled model");
  }
  // Each limit is in range on its own; an aerodynamic span needs them ordered as well.
  if (!(p.tip_loss_a < p.tip_loss_b)) {
    throw InvalidInput(row("tip_loss_a").option, round_trip_text(p.tip_loss_a),
                       std::string("must be below ") + row("tip_loss_b").option + " = " +
                           round_trip_text(p.tip_loss_b));
  }
  // Every other check is per field; this one keeps hover_inflow() defined for valid input.
  hover_inflow(p);
}

double hover_inflow(const RotorParameters& p) {
  const double sa = p.sigma * p.lift_slope;
  // Written as 24 theta / (16 (sqrt(1 + 24 theta/(sigma a)) + 1)), which equals eq 2.24 exactly
  // but does not lose digits to cancellation when 24 theta << sigma a.  Negative theta below
  // -sigma a / 24 makes the square root imaginary: eq 2.24 has no hover inflow there.
  const double r = 1.0 + 24.0 * p.theta / sa;
  if (r < 0.0) {
    throw InvalidInput(
        row("theta").option, round_trip_text(p.theta),
        "eq 2.24 has no real inflow for theta < -sigma a / 24 = " + round_trip_text(-sa / 24.0));
  }
  return 24.0 * p.theta / (16.0 * (std::sqrt(r) + 1.0));
}

}  // namespace flaplag
