// `flaplag modes`: the Fig 9 relation between first rotating and nonrotating frequencies, and
// the exact rotating modes of one blade (frequencies, stiffnesses, shapes, Rayleigh checks): the
// uniform blade, or a blade table's (its stiffness columns scaled, rotating_modes.h).
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.h"
#include "commands_internal.h"
#include "flaplag/blade/imported_modes.h"
#include "flaplag/blade/rotating_modes.h"
#include "flaplag/rotor/parameter_table.h"
#include "options.h"
#include "output.h"
#include "plot.h"

namespace flaplag::cli {

namespace {

using Json = nlohmann::ordered_json;

std::string index_name(const char* base, std::size_t k) { return base + std::to_string(k + 1); }

// As in commands.cc: a value the Galerkin solution did not deliver finite is shown as "-" or
// null, and the output's status says so.
std::string cell(double v) { return std::isfinite(v) ? num(v) : "-"; }
Json jnum(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }
Json jnums(const std::vector<double>& v) {
  Json a = Json::array();
  for (double x : v) a.push_back(jnum(x));
  return a;
}

// What `flaplag modes` shows, computed once for the text and the JSON.
struct ModesShown {
  bool table = false;  // a blade table's modes: the stiffnesses are scales of its columns
  ExactModeOptions opt;
  std::vector<FrequencyPair> flap9, lag9;  // the Fig 9 relation
  ExactModes ex;
  std::vector<double> rayleigh_flap, rayleigh_lag;
  std::vector<double> x0;  // the stations of the shape table
  bool all_finite = true;
  std::string status, message;
};

// The tables are computed from the blade (uniform or a table), not read from a mode file:
// imported shapes would be shown as modes they are not.
void refuse_imported_shapes(const RotorParameters& p) {
  if (p.mode_shapes) {
    throw InvalidInput("mode_shapes", p.mode_shapes->source,
                       "`flaplag modes` computes the exact modes of the blade (uniform or "
                       "--blade-table); imported shapes are checked with every analysis result "
                       "(its notes say when they are not mass-orthogonal)");
  }
}

ExactModeOptions mode_options(const Request& r) {
  const RotorParameters& p = r.params;
  ExactModeOptions opt;
  opt.n_basis = galerkin_basis(r.params);
  opt.flap_modes = r.flap_modes;
  opt.lag_modes = r.lag_modes;
  opt.e1_over_l = p.root_offset / p.length_ratio;
  opt.paper_1974_shapes = p.paper_1974_shapes;
  opt.blade = p.blade;
  return opt;
}

// Every number shown, checked once.
bool every_number_finite(const ModesShown& m) {
  const ModeSet& ms = m.ex.modes;
  bool all_finite = std::isfinite(m.opt.e1_over_l) && std::isfinite(m.ex.omega_flap_nonrotating) &&
                    std::isfinite(m.ex.omega_lag_nonrotating) && std::isfinite(ms.stiffness_flap) &&
                    std::isfinite(ms.stiffness_lag);
  for (const auto& t : {&m.flap9, &m.lag9}) {
    for (const FrequencyPair& f : *t) {
      all_finite = all_finite && std::isfinite(f.nonrotating) && std::isfinite(f.rotating);
    }
  }
  const std::vector<const std::vector<double>*> lists = {&m.ex.omega_flap_all, &m.ex.omega_lag_all,
                                                         &ms.omega_flap,       &ms.omega_lag,
                                                         &m.rayleigh_flap,     &m.rayleigh_lag};
  for (const std::vector<double>* v : lists) {
    for (double x : *v) all_finite = all_finite && std::isfinite(x);
  }
  for (const auto& shapes : {&ms.flap, &ms.lag}) {
    for (const auto& shape : *shapes) {
      for (int der = 0; der <= 3; ++der) {
        for (double x : m.x0) all_finite = all_finite && std::isfinite(shape->value(der, x));
      }
    }
  }
  return all_finite;
}

ModesShown compute_modes(const Request& r) {
  const RotorParameters& p = r.params;
  ModesShown m;
  m.table = p.blade != nullptr;
  m.opt = mode_options(r);
  // fig9_table spaces n points evenly on [lo, hi]: hi is the last multiple of STEP in the range
  // (the command line guarantees at least two points).
  const double hi9 = r.fig9_from + (r.fig9_points - 1) * r.fig9_step;
  m.flap9 = fig9_table(BendingDirection::Flap, r.fig9_from, hi9, r.fig9_points, m.opt);
  m.lag9 = fig9_table(BendingDirection::Lag, r.fig9_from, hi9, r.fig9_points, m.opt);

  m.ex = exact_rotating_modes(p.omega_flap, p.omega_lag, m.opt);
  const ModeSet& ms = m.ex.modes;
  // The Rayleigh quotients with the blade's own distributions (the table's, with its tip mass).
  auto rayleigh_of = [&](BendingDirection dir, const ModeShape& shape, double k) {
    return m.table ? rayleigh_frequency(dir, shape, k, m.opt.e1_over_l, *p.blade)
                   : rayleigh_frequency(dir, shape, k, m.opt.e1_over_l, m.opt.mbar);
  };
  for (const auto& s : ms.flap) {
    m.rayleigh_flap.push_back(rayleigh_of(BendingDirection::Flap, *s, ms.stiffness_flap));
  }
  for (const auto& s : ms.lag) {
    m.rayleigh_lag.push_back(rayleigh_of(BendingDirection::Lag, *s, ms.stiffness_lag));
  }
  m.x0.resize(static_cast<std::size_t>(r.shape_points));
  for (std::size_t i = 0; i < m.x0.size(); ++i) {
    m.x0[i] = static_cast<double>(i) / static_cast<double>(m.x0.size() - 1);
  }
  m.all_finite = every_number_finite(m);
  m.status = m.all_finite ? "ok" : "failed";
  m.message = m.all_finite ? "" : "non-finite frequencies, stiffnesses or shape values (not shown)";
  return m;
}

// --export-shapes: the mode file (imported_modes.h) of the shapes shown; none of a failed
// solution.
void export_shapes(const Request& r, const ModesShown& m, const OutputTarget& shapes_file,
                   std::string* warning) {
  if (r.export_shapes.empty()) return;
  if (m.all_finite) {
    shapes_file.write(mode_table_text(m.ex.modes, kExportedModeStations));
  } else if (warning != nullptr) {
    *warning = "--export-shapes = " + r.export_shapes + " not written: " + m.message;
  }
}

// One direction's frequencies, stiffness and mode shapes (values and derivatives 1..3 at x0).
Json direction_json(const ModesShown& m, BendingDirection dir, double given) {
  const bool flap = dir == BendingDirection::Flap;
  const ModeSet& ms = m.ex.modes;
  const std::vector<std::shared_ptr<const ModeShape>>& shapes = flap ? ms.flap : ms.lag;
  const std::vector<double>& returned = flap ? ms.omega_flap : ms.omega_lag;
  const std::vector<double>& rayleigh = flap ? m.rayleigh_flap : m.rayleigh_lag;
  Json d;
  d["rotating_first"] = given;
  d["nonrotating_first"] = jnum(flap ? m.ex.omega_flap_nonrotating : m.ex.omega_lag_nonrotating);
  d[m.table ? "stiffness_scale" : "stiffness"] = jnum(flap ? ms.stiffness_flap : ms.stiffness_lag);
  d["rotating_all"] = jnums(flap ? m.ex.omega_flap_all : m.ex.omega_lag_all);
  Json modes = Json::array();
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    Json mode;
    mode["name"] = index_name(flap ? "eta" : "gamma", k);
    mode["omega"] = k < returned.size() ? jnum(returned[k]) : Json();
    mode["rayleigh_omega"] = jnum(rayleigh[k]);
    for (int der = 0; der <= 3; ++der) {
      Json col = Json::array();
      for (double x : m.x0) col.push_back(jnum(shapes[k]->value(der, x)));
      mode[der == 0 ? "value" : "d" + std::to_string(der)] = col;
    }
    modes.push_back(mode);
  }
  d["modes"] = modes;
  return d;
}

Json modes_json(const Request& r, const ModesShown& m) {
  const RotorParameters& p = r.params;
  Json j;
  j["command"] = "modes";
  j["basis"] = galerkin_basis(r.params);
  Json params = Json::object();
  for (const char* field :
       {"omega_flap", "omega_lag", "length_ratio", "root_offset", "paper_1974_shapes"}) {
    const ParameterSpec& spec = *find_parameter(field);
    if (spec.type == ParameterType::Flag) {
      params[json_key(spec)] = p.*spec.flag;
    } else {
      params[json_key(spec)] = p.*spec.real;
    }
  }
  j["parameters"] = params;
  if (m.table) j["blade_table"] = cmd::blade_table_json(*p.blade);
  j["e1_over_l"] = jnum(m.opt.e1_over_l);
  Json fig9 = Json::array();
  for (std::size_t i = 0; i < m.flap9.size(); ++i) {
    fig9.push_back(Json{{"nonrotating", jnum(m.flap9[i].nonrotating)},
                        {"flap_rotating", jnum(m.flap9[i].rotating)},
                        {"lag_rotating", i < m.lag9.size() ? jnum(m.lag9[i].rotating) : Json()}});
  }
  j["fig9"] = fig9;
  j["x0"] = m.x0;
  j["flap"] = direction_json(m, BendingDirection::Flap, p.omega_flap);
  j["lag"] = direction_json(m, BendingDirection::Lag, p.omega_lag);
  j["status"] = m.status;
  j["message"] = m.message;
  return j;
}

std::string fig9_text(const Request& r, const ModesShown& m) {
  std::string out = "Fig 9: first rotating vs first nonrotating frequency, by Omega\n(" +
                    std::to_string(galerkin_basis(r.params)) +
                    " cantilever functions per direction, e1/l = " + cell(m.opt.e1_over_l) + ")\n";
  if (m.table) out += "blade table " + cmd::blade_table_text(*r.params.blade, r.params) + "\n";
  TextTable t9({"nonrotating", "flap rotating", "lag rotating"});
  for (std::size_t i = 0; i < m.flap9.size(); ++i) {
    t9.add_row({cell(m.flap9[i].nonrotating), cell(m.flap9[i].rotating),
                i < m.lag9.size() ? cell(m.lag9[i].rotating) : "-"});
  }
  return out + t9.render() + "\n";
}

// Frequencies, stiffnesses and the Rayleigh check of each shape.
std::string exact_modes_text(const RotorParameters& p, const ModesShown& m) {
  const ExactModes& ex = m.ex;
  const ModeSet& ms = ex.modes;
  std::string out = "Exact rotating modes of the blade";
  if (m.opt.paper_1974_shapes)
    out += "\n(1974 sign convention: the shapes are NOT modes of the blade)";
  out += "\n";
  TextTable tb({"", "flap", "lag"});
  tb.add_row({"first rotating frequency", cell(p.omega_flap), cell(p.omega_lag)});
  tb.add_row({"first nonrotating frequency", cell(ex.omega_flap_nonrotating),
              cell(ex.omega_lag_nonrotating)});
  tb.add_row({m.table ? "stiffness scale s of the table's EI" : "stiffness EI/(Omega^2 l I_b)",
              cell(ms.stiffness_flap), cell(ms.stiffness_lag)});
  const std::size_t n_all = std::max(ex.omega_flap_all.size(), ex.omega_lag_all.size());
  for (std::size_t k = 0; k < n_all; ++k) {
    tb.add_row({"rotating frequency " + std::to_string(k + 1),
                k < ex.omega_flap_all.size() ? cell(ex.omega_flap_all[k]) : "-",
                k < ex.omega_lag_all.size() ? cell(ex.omega_lag_all[k]) : "-"});
  }
  // The Rayleigh quotient of a true mode is its frequency; a wrong shape shows up here.
  const std::size_t n_shapes = std::max(m.rayleigh_flap.size(), m.rayleigh_lag.size());
  for (std::size_t k = 0; k < n_shapes; ++k) {
    tb.add_row({"Rayleigh frequency of shape " + std::to_string(k + 1),
                k < m.rayleigh_flap.size() ? cell(m.rayleigh_flap[k]) : "-",
                k < m.rayleigh_lag.size() ? cell(m.rayleigh_lag[k]) : "-"});
  }
  out += tb.render();
  if (m.table) {
    out += p.blade->origin.dimensional
               ? "(EI/(Omega^2 l I_b) = s x the table's EI column; a dimensional table's columns "
                 "are absolute: s = 1)\n"
               : "(EI/(Omega^2 l I_b) = s x the table's EI column, which is relative to its root "
                 "value: s is EI/(Omega^2 l I_b) at the root)\n";
  }
  return out;
}

std::string shapes_text(const ModesShown& m) {
  const ModeSet& ms = m.ex.modes;
  std::string out = "\nMode shapes (tip value 1)\n";
  std::vector<std::string> header{"x0"};
  for (std::size_t k = 0; k < ms.flap.size(); ++k) header.push_back(index_name("eta", k));
  for (std::size_t k = 0; k < ms.lag.size(); ++k) header.push_back(index_name("gamma", k));
  TextTable ts(header);
  for (double x : m.x0) {
    std::vector<std::string> row{cell(x)};
    for (const auto& s : ms.flap) row.push_back(cell(s->value(0, x)));
    for (const auto& s : ms.lag) row.push_back(cell(s->value(0, x)));
    ts.add_row(row);
  }
  return out + ts.render();
}

}  // namespace

std::string run_modes(const Request& r, std::string* warning) {
  refuse_imported_shapes(r.params);
  // --export-shapes: the path checked before anything is computed, written after.
  const OutputTarget shapes_file(r.export_shapes, "export_shapes");
  const ModesShown m = compute_modes(r);
  export_shapes(r, m, shapes_file, warning);
  if (r.json || !r.plot.empty()) {
    const Json j = modes_json(r, m);
    // The picture of the result, as `flaplag plot` draws it (plot.h).
    if (!r.plot.empty()) {
      const std::string w = render_plot(*result_plot_script(j, r.plot), r.plot);
      if (warning != nullptr && !w.empty()) *warning = warning->empty() ? w : *warning + "; " + w;
    }
    if (r.json) return j.dump(2) + "\n";
  }
  std::string out = fig9_text(r, m) + exact_modes_text(r.params, m) + shapes_text(m);
  if (!m.all_finite) out += "  status: " + m.status + ": " + m.message + "\n";
  return out;
}

}  // namespace flaplag::cli
