// flaplag CLI — `flaplag plot DATA.json`: the picture of an existing result, from the numbers
// its JSON holds, through the same script builders as --plot (plot.h).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "options.h"
#include "plot.h"
#include "read_file.h"

namespace flaplag::cli {

namespace {

using Json = nlohmann::json;

[[noreturn]] void refuse(const std::string& file, const std::string& reason) {
  throw InvalidInput("argument", shown(file), reason);
}

// A number of the output; null, "-inf" (the zeta of a zero multiplier) and the like: a gap.
double number(const Json& v) { return v.is_number() ? v.get<double>() : NAN; }

std::vector<double> numbers(const Json& a) {
  std::vector<double> v;
  for (const Json& x : a.get<std::vector<Json>>()) v.push_back(number(x));
  return v;
}

SweepOverlay sweep_data(const Json& j) {
  SweepOverlay s;
  for (const Json& l : j.at("labels")) s.modes.push_back({l.get<std::string>(), {}, {}});
  for (const Json& row : j.at("rows")) {
    s.mu.push_back(number(row.at("mu")));
    for (ModeCurve& m : s.modes) {
      const Json& e = row.at(m.label);
      m.zeta.push_back(e.is_object() ? number(e.at("zeta")) : NAN);
      m.omega.push_back(e.is_object() ? number(e.at("omega")) : NAN);
    }
  }
  return s;
}

std::string sweep_script(const Json& j) {
  const SweepOverlay s = sweep_data(j);
  return sweep_plot_script(j.at("model").at("name").get<std::string>(), s.mu, s.modes);
}

// A short label of a result from its case (the command line behind it): the model, the trim
// and the periodic linearization, e.g. "paper-cyclic, moment trim, periodic".
std::string case_label(const Json& j) {
  std::string label = j.at("model").at("name").get<std::string>();
  const Json& c = j.contains("case") && j["case"].is_object() ? j["case"] : Json::object();
  if (c.contains("trim") && c["trim"].is_string() && c["trim"] != "none")
    label += ", " + c["trim"].get<std::string>() + " trim";
  // The resolved parameters say it whether the option or the case file set it.
  const Json& p =
      j.contains("parameters") && j["parameters"].is_object() ? j["parameters"] : Json::object();
  if (p.value("periodic-linearization", false) == true) label += ", periodic linearization";
  return label;
}

std::string study_script(const Json& j) {
  const double mu_max = j.at("mu_max").get<double>();
  std::vector<StudyMark> marks;
  for (const Json& row : j.at("rows")) {
    StudyMark m;
    m.value = row.at("value").get<double>();
    if (row.at("mu_c").is_number()) m.mu_c = row["mu_c"].get<double>();
    m.periodic = row.at("kind") == "periodic";
    for (const Json& iv : row.at("intervals")) {
      const Json& off = iv.at(1);
      m.intervals.emplace_back(number(iv.at(0)), off.is_null() ? mu_max : number(off));
    }
    marks.push_back(m);
  }
  return study_plot_script(j.at("vary").get<std::string>(), marks);
}

std::string map_script(const Json& j) {
  std::vector<std::vector<double>> z;
  for (const Json& row : j.at("max_zeta")) z.push_back(numbers(row));
  return max_zeta_plot_script(
      j.at("x").at("name").get<std::string>(), numbers(j.at("x").at("values")),
      j.at("y").at("name").get<std::string>(), numbers(j.at("y").at("values")), z);
}

std::string tip_script(const std::string& file, const std::string& command, const Json& j) {
  if (!j.contains("psi"))
    refuse(file, "a flaplag " + command + " result without data (status " +
                     j.value("status", std::string("unknown")) + "): nothing to draw");
  const std::vector<double> psi = numbers(j.at("psi"));
  const std::vector<double> flap = numbers(j.at("flap_tip")), lag = numbers(j.at("lag_tip"));
  const double mu = j.at("mu").get<double>();
  std::vector<double> x;
  // As the commands compute them: degrees (response), revolutions (simulate).
  for (double p : psi) x.push_back(command == "response" ? p * 180.0 / kPi : p / kTwoPi);
  return command == "response" ? response_plot_script(mu, x, flap, lag)
                               : simulate_plot_script(mu, x, flap, lag);
}

Json read_result(const std::string& data) {
  Json j;
  std::string error;
  const JsonParse parsed = parse_json(
      read_text_file(data, kMaxResultBytes, "result file", "cannot be read"), &j, &error);
  if (parsed == JsonParse::NotJson)
    refuse(data, "not JSON (flaplag plot draws a --json output of flaplag)");
  if (parsed == JsonParse::Refused) refuse(data, "not a flaplag --json output: " + error);
  if (!j.is_object() || !j.contains("flaplag") || !j.contains("command") ||
      !j["command"].is_string())
    refuse(data, "not a flaplag --json output");
  return j;
}

}  // namespace

std::string plot_data_file(const std::string& data, const std::string& plot) {
  const Json j = read_result(data);
  const std::string command = j["command"].get<std::string>();
  std::string script;
  try {
    if (command == "sweep")
      script = sweep_script(j);
    else if (command == "study")
      script = study_script(j);
    else if (command == "map")
      script = map_script(j);
    else if (command == "response" || command == "simulate")
      script = tip_script(data, command, j);
    else
      refuse(data, "a flaplag " + command +
                       " result has no picture (flaplag plot draws sweep, study, map, response "
                       "and simulate results)");
  } catch (const Json::exception&) {
    refuse(data,
           "a damaged flaplag " + command + " result (a key is missing or has the wrong type)");
  }
  const std::string warning = render_plot(script, plot);
  if (!warning.empty()) throw RendererUnavailable(warning);
  return "";
}

std::string plot_data_files(const std::vector<std::string>& data,
                            const std::vector<std::string>& labels, bool max_zeta,
                            const std::string& mode, const std::string& plot) {
  if (data.size() == 1 && labels.empty() && !max_zeta && mode.empty())
    return plot_data_file(data[0], plot);
  std::vector<SweepOverlay> sweeps;
  std::string first;  // the kind of the first file
  for (std::size_t i = 0; i < data.size(); ++i) {
    const Json j = read_result(data[i]);
    const std::string command = j["command"].get<std::string>();
    if (i == 0) first = command;
    if (command != first)
      refuse(data[i], "a flaplag " + command + " result, not a " + first + " like " +
                          shown(data[0]) + ": one picture draws results of one kind");
    if (command != "sweep")
      refuse(data[i], std::string("a flaplag ") + command + " result: " +
                          (data.size() > 1 ? "several results in one picture"
                                           : "--label, --max-zeta and --mode") +
                          " are for sweep results only");
    try {
      SweepOverlay s = sweep_data(j);
      s.label = labels.empty() ? case_label(j) : labels[i];
      if (!mode.empty()) {
        std::vector<ModeCurve> kept;
        for (ModeCurve& m : s.modes)
          if (m.label == mode) kept.push_back(std::move(m));
        if (kept.empty())
          throw InvalidInput(
              "mode", shown(mode),
              "not a mode of " + shown(data[i]) + " (its modes: " + j.at("labels").dump() + ")");
        s.modes = std::move(kept);
      }
      sweeps.push_back(std::move(s));
    } catch (const Json::exception&) {
      refuse(data[i], "a damaged flaplag sweep result (a key is missing or has the wrong type)");
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
  const std::string warning = render_plot(sweep_overlay_script(sweeps, max_zeta), plot);
  if (!warning.empty()) throw RendererUnavailable(warning);
  return "";
}

}  // namespace flaplag::cli
