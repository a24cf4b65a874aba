// flaplag documents — the HTML report of a result (report.h).
#include "flaplag/documents/report.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "flaplag/core/errors.h"
#include "flaplag/documents/output.h"
#include "flaplag/documents/plot.h"
#include "flaplag/documents/read_file.h"
#include "flaplag/rotor/parameter_table.h"

namespace flaplag::documents {

namespace {

using Json = nlohmann::ordered_json;

// ---- text ----------------------------------------------------------------------------------

// Every text of the document reaches the page through this function: the five characters that
// mean something in HTML are escaped, control characters become blanks.
std::string esc(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += (u < 0x20 || u == 0x7f) ? ' ' : c;
    }
  }
  return out;
}

// A value of the document as a table cell: numbers to six digits, "–" for null (not
// computed), "-inf" for the zeta of a zero multiplier, a complex number as re ± i im.
std::string cell(const Json& v) {
  if (v.is_null()) return "&ndash;";
  if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
  if (v.is_number()) {
    const double x = v.get<double>();
    return std::isfinite(x) ? esc(num(x)) : "&ndash;";
  }
  if (v.is_string()) return esc(v.get<std::string>());
  if (v.is_object() && v.size() == 2 && v.contains("re") && v.contains("im") &&
      v["re"].is_number() && v["im"].is_number()) {
    const double im = v["im"].get<double>();
    return cell(v["re"]) + (im < 0 ? " &minus; " : " + ") + esc(num(std::abs(im))) + "i";
  }
  if (v.is_array()) {
    bool numbers = !v.empty();
    for (const Json& x : v) numbers = numbers && (x.is_number() || x.is_null());
    if (numbers && v.size() > 6)
      return std::to_string(v.size()) + " values, " + cell(v.front()) + " &hellip; " +
             cell(v.back());
    std::string s = "[";
    std::size_t k = 0;
    for (const Json& x : v) {
      if (k == 6) {
        s += ", &hellip; (" + std::to_string(v.size()) + " in all)";
        break;
      }
      s += (k++ ? ", " : "") + cell(x);
    }
    return s + "]";
  }
  std::string s;
  for (auto it = v.begin(); it != v.end(); ++it)
    s += (s.empty() ? "" : "; ") + esc(it.key()) + " " + cell(it.value());
  return s;
}

// The paper's ASCII symbol ("omega_L1", "beta_P", "C_Do", "l/R") in HTML: Greek letters and
// the part after '_' as a subscript.
std::string symbol_html(const std::string& ascii) {
  static const std::map<std::string, std::string> greek = {
      {"alpha", "&alpha;"}, {"beta", "&beta;"},     {"gamma", "&gamma;"}, {"eta", "&eta;"},
      {"theta", "&theta;"}, {"lambda", "&lambda;"}, {"mu", "&mu;"},       {"sigma", "&sigma;"},
      {"omega", "&omega;"}, {"zeta", "&zeta;"},     {"psi", "&psi;"}};
  const std::size_t u = ascii.find('_');
  const std::string base = ascii.substr(0, u);
  const auto g = greek.find(base);
  std::string s = g != greek.end() ? g->second : esc(base);
  if (base == "omega") s = "&omega;&#772;";  // the paper's bar: frequency by Omega
  if (u != std::string::npos) s += "<sub>" + esc(ascii.substr(u + 1)) + "</sub>";
  return s;
}

// Rows of a table on the page (the JSON holds them all).
constexpr std::size_t kMaxRows = 80;

// A damping ratio (a fraction of critical in the JSON) in percent, as a review reads it.
std::string keyed_cell(const std::string& key, const Json& v) {
  const bool ratio = key == "damping_ratio" ||
                     (key.size() > 14 && key.compare(key.size() - 14, 14, ".damping_ratio") == 0);
  if (ratio && v.is_number() && std::isfinite(v.get<double>()))
    return esc(num(100.0 * v.get<double>())) + " %";
  return cell(v);
}

// A table column of numbers too many for a cell (exponents, multipliers, time histories).
bool is_bulky(const Json& v) {
  return v.is_array() && (v.size() > 6 || (!v.empty() && v[0].is_structured()));
}

// A rotor parameter named by its JSON key ("omega-lag") as the paper's symbol and the key.
std::string parameter_html(const std::string& key) {
  for (const ParameterSpec& spec : parameter_table())
    if (json_key(spec) == key && spec.symbol[0] != '\0')
      return symbol_html(spec.symbol) + " (<code>" + esc(key) + "</code>)";
  return esc(key);
}

// ---- the document ---------------------------------------------------------------------------

const Json& member(const Json& j, const char* key) {
  static const Json none;
  return j.is_object() && j.contains(key) ? j[key] : none;
}

std::string string_of(const Json& j, const char* key, const std::string& otherwise = "") {
  const Json& v = member(j, key);
  return v.is_string() ? v.get<std::string>() : otherwise;
}

// Where a status sits in the document ("rows[3]", "critical", "" for the top).
struct Outcome {
  std::string where, status, message;
};

int severity(const std::string& status) {
  if (status == "ok") return 0;
  if (status == "warning") return 1;
  if (status == "cancelled") return 2;
  return 3;  // failed, or a status flaplag does not write
}

// Every status of the document, depth first (the nesting is bounded: read_file.h).
void collect_outcomes(const Json& j, const std::string& where, std::vector<Outcome>& out) {
  if (j.is_object()) {
    if (j.contains("status") && j["status"].is_string())
      out.push_back({where, j["status"].get<std::string>(), string_of(j, "message")});
    for (auto it = j.begin(); it != j.end(); ++it) {
      // A damping crossing's status says where a mode crossed (crossing_words), not how a
      // computation went; an unresolved one is a warning about the result.
      const std::string here = where.empty() ? it.key() : where + "." + it.key();
      if (it.key() == "damping_crossings" && it.value().is_array()) {
        for (std::size_t i = 0; i < it.value().size(); ++i)
          if (string_of(it.value()[i], "status") == "unresolved")
            out.push_back({here + "[" + std::to_string(i) + "]", "warning",
                           "the first mu below the damping criterion is unresolved for " +
                               string_of(it.value()[i], "mode", "a mode") +
                               " (a point's error estimate is wider than its margin to the "
                               "criterion, or a point failed: refine the step or the zeta "
                               "tolerance)"});
        continue;
      }
      if (it.key() == "case" || it.key() == "flaplag") continue;
      if (it.value().is_structured())
        collect_outcomes(it.value(), where.empty() ? it.key() : where + "." + it.key(), out);
    }
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i)
      if (j[i].is_structured()) collect_outcomes(j[i], where + "[" + std::to_string(i) + "]", out);
  }
}

// The evidence of convergence: every number under a key that is an error estimate, a residual
// or a resolution, by its key path with the array positions left out ("rows[].error_estimate").
struct Evidence {
  std::size_t count = 0;
  double largest = -INFINITY;
};

bool is_evidence_key(const std::string& key) {
  return key.find("error") != std::string::npos || key.find("residual") != std::string::npos ||
         key == "closure" || key == "steps" || key == "steps_per_rev" || key == "evaluations" ||
         key == "iterations" || key == "basis";
}

void collect_evidence(const Json& j, const std::string& path,
                      std::map<std::string, Evidence>& out) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      if (it.key() == "case" || it.key() == "flaplag" || it.key() == "parameters") continue;
      const std::string p = path.empty() ? it.key() : path + "." + it.key();
      if (is_evidence_key(it.key()) && (it.value().is_number() || it.value().is_null())) {
        Evidence& e = out[p];
        if (it.value().is_number()) {
          ++e.count;
          e.largest = std::max(e.largest, it.value().get<double>());
        }
      } else if (it.value().is_structured()) {
        collect_evidence(it.value(), p, out);
      }
    }
  } else if (j.is_array()) {
    for (const Json& x : j)
      if (x.is_structured()) collect_evidence(x, path + "[]", out);
  }
}

// ---- sections -------------------------------------------------------------------------------

const char* const kHeaderKeys[] = {"command", "model",      "mode_shapes", "elastic_coupling",
                                   "method",  "parameters", "flaplag",     "case",
                                   "status",  "message"};

bool is_header_key(const std::string& key) {
  return std::any_of(std::begin(kHeaderKeys), std::end(kHeaderKeys),
                     [&](const char* k) { return key == k; });
}

std::string section(const std::string& id, const std::string& title, const std::string& body) {
  return "<section id=\"" + id + "\">\n<h2>" + title + "</h2>\n" + body + "</section>\n";
}

std::string key_value_table(const std::vector<std::pair<std::string, std::string>>& rows) {
  std::string s = "<table class=\"kv\">\n";
  for (const auto& [k, v] : rows) s += "<tr><th>" + k + "</th><td>" + v + "</td></tr>\n";
  return s + "</table>\n";
}

// The linearization and trim of the case, in words.
std::string linearization_text(const Json& result) {
  // The header's linearization, or the parameter of results written before it moved there.
  const bool periodic = member(result, "linearization") == "periodic" ||
                        member(member(result, "parameters"), "periodic-linearization") == true;
  const std::string trim = string_of(member(result, "case"), "trim", "none");
  std::string s = periodic ? "about the periodic equilibrium of the nonlinear equations"
                           : "about the hover equilibrium (as in the paper)";
  if (trim != "none") {
    s += "; the rotor trimmed at each advance ratio (" + esc(trim) + " trim";
    const Json& ct = member(member(result, "case"), "thrust-coefficient");
    if (ct.is_string()) s += ", C<sub>T</sub> = " + esc(ct.get<std::string>());
    s += ")";
  } else if (string_of(member(result, "case"), "inflow", "uniform") == "momentum") {
    s += "; fixed controls at the momentum inflow of eq 2.25 at each advance ratio";
    const Json& ct = member(member(result, "case"), "thrust-coefficient");
    if (ct.is_string()) s += " (C<sub>T</sub> = " + esc(ct.get<std::string>()) + ")";
  } else {
    s += "; fixed controls (no trim)";
  }
  return s;
}

std::string outcome_section(const Json& result, const std::vector<Outcome>& outcomes) {
  int worst = 0;
  for (const Outcome& o : outcomes) worst = std::max(worst, severity(o.status));
  static const char* const kWords[] = {"ok", "warning", "cancelled", "failed"};
  const std::string top = string_of(result, "status");
  const std::string message = string_of(result, "message");
  std::string s = "<p class=\"status s" + std::to_string(worst) + "\"><b>" + kWords[worst] + "</b>";
  if (!message.empty()) s += ": " + esc(message);
  s += "</p>\n";
  if (top.empty() && outcomes.empty()) s += "<p>This result carries no status of its own.</p>\n";
  std::size_t nonok = 0;
  for (const Outcome& o : outcomes) nonok += o.status != "ok" ? 1 : 0;
  if (nonok > 0)
    s += "<p>Not ok: " + std::to_string(nonok) + " of the " + std::to_string(outcomes.size()) +
         " results in this document (see <a href=\"#warnings\">Warnings</a>). A result is never "
         "better than what it rests on.</p>\n";
  return section("outcome", "Outcome", s);
}

// ---- key results: what a reviewer asks first, read from the document ---------------------

double number_or_nan(const Json& v) { return v.is_number() ? v.get<double>() : NAN; }

// mu_c of a critical result (or a study row) in words, with its error estimate.
std::string critical_words(const Json& c, const Json& mu_max_of_study = Json()) {
  if (member(c, "hover_unstable") == true)
    return "unstable in hover: there is no critical advance ratio";
  const Json& mu_c = member(c, "mu_c");
  if (!mu_c.is_number()) {
    const Json& mu_max = c.contains("mu_max") ? c["mu_max"] : mu_max_of_study;
    return "no instability found up to &mu; = " +
           (mu_max.is_number() ? cell(mu_max) : std::string("&mu;<sub>max</sub>"));
  }
  std::string s = "&mu;<sub>c</sub> = " + cell(mu_c);
  if (member(c, "mu_c_error").is_number()) s += " &plusmn; " + cell(c["mu_c_error"]);
  std::string detail;
  for (const char* k : {"mode", "kind"})
    if (member(c, k).is_string()) detail += (detail.empty() ? "" : ", ") + cell(c[k]);
  if (member(c, "omega").is_number())
    detail +=
        (detail.empty() ? "" : ", ") + std::string("&omega; = ") + cell(c["omega"]) + " per rev";
  return s + (detail.empty() ? "" : " (" + detail + ")");
}

// For each mode of a sweep table: the least damping ratio and where, and the first mu with a
// positive zeta.
std::string sweep_words(const Json& labels, const Json& rows) {
  if (!labels.is_array() || !rows.is_array()) return "";
  std::string s =
      "<table>\n<tr><th>mode</th><th>least damping ratio</th><th>at &mu;</th><th>first &mu; with "
      "&zeta; &gt; 0</th></tr>\n";
  for (const Json& l : labels) {
    if (!l.is_string()) continue;
    const std::string label = l.get<std::string>();
    double least = INFINITY, at = NAN, first_unstable = NAN;
    for (const Json& row : rows) {
      const Json& e = member(row, label.c_str());
      const double mu = number_or_nan(member(row, "mu"));
      const double r = number_or_nan(member(e, "damping_ratio"));
      const double z = number_or_nan(member(e, "zeta"));
      if (std::isfinite(r) && r < least) {
        least = r;
        at = mu;
      }
      if (std::isfinite(z) && z > 0 && !std::isfinite(first_unstable)) first_unstable = mu;
    }
    s += "<tr><td>" + esc(label) + "</td><td>" +
         (std::isfinite(least) ? esc(num(100.0 * least)) + " %" : "&ndash;") + "</td><td>" +
         (std::isfinite(at) ? esc(num(at)) : "&ndash;") + "</td><td>" +
         (std::isfinite(first_unstable) ? esc(num(first_unstable)) : "none in the sweep") +
         "</td></tr>\n";
  }
  return s + "</table>\n";
}

// The damping crossings of a sweep (or a study row): where each mode's damping ratio first falls
// below the criterion.
std::string crossing_words(const Json& d) {
  const std::string status = string_of(d, "status");
  const std::string mode = "<b>" + cell(member(d, "mode")) + "</b>";
  if (status == "crossed")
    return mode + " falls below it at &mu; = " + cell(member(d, "mu")) + " (between " +
           cell(member(d, "mu_above")) + " and " + cell(member(d, "mu_below")) + ")";
  if (status == "below_at_start")
    return mode + " is below it from the first &mu; = " + cell(member(d, "mu"));
  if (status == "not_crossed") return mode + " stays above it over the sweep";
  if (status == "unresolved")
    return mode + ": <b>unresolved</b> between &mu; = " + cell(member(d, "mu_above")) + " and " +
           cell(member(d, "mu_below")) + " (see Warnings)";
  return mode + ": " + esc(status);
}

std::string crossings_words(const Json& result) {
  const Json& crossings = member(result, "damping_crossings");
  const Json& criterion = member(result, "damping_criterion");
  if (!crossings.is_array() || !criterion.is_number()) return "";
  std::string s = "<p>Damping criterion " + esc(num(100.0 * criterion.get<double>())) +
                  " % of critical:</p>\n<ul>\n";
  for (const Json& d : crossings) s += "<li>" + crossing_words(d) + "</li>\n";
  return s + "</ul>\n";
}

std::string key_results_section(const Json& result) {
  const std::string command = string_of(result, "command");
  std::string s;
  if (command == "critical") s = "<p>" + critical_words(result) + "</p>\n";
  if (command.empty() && result.contains("critical")) {
    s = "<p>" + critical_words(result["critical"]) + "</p>\n";
    const Json& t = member(result, "table");
    s += sweep_words(member(t, "labels"), member(t, "rows"));
  }
  if (command == "point" && member(result, "stable").is_boolean())
    s = "<p>At &mu; = " + cell(member(result, "mu")) + " the blade is " +
        (result["stable"] == true ? "stable" : "<b>unstable</b>") + ".</p>\n";
  if (command == "sweep")
    s = sweep_words(member(result, "labels"), member(result, "rows")) + crossings_words(result);
  if (command == "study" && member(result, "rows").is_array()) {
    s = "<table>\n<tr><th>" + parameter_html(string_of(result, "vary")) +
        "</th><th>outcome</th></tr>\n";
    std::size_t k = 0;
    for (const Json& row : result["rows"]) {
      if (k++ == kMaxRows) break;
      const std::string status = string_of(row, "status", "ok");
      s += (status == "ok" ? "<tr>" : "<tr class=\"s" + std::to_string(severity(status)) + "\">") +
           "<td>" + cell(member(row, "value")) + "</td><td>" +
           critical_words(row, member(result, "mu_max")) + "</td></tr>\n";
    }
    s += "</table>\n";
  }
  if (command == "trim") {
    s = "<p>At &mu; = " + cell(member(result, "mu")) +
        ": &theta;<sub>0</sub> = " + cell(member(result, "theta0")) +
        ", &theta;<sub>1c</sub> = " + cell(member(result, "theta1c")) +
        ", &theta;<sub>1s</sub> = " + cell(member(result, "theta1s")) +
        " rad, &lambda; = " + cell(member(result, "inflow")) +
        ", C<sub>T</sub> = " + cell(member(result, "thrust_coefficient")) +
        (member(result, "converged") == true ? " (converged)" : " (<b>not converged</b>)") +
        ".</p>\n";
  }
  if (command == "campbell" && member(result, "crossings").is_array()) {
    s = "<p>Crossings of the mode frequencies with the per-rev lines n&Omega; (rotor speed "
        "&Omega;/&Omega;<sub>0</sub>):</p>\n<table>\n<tr><th>mode</th><th>n/rev</th><th>"
        "&Omega;/&Omega;<sub>0</sub></th><th>frequency &omega;/&Omega;<sub>0</sub></th></tr>\n";
    for (const Json& x : result["crossings"])
      s += "<tr><td>" + cell(member(x, "label")) + "</td><td>" + cell(member(x, "harmonic")) +
           "</td><td>" + cell(member(x, "speed")) + "</td><td>" + cell(member(x, "frequency")) +
           "</td></tr>\n";
    if (result["crossings"].empty()) s += "<tr><td colspan=\"4\">none</td></tr>\n";
    s += "</table>\n";
  }
  if (s.empty()) return "";
  return section("key", "Key results", s);
}

std::string model_section(const Json& result) {
  const Json& m = member(result, "model");
  const Json& p = member(result, "parameters");
  const Json& method = member(result, "method");
  std::vector<std::pair<std::string, std::string>> rows;
  if (m.is_object()) {
    rows.push_back({"ordering model",
                    cell(member(m, "name")) + " (spec " + cell(member(m, "spec_file")) + ")"});
    rows.push_back({"equations", cell(member(m, "summary"))});
    rows.push_back({"modes", cell(member(m, "flap_modes")) + " flap &times; " +
                                 cell(member(m, "lag_modes")) + " lag"});
  }
  if (result.contains("mode_shapes"))
    rows.push_back(
        {"mode shapes", cell(result["mode_shapes"]) + (member(result, "elastic_coupling") == true
                                                           ? ", elastic coupling (Appendix E)"
                                                           : "")});
  if (p.contains("basis") && member(result, "mode_shapes") == "exact")
    rows.push_back({"mode discretization", cell(p["basis"])});
  if (p.is_object()) {
    std::string rf = member(p, "reversed-flow") == false ? "left out"
                     : member(p, "exact-reversed-flow") == true
                         ? "the exact circular region x &lt; &minus;&mu; sin &psi;"
                         : "the sector of Appendix D";
    rows.push_back({"reversed flow", rf});
  }
  rows.push_back({"linearization", linearization_text(result)});
  if (method.is_object()) {
    std::string s = cell(member(method, "name"));
    if (method.contains("steps")) s += ", steps " + cell(method["steps"]);
    if (method.contains("terms")) s += ", " + cell(method["terms"]) + " terms";
    if (method.contains("zeta-tolerance"))
      s += ", &zeta; tolerance " + cell(method["zeta-tolerance"]) + " per rev";
    rows.push_back({"Floquet method", s});
  }
  return section("model", "Model and assumptions", key_value_table(rows));
}

std::string inputs_section(const Json& result) {
  const Json& p = member(result, "parameters");
  if (!p.is_object()) return "";
  std::string s =
      "<table>\n<tr><th>symbol</th><th>option</th><th>value</th><th>units</th><th>meaning</th></tr>"
      "\n";
  std::set<std::string> shown_keys;
  for (const ParameterSpec& spec : parameter_table()) {
    const std::string key = json_key(spec);
    if (!p.contains(key)) continue;
    shown_keys.insert(key);
    s += "<tr><td>" + symbol_html(spec.symbol) + "</td><td><code>" + esc(key) + "</code></td><td>" +
         cell(p[key]) + "</td><td>" + esc(spec.units) + "</td><td>" + esc(spec.description) +
         "</td></tr>\n";
  }
  // Keys of another flaplag version: shown as they are.
  for (auto it = p.begin(); it != p.end(); ++it)
    if (!shown_keys.count(it.key()))
      s += "<tr><td></td><td><code>" + esc(it.key()) + "</code></td><td>" + cell(it.value()) +
           "</td><td></td><td>(not a parameter of this flaplag)</td></tr>\n";
  s += "</table>\n<p class=\"note\">Nondimensional as in the paper: frequencies by &Omega;, "
       "lengths by R (l/R, e1) or l (A, B), angles in radians.";
  const Json& b = member(result, "blade_table");
  if (!b.is_object()) {
    s += " Dimensional inputs: none given (the paper's uniform blade, by its nondimensional "
         "groups).</p>\n";
    return section("inputs", "Inputs", s);
  }
  s += "</p>\n<h3>Blade table</h3>\n";
  // Every key of the result's blade_table, with the meaning and units of docs/json.md.
  static const std::pair<const char*, const char*> kBladeRows[] = {
      {"source", "the table"},
      {"stations", "stations along the span"},
      {"root_offset", "e1, root of the elastic blade by R"},
      {"length_ratio", "l/R"},
      {"tip_mass", "M_tip l^2 / I_b"},
      {"twist_min", "least built-in twist [rad]"},
      {"twist_max", "largest built-in twist [rad]"},
      {"radius", "R [m]"},
      {"rotor_speed", "Omega [rad/s]"},
      {"air_density", "rho [kg/m^3]"},
      {"blades", "number of blades"},
      {"reference_chord", "c_ref, chord at 0.75 R [m]"},
      {"inertia", "I_b = int m r0^2 dr0 + M_tip l^2 [kg m^2]"},
      {"gamma", "Lock number rho a c_ref R^4 / I_b"},
      {"sigma", "solidity b c_ref / (pi R)"},
      {"omega_flap_hz", "first rotating flap frequency [Hz]"},
      {"omega_lag_hz", "first rotating lag frequency [Hz]"}};
  std::vector<std::pair<std::string, std::string>> rows;
  for (const auto& [key, meaning] : kBladeRows)
    if (b.contains(key)) rows.push_back({esc(meaning), cell(b[key])});
  s += key_value_table(rows);
  return section("inputs", "Inputs", s);
}

std::string evidence_section(const Json& result) {
  std::map<std::string, Evidence> evidence;
  collect_evidence(result, "", evidence);
  std::string s;
  if (evidence.empty()) {
    s = "<p>This result holds no error estimate or residual.</p>\n";
  } else {
    s = "<table>\n<tr><th>quantity (JSON key)</th><th>values</th><th>largest</th></tr>\n";
    for (const auto& [key, e] : evidence)
      s += "<tr><td><code>" + esc(key) + "</code></td><td>" + std::to_string(e.count) +
           "</td><td>" + (e.count > 0 ? esc(num(e.largest)) : "not computed") + "</td></tr>\n";
    s += "</table>\n";
  }
  s += "<p class=\"note\">Error estimates are per rev for exponents and absolute in &mu; for "
       "advance ratios; <code>basis_error</code> is the change of exact modes to their reference "
       "discretization (from 12 to 11 Galerkin functions; for a blade table, to finite "
       "elements), already included in the error estimates. The keys are "
       "described in docs/json.md.</p>\n";
  return section("convergence", "Convergence evidence", s);
}

std::string warnings_section(const std::vector<Outcome>& outcomes, const Json& result,
                             const std::vector<std::string>& run_warnings) {
  // Grouped by status and message: a study of a thousand rows with one warning each says it
  // once, with where it happened.
  std::map<std::pair<std::string, std::string>, std::vector<std::string>> grouped;
  std::vector<std::pair<std::string, std::string>> order;
  for (const Outcome& o : outcomes) {
    if (o.status == "ok") continue;
    const auto key = std::make_pair(o.status, o.message);
    if (!grouped.count(key)) order.push_back(key);
    grouped[key].push_back(o.where.empty() ? "the result" : o.where);
  }
  std::vector<std::string> notes;
  std::function<void(const Json&)> find_notes = [&](const Json& j) {
    if (j.is_object()) {
      for (auto it = j.begin(); it != j.end(); ++it) {
        if (it.key() == "case" || it.key() == "flaplag") continue;
        if ((it.key() == "notes" || it.key() == "warnings") && it.value().is_array()) {
          for (const Json& n : it.value())
            if (n.is_string() &&
                std::find(notes.begin(), notes.end(), n.get<std::string>()) == notes.end())
              notes.push_back(n.get<std::string>());
        } else if (it.value().is_structured()) {
          find_notes(it.value());
        }
      }
    } else if (j.is_array()) {
      for (const Json& x : j)
        if (x.is_structured()) find_notes(x);
    }
  };
  find_notes(result);
  std::string s;
  if (order.empty() && notes.empty() && run_warnings.empty())
    return section("warnings", "Warnings", "<p>None.</p>\n");
  s += "<ul>\n";
  for (const auto& key : order) {
    const std::vector<std::string>& where = grouped[key];
    std::string at;
    for (std::size_t i = 0; i < where.size() && i < 8; ++i) at += (i ? ", " : "") + esc(where[i]);
    if (where.size() > 8) at += ", &hellip; (" + std::to_string(where.size()) + " in all)";
    s += "<li class=\"s" + std::to_string(severity(key.first)) + "\"><b>" + esc(key.first) +
         "</b>: " + esc(key.second) + " <span class=\"where\">(" + at + ")</span></li>\n";
  }
  for (const std::string& n : notes) s += "<li>note: " + esc(n) + "</li>\n";

  for (const std::string& w : run_warnings) s += "<li>run: " + esc(w) + "</li>\n";
  return section("warnings", "Warnings", s + "</ul>\n");
}

// An array of objects as a table: a column per key (an object value: a column per its keys,
// "flap.zeta"), at most kMaxRows rows.

std::string object_table(const Json& rows) {
  std::vector<std::string> columns;
  auto add_column = [&](const std::string& c) {
    if (std::find(columns.begin(), columns.end(), c) == columns.end()) columns.push_back(c);
  };
  std::vector<std::string> left_out;
  for (std::size_t i = 0; i < rows.size() && i < kMaxRows; ++i) {
    for (auto it = rows[i].begin(); it != rows[i].end(); ++it) {
      const Json& v = it.value();
      if (is_bulky(v)) {
        if (std::find(left_out.begin(), left_out.end(), it.key()) == left_out.end())
          left_out.push_back(it.key());
        continue;
      }
      const bool nested = v.is_object() && !(v.size() == 2 && v.contains("re"));
      if (nested && v.size() <= 8) {
        for (auto jt = v.begin(); jt != v.end(); ++jt) add_column(it.key() + "." + jt.key());
      } else {
        add_column(it.key());
      }
    }
  }
  if (columns.size() > 40) columns.resize(40);
  std::string s = "<div class=\"wide\"><table>\n<tr>";
  for (const std::string& c : columns) s += "<th>" + esc(c) + "</th>";
  s += "</tr>\n";
  for (std::size_t i = 0; i < rows.size() && i < kMaxRows; ++i) {
    const Json& row = rows[i];
    const std::string status = string_of(row, "status", "ok");
    s += status == "ok" ? "<tr>" : "<tr class=\"s" + std::to_string(severity(status)) + "\">";
    for (const std::string& c : columns) {
      const std::size_t dot = c.find('.');
      const Json* v = nullptr;
      if (row.contains(c)) {
        v = &row[c];
      } else if (dot != std::string::npos && row.contains(c.substr(0, dot)) &&
                 row[c.substr(0, dot)].is_object() &&
                 row[c.substr(0, dot)].contains(c.substr(dot + 1))) {
        v = &row[c.substr(0, dot)][c.substr(dot + 1)];
      }
      s += "<td>" + (v != nullptr && !is_bulky(*v) ? keyed_cell(c, *v) : std::string()) + "</td>";
    }
    s += "</tr>\n";
  }
  s += "</table></div>\n";
  std::string bulky;
  for (const std::string& k : left_out)
    bulky += (bulky.empty() ? "" : ", ") + ("<code>" + esc(k) + "</code>");
  if (!bulky.empty())
    s += "<p class=\"note\">Not shown per row: " + bulky + " (in the JSON result).</p>\n";
  if (rows.size() > kMaxRows)
    s += "<p class=\"note\">The first " + std::to_string(kMaxRows) + " of " +
         std::to_string(rows.size()) + " rows; the JSON result holds them all.</p>\n";
  return s;
}

bool is_object_array(const Json& v) {
  return v.is_array() && !v.empty() &&
         std::all_of(v.begin(), v.end(), [](const Json& x) { return x.is_object(); });
}

std::string results_section(const Json& result) {
  std::vector<std::pair<std::string, std::string>> scalars;
  std::string tables;
  std::function<void(const Json&, const std::string&)> walk = [&](const Json& j,
                                                                  const std::string& prefix) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      if (prefix.empty() && is_header_key(it.key())) continue;
      const std::string name = prefix + it.key();
      const Json& v = it.value();
      if (is_object_array(v)) {
        tables += "<h3><code>" + esc(name) + "</code></h3>\n" + object_table(v);
      } else if (v.is_object() && !(v.size() == 2 && v.contains("re")) && prefix.empty()) {
        walk(v, name + ".");
      } else {
        scalars.push_back({"<code>" + esc(name) + "</code>", keyed_cell(name, v)});
      }
    }
  };
  walk(result, "");
  return section("results", "Results", key_value_table(scalars) + tables);
}

// The typical case's table is a sweep: its picture is the sweep's.
Json picture_document(const Json& result) {
  if (string_of(result, "command") != "" || !result.contains("table")) return result;
  Json sweep = result;
  sweep["command"] = "sweep";
  const Json& t = result["table"];
  sweep["labels"] = member(t, "labels");
  sweep["rows"] = member(t, "rows");
  return sweep;
}

std::string pictures_section(const Json& result, const std::string& source, const Spelling& option,
                             std::vector<std::string>& page_warnings) {
  const nlohmann::json plain = nlohmann::json::parse(picture_document(result).dump());
  std::optional<std::string> script;
  try {
    // The quantity the case drew (--plot-quantity), so that the page shows what --plot drew.
    const bool zeta = string_of(member(result, "case"), "plot-quantity") == "zeta";
    script =
        result_plot_script(plain, source, zeta ? SweepQuantity::Zeta : SweepQuantity::DampingRatio);
  } catch (const nlohmann::json::exception&) {
    refuse_file(source, "a damaged flaplag result (a key is missing or has the wrong type)");
  }
  if (!script) return "";
  std::string svg;
  try {
    svg = render_svg(*script);
  } catch (const RendererUnavailable& e) {
    page_warnings.push_back(std::string(e.what()) + ": the picture is not in this report");
    return section("pictures", "Pictures",
                   "<p class=\"s1\">No picture: " + esc(e.what()) + ".</p>\n");
  }
  // gnuplot's SVG starts with an XML declaration and a DOCTYPE, which have no place inside
  // HTML: the page takes the <svg> element itself.  Its texts are escaped by gnuplot; the page's
  // Content-Security-Policy is the second line of defence.
  const std::size_t start = svg.find("<svg");
  if (start == std::string::npos) {
    page_warnings.push_back("gnuplot gave no SVG: the picture is not in this report");
    return "";
  }
  return section("pictures", "Pictures",
                 "<figure>\n" + svg.substr(start) + "\n<figcaption>The picture of this result " +
                     "(the same as <code>" + esc(option("plot")) +
                     "</code> and <code>flaplag plot</code> draw)." + "</figcaption>\n</figure>\n");
}

// The command line of the case, each word quoted for a POSIX shell where it needs it.
std::string shell_word(const std::string& w) {
  const bool plain = !w.empty() && std::all_of(w.begin(), w.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) ||
           std::string("-_.:/=,+").find(c) != std::string::npos;
  });
  if (plain) return w;
  std::string q = "'";
  for (char c : w) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string command_line(const Json& c, const Spelling& option) {
  std::string s = "flaplag";
  const std::string command = string_of(c, "command");
  if (!command.empty()) s += " " + shell_word(command);
  for (auto it = c.begin(); it != c.end(); ++it) {
    if (it.key() == "command") continue;
    if (it.value() == true) {
      s += " " + shell_word(option(it.key()));
    } else if (it.value().is_string()) {
      s += " " + shell_word(option(it.key())) + " " + shell_word(it.value().get<std::string>());
    }
  }
  return s;
}

std::string provenance_section(const Json& result, const ReportSource& source) {
  const Json& f = member(result, "flaplag");
  std::vector<std::pair<std::string, std::string>> rows;
  rows.push_back({"made from", esc(source.title)});
  rows.push_back({"flaplag", cell(member(f, "version")) + ", commit <code>" +
                                 cell(member(f, "commit")) + "</code>"});
  const Json& c = member(result, "case");
  if (c.is_object() && source.case_option) {
    rows.push_back({"reproduce", "<code>" + esc(command_line(c, source.case_option)) + "</code>"});
    rows.push_back({"",
                    "or <code>flaplag run RESULT.json</code> on the JSON output, whose "
                    "<code>case</code> holds these options"});
  }
  if (source.with_date) {
    const std::time_t now = std::time(nullptr);
    char when[32];
    std::tm utc{};
    gmtime_r(&now, &utc);
    std::strftime(when, sizeof when, "%Y-%m-%d %H:%M UTC", &utc);
    rows.push_back({"made on", when});
  }
  return section("provenance", "Provenance", key_value_table(rows));
}

const char* const kStyle =
    R"(body{font-family:sans-serif;max-width:60em;margin:1.5em auto;padding:0 1em;color:#222;line-height:1.4}
h1{font-size:1.5em;margin-bottom:.2em}h2{font-size:1.2em;border-bottom:1px solid #ccc;margin-top:1.6em}
h3{font-size:1em}.sub{color:#555;margin-top:0}table{border-collapse:collapse;font-size:.9em}
td,th{border:1px solid #ddd;padding:.2em .5em;text-align:left;vertical-align:top}
table.kv th{background:#f4f4f4;white-space:nowrap}.wide{overflow-x:auto}
.status{padding:.6em 1em;border-radius:4px;font-size:1.1em}.s0{background:#e6f4ea}
.s1{background:#fff4d6}.s2{background:#fde2cf}.s3{background:#fbd3d3}
.note{color:#555;font-size:.85em}.where{color:#666;font-size:.85em}
figure{margin:1em 0}figure svg{width:100%;height:auto;border:1px solid #eee}
figcaption{color:#555;font-size:.85em}code{font-size:.95em}
nav a{margin-right:.8em})";

}  // namespace

bool is_report_path(const std::string& path) {
  auto ends = [&](const std::string& s) {
    return path.size() > s.size() && path.compare(path.size() - s.size(), s.size(), s) == 0;
  };
  return ends(".html") || ends(".htm");
}

std::string html_report(const Json& result, const ReportSource& source, std::string* warning) {
  if (!result.is_object() || !result.contains("flaplag") || !result.contains("command") ||
      !result["command"].is_string())
    refuse_file(source.input, "not a flaplag " + source.option("json") + " output");
  const std::string command = result["command"].get<std::string>();
  if (command == "models" || command == "merge")
    refuse_file(source.input, "a flaplag " + command + " output is not a result to report on");
  std::vector<Outcome> outcomes;
  collect_outcomes(result, "", outcomes);
  std::vector<std::string> page_warnings;
  const std::string pictures = pictures_section(result, source.input, source.option, page_warnings);
  std::vector<std::string> run_warnings = source.warnings;
  run_warnings.insert(run_warnings.end(), page_warnings.begin(), page_warnings.end());
  if (warning != nullptr) {
    for (const std::string& w : page_warnings) *warning += (warning->empty() ? "" : "; ") + w;
  }

  const std::string key = key_results_section(result);
  const std::string name = command.empty() ? "typical case" : command;
  const std::string summary = string_of(member(result, "model"), "summary");
  std::string page =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; "
      "style-src 'unsafe-inline'; img-src data:\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<meta name=\"generator\" content=\"flaplag\">\n<title>flaplag report: " +
      esc(name) + " &mdash; " + esc(source.title) + "</title>\n<style>\n" + kStyle +
      "\n</style>\n</head>\n<body>\n<h1>flaplag " + esc(name) + "</h1>\n<p class=\"sub\">" +
      esc(source.title) + (summary.empty() ? "" : " &middot; " + esc(summary)) + "</p>\n";
  page += "<nav><a href=\"#outcome\">Outcome</a>" +
          std::string(key.empty() ? "" : "<a href=\"#key\">Key results</a>") +
          std::string(pictures.empty() ? "" : "<a href=\"#pictures\">Pictures</a>") +
          "<a href=\"#warnings\">Warnings</a><a href=\"#model\">Model</a><a "
          "href=\"#inputs\">Inputs</a><a href=\"#convergence\">Convergence</a><a "
          "href=\"#results\">Results</a><a href=\"#provenance\">Provenance</a></nav>\n";
  page += outcome_section(result, outcomes);
  page += key;
  page += pictures;
  page += warnings_section(outcomes, result, run_warnings);
  page += model_section(result);
  page += inputs_section(result);
  page += evidence_section(result);
  page += results_section(result);
  page += provenance_section(result, source);
  return page + "</body>\n</html>\n";
}

bool is_json_text(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  return first != std::string::npos && text[first] == '{';
}

std::string html_report_of_text(const std::string& path, const std::string& text,
                                const Spelling& option, const Spelling& case_option,
                                std::string* warning) {
  Json j;
  std::string error;
  const JsonParse parsed = parse_json(text, &j, &error);
  const std::string json = option("json");
  if (parsed == JsonParse::NotJson)
    refuse_file(path,
                "not JSON (flaplag report takes a case file or a " + json + " output of flaplag)");
  if (parsed == JsonParse::Refused)
    refuse_file(path, "not a flaplag " + json + " output: " + error);
  ReportSource source;
  source.title = "result file " + path;
  source.input = path;
  source.option = option;
  source.case_option = case_option;
  return html_report(j, source, warning);
}

}  // namespace flaplag::documents
