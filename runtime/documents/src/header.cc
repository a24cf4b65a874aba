// flaplag documents — the header every analysis document starts with: what was computed (the
// model, the blade, the parameters, the inflow) and how (the method), as JSON and as text.
#include "flaplag/documents/header.h"

#include <algorithm>
#include <utility>

#include "flaplag/blade/imported_modes.h"
#include "flaplag/core/constants.h"
#include "flaplag/core/format.h"
#include "flaplag/documents/json_fields.h"
#include "flaplag/documents/output.h"
#include "flaplag/model_fields.h"
#include "flaplag/rotor/parameter_table.h"

namespace flaplag::documents {

namespace {

Json parameters_json(const RotorParameters& p) {
  Json j = Json::object();
  for (const ParameterSpec& s : parameter_table()) {
    switch (s.type) {
      case ParameterType::Real:
        j[json_key(s)] = p.*s.real;
        break;
      case ParameterType::Integer:
        // A named value outside the range by its name ("basis": "converged").
        if (const std::string name = integer_name(s, p.*s.integer); !name.empty())
          j[json_key(s)] = name;
        else
          j[json_key(s)] = p.*s.integer;
        break;
      case ParameterType::Flag:
        j[json_key(s)] = p.*s.flag;
        break;
      case ParameterType::Choice:
      case ParameterType::Text:
        j[json_key(s)] = parameter_text(p, s);
        break;
    }
  }
  return j;
}

// "symbol = value" pairs, several lines; flags and the model are shown elsewhere.
std::string parameters_text(const RotorParameters& p) {
  std::string out, line;
  for (const ParameterSpec& s : parameter_table()) {
    if (s.type != ParameterType::Real) continue;
    std::string item = std::string(s.symbol) + " = " + num(p.*s.real);
    if (std::string(s.units) == "rad") item += " rad";
    if (!line.empty() && line.size() + item.size() + 2 > 80) {
      out += line + ",\n";
      line.clear();
    }
    line += (line.empty() ? "" : ", ") + item;
  }
  return out + line;
}

Json method_json(const TransitionOptions& o) {
  Json j{{"name", method_name(o.method)}};
  j["steps"] = o.steps == TransitionOptions::kAutomatic ? Json("automatic") : Json(o.steps);
  if (o.method == TransitionMethod::Hsu) j["terms"] = o.terms;
  j["zeta-tolerance"] = o.zeta_tolerance;
  return j;
}

std::string method_text(const TransitionOptions& o) {
  const bool automatic = o.steps == TransitionOptions::kAutomatic;
  const std::string n = automatic ? "automatic" : std::to_string(o.steps);
  std::string t;
  switch (o.method) {
    case TransitionMethod::RK4:
      t = "rk4, N = " + n + " steps per period";
      break;
    case TransitionMethod::Hsu:
      t = "hsu, K = " + n + " intervals, J = " + std::to_string(o.terms) + " Taylor terms";
      break;
    case TransitionMethod::Magnus4:
      t = "magnus (4th order, Richardson-extrapolated), " + n + " steps per period";
      break;
    case TransitionMethod::Automatic:  // an Analysis's options name the method it stands for
      t = "auto, " + n + " steps per period";
      break;
  }
  return t + (automatic ? " (zeta resolved to " + num(o.zeta_tolerance) + " per rev)" : "");
}

bool coupling_on(const Analysis& an) {
  return an.parameters().elastic_coupling && an.modes().kind != "assumed";
}

}  // namespace

Json model_json(const model::ModelDescriptor& m) {
  return to_json(m, [](const std::string& text) { return text; });
}

// What a blade table gave: its stations and nondimensional groups, and for a dimensional table
// the data behind them (the groups printed with every result, frequencies also in Hz).
Json blade_table_json(const BladeProperties& b) {
  const BladeOrigin& o = b.origin;
  Json j;
  j["source"] = b.source;
  j["stations"] = b.x0.size();
  j["root_offset"] = o.root_offset;
  j["length_ratio"] = o.length_ratio;
  j["tip_mass"] = b.tip_mass;
  double lo = b.twist.front(), hi = b.twist.front();
  for (double t : b.twist) lo = std::min(lo, t), hi = std::max(hi, t);
  j["twist_min"] = lo;
  j["twist_max"] = hi;
  if (o.dimensional) {
    j["radius"] = o.radius;
    j["rotor_speed"] = o.rotor_speed;
    j["air_density"] = o.air_density;
    j["blades"] = o.blades;
    j["reference_chord"] = o.reference_chord;
    j["inertia"] = o.inertia;
    j["gamma"] = o.gamma;
    j["sigma"] = o.sigma;
    j["omega_flap_hz"] = o.omega_flap * o.rotor_speed / kTwoPi;
    j["omega_lag_hz"] = o.omega_lag * o.rotor_speed / kTwoPi;
  }
  return j;
}

std::string blade_table_text(const BladeProperties& b, const RotorParameters& p) {
  const BladeOrigin& o = b.origin;
  double lo = b.twist.front(), hi = b.twist.front();
  for (double t : b.twist) lo = std::min(lo, t), hi = std::max(hi, t);
  std::string t = b.source + ": " + std::to_string(b.x0.size()) +
                  " stations, e1 = " + num(o.root_offset) + ", l/R = " + num(o.length_ratio) +
                  ", tip mass M_tip l^2/I_b = " + num(b.tip_mass) + ", twist " +
                  num(lo * 180.0 / kPi) + ".." + num(hi * 180.0 / kPi) + " deg";
  if (o.dimensional) {
    const double hz = o.rotor_speed / kTwoPi;
    t += "\nR = " + num(o.radius) + " m, Omega = " + num(o.rotor_speed * 60.0 / kTwoPi) + " rpm (" +
         num(hz) + " Hz), rho = " + num(o.air_density) + " kg/m^3, " + std::to_string(o.blades) +
         " blades, c_ref = " + num(o.reference_chord) + " m (at 0.75 R), I_b = " + num(o.inertia) +
         " kg m^2\n-> gamma = " + num(o.gamma) + ", sigma = " + num(o.sigma) +
         ", omega_F1 = " + num(p.omega_flap) + " per rev (" + num(p.omega_flap * hz) +
         " Hz), omega_L1 = " + num(p.omega_lag) + " per rev (" + num(p.omega_lag * hz) + " Hz)";
  }
  return t;
}

// The momentum inflow by its eq 2.25 inputs; the default eq 2.24 and a
// trim's given lambda (in the trim's own result) are not written, so that their documents stay
// as they were.
std::optional<Json> inflow_json(const Analysis& an) {
  const InflowModel& m = an.condition().inflow;
  if (m.kind != InflowKind::Momentum) return std::nullopt;
  return Json{{"kind", enum_name(m.kind)},
              {"thrust_coefficient", jnum(m.thrust_coefficient)},
              {"shaft_angle", jnum(m.shaft_angle)}};
}

std::optional<double> inflow_at(const Analysis& an, double mu) {
  const InflowModel& m = an.condition().inflow;
  if (m.kind != InflowKind::Momentum) return std::nullopt;
  return m.lambda(an.parameters(), mu);
}

// The part every analysis output starts with: what was computed, and how.
Json header_json(const char* command, const Analysis& an, bool with_method) {
  const model::ModelDescriptor& m = an.model();
  Json j;
  j["command"] = command;
  j["model"] = model_json(m);
  j["mode_shapes"] = an.modes().kind;
  j["elastic_coupling"] = coupling_on(an);
  if (with_method) j["method"] = method_json(an.options());
  j["parameters"] = parameters_json(an.parameters());
  if (an.parameters().blade) j["blade_table"] = blade_table_json(*an.parameters().blade);
  if (std::optional<Json> inflow = inflow_json(an)) j["inflow"] = std::move(*inflow);
  // Only about the periodic equilibrium, so that the documents about hover stay as they were.
  if (an.condition().periodic()) j["linearization"] = enum_name(an.condition().linearization);
  return j;
}

std::string header_text(const Analysis& an, bool with_method) {
  const RotorParameters& p = an.parameters();
  const model::ModelDescriptor& m = an.model();
  KeyValues kv;
  kv.add("model", std::string(m.name) + " (" + m.spec_file + "): " + m.summary);
  std::string blade =
      an.modes().kind == "imported" ? "imported mode shapes (" + p.mode_shapes->source + ")"
      : an.modes().kind == "exact"  ? "exact rotating mode shapes (" + basis_description(p.basis) +
                                         (p.basis == kConvergedBasis ? ", converged" : "") + ")"
                                   : "assumed mode shape (eq 4.1)";
  if (p.paper_1974_shapes && an.modes().kind == "exact") blade += " (1974 shapes)";
  blade += ", " + std::to_string(m.flap_modes) + " flap x " + std::to_string(m.lag_modes) +
           " lag; elastic coupling " + (coupling_on(an) ? "on" : "off") + "; reversed flow " +
           (!p.reversed_flow        ? "off"
            : p.exact_reversed_flow ? "on (exact circle)"
                                    : "on");
  kv.add("blade", blade);
  if (p.blade) kv.add("blade table", blade_table_text(*p.blade, p));
  if (an.condition().periodic()) {
    kv.add("linearized",
           "about the periodic equilibrium of the nonlinear equations (harmonic "
           "balance, K automatic: doubled from " +
               std::to_string(PeriodicEquilibriumOptions::kFirstHarmonics) + " up to " +
               std::to_string(PeriodicEquilibriumOptions::kMaxHarmonics) +
               " until the coefficients agree to " +
               short_text(PeriodicEquilibriumOptions{}.harmonics_tolerance) + "), not about hover");
  }
  if (with_method) kv.add("method", method_text(an.options()));
  kv.add("parameters", parameters_text(p));
  if (const InflowModel& in = an.condition().inflow; in.kind == InflowKind::Momentum) {
    kv.add("inflow", "momentum (eq 2.25) at every mu for C_T = " + num(in.thrust_coefficient) +
                         ", alpha_R = " + num(in.shaft_angle) +
                         " rad; lambda = " + num(in.lambda(p, 0.0)) + " in hover");
  }
  return kv.render();
}

Json status_json(Json j, Status status, const std::string& message) {
  j["status"] = status_name(status);
  j["message"] = message;
  return j;
}

std::string status_text(Status status, const std::string& message) {
  if (status == Status::Ok && message.empty()) return "";
  return std::string("  status: ") + status_name(status) + (message.empty() ? "" : ": " + message) +
         "\n";
}

std::string warnings_text(const Analysis& an) {
  std::string out;
  if (an.hover().neutral)
    out +=
        "warning: the stability of hover is unknown (an eigenvalue of A0 is within rounding "
        "of the imaginary axis)\n";
  else if (!an.hover().stable)
    out += "warning: the hover equilibrium itself is unstable; see the hover exponents\n";
  if (!an.validity().empty()) out += "warning: " + an.validity() + "\n";
  return out;
}

}  // namespace flaplag::documents
