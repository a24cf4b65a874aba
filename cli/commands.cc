#include "commands.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/core/constants.h"
#include "flaplag/core/format.h"
#include "flaplag/rotor/parameter_table.h"
#include "flaplag/study.h"
#include "flaplag/trim.h"
#include "flaplag/version.h"
#include "options.h"
#include "output.h"
#include "plot.h"
#include "shard.h"

namespace flaplag::cli {

namespace {

using Json = nlohmann::ordered_json;

// The short zeta(mu) table of the typical case: mu = 0, 0.1, ..., 1.0, continued from hover in
// steps of kTableScan (every kTableEvery-th point of the continuation is shown).
constexpr double kTableStop = 1.0;
constexpr double kTableScan = 0.01;
constexpr int kTableEvery = 10;

std::string dump(const Json& j) { return j.dump(2) + "\n"; }

// ---- numbers that may not be finite ------------------------------------------------------------
//
// The library promises finite results, with two documented exceptions: the zeta of a zero
// multiplier is -inf, and optional diagnostics are absent rather than NaN.  The printers do not
// take that on trust: every result is audited first (audit_*), and a value that breaks the
// promise marks its result "failed" with a message saying what was not shown; the printers then
// show such values as "-" (text), an empty field (CSV) or null (JSON).  num() itself refuses
// non-finite values, so a value no audit covered ends the run as an internal error instead of
// printing "nan".

bool finite(double v) { return std::isfinite(v); }
bool finite(std::complex<double> z) { return finite(z.real()) && finite(z.imag()); }
bool zeta_ok(double zeta) {
  return finite(zeta) || zeta == -std::numeric_limits<double>::infinity();
}

std::string cell(double v) { return finite(v) ? num(v) : "-"; }
std::string zeta_cell(double zeta) { return zeta_ok(zeta) ? zeta_text(zeta) : "-"; }
Json jnum(double v) { return finite(v) ? Json(v) : Json(nullptr); }
// zeta of a zero multiplier is -inf, which JSON cannot hold: it is written as the string "-inf".
Json zeta_json(double zeta) {
  if (finite(zeta)) return Json(zeta);
  return zeta_ok(zeta) ? Json("-inf") : Json(nullptr);
}
Json complex_json(std::complex<double> z) {
  return Json{{"re", jnum(z.real())}, {"im", jnum(z.imag())}};
}

std::string complex_text(std::complex<double> z) {
  if (!finite(z)) return "-";
  return num(z.real()) + (std::signbit(z.imag()) ? " - " : " + ") + num(std::abs(z.imag())) + "i";
}

Json optional_json(const std::optional<double>& v) { return v ? jnum(*v) : Json(nullptr); }
std::string optional_text(const std::optional<double>& v) { return v ? cell(*v) : "-"; }

// ---- exponents in tables: damping ratio and locked frequencies (issue 9 item 6) ----------------

// What the exponent columns mean, above every table that has them.
const char* const kExponentLegend =
    "  zeta: real part of the characteristic exponent lambda = zeta + i omega, 1/rev (> 0: "
    "unstable)\n"
    "  damping ratio: -zeta/|lambda|; for omega = 0 (a real exponent) +1 if decaying, -1 if "
    "growing\n"
    "  locked: omega locked to 0, 1/2 or 1 per rev (mod 1; a real multiplier: the periodic kind)\n";
// The same, short, above the zeta(mu) tables.
const char* const kSweepLegend =
    "  zeta in 1/rev (real part of the exponent lambda = zeta + i omega); ratio: damping ratio\n"
    "  -zeta/|lambda|; p after omega: locked to 0, 1/2 or 1 per rev (mod 1: the periodic kind)\n";

// The locked frequency of a periodic-kind exponent (classify_crossing: omega within 1e-3 of a
// multiple of 1/2) as "0", "1/2", "1", "3/2", ...; "" when omega is not locked.
std::string locked_text(double omega) {
  if (!finite(omega) || classify_crossing(omega) != InstabilityKind::Periodic) return "";
  const long k = std::lround(2.0 * omega);
  if (k % 2 == 0) return std::to_string(k / 2);
  return std::to_string(k) + "/2";
}

std::string ratio_cell(double zeta, double omega) {
  const std::optional<double> r = damping_ratio(zeta, omega);
  return r ? num(*r) : "-";
}
Json ratio_json(double zeta, double omega) { return optional_json(damping_ratio(zeta, omega)); }

Json stable_json(const std::optional<bool>& v) { return v ? Json(*v) : Json(nullptr); }
std::string stable_text(const std::optional<bool>& v) { return !v ? "unknown" : *v ? "yes" : "NO"; }

// Records that `what` could not be shown: the result becomes `worst` (at least) and says why.
void demote(Status& status, std::string& message, Status worst, const std::string& what) {
  if (static_cast<int>(status) < static_cast<int>(worst)) status = worst;
  const std::string note = "non-finite " + what + " (not shown)";
  message = message.empty() ? note : message + "; " + note;
}

void audit_exponents(const std::vector<LabelledExponent>& ex, Status& status,
                     std::string& message) {
  for (const LabelledExponent& e : ex) {
    if (!zeta_ok(e.zeta) || !finite(e.omega) || !finite(e.multiplier)) {
      demote(status, message, Status::Failed, "exponent of mode " + e.label);
      return;
    }
  }
}

void audit(PointResult& p) {
  const Status before = p.status;
  audit_exponents(p.exponents, p.status, p.message);
  if (!finite(p.mu)) demote(p.status, p.message, Status::Failed, "mu");
  // The exponents are what stability is read from: without them it is unknown.
  if (p.status == Status::Failed && before != Status::Failed) p.stable.reset();
  if (p.liouville_residual && !finite(*p.liouville_residual)) {
    demote(p.status, p.message, Status::Warning, "Liouville residual");
  }
  if (p.error && !finite(*p.error)) demote(p.status, p.message, Status::Warning, "error estimate");
}

void audit(SweepResult& s) {
  for (PointResult& p : s.points) {
    audit(p);
    if (static_cast<int>(p.status) > static_cast<int>(s.status)) {
      s.status = p.status;
      if (s.message.empty()) s.message = "at mu = " + cell(p.mu) + ": " + p.message;
    }
  }
}

void audit(CriticalResult& c) {
  if (c.mu_c && (!finite(*c.mu_c) || !finite(c.omega))) {
    demote(c.status, c.message, Status::Failed, "mu_c or omega");
    c.mu_c.reset();
  }
  if (c.mu_c_error && !finite(*c.mu_c_error)) {
    demote(c.status, c.message, Status::Warning, "mu_c error estimate");
  }
  if (!finite(c.mu_max)) demote(c.status, c.message, Status::Failed, "mu_max");
}

// The hover result with its own audit (HoverResult is the analysis' const member).
struct Hover {
  HoverResult h;
  std::optional<bool> stable;  // unknown when the hover analysis failed
};

Hover audited_hover(const Analysis& an) {
  Hover r{an.hover(), an.hover().stable};
  HoverResult& h = r.h;
  bool ok = finite(h.inflow);
  for (Eigen::Index i = 0; i < h.q0.size(); ++i) ok = ok && finite(h.q0[i]);
  for (const auto& z : h.eigenvalues) ok = ok && finite(z);
  if (!ok) demote(h.status, h.message, Status::Failed, "hover equilibrium or eigenvalue");
  if (h.status == Status::Failed || h.neutral) r.stable.reset();
  return r;
}

std::string vocab(const Request& r, const std::string& message) {
  return in_cli_vocabulary(r.command, message);
}

Json parameters_json(const RotorParameters& p) {
  Json j = Json::object();
  for (const ParameterSpec& s : parameter_table()) {
    switch (s.type) {
      case ParameterType::Real:
        j[json_key(s)] = p.*s.real;
        break;
      case ParameterType::Integer:
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

Json model_json(const model::ModelDescriptor& m) {
  return Json{{"name", m.name},           {"spec_file", m.spec_file},
              {"summary", m.summary},     {"flap_modes", m.flap_modes},
              {"lag_modes", m.lag_modes}, {"harmonics", m.n_harmonics}};
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
  }
  return t + (automatic ? " (zeta resolved to " + num(o.zeta_tolerance) + " per rev)" : "");
}

bool coupling_on(const Analysis& an) {
  return an.parameters().elastic_coupling && an.modes().kind == "exact";
}

// The part every analysis output starts with: what was computed, and how.
Json header_json(const char* command, const Analysis& an, bool with_method = true) {
  const model::ModelDescriptor& m = an.model();
  Json j;
  j["command"] = command;
  j["model"] = model_json(m);
  j["mode_shapes"] = an.modes().kind;
  j["elastic_coupling"] = coupling_on(an);
  if (with_method) j["method"] = method_json(an.options());
  j["parameters"] = parameters_json(an.parameters());
  return j;
}

std::string header_text(const Analysis& an, bool with_method = true) {
  const RotorParameters& p = an.parameters();
  const model::ModelDescriptor& m = an.model();
  KeyValues kv;
  kv.add("model", std::string(m.name) + " (" + m.spec_file + "): " + m.summary);
  std::string blade =
      an.modes().kind == "exact"
          ? "exact rotating mode shapes (" + std::to_string(p.basis) + " cantilever functions)"
          : "assumed mode shape (eq 4.1)";
  if (p.paper_1974_shapes && an.modes().kind == "exact") blade += " (1974 shapes)";
  blade += ", " + std::to_string(m.flap_modes) + " flap x " + std::to_string(m.lag_modes) +
           " lag; elastic coupling " + (coupling_on(an) ? "on" : "off") + "; reversed flow " +
           (!p.reversed_flow        ? "off"
            : p.exact_reversed_flow ? "on (exact circle)"
                                    : "on");
  kv.add("blade", blade);
  if (p.periodic_linearization) {
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
  return kv.render();
}

std::vector<std::string> state_names(int M, int N) {
  std::vector<std::string> s;
  for (int col = 0; col < 2 * (M + N); ++col) s.push_back(model::state_name(col, M, N));
  return s;
}

std::vector<std::string> equilibrium_names(int M, int N) {
  std::vector<std::string> s;
  for (int k = 1; k <= M; ++k) s.push_back("g0_" + std::to_string(k));
  for (int k = 1; k <= N; ++k) s.push_back("h0_" + std::to_string(k));
  return s;
}

// Mode labels in the order hover reports them, each once.
std::vector<std::string> mode_labels(const Analysis& an) {
  std::vector<std::string> labels;
  for (const std::string& l : an.hover().labels) {
    if (std::find(labels.begin(), labels.end(), l) == labels.end()) labels.push_back(l);
  }
  return labels;
}

// The exponent that decides a mode's stability: largest zeta; of a conjugate pair the one with
// omega >= 0.
const LabelledExponent* dominant(const PointResult& r, const std::string& label) {
  const LabelledExponent* best = nullptr;
  for (const LabelledExponent& e : r.exponents) {
    if (e.label != label) continue;
    if (best == nullptr || e.zeta > best->zeta ||
        (e.zeta == best->zeta && e.omega >= 0.0 && best->omega < 0.0)) {
      best = &e;
    }
  }
  return best;
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

Json hover_json(const Request& r, const Analysis& an) {
  const Hover hv = audited_hover(an);
  const HoverResult& h = hv.h;
  const model::ModelDescriptor& m = an.model();
  Json j;
  j["inflow"] = jnum(h.inflow);
  Json q0 = Json::object();
  const auto names = equilibrium_names(m.flap_modes, m.lag_modes);
  for (Eigen::Index i = 0; i < h.q0.size() && i < static_cast<Eigen::Index>(names.size()); ++i) {
    q0[names[static_cast<std::size_t>(i)]] = jnum(h.q0[i]);
  }
  j["equilibrium"] = q0;
  Json ex = Json::array();
  for (std::size_t i = 0; i < h.eigenvalues.size(); ++i) {
    ex.push_back(
        Json{{"zeta", jnum(h.eigenvalues[i].real())},
             {"omega", jnum(h.eigenvalues[i].imag())},
             {"damping_ratio", ratio_json(h.eigenvalues[i].real(), h.eigenvalues[i].imag())},
             {"label", i < h.labels.size() ? h.labels[i] : ""}});
  }
  j["exponents"] = ex;
  j["stable"] = stable_json(hv.stable);
  return status_json(j, h.status, vocab(r, h.message));
}

std::string hover_text(const Request& r, const Analysis& an) {
  const Hover hv = audited_hover(an);
  const HoverResult& h = hv.h;
  const model::ModelDescriptor& m = an.model();
  std::string out = "Hover equilibrium (eqs 2.24, 2.29-2.32)\n";
  KeyValues kv;
  kv.add("inflow lambda", cell(h.inflow));
  const auto names = equilibrium_names(m.flap_modes, m.lag_modes);
  for (Eigen::Index i = 0; i < h.q0.size() && i < static_cast<Eigen::Index>(names.size()); ++i) {
    kv.add(names[static_cast<std::size_t>(i)], cell(h.q0[i]));
  }
  out += kv.render();
  out += "\nHover exponents (eigenvalues of A at mu = 0, per rev)\n";
  out += kExponentLegend;
  TextTable t({"mode", "zeta [1/rev]", "omega [per rev]", "damping ratio", "locked"});
  for (std::size_t i = 0; i < h.eigenvalues.size(); ++i) {
    const double zeta = h.eigenvalues[i].real(), omega = h.eigenvalues[i].imag();
    const std::string locked = locked_text(omega);
    t.add_row({i < h.labels.size() ? h.labels[i] : "?", cell(zeta), cell(omega),
               ratio_cell(zeta, omega), locked.empty() ? "-" : locked});
  }
  out += t.render();
  out += std::string("  hover is ") +
         (!hv.stable   ? "of unknown stability"
          : *hv.stable ? "stable"
                       : "UNSTABLE") +
         "\n";
  return out + status_text(h.status, vocab(r, h.message));
}

Json exponent_json(const LabelledExponent& e) {
  return Json{{"label", e.label},
              {"zeta", zeta_json(e.zeta)},
              {"omega", jnum(e.omega)},
              {"damping_ratio", ratio_json(e.zeta, e.omega)},
              {"multiplier", complex_json(e.multiplier)}};
}

Json point_json(const Request& r, const PointResult& p) {
  Json j;
  j["mu"] = jnum(p.mu);
  Json ex = Json::array(), mult = Json::array();
  for (const LabelledExponent& e : p.exponents) {
    ex.push_back(exponent_json(e));
    mult.push_back(complex_json(e.multiplier));
  }
  j["exponents"] = ex;
  j["multipliers"] = mult;
  j["liouville_residual"] = optional_json(p.liouville_residual);
  j["error_estimate"] = optional_json(p.error);
  j["stable"] = stable_json(p.stable);
  return status_json(j, p.status, vocab(r, p.message));
}

std::string point_text(const Request& r, const PointResult& p) {
  std::string out = "Characteristic exponents at mu = " + cell(p.mu) + " (per rev)\n";
  out += kExponentLegend;
  TextTable t({"mode", "zeta [1/rev]", "omega [per rev]", "damping ratio", "locked", "multiplier"});
  for (const LabelledExponent& e : p.exponents) {
    const std::string locked = locked_text(e.omega);
    t.add_row({e.label, zeta_cell(e.zeta), cell(e.omega), ratio_cell(e.zeta, e.omega),
               locked.empty() ? "-" : locked, complex_text(e.multiplier)});
  }
  out += t.render();
  KeyValues kv;
  kv.add("stable", stable_text(p.stable));
  kv.add("Liouville residual",
         optional_text(p.liouville_residual) + "  (|det Phi - exp int tr A|, relative)");
  kv.add("error estimate",
         optional_text(p.error) + "  (largest zeta error, per rev: Richardson from K and K/2)");
  out += kv.render();
  return out + status_text(p.status, vocab(r, p.message));
}

Json critical_json(const Request& r, const CriticalResult& c) {
  Json j;
  const bool found = c.mu_c.has_value();
  j["hover_unstable"] = c.hover_unstable;
  j["mu_c"] = optional_json(c.mu_c);
  j["mu_c_error"] = optional_json(c.mu_c_error);
  j["omega"] = found ? jnum(c.omega) : Json(nullptr);
  j["mode"] = found ? Json(c.mode) : Json(nullptr);
  j["kind"] = found ? Json(kind_name(c.kind)) : Json(nullptr);
  j["mu_max"] = jnum(c.mu_max);
  return status_json(j, c.status, vocab(r, c.message));
}

std::string critical_text(const Request& r, const CriticalResult& c) {
  std::string out =
      "Critical advance ratio (first mu in 0.." + cell(c.mu_max) + " with zeta > 0)\n";
  KeyValues kv;
  if (c.mu_c) {
    kv.add("mu_c", num(*c.mu_c) + (c.mu_c_error && finite(*c.mu_c_error)
                                       ? "  (estimated error " + num(*c.mu_c_error) + ")"
                                       : ""));
    kv.add("mode", c.mode);
    kv.add("omega", cell(c.omega) + " per rev");
    kv.add("kind", c.kind == InstabilityKind::Flutter
                       ? "flutter (omega not locked to 0, 1/2 or 1 per rev)"
                       : "periodic (omega locked to 0, 1/2 or 1 per rev)");
  } else if (c.hover_unstable) {
    kv.add("mu_c", "none: the blade is unstable already in hover");
  } else if (c.status == Status::Failed) {
    kv.add("mu_c", "unknown: the search failed");
  } else {
    kv.add("mu_c", "none: stable up to mu = " + cell(c.mu_max));
  }
  out += kv.render();
  return out + status_text(c.status, vocab(r, c.message));
}

// Largest Liouville residual over the points that have one; nullopt when none has.
std::optional<double> max_liouville(const SweepResult& s) {
  std::optional<double> m;
  for (const PointResult& p : s.points) {
    if (p.liouville_residual && finite(*p.liouville_residual)) {
      m = std::max(m.value_or(0.0), *p.liouville_residual);
    }
  }
  return m;
}

Json sweep_rows_json(const Request& r, const SweepResult& s,
                     const std::vector<std::string>& labels) {
  Json rows = Json::array();
  for (const PointResult& p : s.points) {
    Json row;
    row["mu"] = jnum(p.mu);
    for (const std::string& l : labels) {
      const LabelledExponent* e = dominant(p, l);
      row[l] = e ? Json{{"zeta", zeta_json(e->zeta)}, {"omega", jnum(e->omega)}} : Json(nullptr);
    }
    row["liouville_residual"] = optional_json(p.liouville_residual);
    row["error_estimate"] = optional_json(p.error);
    row["stable"] = stable_json(p.stable);
    row["status"] = status_name(p.status);
    row["message"] = vocab(r, p.message);
    Json ex = Json::array();
    for (const LabelledExponent& e : p.exponents) ex.push_back(exponent_json(e));
    row["exponents"] = ex;
    rows.push_back(row);
  }
  return rows;
}

std::string sweep_table_text(const Request& r, const SweepResult& s,
                             const std::vector<std::string>& labels) {
  std::vector<std::string> header{"mu"};
  for (const std::string& l : labels) {
    header.push_back(l + " zeta");
    header.push_back(l + " omega");
    header.push_back(l + " ratio");
  }
  header.push_back("stable");
  header.push_back("Liouville");
  TextTable t(header);
  std::string notes;
  for (const PointResult& p : s.points) {
    std::vector<std::string> row{cell(p.mu)};
    for (const std::string& l : labels) {
      const LabelledExponent* e = dominant(p, l);
      row.push_back(e ? zeta_cell(e->zeta) : "-");
      // " p": locked (periodic kind), as the paper marks Fig 15's periodic points.
      row.push_back(e ? cell(e->omega) + (locked_text(e->omega).empty() ? "  " : " p") : "-");
      row.push_back(e ? ratio_cell(e->zeta, e->omega) : "-");
    }
    row.push_back(stable_text(p.stable));
    row.push_back(optional_text(p.liouville_residual));
    t.add_row(row);
    if (p.status != Status::Ok || !p.message.empty()) {
      notes +=
          "  mu = " + cell(p.mu) + ": " + status_name(p.status) + ": " + vocab(r, p.message) + "\n";
    }
  }
  return kSweepLegend + t.render() + notes + status_text(s.status, vocab(r, s.message));
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// Empty fields for what is not known (no exponent of a label, no residual, unknown stability).
std::string sweep_csv(const Request& r, const SweepResult& s,
                      const std::vector<std::string>& labels) {
  auto field = [](double v) { return finite(v) ? exact_num(v) : std::string(); };
  std::string out = "mu";
  for (const std::string& l : labels) out += "," + l + "_zeta," + l + "_omega";
  out += ",liouville_residual,error_estimate,stable,status,message\n";
  for (const PointResult& p : s.points) {
    out += field(p.mu);
    for (const std::string& l : labels) {
      const LabelledExponent* e = dominant(p, l);
      out += "," + (e && zeta_ok(e->zeta) ? exact_zeta_text(e->zeta) : std::string()) + "," +
             (e ? field(e->omega) : std::string());
    }
    out += "," + (p.liouville_residual ? field(*p.liouville_residual) : std::string());
    out += "," + (p.error ? field(*p.error) : std::string());
    out += "," + std::string(!p.stable ? "" : *p.stable ? "true" : "false");
    out += "," + csv_field(status_name(p.status)) + "," + csv_field(vocab(r, p.message)) + "\n";
  }
  return out;
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

// ---- commands --------------------------------------------------------------------------------

std::string typical(const Request& r, const Analysis& an) {
  CriticalResult crit = an.critical(CriticalOptions{});
  audit(crit);
  // One continuation from hover in steps of kTableScan, shown every kTableEvery-th point: the
  // exponents of each row are continued exactly as `flaplag point` continues them, at a tenth of
  // the cost of continuing every row from hover again.
  const SweepResult all = an.sweep(0.0, kTableStop, kTableScan);
  SweepResult table;
  table.status = all.status;
  table.message = all.message;
  for (std::size_t i = 0; i < all.points.size(); ++i) {
    // A sweep that stopped early ends with the failed point: show it too.
    if (i % kTableEvery == 0 || i + 1 == all.points.size()) table.points.push_back(all.points[i]);
  }
  audit(table);
  const std::vector<std::string> labels = mode_labels(an);
  const std::optional<double> max_res = max_liouville(table);
  if (r.json) {
    Json j = header_json("typical", an);
    j["hover"] = hover_json(r, an);
    j["critical"] = critical_json(r, crit);
    Json t;
    t["labels"] = labels;
    t["rows"] = sweep_rows_json(r, table, labels);
    t["max_liouville_residual"] = optional_json(max_res);
    j["table"] = status_json(t, table.status, vocab(r, table.message));
    return dump(j);
  }
  std::string out =
      "flaplag: coupled flap-lag stability of a hingeless blade in forward flight "
      "(NASA CR-132431)\n";
  out += header_text(an) + "\n";
  out += warnings_text(an);
  out += hover_text(r, an) + "\n";
  out += critical_text(r, crit) + "\n";
  out += "Exponents zeta(mu), omega(mu) per rev (dominant exponent of each mode)\n";
  out += sweep_table_text(r, table, labels);
  out += "  Liouville residual |det Phi - exp int tr A| (relative), max over the table: " +
         optional_text(max_res) + "\n";
  return out;
}

// ---- trim (trim.h) ----------------------------------------------------------------------------

bool trimmed(const Request& r) { return r.trim.kind != TrimKind::None; }

Json trim_json(const Request& r, const TrimResult& t) {
  // The keys of the Python module's TrimResult (python/src/module.cc trim_dict): one
  // vocabulary for `flaplag trim`, the trim of point/sweep/critical --trim and of study rows.
  // (The trimmed rotor's parameters are the header's for `flaplag trim`; alpha_R is the case's
  // shaft_angle.)
  Json j;
  j["mu"] = jnum(t.mu);
  j["kind"] = trim_kind_name(t.kind);
  j["theta0"] = jnum(t.theta0);
  j["theta1c"] = jnum(t.theta1c);
  j["theta1s"] = jnum(t.theta1s);
  j["inflow"] = jnum(t.inflow);
  j["thrust_coefficient"] = jnum(t.thrust_coefficient);
  j["target"] = jnum(t.target);
  j["flap_1c"] = jnum(t.flap_1c);
  j["flap_1s"] = jnum(t.flap_1s);
  j["iterations"] = t.iterations;
  j["converged"] = t.converged;
  if (t.parameters.periodic_linearization) {
    j["equilibrium"] = Json{{"harmonics", t.equilibrium.harmonics},
                            {"truncation", jnum(t.equilibrium.truncation)}};
  }
  return status_json(j, t.status, vocab(r, t.message));
}

std::string trim_text(const Request& r, const TrimResult& t) {
  std::string out = std::string("Trim (") + trim_kind_name(t.kind) + ") at mu = " + cell(t.mu) +
                    ", C_T = " + cell(t.target) + ", alpha_R = " + cell(r.trim.shaft_angle) +
                    " rad\n";
  KeyValues kv;
  kv.add("theta0", cell(t.theta0) + " rad");
  kv.add("theta1c", cell(t.theta1c) + " rad");
  kv.add("theta1s", cell(t.theta1s) + " rad");
  kv.add("lambda", cell(t.inflow) + "  (eq 2.25)");
  kv.add("C_T achieved", cell(t.thrust_coefficient) + "  (the model's own lift, azimuth mean)");
  kv.add("flap tip 1st harmonic", cell(t.flap_1c) + " cos psi + " + cell(t.flap_1s) + " sin psi");
  if (t.parameters.periodic_linearization) {
    kv.add("trimmed about",
           "the periodic equilibrium of the nonlinear equations (harmonic "
           "balance, K = " +
               std::to_string(t.equilibrium.harmonics) + "; last harmonic " +
               cell(t.equilibrium.truncation) + " of the largest)");
  }
  kv.add("iterations", std::to_string(t.iterations));
  out += kv.render();
  return out + status_text(t.status, vocab(r, t.message));
}

std::string trim_command(const Request& r) {
  const TrimResult t = trim(r.params, r.mu, r.trim);
  if (r.json) {
    Json j = header_json("trim", Analysis(t.parameters, r.transition, t.inflow), false);
    j.update(trim_json(r, t));
    return dump(j);
  }
  return trim_text(r, t);
}

std::string point(const Request& r, const Analysis& an) {
  // Trimmed: the trim the point rests on (its problems are in the point's status).
  std::vector<TrimResult> trims;
  PointResult p = trimmed(r)
                      ? trimmed_point(r.params, r.transition, r.trim, r.mu, r.scan_step, &trims)
                      : an.point(r.mu, r.scan_step);
  audit(p);
  std::optional<TrimResult> t;
  if (!trims.empty()) t = trims.front();
  if (r.json) {
    Json j = header_json("point", an);
    j.update(point_json(r, p));
    j["hover"] = hover_json(r, an);
    if (t) j["trim"] = trim_json(r, *t);
    return dump(j);
  }
  return header_text(an) + "\n" + warnings_text(an) + (t ? trim_text(r, *t) + "\n" : "") +
         point_text(r, p);
}

std::string plot_if_asked(const Request& r, const std::string& script);

std::string sweep(const Request& r, const Analysis& an, std::string& warning) {
  // The trimmed controls at each point of the sweep: the trims its points rest on (their
  // problems are in the points' status).
  std::vector<TrimResult> trims;
  SweepResult s = trimmed(r) ? trimmed_sweep(r.params, r.transition, r.trim, r.sweep_start,
                                             r.sweep_stop, r.sweep_step, &trims)
                             : an.sweep(r.sweep_start, r.sweep_stop, r.sweep_step, r.threads);
  audit(s);
  const std::vector<std::string> labels = mode_labels(an);
  if (!r.plot.empty()) {
    std::vector<double> mu;
    for (const PointResult& p : s.points) mu.push_back(p.mu);
    std::vector<ModeCurve> modes;
    for (const std::string& l : labels) {
      ModeCurve m{l, {}, {}};
      for (const PointResult& p : s.points) {
        const LabelledExponent* e = dominant(p, l);
        m.zeta.push_back(e != nullptr && finite(e->zeta) ? e->zeta : NAN);
        m.omega.push_back(e != nullptr ? e->omega : NAN);
      }
      modes.push_back(m);
    }
    warning = plot_if_asked(r, sweep_plot_script(an.model().name, mu, modes));
  }
  if (r.csv) return sweep_csv(r, s, labels);
  if (r.json) {
    Json j = header_json("sweep", an);
    j["mu"] = Json{{"start", r.sweep_start}, {"stop", r.sweep_stop}, {"step", r.sweep_step}};
    j["labels"] = labels;
    j["rows"] = sweep_rows_json(r, s, labels);
    j["max_liouville_residual"] = optional_json(max_liouville(s));
    if (trimmed(r)) {
      Json tj = Json::array();
      for (const TrimResult& t : trims) tj.push_back(trim_json(r, t));
      j["trim"] = tj;
    }
    return dump(status_json(j, s.status, vocab(r, s.message)));
  }
  std::string trim_table;
  if (trimmed(r)) {
    trim_table = std::string("\nTrim (") + trim_kind_name(r.trim.kind) +
                 ") at each mu, C_T = " + cell(r.trim.thrust_coefficient) + "\n";
    TextTable t({"mu", "theta0", "theta1c", "theta1s", "lambda", "C_T", "status"});
    for (const TrimResult& x : trims) {
      t.add_row({cell(x.mu), cell(x.theta0), cell(x.theta1c), cell(x.theta1s), cell(x.inflow),
                 cell(x.thrust_coefficient), status_name(x.status)});
    }
    trim_table += t.render();
  }
  return header_text(an) + "\n" + warnings_text(an) +
         "Exponents per rev (dominant exponent of each mode)\n" + sweep_table_text(r, s, labels) +
         trim_table;
}

std::string critical(const Request& r, const Analysis& an) {
  CriticalOptions opt;
  opt.mu_max = r.mu_max;
  opt.scan_step = r.scan_step;
  std::vector<TrimResult> trims;  // the trim at mu_c the result rests on
  CriticalResult c =
      trimmed(r) ? trimmed_critical(r.params, r.transition, r.trim, opt, &trims) : an.critical(opt);
  audit(c);
  std::optional<TrimResult> t;
  if (!trims.empty()) t = trims.front();
  if (r.json) {
    Json j = header_json("critical", an);
    j.update(critical_json(r, c));
    if (trimmed(r)) j["trim"] = t ? trim_json(r, *t) : Json(nullptr);
    return dump(j);
  }
  return header_text(an) + "\n" + warnings_text(an) + critical_text(r, c) +
         (t ? "\n" + trim_text(r, *t) : "");
}

// Paper (Appendix B) name of an integral, looked up by its canonical name.
template <typename Integral>
std::string paper_name(const Integral* list, int n, const std::string& name) {
  for (int i = 0; i < n; ++i) {
    if (name == list[i].name) return list[i].paper_name;
  }
  return "";
}

std::string system_snapshot(const Request& r, const Analysis& an) {
  const SystemSnapshot s = an.snapshot(r.mu, r.psi);
  const model::ModelDescriptor& m = an.model();
  const std::vector<std::string> states = state_names(m.flap_modes, m.lag_modes);
  const Eigen::Index n = s.A.rows();
  auto state = [&](Eigen::Index i) {
    return i < static_cast<Eigen::Index>(states.size()) ? states[static_cast<std::size_t>(i)]
                                                        : std::to_string(i);
  };
  // The snapshot has no status of its own: the audit gives it one.
  Status status = Status::Ok;
  std::string message;
  if (!s.A.allFinite() || !s.f.allFinite() || !finite(s.psi)) {
    demote(status, message, Status::Failed, "entries of A(psi) or f(psi)");
  }
  bool integrals_ok = true;
  for (const auto& v : {&s.aero_integrals, &s.aero_integrals_region, &s.structural_integrals}) {
    for (const auto& [name, value] : *v) integrals_ok = integrals_ok && finite(value);
  }
  if (!integrals_ok) demote(status, message, Status::Failed, "spanwise integrals");
  if (r.json) {
    Json j = header_json("system", an, false);
    j["mu"] = s.mu;
    j["psi"] = jnum(s.psi);
    j["region"] = s.region;
    j["state"] = states;
    Json A = Json::array();
    for (Eigen::Index i = 0; i < n; ++i) {
      Json row = Json::array();
      for (Eigen::Index k = 0; k < s.A.cols(); ++k) row.push_back(jnum(s.A(i, k)));
      A.push_back(row);
    }
    j["A"] = A;
    Json f = Json::array();
    for (Eigen::Index i = 0; i < s.f.size(); ++i) f.push_back(jnum(s.f[i]));
    j["f"] = f;
    j["hover"] = hover_json(r, an);
    Json aero = Json::array();
    for (std::size_t i = 0; i < s.aero_integrals.size(); ++i) {
      const std::string& name = s.aero_integrals[i].first;
      Json a{{"name", name},
             {"paper_name", paper_name(m.aero, m.n_aero, name)},
             {"normal", jnum(s.aero_integrals[i].second)}};
      a["at_psi"] = i < s.aero_integrals_region.size() ? jnum(s.aero_integrals_region[i].second)
                                                       : Json(nullptr);
      aero.push_back(a);
    }
    j["aero_integrals"] = aero;
    Json st = Json::array();
    for (const auto& [name, value] : s.structural_integrals) {
      st.push_back(Json{{"name", name},
                        {"paper_name", paper_name(m.structural, m.n_structural, name)},
                        {"value", jnum(value)}});
    }
    j["structural_integrals"] = st;
    return dump(status_json(j, status, message));
  }
  std::string out = header_text(an, false) + "\n" + warnings_text(an);
  out += "System y' = A(psi) y + f(psi) at mu = " + num(s.mu) + ", psi = " + cell(s.psi) +
         " rad: " + s.region + " flow region\n";
  std::string state_list;
  for (const std::string& x : states) state_list += (state_list.empty() ? "" : ", ") + x;
  out += "  state y = [" + state_list + "]\n\nA(psi)\n";
  std::vector<std::string> header{"row"};
  for (Eigen::Index k = 0; k < s.A.cols(); ++k) header.push_back(state(k));
  header.push_back("f(psi)");
  TextTable t(header);
  for (Eigen::Index i = 0; i < n; ++i) {
    std::vector<std::string> row{state(i) + "'"};
    for (Eigen::Index k = 0; k < s.A.cols(); ++k) row.push_back(cell(s.A(i, k)));
    row.push_back(i < s.f.size() ? cell(s.f[i]) : "");
    t.add_row(row);
  }
  out += t.render() + status_text(status, message) + "\n" + hover_text(r, an) + "\n";
  out += "Aerodynamic spanwise integrals (int x^p ... dx0 over the aerodynamic span)\n";
  TextTable a({"integral", "paper", "normal flow", "used at psi"});
  a.left_align(1);
  for (std::size_t i = 0; i < s.aero_integrals.size(); ++i) {
    const std::string& name = s.aero_integrals[i].first;
    const std::string pn = paper_name(m.aero, m.n_aero, name);
    a.add_row({name, pn.empty() ? "-" : pn, cell(s.aero_integrals[i].second),
               i < s.aero_integrals_region.size() ? cell(s.aero_integrals_region[i].second) : "-"});
  }
  out += a.render() + "\nGeneralized masses and structural integrals (by I_b)\n";
  TextTable g({"integral", "paper", "value"});
  g.left_align(1);
  for (const auto& [name, value] : s.structural_integrals) {
    const std::string pn = paper_name(m.structural, m.n_structural, name);
    g.add_row({name, pn.empty() ? "-" : pn, cell(value)});
  }
  return out + g.render();
}

std::string models(const Request& r) {
  if (!r.spec.empty()) {
    const model::ModelDescriptor& m = find_model(r.spec);
    if (r.json) {
      return dump(Json{{"name", m.name}, {"spec_file", m.spec_file}, {"spec_text", m.spec_text}});
    }
    std::string text = m.spec_text;
    if (!text.empty() && text.back() != '\n') text += '\n';
    return text;
  }
  if (r.json) {
    Json list = Json::array();
    for (const model::ModelDescriptor* m : compiled_models()) list.push_back(model_json(*m));
    return dump(Json{{"command", "models"}, {"models", list}});
  }
  TextTable t({"model", "spec file", "modes", "summary"});
  t.left_align(1);
  t.left_align(3);
  for (const model::ModelDescriptor* m : compiled_models()) {
    t.add_row({m->name, m->spec_file,
               std::to_string(m->flap_modes) + "x" + std::to_string(m->lag_modes), m->summary});
  }
  return "Compiled ordering models (flaplag --model NAME; flaplag models --spec NAME)\n" +
         t.render();
}

// ---- studies, maps, response, simulation -------------------------------------------------------

// The word of a field in this command line's vocabulary ("omega_lag" -> "omega-lag").
std::string word(const std::string& field) {
  std::string s = field;
  for (char& c : s)
    if (c == '_') c = '-';
  return s;
}

// A plot, if asked for: "" or a warning line for stderr (the data is written in any case).
std::string plot_if_asked(const Request& r, const std::string& script) {
  if (r.plot.empty()) return "";
  return render_plot(script, r.plot);
}

// A run stopped by RunControl::cancel: what the output holds.
void note_cancelled(RunControl* control, std::size_t done, std::size_t all,
                    const std::string& lines) {
  if (control == nullptr) return;
  control->cancelled = true;
  control->message = "interrupted: " + std::to_string(done) + " of " + std::to_string(all) + " " +
                     lines + " finished; the output holds those";
}

Json interval_json(const InstabilityInterval& iv) {
  Json j = Json::array();
  j.push_back(jnum(iv.onset));
  j.push_back(iv.end ? jnum(*iv.end) : Json(nullptr));
  return j;
}

std::string study(const Request& request, std::string& warning, RunControl* control) {
  const Request r = shard_request(request);     // --shard: this part's values only
  const Analysis base(r.params, r.transition);  // the header, and the base parameters checked
  StudyOptions so;
  so.parameter = r.vary;
  so.values = r.vary_values;
  so.critical.mu_max = r.mu_max;
  so.critical.scan_step = r.scan_step;
  so.threads = r.threads;
  so.trim = r.trim;
  StudyResult s;
  if (!so.values.empty()) {  // an empty part of a job with more parts than values
    s = run_study(r.params, r.transition, so, control ? control->cancel : nullptr,
                  control ? control->progress : ProgressFunction{});
  }
  if (s.cancelled)
    note_cancelled(control, s.rows_done, so.values.size(), "values (" + word(r.vary) + ")");
  for (StudyRow& row : s.rows) audit(row.critical);
  // A trimmed study reports each row's trim at its mu_c (theta0, theta1c, theta1s, lambda
  // there), as `critical --trim` and the Python module's study rows do: the trim the row's
  // search made there, whose problems are in the row's status.
  std::vector<std::optional<TrimResult>> trims(s.rows.size());
  for (std::size_t i = 0; trimmed(r) && i < s.rows.size(); ++i) trims[i] = s.rows[i].trim;
  if (!r.plot.empty()) {
    std::vector<StudyMark> marks;
    for (const StudyRow& row : s.rows) {
      const CriticalResult& c = row.critical;
      StudyMark m{row.value, c.mu_c, c.kind == InstabilityKind::Periodic, {}};
      // An open interval is drawn to the scan limit (r.mu_max: what the JSON output holds).
      for (const InstabilityInterval& iv : c.intervals)
        m.intervals.emplace_back(iv.onset, iv.end.value_or(r.mu_max));
      marks.push_back(m);
    }
    warning = plot_if_asked(r, study_plot_script(word(r.vary), marks));
  }
  if (r.json) {
    Json j = header_json("study", base);
    j["vary"] = word(r.vary);
    j["mu_max"] = r.mu_max;
    j["scan_step"] = r.scan_step;
    Json rows = Json::array();
    for (std::size_t k = 0; k < s.rows.size(); ++k) {
      const StudyRow& row = s.rows[k];
      const CriticalResult& c = row.critical;
      Json x;
      x["value"] = row.value;
      x["hover_unstable"] = c.hover_unstable;
      x["mu_c"] = optional_json(c.mu_c);
      x["mu_c_error"] = optional_json(c.mu_c_error);
      x["mode"] = c.mu_c ? Json(c.mode) : Json(nullptr);
      x["omega"] = c.mu_c ? jnum(c.omega) : Json(nullptr);
      x["kind"] = c.mu_c ? Json(kind_name(c.kind)) : Json(nullptr);
      Json iv = Json::array();
      for (const InstabilityInterval& i : c.intervals) iv.push_back(interval_json(i));
      x["intervals"] = iv;
      if (trimmed(r)) x["trim"] = trims[k] ? trim_json(r, *trims[k]) : Json(nullptr);
      rows.push_back(status_json(x, c.status, vocab(r, c.message)));
    }
    j["rows"] = rows;
    return dump(status_json(j, s.status, vocab(r, s.message)));
  }
  std::string out = header_text(base) + "\n";
  out += "mu_c and instability intervals versus " + word(r.vary) + " (mu up to " + num(r.mu_max) +
         ")\n";
  std::vector<std::string> head = {word(r.vary), "mu_c", "mode",
                                   "omega",      "kind", "unstable for mu in"};
  // Trimmed: the controls and inflow of the trim at mu_c [rad; lambda of eq 2.25].
  if (trimmed(r)) head.insert(head.end(), {"theta0", "theta1c", "theta1s", "lambda"});
  head.push_back("status");
  TextTable t(head);
  t.left_align(head.size() - 1);
  t.left_align(5);
  for (std::size_t k = 0; k < s.rows.size(); ++k) {
    const StudyRow& row = s.rows[k];
    const CriticalResult& c = row.critical;
    std::string ivs;
    for (const InstabilityInterval& i : c.intervals)
      ivs += (ivs.empty() ? "" : " ") + std::string("(") + short_text(i.onset) + ", " +
             (i.end ? short_text(*i.end) : std::string("mu-max")) + ")";
    std::vector<std::string> cells = {
        num(row.value),
        c.mu_c ? short_text(*c.mu_c) : (c.hover_unstable ? "hover" : "-"),
        c.mu_c ? c.mode : "-",
        c.mu_c ? short_text(c.omega) : "-",
        c.mu_c ? kind_name(c.kind) : "-",
        ivs.empty() ? "-" : ivs};
    if (trimmed(r)) {
      const std::optional<TrimResult>& x = trims[k];
      for (double v :
           {x ? x->theta0 : 0.0, x ? x->theta1c : 0.0, x ? x->theta1s : 0.0, x ? x->inflow : 0.0})
        cells.push_back(x ? short_text(v) : "-");
    }
    cells.push_back(status_name(c.status));
    t.add_row(cells);
  }
  out += t.render();
  for (const StudyRow& row : s.rows)
    if (row.critical.status != Status::Ok)
      out += "  " + word(r.vary) + " = " + num(row.value) + ": " +
             status_name(row.critical.status) + ": " + vocab(r, row.critical.message) + "\n";
  return out;
}

std::string map(const Request& request, std::string& warning, RunControl* control) {
  Request r = shard_request(request);  // --shard: this part's lines only
  const Analysis base(r.params, r.transition);
  MapOptions mo;
  mo.x = {r.x_name, r.x_values};
  mo.y = {r.y_name, r.y_values};
  mo.mu = r.mu;
  mo.scan_step = r.scan_step;
  mo.threads = r.threads;
  mo.trim = r.trim;
  MapResult m;
  m.cells.assign(r.y_values.size(), {});  // an empty part: no lines
  if (!r.x_values.empty() && !r.y_values.empty()) {
    m = run_map(r.params, r.transition, mo, control ? control->cancel : nullptr,
                control ? control->progress : ProgressFunction{});
  }
  if (m.cancelled) {
    // The output is the map of the lines finished: rows, or columns when y is mu.
    const bool columns = r.y_name == "mu";
    note_cancelled(control, m.lines_done, columns ? r.x_values.size() : r.y_values.size(),
                   (columns ? "columns (" + word(r.x_name) : "rows (" + word(r.y_name)) + ")");
    if (columns) {
      r.x_values.resize(m.lines_done);
      for (auto& row : m.cells) row.resize(m.lines_done);
    } else {
      r.y_values.resize(m.lines_done);
      m.cells.resize(m.lines_done);
    }
  }
  std::vector<std::vector<double>> z(r.y_values.size());
  for (std::size_t i = 0; i < m.cells.size(); ++i)
    for (const MapCell& c : m.cells[i])
      z[i].push_back(c.max_zeta && finite(*c.max_zeta) ? *c.max_zeta : NAN);
  warning = plot_if_asked(
      r, max_zeta_plot_script(word(r.x_name), r.x_values, word(r.y_name), r.y_values, z));
  if (r.json) {
    Json j = header_json("map", base);
    j["x"] = Json{{"name", word(r.x_name)}, {"values", r.x_values}};
    j["y"] = Json{{"name", word(r.y_name)}, {"values", r.y_values}};
    if (r.x_name != "mu" && r.y_name != "mu") j["mu"] = r.mu;
    Json zeta = Json::array(), mode = Json::array(), kind = Json::array();
    for (const auto& row : m.cells) {
      Json a = Json::array(), b = Json::array(), c = Json::array();
      for (const MapCell& cell : row) {
        a.push_back(cell.max_zeta ? zeta_json(*cell.max_zeta) : Json(nullptr));
        b.push_back(cell.max_zeta ? Json(cell.mode) : Json(nullptr));
        c.push_back(cell.max_zeta ? Json(kind_name(cell.kind)) : Json(nullptr));
      }
      zeta.push_back(a);
      mode.push_back(b);
      kind.push_back(c);
    }
    j["max_zeta"] = zeta;
    j["mode"] = mode;
    j["kind"] = kind;
    return dump(status_json(j, m.status, vocab(r, m.message)));
  }
  std::string out = header_text(base) + "\n";
  out += "Largest zeta (per rev) over " + word(r.y_name) + " (rows) x " + word(r.x_name) +
         " (columns); * marks an unstable point\n";
  std::vector<std::string> header{word(r.y_name) + " \\ " + word(r.x_name)};
  for (double x : r.x_values) header.push_back(short_text(x));
  TextTable t(header);
  for (std::size_t i = 0; i < m.cells.size(); ++i) {
    std::vector<std::string> row{short_text(r.y_values[i])};
    for (const MapCell& c : m.cells[i])
      row.push_back(c.max_zeta ? short_text(*c.max_zeta) + (*c.max_zeta > 0 ? "*" : " ") : "-");
    t.add_row(row);
  }
  return out + t.render() + status_text(m.status, vocab(r, m.message));
}

std::string response(const Request& r, const Analysis& an, std::string& warning) {
  ResponseOptions ro;
  ro.samples = r.samples;
  const ForcedResponse f = an.response(r.mu, ro);
  if (f.status != Status::Failed) {
    std::vector<double> deg;
    for (double p : f.periodic.psi) deg.push_back(p * 180.0 / kPi);
    warning = plot_if_asked(r, response_plot_script(r.mu, deg, f.flap_tip, f.lag_tip));
  }
  if (r.json) {
    Json j = header_json("response", an, false);
    j["mu"] = r.mu;
    if (f.status != Status::Failed) {
      j["psi"] = f.periodic.psi;
      j["flap_tip"] = f.flap_tip;
      j["lag_tip"] = f.lag_tip;
      Json h = Json::object(), g = Json::object();
      for (std::size_t k = 0; k < f.flap_harmonics.size(); ++k) {
        h[harmonic_name(static_cast<int>(k))] = f.flap_harmonics[k];
        g[harmonic_name(static_cast<int>(k))] = f.lag_harmonics[k];
      }
      j["flap_harmonics"] = h;
      j["lag_harmonics"] = g;
      j["closure"] = f.periodic.closure;
      j["error_estimate"] = optional_json(f.periodic.error);
      j["steps"] = f.periodic.steps;
    }
    return dump(status_json(j, f.status, vocab(r, f.message)));
  }
  std::string out = header_text(an, false) + "\n";
  out += "Periodic forced response at mu = " + num(r.mu) +
         " (tip deflections by l, hover equilibrium included)\n";
  if (f.status == Status::Failed) return out + status_text(f.status, vocab(r, f.message));
  TextTable h({"harmonic", "flap w/l", "lag v/l"});
  for (std::size_t k = 0; k < f.flap_harmonics.size(); ++k)
    h.add_row({harmonic_name(static_cast<int>(k)), short_text(f.flap_harmonics[k]),
               short_text(f.lag_harmonics[k])});
  out += h.render();
  TextTable t({"psi [deg]", "flap w/l", "lag v/l"});
  const std::size_t every = std::max<std::size_t>(1, f.flap_tip.size() / 24);
  for (std::size_t k = 0; k < f.flap_tip.size(); k += every)
    t.add_row({short_text(f.periodic.psi[k] * 180.0 / kPi), short_text(f.flap_tip[k]),
               short_text(f.lag_tip[k])});
  out += "\n" + t.render();
  out += "  periodicity |y(2 pi) - y(0)| / |y0| = " + short_text(f.periodic.closure) + "\n";
  return out + status_text(f.status, vocab(r, f.message));
}

std::string simulate_command(const Request& r, const Analysis& an, std::string& warning) {
  SimulationOptions so;
  so.revolutions = r.revolutions;
  so.samples_per_rev = r.samples;
  so.nonlinear = r.nonlinear;
  const Eigen::VectorXd y0 = Eigen::VectorXd::Constant(an.state_size(), r.perturbation);
  const TipSimulation ts = an.simulate(r.mu, y0, r.forced, so);
  const Simulation& s = ts.simulation;
  const std::vector<double>& flap = ts.flap_tip;
  const std::vector<double>& lag = ts.lag_tip;
  std::vector<double> revs;
  for (double psi : s.psi) revs.push_back(psi / kTwoPi);
  const std::optional<double>& flap_rate = ts.flap_growth_rate;
  const std::optional<double>& lag_rate = ts.lag_growth_rate;
  warning = plot_if_asked(r, simulate_plot_script(r.mu, revs, flap, lag));
  if (r.json) {
    Json j = header_json("simulate", an, false);
    j["mu"] = r.mu;
    j["forced"] = r.forced;
    j["nonlinear"] = ts.nonlinear;
    j["reference"] = ts.reference;
    j["revolutions"] = r.revolutions;
    j["steps_per_rev"] = s.steps_per_rev;
    j["psi"] = s.psi;
    j["flap_tip"] = flap;
    j["lag_tip"] = lag;
    if (ts.nonlinear) {
      j["flap_total"] = ts.flap_total;
      j["lag_total"] = ts.lag_total;
    }
    j["flap_growth_rate"] = optional_json(flap_rate);
    j["lag_growth_rate"] = optional_json(lag_rate);
    return dump(status_json(j, ts.status, vocab(r, ts.message)));
  }
  std::string out = header_text(an, false) + "\n";
  if (ts.nonlinear) {
    out += "Nonlinear response at mu = " + num(r.mu) + " from the " + ts.reference + " + " +
           num(r.perturbation) + " in every state, " + num(r.revolutions) + " revolutions (" +
           std::to_string(s.steps_per_rev) + " RK4 steps per rev); d: deviation from the " +
           ts.reference + "\n";
  } else {
    out += std::string(r.forced ? "Forced" : "Free") + " response at mu = " + num(r.mu) +
           " from y0 = " + num(r.perturbation) + " in every state, " + num(r.revolutions) +
           " revolutions (" + std::to_string(s.steps_per_rev) + " RK4 steps per rev)\n";
  }
  TextTable t(ts.nonlinear
                  ? std::vector<std::string>{"rev", "flap dw/l", "lag dv/l", "flap w/l", "lag v/l"}
                  : std::vector<std::string>{"rev", "flap dw/l", "lag dv/l"});
  const std::size_t every = std::max<std::size_t>(1, s.y.size() / 20);
  for (std::size_t k = 0; k < s.y.size(); k += every) {
    std::vector<std::string> row{short_text(revs[k]), short_text(flap[k]), short_text(lag[k])};
    if (ts.nonlinear) {
      row.push_back(short_text(ts.flap_total[k]));
      row.push_back(short_text(ts.lag_total[k]));
    }
    t.add_row(row);
  }
  out += t.render();
  out +=
      "  envelope growth rate (last 3/4 of the run; compare with the largest Floquet zeta): flap " +
      (flap_rate ? short_text(*flap_rate) : std::string("-")) + ", lag " +
      (lag_rate ? short_text(*lag_rate) : std::string("-")) + " per rev\n";
  return out + status_text(ts.status, vocab(r, ts.message));
}

// The command line behind a result, as the "case" object of JSON outputs: `flaplag run` takes
// it back (case_file.h).
Json case_json(const Request& r) {
  // Keys in a canonical order (command, then alphabetical), so that a case read back from a
  // file in any key order reproduces the same bytes.
  std::map<std::string, Json> options;
  const std::vector<std::string>& a = r.arguments;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string& s = a[i];
    if (s.rfind("-", 0) != 0 || s == "-") continue;  // the subcommand
    std::string name = s, value;
    bool attached = false;
    const auto eq = s.find('=');
    if (s.rfind("--", 0) == 0 && eq != std::string::npos) {
      name = s.substr(0, eq);
      value = s.substr(eq + 1);
      attached = true;
    } else if (s.rfind("-o", 0) == 0 && s.size() > 2 && s.rfind("--", 0) != 0) {
      name = "-o";
      value = s.substr(2);
      attached = true;
    }
    const OptionSpec* o = find_option(r.command, name);
    if (o == nullptr) continue;
    // Where the result goes is not part of it: the same run to stdout and to -o FILE writes
    // the same bytes.
    if (o->name == "-o") {
      if (!attached) ++i;
      continue;
    }
    if (o->name == "--quiet") continue;  // how the run looked, not what it computed
    const std::string key = o->name.substr(2);
    if (!o->takes_value) {
      options[key] = true;
    } else {
      if (!attached && i + 1 < a.size()) value = a[++i];
      options[key] = value;
    }
  }
  Json c = Json::object();
  c["command"] = command_name(r.command);
  for (const auto& [key, value] : options) c[key] = value;
  return c;
}

}  // namespace

std::string run_command(const Request& r, std::string* warning, RunControl* control) {
  std::string text = run_command_text(r, warning, control);
  const bool cancelled = control != nullptr && control->cancelled;
  if (!r.json || text.empty() || text[0] != '{') {
    if (cancelled) text += "  status: cancelled: " + control->message + "\n";
    return text;
  }
  // Provenance in every JSON output: the flaplag version and commit, and the case that
  // reproduces it (`flaplag run FILE.json`).
  Json j = Json::parse(text);
  if (cancelled) {
    const std::string before = j.value("message", "");
    j["status"] = "cancelled";
    j["message"] = control->message + (before.empty() ? "" : "; " + before);
  }
  if (r.shard_count > 0) j["shard"] = shard_json(r);  // which part of a --shard job
  j["flaplag"] = Json{{"version", FLAPLAG_VERSION}, {"commit", FLAPLAG_GIT_COMMIT}};
  j["case"] = case_json(r);
  if (r.shard_count > 0) seal_part(j);  // last: the digest covers everything above
  return dump(j);
}

std::string run_command_text(const Request& r, std::string* warning, RunControl* control) {
  std::string ignored;
  std::string& w = warning != nullptr ? *warning : ignored;
  switch (r.command) {
    case Command::Models:
      return models(r);
    case Command::Modes:
      return run_modes(r);
    case Command::Study:
      return study(r, w, control);
    case Command::Map:
      return map(r, w, control);
    case Command::Merge:
      return merge_parts(r);
    case Command::Plot:
      return plot_data_files(r.inputs, r.labels, r.max_zeta, r.mode, r.plot, r.memory_limit);
    case Command::Trim:
      return trim_command(r);
    default:
      break;
  }
  if (trimmed(r)) {
    // The header shows the rotor trimmed in hover (its theta0 and eq 2.25 lambda); each mu of
    // the analysis is trimmed on its own.
    const TrimResult h = trim(r.params, 0.0, r.trim);
    if (h.status == Status::Failed) {
      throw InvalidInput("thrust_coefficient", round_trip_text(r.trim.thrust_coefficient),
                         "the rotor cannot be trimmed in hover: " + h.message);
    }
    const Analysis an(h.parameters, r.transition, h.inflow);
    switch (r.command) {
      case Command::Point:
        return point(r, an);
      case Command::Sweep:
        return sweep(r, an, w);
      case Command::Critical:
        return critical(r, an);
      default:
        break;
    }
  }
  const Analysis an(r.params, r.transition);
  switch (r.command) {
    case Command::Point:
      return point(r, an);
    case Command::Sweep:
      return sweep(r, an, w);
    case Command::Critical:
      return critical(r, an);
    case Command::System:
      return system_snapshot(r, an);
    case Command::Response:
      return response(r, an, w);
    case Command::Simulate:
      return simulate_command(r, an, w);
    default:
      return typical(r, an);
  }
}

}  // namespace flaplag::cli
