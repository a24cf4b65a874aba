// flaplag CLI — the blade in time: `flaplag response` (the periodic forced response) and
// `flaplag simulate` (a time-domain run from a perturbation).
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "commands_internal.h"
#include "flaplag/core/constants.h"
#include "flaplag/core/format.h"
#include "output.h"
#include "plot.h"

namespace flaplag::cli::cmd {

Output response(const Request& r, const Analysis& an, std::string& warning) {
  ResponseOptions ro;
  ro.samples = r.samples;
  const ForcedResponse f = an.response(r.mu, ro);
  const auto json = [&] {
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
    return status_json(j, f.status, vocab(r, f.message));
  };
  // A failed response has no curves to draw.
  std::optional<Json> j = result_document(r, json, f.status != Status::Failed ? &warning : nullptr);
  if (r.json) return std::move(*j);
  std::string out = header_text(an, false) + "\n";
  out += "Periodic forced response at mu = " + num(r.mu) +
         " (tip deflections by l, hover equilibrium included)\n";
  if (f.status == Status::Failed)
    return text_output(r, out + status_text(f.status, vocab(r, f.message)), std::move(j));
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
  return text_output(r, out + status_text(f.status, vocab(r, f.message)), std::move(j));
}

Output simulate_command(const Request& r, const Analysis& an, std::string& warning) {
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
  const auto json = [&] {
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
    return status_json(j, ts.status, vocab(r, ts.message));
  };
  std::optional<Json> j = result_document(r, json, &warning);
  if (r.json) return std::move(*j);
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
  return text_output(r, out + status_text(ts.status, vocab(r, ts.message)), std::move(j));
}

}  // namespace flaplag::cli::cmd
