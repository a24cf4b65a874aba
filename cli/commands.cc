#include "commands.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/rotor/parameter_table.h"
#include "output.h"

namespace flaplag::cli {

namespace {

using Json = nlohmann::ordered_json;

// The short zeta(mu) table of the typical case: mu = 0, 0.1, ..., 1.0.
constexpr double kTableStop = 1.0;
constexpr double kTableStep = 0.1;

std::string dump(const Json& j) { return j.dump(2) + "\n"; }

Json complex_json(std::complex<double> z) { return Json{{"re", z.real()}, {"im", z.imag()}}; }

std::string complex_text(std::complex<double> z) {
  return num(z.real()) + (std::signbit(z.imag()) ? " - " : " + ") + num(std::abs(z.imag())) + "i";
}

Json parameters_json(const RotorParameters& p) {
  Json j = Json::object();
  for (const ParameterSpec& s : parameter_table()) {
    switch (s.type) {
      case ParameterType::Real:
        j[s.field] = p.*s.real;
        break;
      case ParameterType::Flag:
        j[s.field] = p.*s.flag;
        break;
      case ParameterType::Choice:
      case ParameterType::Text:
        j[s.field] = parameter_text(p, s);
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
  Json j{{"name", method_name(o.method)}, {"steps", o.steps}};
  if (o.method == TransitionMethod::Hsu) j["terms"] = o.terms;
  return j;
}

std::string method_text(const TransitionOptions& o) {
  switch (o.method) {
    case TransitionMethod::RK4:
      return "rk4, N = " + std::to_string(o.steps) + " steps per period";
    case TransitionMethod::Hsu:
      return "hsu, K = " + std::to_string(o.steps) + " intervals, J = " + std::to_string(o.terms) +
             " Taylor terms";
    case TransitionMethod::Magnus4:
      return "magnus (4th order, Richardson error estimate), " + std::to_string(o.steps) +
             " steps per period";
  }
  return method_name(o.method);
}

bool coupling_on(const Analysis& an) {
  return an.parameters().elastic_coupling && an.modes().kind == "exact";
}

// The part every analysis output starts with: what was computed, and how.
Json header_json(const char* command, const Analysis& an) {
  const model::ModelDescriptor& m = an.model();
  Json j;
  j["command"] = command;
  j["model"] = model_json(m);
  j["mode_shapes"] = an.modes().kind;
  j["elastic_coupling"] = coupling_on(an);
  j["method"] = method_json(an.options());
  j["parameters"] = parameters_json(an.parameters());
  return j;
}

std::string header_text(const Analysis& an) {
  const RotorParameters& p = an.parameters();
  const model::ModelDescriptor& m = an.model();
  KeyValues kv;
  kv.add("model", std::string(m.name) + " (" + m.spec_file + "): " + m.summary);
  std::string blade =
      an.modes().kind == "exact" ? "exact rotating mode shapes" : "assumed mode shape (eq 4.1)";
  if (p.paper_1974_shapes && an.modes().kind == "exact") blade += " (1974 shapes)";
  blade += ", " + std::to_string(m.flap_modes) + " flap x " + std::to_string(m.lag_modes) +
           " lag; elastic coupling " + (coupling_on(an) ? "on" : "off") + "; reversed flow " +
           (p.reversed_flow ? "on" : "off");
  kv.add("blade", blade);
  kv.add("method", method_text(an.options()));
  kv.add("parameters", parameters_text(p));
  return kv.render();
}

std::vector<std::string> state_names(int M, int N) {
  std::vector<std::string> s;
  for (int k = 1; k <= M; ++k) s.push_back("dg'_" + std::to_string(k));
  for (int k = 1; k <= M; ++k) s.push_back("dg_" + std::to_string(k));
  for (int k = 1; k <= N; ++k) s.push_back("dh'_" + std::to_string(k));
  for (int k = 1; k <= N; ++k) s.push_back("dh_" + std::to_string(k));
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

Json hover_json(const Analysis& an) {
  const HoverResult& h = an.hover();
  const model::ModelDescriptor& m = an.model();
  Json j;
  j["inflow"] = h.inflow;
  Json q0 = Json::object();
  const auto names = equilibrium_names(m.flap_modes, m.lag_modes);
  for (Eigen::Index i = 0; i < h.q0.size() && i < static_cast<Eigen::Index>(names.size()); ++i) {
    q0[names[static_cast<std::size_t>(i)]] = h.q0[i];
  }
  j["equilibrium"] = q0;
  Json ex = Json::array();
  for (std::size_t i = 0; i < h.eigenvalues.size(); ++i) {
    ex.push_back(Json{{"zeta", h.eigenvalues[i].real()},
                      {"omega", h.eigenvalues[i].imag()},
                      {"label", i < h.labels.size() ? h.labels[i] : ""}});
  }
  j["exponents"] = ex;
  j["stable"] = h.stable;
  return status_json(j, h.status, h.message);
}

std::string hover_text(const Analysis& an) {
  const HoverResult& h = an.hover();
  const model::ModelDescriptor& m = an.model();
  std::string out = "Hover equilibrium (eqs 2.24, 2.29-2.32)\n";
  KeyValues kv;
  kv.add("inflow lambda", num(h.inflow));
  const auto names = equilibrium_names(m.flap_modes, m.lag_modes);
  for (Eigen::Index i = 0; i < h.q0.size() && i < static_cast<Eigen::Index>(names.size()); ++i) {
    kv.add(names[static_cast<std::size_t>(i)], num(h.q0[i]));
  }
  out += kv.render();
  out += "\nHover exponents (eigenvalues of A at mu = 0, per rev)\n";
  TextTable t({"mode", "zeta", "omega"});
  for (std::size_t i = 0; i < h.eigenvalues.size(); ++i) {
    t.add_row({i < h.labels.size() ? h.labels[i] : "?", num(h.eigenvalues[i].real()),
               num(h.eigenvalues[i].imag())});
  }
  out += t.render();
  out += std::string("  hover is ") + (h.stable ? "stable" : "UNSTABLE") + "\n";
  return out + status_text(h.status, h.message);
}

// zeta of a zero multiplier is -inf, which JSON cannot hold: it is written as the string "-inf".
Json zeta_json(double zeta) { return std::isfinite(zeta) ? Json(zeta) : Json(round_trip_text(zeta)); }

Json optional_json(const std::optional<double>& v) { return v ? Json(*v) : Json(nullptr); }

Json stable_json(const std::optional<bool>& v) { return v ? Json(*v) : Json(nullptr); }

std::string stable_text(const std::optional<bool>& v) { return !v ? "unknown" : *v ? "yes" : "NO"; }

std::string optional_text(const std::optional<double>& v) { return v ? num(*v) : "-"; }

Json exponent_json(const LabelledExponent& e) {
  return Json{{"label", e.label},
              {"zeta", zeta_json(e.zeta)},
              {"omega", e.omega},
              {"multiplier", complex_json(e.multiplier)}};
}

Json point_json(const PointResult& r) {
  Json j;
  j["mu"] = r.mu;
  Json ex = Json::array(), mult = Json::array();
  for (const LabelledExponent& e : r.exponents) {
    ex.push_back(exponent_json(e));
    mult.push_back(complex_json(e.multiplier));
  }
  j["exponents"] = ex;
  j["multipliers"] = mult;
  j["liouville_residual"] = optional_json(r.liouville_residual);
  j["error_estimate"] = optional_json(r.error);
  j["stable"] = stable_json(r.stable);
  return status_json(j, r.status, r.message);
}

std::string point_text(const PointResult& r, const TransitionOptions& o) {
  std::string out = "Characteristic exponents at mu = " + num(r.mu) + " (per rev)\n";
  TextTable t({"mode", "zeta", "omega", "multiplier"});
  for (const LabelledExponent& e : r.exponents) {
    t.add_row({e.label, num(e.zeta), num(e.omega), complex_text(e.multiplier)});
  }
  out += t.render();
  KeyValues kv;
  kv.add("stable", stable_text(r.stable));
  kv.add("Liouville residual",
         optional_text(r.liouville_residual) + "  (|det Phi - exp int tr A|, relative)");
  kv.add("error estimate",
         optional_text(r.error) + "  (exponents, per rev: Richardson from K and K/2 steps)");
  (void)o;
  out += kv.render();
  return out + status_text(r.status, r.message);
}

Json critical_json(const CriticalResult& c) {
  Json j;
  const bool found = c.mu_c.has_value();
  j["hover_unstable"] = c.hover_unstable;
  j["mu_c"] = optional_json(c.mu_c);
  j["mu_c_error"] = optional_json(c.mu_c_error);
  j["omega"] = found ? Json(c.omega) : Json(nullptr);
  j["mode"] = found ? Json(c.mode) : Json(nullptr);
  j["kind"] = found ? Json(kind_name(c.kind)) : Json(nullptr);
  j["mu_max"] = c.mu_max;
  return status_json(j, c.status, c.message);
}

std::string critical_text(const CriticalResult& c) {
  std::string out = "Critical advance ratio (first mu in 0.." + num(c.mu_max) + " with zeta > 0)\n";
  KeyValues kv;
  if (c.mu_c) {
    kv.add("mu_c", num(*c.mu_c) + (c.mu_c_error ? "  (estimated error " + num(*c.mu_c_error) + ")" : ""));
    kv.add("mode", c.mode);
    kv.add("omega", num(c.omega) + " per rev");
    kv.add("kind", c.kind == InstabilityKind::Flutter
                       ? "flutter (omega not locked to 0, 1/2 or 1 per rev)"
                       : "periodic (omega locked to 0, 1/2 or 1 per rev)");
  } else if (c.hover_unstable) {
    kv.add("mu_c", "none: the blade is unstable already in hover");
  } else if (c.status == Status::Failed) {
    kv.add("mu_c", "unknown: the search failed");
  } else {
    kv.add("mu_c", "none: stable up to mu = " + num(c.mu_max));
  }
  out += kv.render();
  return out + status_text(c.status, c.message);
}

Json sweep_rows_json(const SweepResult& s, const std::vector<std::string>& labels) {
  Json rows = Json::array();
  for (const PointResult& p : s.points) {
    Json row;
    row["mu"] = p.mu;
    for (const std::string& l : labels) {
      const LabelledExponent* e = dominant(p, l);
      row[l] = e ? Json{{"zeta", zeta_json(e->zeta)}, {"omega", e->omega}} : Json(nullptr);
    }
    row["liouville_residual"] = optional_json(p.liouville_residual);
    row["error_estimate"] = optional_json(p.error);
    row["stable"] = stable_json(p.stable);
    row["status"] = status_name(p.status);
    if (!p.message.empty()) row["message"] = p.message;
    Json ex = Json::array();
    for (const LabelledExponent& e : p.exponents) ex.push_back(exponent_json(e));
    row["exponents"] = ex;
    rows.push_back(row);
  }
  return rows;
}

std::string sweep_table_text(const SweepResult& s, const std::vector<std::string>& labels) {
  std::vector<std::string> header{"mu"};
  for (const std::string& l : labels) {
    header.push_back(l + " zeta");
    header.push_back(l + " omega");
  }
  header.push_back("Liouville");
  TextTable t(header);
  std::string notes;
  for (const PointResult& p : s.points) {
    std::vector<std::string> row{num(p.mu)};
    for (const std::string& l : labels) {
      const LabelledExponent* e = dominant(p, l);
      row.push_back(e ? num(e->zeta) : "-");
      row.push_back(e ? num(e->omega) : "-");
    }
    row.push_back(optional_text(p.liouville_residual));
    t.add_row(row);
    if (p.status != Status::Ok || !p.message.empty()) {
      notes += "  mu = " + num(p.mu) + ": " + status_name(p.status) + ": " + p.message + "\n";
    }
  }
  return t.render() + notes + status_text(s.status, s.message);
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string sweep_csv(const SweepResult& s, const std::vector<std::string>& labels) {
  std::string out = "mu";
  for (const std::string& l : labels) out += "," + l + "_zeta," + l + "_omega";
  out += ",liouville_residual,stable,status\n";
  for (const PointResult& p : s.points) {
    out += num(p.mu);
    for (const std::string& l : labels) {
      const LabelledExponent* e = dominant(p, l);
      out += e ? "," + num(e->zeta) + "," + num(e->omega) : std::string(",,");
    }
    out += "," + (p.liouville_residual ? num(*p.liouville_residual) : std::string()) + "," +
           (!p.stable ? "" : *p.stable ? "true" : "false") + "," +
           csv_field(status_name(p.status)) + "\n";
  }
  return out;
}

double max_liouville(const SweepResult& s) {
  double m = 0.0;
  for (const PointResult& p : s.points) m = std::max(m, p.liouville_residual.value_or(0.0));
  return m;
}

std::string warnings_text(const Analysis& an) {
  const HoverResult& h = an.hover();
  return h.stable ? ""
                  : "warning: the hover equilibrium itself is unstable; see the hover exponents\n";
}

// ---- commands --------------------------------------------------------------------------------

std::string typical(const Request& r, const Analysis& an) {
  const CriticalResult crit = an.critical(CriticalOptions{});
  // Points one by one so that mu is exactly k/10 in the table (mu0 + k * step is not).
  SweepResult table;
  const int n_table = static_cast<int>(std::lround(kTableStop / kTableStep));
  for (int k = 0; k <= n_table; ++k) {
    table.points.push_back(an.point(static_cast<double>(k) / n_table * kTableStop));
  }
  const std::vector<std::string> labels = mode_labels(an);
  if (r.json) {
    Json j = header_json("typical", an);
    j["hover"] = hover_json(an);
    j["critical"] = critical_json(crit);
    Json t;
    t["labels"] = labels;
    t["rows"] = sweep_rows_json(table, labels);
    t["max_liouville_residual"] = max_liouville(table);
    j["table"] = status_json(t, table.status, table.message);
    return dump(j);
  }
  std::string out =
      "flaplag: coupled flap-lag stability of a hingeless blade in forward flight "
      "(NASA CR-132431)\n";
  out += header_text(an) + "\n";
  out += warnings_text(an);
  out += hover_text(an) + "\n";
  out += critical_text(crit) + "\n";
  out += "Exponents zeta(mu), omega(mu) per rev (dominant exponent of each mode)\n";
  out += sweep_table_text(table, labels);
  out += "  Liouville residual |det Phi - exp int tr A| (relative), max over the table: " +
         num(max_liouville(table)) + "\n";
  return out;
}

std::string point(const Request& r, const Analysis& an) {
  const PointResult p = an.point(r.mu);
  if (r.json) {
    Json j = header_json("point", an);
    j.update(point_json(p));
    j["hover"] = hover_json(an);
    return dump(j);
  }
  return header_text(an) + "\n" + warnings_text(an) + point_text(p, an.options());
}

std::string sweep(const Request& r, const Analysis& an) {
  const SweepResult s = an.sweep(r.sweep_start, r.sweep_stop, r.sweep_step);
  const std::vector<std::string> labels = mode_labels(an);
  if (r.csv) return sweep_csv(s, labels);
  if (r.json) {
    Json j = header_json("sweep", an);
    j["mu"] = Json{{"start", r.sweep_start}, {"stop", r.sweep_stop}, {"step", r.sweep_step}};
    j["labels"] = labels;
    j["rows"] = sweep_rows_json(s, labels);
    j["max_liouville_residual"] = max_liouville(s);
    return dump(status_json(j, s.status, s.message));
  }
  return header_text(an) + "\n" + warnings_text(an) +
         "Exponents per rev (dominant exponent of each mode)\n" + sweep_table_text(s, labels);
}

std::string critical(const Request& r, const Analysis& an) {
  CriticalOptions opt;
  opt.mu_max = r.mu_max;
  const CriticalResult c = an.critical(opt);
  if (r.json) {
    Json j = header_json("critical", an);
    j.update(critical_json(c));
    return dump(j);
  }
  return header_text(an) + "\n" + warnings_text(an) + critical_text(c);
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
  if (r.json) {
    Json j = header_json("system", an);
    j["mu"] = s.mu;
    j["psi"] = s.psi;
    j["region"] = s.region;
    j["state"] = states;
    Json A = Json::array();
    for (Eigen::Index i = 0; i < n; ++i) {
      Json row = Json::array();
      for (Eigen::Index k = 0; k < s.A.cols(); ++k) row.push_back(s.A(i, k));
      A.push_back(row);
    }
    j["A"] = A;
    Json f = Json::array();
    for (Eigen::Index i = 0; i < s.f.size(); ++i) f.push_back(s.f[i]);
    j["f"] = f;
    j["hover"] = hover_json(an);
    Json aero = Json::array();
    for (std::size_t i = 0; i < s.aero_integrals.size(); ++i) {
      const std::string& name = s.aero_integrals[i].first;
      Json a{{"name", name},
             {"paper_name", paper_name(m.aero, m.n_aero, name)},
             {"normal", s.aero_integrals[i].second}};
      a["at_psi"] = i < s.aero_integrals_region.size() ? Json(s.aero_integrals_region[i].second)
                                                       : Json(nullptr);
      aero.push_back(a);
    }
    j["aero_integrals"] = aero;
    Json st = Json::array();
    for (const auto& [name, value] : s.structural_integrals) {
      st.push_back(Json{{"name", name},
                        {"paper_name", paper_name(m.structural, m.n_structural, name)},
                        {"value", value}});
    }
    j["structural_integrals"] = st;
    return dump(j);
  }
  std::string out = header_text(an) + "\n" + warnings_text(an);
  out += "System y' = A(psi) y + f(psi) at mu = " + num(s.mu) + ", psi = " + num(s.psi) +
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
    for (Eigen::Index k = 0; k < s.A.cols(); ++k) row.push_back(num(s.A(i, k)));
    row.push_back(i < s.f.size() ? num(s.f[i]) : "");
    t.add_row(row);
  }
  out += t.render() + "\n" + hover_text(an) + "\n";
  out += "Aerodynamic spanwise integrals (int x^p ... dx0 over the aerodynamic span)\n";
  TextTable a({"integral", "paper", "normal flow", "used at psi"});
  a.left_align(1);
  for (std::size_t i = 0; i < s.aero_integrals.size(); ++i) {
    const std::string& name = s.aero_integrals[i].first;
    const std::string pn = paper_name(m.aero, m.n_aero, name);
    a.add_row({name, pn.empty() ? "-" : pn, num(s.aero_integrals[i].second),
               i < s.aero_integrals_region.size() ? num(s.aero_integrals_region[i].second) : "-"});
  }
  out += a.render() + "\nGeneralized masses and structural integrals (by I_b)\n";
  TextTable g({"integral", "paper", "value"});
  g.left_align(1);
  for (const auto& [name, value] : s.structural_integrals) {
    const std::string pn = paper_name(m.structural, m.n_structural, name);
    g.add_row({name, pn.empty() ? "-" : pn, num(value)});
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

}  // namespace

std::string run_command(const Request& r) {
  switch (r.command) {
    case Command::Models:
      return models(r);
    case Command::Modes:
      return run_modes(r);
    default:
      break;
  }
  const Analysis an(r.params, r.transition);
  switch (r.command) {
    case Command::Point:
      return point(r, an);
    case Command::Sweep:
      return sweep(r, an);
    case Command::Critical:
      return critical(r, an);
    case Command::System:
      return system_snapshot(r, an);
    default:
      return typical(r, an);
  }
}

}  // namespace flaplag::cli
