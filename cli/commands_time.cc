// flaplag CLI — the blade in time: `flaplag response` (the periodic forced response) and
// `flaplag simulate` (a time-domain run from a perturbation).
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "commands_internal.h"
#include "flaplag/core/constants.h"
#include "flaplag/core/format.h"
#include "flaplag/documents/output.h"

namespace flaplag::cli::cmd {

namespace {

// The model's directions (model_api.h), in the order of a result's tips.
std::vector<model::DirectionBlock> directions(const Analysis& an) {
  return model::direction_blocks(an.model().flap_modes, an.model().lag_modes);
}

// "<direction><suffix>" of every direction: the keys of per-direction values in JSON.
std::string key(const TipMotion& t, const char* suffix) { return t.direction + suffix; }

// Column heads "<direction> <prefix><deflection>/l" (e.g. "flap w/l", "lag dv/l").
std::vector<std::string> deflection_heads(const Analysis& an, const std::string& prefix) {
  std::vector<std::string> heads;
  for (const model::DirectionBlock& b : directions(an))
    heads.push_back(std::string(b.name) + " " + prefix + b.deflection + "/l");
  return heads;
}

}  // namespace

Output response(const Request& r, const Analysis& an, std::string& warning) {
  const ForcedResponse f = an.response(r.mu, r.response);
  const auto json = [&] {
    Json j = header_json("response", an, false);
    j["mu"] = r.mu;
    if (f.status != Status::Failed) {
      j["psi"] = f.periodic.psi;
      for (const TipMotion& t : f.tips) j[key(t, "_tip")] = t.deflection;
      for (const TipMotion& t : f.tips) {
        Json h = Json::object();
        for (std::size_t k = 0; k < t.harmonics.size(); ++k)
          h[harmonic_name(static_cast<int>(k))] = t.harmonics[k];
        j[key(t, "_harmonics")] = h;
      }
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
  std::vector<std::string> heads = deflection_heads(an, "");
  heads.insert(heads.begin(), "harmonic");
  TextTable h(heads);
  for (std::size_t k = 0; k < f.tips.front().harmonics.size(); ++k) {
    std::vector<std::string> row{harmonic_name(static_cast<int>(k))};
    for (const TipMotion& t : f.tips) row.push_back(short_text(t.harmonics[k]));
    h.add_row(row);
  }
  out += h.render();
  heads.front() = "psi [deg]";
  TextTable t(heads);
  const std::size_t samples = f.periodic.psi.size();
  const std::size_t every = std::max<std::size_t>(1, samples / 24);
  for (std::size_t k = 0; k < samples; k += every) {
    std::vector<std::string> row{short_text(f.periodic.psi[k] * 180.0 / kPi)};
    for (const TipMotion& m : f.tips) row.push_back(short_text(m.deflection[k]));
    t.add_row(row);
  }
  out += "\n" + t.render();
  out += "  periodicity |y(2 pi) - y(0)| / |y0| = " + short_text(f.periodic.closure) + "\n";
  return text_output(r, out + status_text(f.status, vocab(r, f.message)), std::move(j));
}

Output simulate_command(const Request& r, const Analysis& an, std::string& warning) {
  const Eigen::VectorXd y0 = Eigen::VectorXd::Constant(an.state_size(), r.perturbation);
  const TipSimulation ts = an.simulate(r.mu, y0, r.forced, r.simulation);
  const Simulation& s = ts.simulation;
  std::vector<double> revs;
  for (double psi : s.psi) revs.push_back(psi / kTwoPi);
  const auto json = [&] {
    Json j = header_json("simulate", an, false);
    j["mu"] = r.mu;
    j["forced"] = r.forced;
    j["nonlinear"] = ts.nonlinear;
    j["reference"] = ts.reference;
    j["revolutions"] = r.simulation.revolutions;
    j["steps_per_rev"] = s.steps_per_rev;
    j["psi"] = s.psi;
    for (const TipMotion& t : ts.tips) j[key(t, "_tip")] = t.deflection;
    if (ts.nonlinear)
      for (const TipMotion& t : ts.tips) j[key(t, "_total")] = t.total;
    for (const TipMotion& t : ts.tips) j[key(t, "_growth_rate")] = optional_json(t.growth_rate);
    return status_json(j, ts.status, vocab(r, ts.message));
  };
  std::optional<Json> j = result_document(r, json, &warning);
  if (r.json) return std::move(*j);
  std::string out = header_text(an, false) + "\n";
  if (ts.nonlinear) {
    out += "Nonlinear response at mu = " + num(r.mu) + " from the " + ts.reference + " + " +
           num(r.perturbation) + " in every state, " + num(r.simulation.revolutions) +
           " revolutions (" + std::to_string(s.steps_per_rev) +
           " RK4 steps per rev); d: deviation from the " + ts.reference + "\n";
  } else {
    out += std::string(r.forced ? "Forced" : "Free") + " response at mu = " + num(r.mu) +
           " from y0 = " + num(r.perturbation) + " in every state, " +
           num(r.simulation.revolutions) + " revolutions (" + std::to_string(s.steps_per_rev) +
           " RK4 steps per rev)\n";
  }
  std::vector<std::string> heads = deflection_heads(an, "d");
  if (ts.nonlinear) {
    const std::vector<std::string> totals = deflection_heads(an, "");
    heads.insert(heads.end(), totals.begin(), totals.end());
  }
  heads.insert(heads.begin(), "rev");
  TextTable t(heads);
  const std::size_t every = std::max<std::size_t>(1, s.y.size() / 20);
  for (std::size_t k = 0; k < s.y.size(); k += every) {
    std::vector<std::string> row{short_text(revs[k])};
    for (const TipMotion& m : ts.tips) row.push_back(short_text(m.deflection[k]));
    if (ts.nonlinear)
      for (const TipMotion& m : ts.tips) row.push_back(short_text(m.total[k]));
    t.add_row(row);
  }
  out += t.render();
  std::string rates;
  for (const TipMotion& m : ts.tips)
    rates += (rates.empty() ? " " : ", ") + m.direction + " " +
             (m.growth_rate ? short_text(*m.growth_rate) : std::string("-"));
  out += "  envelope growth rate (last 3/4 of the run; compare with the largest Floquet zeta):" +
         rates + " per rev\n";
  return text_output(r, out + status_text(ts.status, vocab(r, ts.message)), std::move(j));
}

}  // namespace flaplag::cli::cmd
