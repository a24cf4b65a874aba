// flaplag documents — `flaplag plot DATA.json`: the picture of an existing result, from the numbers
// its JSON holds, through the same script builders as --plot (plot.h).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "flaplag/campbell.h"
#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/documents/plot.h"
#include "flaplag/documents/read_file.h"
#include "flaplag/model_api.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/rotor/parameter_table.h"
#include "flaplag/trim.h"

namespace flaplag::documents {

namespace {

// Plots read result files unordered: they look keys up, never write them.
using PlotJson = nlohmann::json;

// A number of the output; null, "-inf" (the zeta of a zero multiplier) and the like: a gap.
double number(const PlotJson& v) { return v.is_number() ? v.get<double>() : NAN; }

std::vector<double> numbers(const PlotJson& a) {
  std::vector<double> v;
  for (const PlotJson& x : a.get<std::vector<PlotJson>>()) v.push_back(number(x));
  return v;
}

// ---- the texts a result gives the picture ----------------------------------------------------
// Every string of a result file that reaches the gnuplot script is checked against what flaplag
// itself writes there (and quoted in the script in any case: plot.cc).  A refusal names the
// file and the key: "key labels[1] = "...": not a mode label ...".

[[noreturn]] void refuse_key(const std::string& file, const std::string& key, const PlotJson& value,
                             const std::string& reason) {
  refuse_file(file, "key " + key + " = " +
                        value.dump(-1, ' ', false, PlotJson::error_handler_t::replace) + ": " +
                        reason);
}

const std::string& text_at(const std::string& file, const std::string& key, const PlotJson& v) {
  if (!v.is_string()) refuse_key(file, key, v, "not a string");
  return v.get_ref<const std::string&>();
}

// A mode label as the hover analysis names modes (model_api.h: flap, lag, flap2, ...; lag1 of
// older files).
bool is_mode_label(const std::string& s) {
  std::string direction;
  int k = 0;
  return model::parse_mode_label(s, &direction, &k);
}

// One mode by two labels: "lag" is "lag1" (the spelling of files written before the one scheme).
bool same_mode(const std::string& a, const std::string& b) {
  std::string da, db;
  int ka = 0, kb = 0;
  if (!model::parse_mode_label(a, &da, &ka) || !model::parse_mode_label(b, &db, &kb)) return a == b;
  return da == db && ka == kb;
}

// A model name: a compiled model's or one of the same form (a result of another build).
bool is_model_name(const std::string& s) {
  if (s.empty() || s.size() > 64 || !std::isalnum(static_cast<unsigned char>(s[0]))) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
  });
}

std::string model_name(const std::string& file, const PlotJson& j) {
  const std::string& name = text_at(file, "model.name", j.at("model").at("name"));
  if (!is_model_name(name))
    refuse_key(file, "model.name", j["model"]["name"],
               "not a model name (letters, digits, '-', '_' and '.')");
  return name;
}

// A varied quantity (study vary, map axis names): a numeric rotor parameter's word, or "mu".
std::string axis_name(const std::string& file, const std::string& key, const PlotJson& v,
                      bool allow_mu) {
  const std::string& word = text_at(file, key, v);
  std::string field = word;
  for (char& c : field)
    if (c == '-') c = '_';
  const ParameterSpec* spec = find_parameter(field);
  const bool known =
      (allow_mu && field == "mu") ||
      (spec != nullptr && spec->type == ParameterType::Real && word.find('_') == std::string::npos);
  if (!known)
    refuse_key(file, key, v,
               std::string("not a numeric rotor parameter") + (allow_mu ? " or mu" : "") +
                   " (e.g. omega-lag, theta)");
  return word;
}

// A label typed: any text but control characters (it is quoted in the script).
void check_label(const std::string& label, const Spelling& option) {
  for (char c : label) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f)
      throw InvalidInput(option("label"),
                         PlotJson(label).dump(-1, ' ', false, PlotJson::error_handler_t::replace),
                         "a control character (newline, tab, ...) cannot be part of a label");
  }
}

// A result's `labels`, each a mode label and each once: one empty curve per label.
std::vector<ModeCurve> mode_curves(const std::string& file, const PlotJson& j) {
  std::vector<ModeCurve> curves;
  const PlotJson& labels = j.at("labels");
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const std::string key = "labels[" + std::to_string(i) + "]";
    const std::string& l = text_at(file, key, labels.at(i));
    if (!is_mode_label(l))
      refuse_key(file, key, labels[i], "not a mode label (flap, lag, lag2, ...)");
    for (const ModeCurve& m : curves)
      if (m.label == l) refuse_key(file, key, labels[i], "the same label twice");
    curves.push_back({l, {}, {}});
  }
  return curves;
}

// A row's status (a result written before rows had one: ok); only compared, never drawn.
RowStatus row_status(const PlotJson& row) {
  const PlotJson* status = row.contains("status") ? &row["status"] : nullptr;
  if (status == nullptr || !status->is_string()) return RowStatus::Ok;
  if (*status == "warning") return RowStatus::Warning;
  if (*status == "failed") return RowStatus::Failed;
  return RowStatus::Ok;
}

SweepOverlay sweep_data(const std::string& file, const PlotJson& j) {
  SweepOverlay s;
  s.modes = mode_curves(file, j);
  for (const PlotJson& row : j.at("rows")) {
    s.mu.push_back(number(row.at("mu")));
    s.status.push_back(row_status(row));
    for (ModeCurve& m : s.modes) {
      const PlotJson& e = row.at(m.label);
      m.zeta.push_back(e.is_object() ? number(e.at("zeta")) : NAN);
      m.omega.push_back(e.is_object() ? number(e.at("omega")) : NAN);
    }
  }
  return s;
}

// The damping criterion a sweep result holds (only a number in [0, 1) is drawn: anything else
// is refused).
std::optional<double> sweep_criterion(const std::string& file, const PlotJson& j) {
  if (!j.contains("damping_criterion")) return std::nullopt;
  const PlotJson& c = j["damping_criterion"];
  if (!c.is_number() || !kDampingCriterionRange.interval.Contains(c.get<double>()))
    refuse_key(
        file, "damping_criterion", c,
        std::string("not a damping criterion (a number ") + kDampingCriterionRange.words + ")");
  return c.get<double>();
}

// About the periodic equilibrium: the header's `linearization`, or (results written before it
// was part of the operating condition) the parameters' `periodic-linearization`.
bool about_periodic_equilibrium(const PlotJson& j) {
  if (j.contains("linearization")) return j["linearization"] == "periodic";
  const PlotJson& p = j.contains("parameters") && j["parameters"].is_object() ? j["parameters"]
                                                                              : PlotJson::object();
  return p.value("periodic-linearization", false) == true;
}

// A short label of a result from its case (the command line behind it): the model, the trim
// and the periodic linearization, e.g. "paper-2x2, moment trim, periodic".
std::string case_label(const std::string& file, const PlotJson& j) {
  std::string label = model_name(file, j);
  const PlotJson& c = j.contains("case") && j["case"].is_object() ? j["case"] : PlotJson::object();
  if (c.contains("trim") && c["trim"].is_string() && c["trim"] != "none") {
    TrimKind kind = TrimKind::None;
    if (!trim_kind_from_name(c["trim"].get<std::string>(), &kind))
      refuse_key(file, "case.trim", c["trim"], "not a trim (none, thrust or moment)");
    label += std::string(", ") + trim_kind_name(kind) + " trim";
  }
  // Fixed controls at the momentum inflow (--inflow momentum): the header says it.
  if (j.contains("inflow") && j["inflow"].is_object() &&
      j["inflow"].value("kind", "") == "momentum")
    label += ", momentum inflow";
  // The header says it whether the option or the case file set it.
  if (about_periodic_equilibrium(j)) label += ", periodic linearization";
  return label;
}

// The linearization of a result in words: "about hover", "moment trim, about hover", "about the
// periodic equilibrium" (from case.trim and the header's linearization, as case_label).
std::string linearization(const std::string& file, const PlotJson& j) {
  const PlotJson& c = j.contains("case") && j["case"].is_object() ? j["case"] : PlotJson::object();
  std::string words;
  if (c.contains("trim") && c["trim"].is_string() && c["trim"] != "none") {
    TrimKind kind = TrimKind::None;
    if (!trim_kind_from_name(c["trim"].get<std::string>(), &kind))
      refuse_key(file, "case.trim", c["trim"], "not a trim (none, thrust or moment)");
    words = std::string(trim_kind_name(kind)) + " trim, ";
  }
  const bool periodic = about_periodic_equilibrium(j);
  return words +
         (periodic ? "linearized about the periodic equilibrium" : "linearized about hover");
}

// The operating values of a result's rotor in its title, from its parameters: the Lock number,
// the collective (not of a trimmed rotor: trimmed at each mu), the two first frequencies, and
// every other real parameter that differs from the typical case; not the ones the result varies
// (`varied`, option spelling).  A value that is not a number is left out.
std::string operating_values(const PlotJson& j, const std::vector<std::string>& varied,
                             bool trimmed) {
  const PlotJson& p = j.contains("parameters") && j["parameters"].is_object() ? j["parameters"]
                                                                              : PlotJson::object();
  const RotorParameters typical;
  std::string out;
  for (const ParameterSpec& spec : parameter_table()) {
    if (spec.type != ParameterType::Real || spec.symbol[0] == '\0') continue;
    const std::string key = json_key(spec), field = spec.field;
    if (std::find(varied.begin(), varied.end(), key) != varied.end()) continue;
    if (!p.contains(key) || !p[key].is_number()) continue;
    const double v = p[key].get<double>();
    const bool always = field == "gamma" || field == "omega_flap" || field == "omega_lag" ||
                        (field == "theta" && !trimmed);
    if (!always && (v == typical.*spec.real || (field == "theta" && trimmed))) continue;
    out += (out.empty() ? "" : ", ") + symbol_text(spec.symbol) + " = " + num(v);
  }
  if (p.value("modes", std::string()) == "exact")
    out += (out.empty() ? "" : ", ") + std::string("exact modes");
  return out;
}

// The thrust coefficient a trimmed result was trimmed to: the target of the first trim it holds
// (a sweep's trim at each mu, a study row's trim at its mu_c); nullopt when none has one.
std::optional<double> trim_target(const PlotJson& j) {
  auto target = [](const PlotJson& t) -> std::optional<double> {
    if (t.is_object() && t.contains("target") && t["target"].is_number())
      return t["target"].get<double>();
    return std::nullopt;
  };
  if (j.contains("trim") && j["trim"].is_array())
    for (const PlotJson& t : j["trim"])
      if (const auto v = target(t)) return v;
  if (j.contains("rows") && j["rows"].is_array())
    for (const PlotJson& row : j["rows"])
      if (row.is_object() && row.contains("trim"))
        if (const auto v = target(row["trim"])) return v;
  return std::nullopt;
}

// A picture's title: the model, the linearization and the operating values, one line, e.g.
// "paper, linearized about hover: γ = 10, θ = 0.15, ω̄_{F1} = 1.175, ω̄_{L1} = 1.28303"
// (enhanced text; the model name escaped).  `extra`: more values after them ("μ = 0.3").
std::string case_title(const std::string& file, const PlotJson& j,
                       const std::vector<std::string>& varied = {}, const std::string& extra = "",
                       bool nonlinear = false) {
  const PlotJson& c = j.contains("case") && j["case"].is_object() ? j["case"] : PlotJson::object();
  const bool trimmed = c.contains("trim") && c["trim"].is_string() && c["trim"] != "none";
  std::string values = operating_values(j, varied, trimmed);
  if (trimmed) {
    if (const std::optional<double> ct = trim_target(j))
      values = "C_T = " + num(*ct) + (values.empty() ? "" : ", " + values);
  }
  if (!extra.empty()) values = extra + (values.empty() ? "" : ", " + values);
  const std::string how = linearization(file, j);
  return literal_text(model_name(file, j)) + " model" + (nonlinear ? std::string("") : ", " + how) +
         (values.empty() ? "" : ": " + values);
}

std::string sweep_script(const std::string& file, const PlotJson& j, SweepQuantity quantity) {
  const SweepOverlay s = sweep_data(file, j);
  SweepPicture picture;
  picture.quantity = quantity;
  picture.add_criterion(sweep_criterion(file, j));
  return sweep_plot_script(case_title(file, j), s, picture);
}

std::string study_script(const std::string& file, const PlotJson& j) {
  const double mu_max = j.at("mu_max").get<double>();
  std::vector<StudyMark> marks;
  for (const PlotJson& row : j.at("rows")) {
    StudyMark m;
    m.value = row.at("value").get<double>();
    if (row.at("mu_c").is_number()) m.mu_c = row["mu_c"].get<double>();
    m.periodic = row.at("kind") == "periodic";
    if (row.contains("omega")) m.omega = number(row["omega"]);
    m.status = row_status(row);
    m.hover_unstable = row.value("hover_unstable", false) == true;
    for (const PlotJson& iv : row.at("intervals")) {
      const PlotJson& off = iv.at(1);
      m.intervals.emplace_back(number(iv.at(0)), off.is_null() ? mu_max : number(off));
    }
    if (row.contains("damping_crossings")) {
      for (const PlotJson& d : row["damping_crossings"]) {
        const std::string& mode = text_at(file, "damping_crossings.mode", d.at("mode"));
        if (!is_mode_label(mode))
          refuse_key(file, "damping_crossings.mode", d["mode"],
                     "not a mode label (flap, lag, lag2, ...)");
        if (d.at("mu").is_number()) m.crossings.emplace_back(mode, d["mu"].get<double>());
      }
    }
    marks.push_back(m);
  }
  const std::string vary = axis_name(file, "vary", j.at("vary"), false);
  return study_plot_script(case_title(file, j, {vary}), *parameter_axis_label(vary), mu_max, marks,
                           sweep_criterion(file, j));
}

std::string map_script(const std::string& file, const PlotJson& j) {
  std::vector<std::vector<double>> z;
  for (const PlotJson& row : j.at("max_zeta")) z.push_back(numbers(row));
  const std::string x = axis_name(file, "x.name", j.at("x").at("name"), true),
                    y = axis_name(file, "y.name", j.at("y").at("name"), true);
  // The advance ratio of a map over two rotor parameters.
  const std::string mu =
      j.contains("mu") && j["mu"].is_number() ? "μ = " + num(j["mu"].get<double>()) : "";
  return max_zeta_plot_script("largest ζ over the modes: " + case_title(file, j, {x, y}, mu),
                              *parameter_axis_label(x), numbers(j.at("x").at("values")),
                              *parameter_axis_label(y), numbers(j.at("y").at("values")), z);
}

std::string tip_script(const std::string& file, const std::string& command, const PlotJson& j) {
  if (!j.contains("psi"))
    refuse_file(file, "a flaplag " + command + " result without data (status " +
                          j.value("status", std::string("unknown")) + "): nothing to draw");
  const std::vector<double> psi = numbers(j.at("psi"));
  const std::vector<double> flap = numbers(j.at("flap_tip")), lag = numbers(j.at("lag_tip"));
  const double mu = j.at("mu").get<double>();
  std::vector<double> x;
  // As the commands compute them: degrees (response), revolutions (simulate).
  for (double p : psi) x.push_back(command == "response" ? p * 180.0 / kPi : p / kTwoPi);
  std::string title = case_title(file, j, {}, "μ = " + num(mu));
  if (command == "response")
    return response_plot_script("periodic response, " + title, x, flap, lag);
  const bool nonlinear = j.value("nonlinear", false) == true,
             forced = j.value("forced", false) == true;
  if (nonlinear) title = case_title(file, j, {}, "μ = " + num(mu), true);
  return simulate_plot_script(std::string(nonlinear ? "nonlinear"
                                          : forced  ? "forced"
                                                    : "free") +
                                  " response, " + title,
                              x, flap, lag);
}

// The mode names are not read from the file: a mode is named by its direction and position.
std::string modes_script(const PlotJson& j) {
  auto curves = [](const PlotJson& direction) {
    std::vector<ShapeCurves> c;
    for (const PlotJson& m : direction.at("modes"))
      c.push_back({numbers(m.at("value")), numbers(m.at("d1"))});
    return c;
  };
  const PlotJson& p = j.at("parameters");
  auto parameter = [&](const char* field) {
    return number(p.at(json_key(*find_parameter(field))));
  };
  const std::string blade = j.contains("blade_table") ? "the blade table" : "the uniform blade";
  std::string title = "exact rotating modes of " + blade +
                      ": ω̄_{F1} = " + num(parameter("omega_flap")) +
                      ", ω̄_{L1} = " + num(parameter("omega_lag")) + " per rev";
  for (const char* field : {"length_ratio", "root_offset"}) {
    const ParameterSpec& spec = *find_parameter(field);
    const double v = parameter(field);
    if (v != RotorParameters{}.*spec.real)
      title += ", " + symbol_text(spec.symbol) + " = " + num(v);
  }
  return mode_shapes_plot_script(title, numbers(j.at("x0")), curves(j.at("flap")),
                                 curves(j.at("lag")));
}

// The labels are checked as a sweep's; the number of per-rev lines is bounded as the command
// bounds it (each is a line of the script).
std::string campbell_script(const std::string& file, const PlotJson& j) {
  CampbellPicture c;
  c.modes = mode_curves(file, j);
  const PlotJson& harmonics = j.at("harmonics");
  if (!harmonics.is_number_integer() ||
      !kCampbellHarmonicsRange.interval.Contains(harmonics.get<double>()))
    refuse_key(file, "harmonics", harmonics,
               std::string("must be an integer ") + kCampbellHarmonicsRange.words);
  c.harmonics = harmonics.get<int>();
  c.mu = number(j.at("mu"));
  for (const PlotJson& pt : j.at("points")) {
    c.speed.push_back(number(pt.at("speed")));
    const PlotJson& modes = pt.at("modes");
    for (std::size_t m = 0; m < c.modes.size(); ++m)
      c.modes[m].omega.push_back(m < modes.size() ? number(modes.at(m).at("frequency")) : NAN);
  }
  for (const PlotJson& x : j.at("crossings"))
    c.crossings.emplace_back(number(x.at("speed")), number(x.at("frequency")));
  return campbell_plot_script("Campbell diagram, " + case_title(file, j, {}, "μ = " + num(c.mu)),
                              c);
}

PlotJson read_result(const std::string& data, std::uint64_t memory_limit, const Spelling& option) {
  PlotJson j;
  std::string error;
  const JsonParse parsed = parse_json(
      read_json_file(data, memory_limit, "result file", "cannot be read", option), &j, &error);
  const std::string json = option("json");
  if (parsed == JsonParse::NotJson)
    refuse_file(data, "not JSON (flaplag plot draws a " + json + " output of flaplag)");
  if (parsed == JsonParse::Refused)
    refuse_file(data, "not a flaplag " + json + " output: " + error);
  if (!j.is_object() || !j.contains("flaplag") || !j.contains("command") ||
      !j["command"].is_string())
    refuse_file(data, "not a flaplag " + json + " output");
  return j;
}

}  // namespace

std::optional<std::string> result_plot_script(const nlohmann::json& j, const std::string& file,
                                              SweepQuantity quantity) {
  const std::string command = j.at("command").get<std::string>();
  try {
    if (command == "sweep") return sweep_script(file, j, quantity);
    if (command == "study") return study_script(file, j);
    if (command == "map") return map_script(file, j);
    if (command == "response" || command == "simulate") return tip_script(file, command, j);
    if (command == "modes") return modes_script(j);
    if (command == "campbell") return campbell_script(file, j);
  } catch (const PlotJson::exception&) {
    refuse_file(
        file, "a damaged flaplag " + command + " result (a key is missing or has the wrong type)");
  }
  return std::nullopt;
}

std::string plot_data_file(const std::string& data, const std::string& plot,
                           std::uint64_t memory_limit, const Spelling& option,
                           SweepQuantity quantity) {
  const PlotJson j = read_result(data, memory_limit, option);
  const std::optional<std::string> script = result_plot_script(j, data, quantity);
  if (!script)
    refuse_file(data, "a flaplag " + j["command"].get<std::string>() +
                          " result has no picture (flaplag plot draws sweep, study, map, response, "
                          "simulate, modes and campbell results)");
  const std::string warning = render_plot(*script, plot);
  if (!warning.empty()) throw RendererUnavailable(warning);
  return "";
}

std::string plot_data_files(const PlotFiles& files, const Spelling& option) {
  const std::vector<std::string>& data = files.data;
  const std::vector<std::string>& labels = files.labels;
  const std::string& mode = files.mode;
  const bool max_zeta = files.max_zeta;
  if (data.size() == 1 && labels.empty() && !max_zeta && mode.empty())
    return plot_data_file(data[0], files.plot, files.memory_limit, option, files.quantity);
  SweepPicture picture;
  picture.quantity = files.quantity;
  for (const std::string& l : labels) check_label(l, option);
  std::vector<SweepOverlay> sweeps;
  std::string first;  // the kind of the first file
  for (std::size_t i = 0; i < data.size(); ++i) {
    const PlotJson j = read_result(data[i], files.memory_limit, option);
    const std::string command = j["command"].get<std::string>();
    if (i == 0) first = command;
    if (command != first)
      refuse_file(data[i], "a flaplag " + command + " result, not a " + first + " like " +
                               shown(data[0]) + ": one picture draws results of one kind");
    if (command != "sweep")
      refuse_file(data[i], std::string("a flaplag ") + command + " result: " +
                               (data.size() > 1 ? "several results in one picture"
                                                : option("label") + ", " + option("max_zeta") +
                                                      " and " + option("mode")) +
                               " are for sweep results only");
    try {
      SweepOverlay s = sweep_data(data[i], j);
      picture.add_criterion(sweep_criterion(data[i], j));
      s.label = labels.empty() ? case_label(data[i], j) : labels[i];
      if (!mode.empty()) {
        std::vector<ModeCurve> kept;
        for (ModeCurve& m : s.modes)
          if (same_mode(m.label, mode)) kept.push_back(std::move(m));
        if (kept.empty())
          throw InvalidInput(
              "mode", shown(mode),
              "not a mode of " + shown(data[i]) + " (its modes: " + j.at("labels").dump() + ")");
        s.modes = std::move(kept);
      }
      sweeps.push_back(std::move(s));
    } catch (const PlotJson::exception&) {
      refuse_file(data[i],
                  "a damaged flaplag sweep result (a key is missing or has the wrong type)");
    }
  }
  // Two files of the same case get the same label: number them to tell the curves apart.
  if (labels.empty()) {
    std::vector<std::string> base;
    for (const SweepOverlay& s : sweeps) base.push_back(s.label);
    for (std::size_t i = 0; i < sweeps.size(); ++i)
      if (std::count(base.begin(), base.end(), base[i]) > 1)
        sweeps[i].label += " (" + std::to_string(i + 1) + ")";
  }
  const std::string n = std::to_string(sweeps.size()) + (sweeps.size() == 1 ? " sweep" : " sweeps");
  const std::string title = max_zeta        ? "the least stable mode of " + n
                            : !mode.empty() ? "mode " + literal_text(mode) + " of " + n
                                            : n + " compared";
  const std::string warning =
      render_plot(sweep_overlay_script(title, sweeps, max_zeta, picture), files.plot);
  if (!warning.empty()) throw RendererUnavailable(warning);
  return "";
}

}  // namespace flaplag::documents
