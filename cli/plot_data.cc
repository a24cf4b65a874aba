// flaplag CLI — `flaplag plot DATA.json`: the picture of an existing result, from the numbers
// its JSON holds, through the same script builders as --plot (plot.h).
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "options.h"
#include "plot.h"

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

std::string sweep_script(const Json& j) {
  std::vector<double> mu;
  std::vector<ModeCurve> modes;
  for (const Json& l : j.at("labels")) modes.push_back({l.get<std::string>(), {}, {}});
  for (const Json& row : j.at("rows")) {
    mu.push_back(number(row.at("mu")));
    for (ModeCurve& m : modes) {
      const Json& e = row.at(m.label);
      m.zeta.push_back(e.is_object() ? number(e.at("zeta")) : NAN);
      m.omega.push_back(e.is_object() ? number(e.at("omega")) : NAN);
    }
  }
  return sweep_plot_script(j.at("model").at("name").get<std::string>(), mu, modes);
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

}  // namespace

std::string plot_data_file(const std::string& data, const std::string& plot) {
  std::ifstream in(data, std::ios::binary);
  if (!in) refuse(data, "cannot be read");
  std::stringstream ss;
  ss << in.rdbuf();
  if (in.bad()) refuse(data, "cannot be read");
  Json j;
  try {
    j = Json::parse(ss.str());
  } catch (const Json::exception&) {
    refuse(data, "not JSON (flaplag plot draws a --json output of flaplag)");
  }
  if (!j.is_object() || !j.contains("flaplag") || !j.contains("command") ||
      !j["command"].is_string())
    refuse(data, "not a flaplag --json output");
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

}  // namespace flaplag::cli
