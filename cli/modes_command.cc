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

}  // namespace

std::string run_modes(const Request& r, std::string* warning) {
  const RotorParameters& p = r.params;
  // The tables below are computed from the blade (uniform or a table), not read from a mode
  // file: imported shapes would be shown as modes they are not.
  if (p.mode_shapes) {
    throw InvalidInput("mode_shapes", p.mode_shapes->source,
                       "`flaplag modes` computes the exact modes of the blade (uniform or "
                       "--blade-table); imported shapes are checked with every analysis result "
                       "(its notes say when they are not mass-orthogonal)");
  }
  // With a blade table the stiffnesses are the scales of its stiffness columns.
  const bool table = p.blade != nullptr;
  // --export-shapes: the path checked before anything is computed, written after.
  const OutputTarget shapes_file(r.export_shapes, "export_shapes");
  ExactModeOptions opt;
  opt.n_basis = galerkin_basis(r.params);
  opt.flap_modes = r.flap_modes;
  opt.lag_modes = r.lag_modes;
  opt.e1_over_l = p.root_offset / p.length_ratio;
  opt.paper_1974_shapes = p.paper_1974_shapes;
  opt.blade = p.blade;

  // fig9_table spaces n points evenly on [lo, hi]: hi is the last multiple of STEP in the range
  // (the command line guarantees at least two points).
  const double hi9 = r.fig9_from + (r.fig9_points - 1) * r.fig9_step;
  const auto flap9 = fig9_table(BendingDirection::Flap, r.fig9_from, hi9, r.fig9_points, opt);
  const auto lag9 = fig9_table(BendingDirection::Lag, r.fig9_from, hi9, r.fig9_points, opt);

  const ExactModes ex = exact_rotating_modes(p.omega_flap, p.omega_lag, opt);
  const ModeSet& ms = ex.modes;
  // The Rayleigh quotients with the blade's own distributions (the table's, with its tip mass).
  auto rayleigh_of = [&](BendingDirection dir, const ModeShape& shape, double k) {
    return table ? rayleigh_frequency(dir, shape, k, opt.e1_over_l, *p.blade)
                 : rayleigh_frequency(dir, shape, k, opt.e1_over_l, opt.mbar);
  };
  std::vector<double> rayleigh_flap, rayleigh_lag;
  for (const auto& s : ms.flap) {
    rayleigh_flap.push_back(rayleigh_of(BendingDirection::Flap, *s, ms.stiffness_flap));
  }
  for (const auto& s : ms.lag) {
    rayleigh_lag.push_back(rayleigh_of(BendingDirection::Lag, *s, ms.stiffness_lag));
  }
  std::vector<double> x0(static_cast<std::size_t>(r.shape_points));
  for (std::size_t i = 0; i < x0.size(); ++i) {
    x0[i] = static_cast<double>(i) / static_cast<double>(x0.size() - 1);
  }

  // Every number shown, checked once.
  bool all_finite = std::isfinite(opt.e1_over_l) && std::isfinite(ex.omega_flap_nonrotating) &&
                    std::isfinite(ex.omega_lag_nonrotating) && std::isfinite(ms.stiffness_flap) &&
                    std::isfinite(ms.stiffness_lag);
  for (const auto& t : {&flap9, &lag9}) {
    for (const FrequencyPair& f : *t) {
      all_finite = all_finite && std::isfinite(f.nonrotating) && std::isfinite(f.rotating);
    }
  }
  const std::vector<const std::vector<double>*> lists = {&ex.omega_flap_all, &ex.omega_lag_all,
                                                         &ms.omega_flap,     &ms.omega_lag,
                                                         &rayleigh_flap,     &rayleigh_lag};
  for (const std::vector<double>* v : lists) {
    for (double x : *v) all_finite = all_finite && std::isfinite(x);
  }
  for (const auto& shapes : {&ms.flap, &ms.lag}) {
    for (const auto& shape : *shapes) {
      for (int der = 0; der <= 3; ++der) {
        for (double x : x0) all_finite = all_finite && std::isfinite(shape->value(der, x));
      }
    }
  }
  const std::string status = all_finite ? "ok" : "failed";
  const std::string message =
      all_finite ? "" : "non-finite frequencies, stiffnesses or shape values (not shown)";
  // The mode file (imported_modes.h) of the shapes shown; none of a failed solution.
  if (!r.export_shapes.empty()) {
    if (all_finite) {
      shapes_file.write(mode_table_text(ms, kExportedModeStations));
    } else if (warning != nullptr) {
      *warning = "--export-shapes = " + r.export_shapes + " not written: " + message;
    }
  }

  if (r.json || !r.plot.empty()) {
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
    if (table) j["blade_table"] = cmd::blade_table_json(*p.blade);
    j["e1_over_l"] = jnum(opt.e1_over_l);
    Json fig9 = Json::array();
    for (std::size_t i = 0; i < flap9.size(); ++i) {
      fig9.push_back(Json{{"nonrotating", jnum(flap9[i].nonrotating)},
                          {"flap_rotating", jnum(flap9[i].rotating)},
                          {"lag_rotating", i < lag9.size() ? jnum(lag9[i].rotating) : Json()}});
    }
    j["fig9"] = fig9;
    auto direction = [&](const char* base, double given, double nonrot, double k,
                         const std::vector<double>& all, const std::vector<double>& returned,
                         const std::vector<double>& rayleigh,
                         const std::vector<std::shared_ptr<const ModeShape>>& shapes) {
      Json d;
      d["rotating_first"] = given;
      d["nonrotating_first"] = jnum(nonrot);
      d[table ? "stiffness_scale" : "stiffness"] = jnum(k);
      d["rotating_all"] = jnums(all);
      Json modes = Json::array();
      for (std::size_t m = 0; m < shapes.size(); ++m) {
        Json mode;
        mode["name"] = index_name(base, m);
        mode["omega"] = m < returned.size() ? jnum(returned[m]) : Json();
        mode["rayleigh_omega"] = jnum(rayleigh[m]);
        for (int der = 0; der <= 3; ++der) {
          Json col = Json::array();
          for (double x : x0) col.push_back(jnum(shapes[m]->value(der, x)));
          mode[der == 0 ? "value" : "d" + std::to_string(der)] = col;
        }
        modes.push_back(mode);
      }
      d["modes"] = modes;
      return d;
    };
    j["x0"] = x0;
    j["flap"] = direction("eta", p.omega_flap, ex.omega_flap_nonrotating, ms.stiffness_flap,
                          ex.omega_flap_all, ms.omega_flap, rayleigh_flap, ms.flap);
    j["lag"] = direction("gamma", p.omega_lag, ex.omega_lag_nonrotating, ms.stiffness_lag,
                         ex.omega_lag_all, ms.omega_lag, rayleigh_lag, ms.lag);
    j["status"] = status;
    j["message"] = message;
    // The picture of the result, as `flaplag plot` draws it (plot.h).
    if (!r.plot.empty()) {
      const std::string w = render_plot(*result_plot_script(j, r.plot), r.plot);
      if (warning != nullptr && !w.empty()) *warning = warning->empty() ? w : *warning + "; " + w;
    }
    if (r.json) return j.dump(2) + "\n";
  }

  std::string out = "Fig 9: first rotating vs first nonrotating frequency, by Omega\n(" +
                    std::to_string(galerkin_basis(r.params)) +
                    " cantilever functions per direction, e1/l = " + cell(opt.e1_over_l) + ")\n";
  if (table) out += "blade table " + cmd::blade_table_text(*p.blade, p) + "\n";
  TextTable t9({"nonrotating", "flap rotating", "lag rotating"});
  for (std::size_t i = 0; i < flap9.size(); ++i) {
    t9.add_row({cell(flap9[i].nonrotating), cell(flap9[i].rotating),
                i < lag9.size() ? cell(lag9[i].rotating) : "-"});
  }
  out += t9.render() + "\n";

  out += "Exact rotating modes of the blade";
  if (opt.paper_1974_shapes)
    out += "\n(1974 sign convention: the shapes are NOT modes of the blade)";
  out += "\n";
  TextTable tb({"", "flap", "lag"});
  tb.add_row({"first rotating frequency", cell(p.omega_flap), cell(p.omega_lag)});
  tb.add_row({"first nonrotating frequency", cell(ex.omega_flap_nonrotating),
              cell(ex.omega_lag_nonrotating)});
  tb.add_row({table ? "stiffness scale s of the table's EI" : "stiffness EI/(Omega^2 l I_b)",
              cell(ms.stiffness_flap), cell(ms.stiffness_lag)});
  const std::size_t n_all = std::max(ex.omega_flap_all.size(), ex.omega_lag_all.size());
  for (std::size_t m = 0; m < n_all; ++m) {
    tb.add_row({"rotating frequency " + std::to_string(m + 1),
                m < ex.omega_flap_all.size() ? cell(ex.omega_flap_all[m]) : "-",
                m < ex.omega_lag_all.size() ? cell(ex.omega_lag_all[m]) : "-"});
  }
  // The Rayleigh quotient of a true mode is its frequency; a wrong shape shows up here.
  const std::size_t n_shapes = std::max(rayleigh_flap.size(), rayleigh_lag.size());
  for (std::size_t m = 0; m < n_shapes; ++m) {
    tb.add_row({"Rayleigh frequency of shape " + std::to_string(m + 1),
                m < rayleigh_flap.size() ? cell(rayleigh_flap[m]) : "-",
                m < rayleigh_lag.size() ? cell(rayleigh_lag[m]) : "-"});
  }
  out += tb.render();
  if (table) {
    out += p.blade->origin.dimensional
               ? "(EI/(Omega^2 l I_b) = s x the table's EI column; a dimensional table's columns "
                 "are absolute: s = 1)\n"
               : "(EI/(Omega^2 l I_b) = s x the table's EI column, which is relative to its root "
                 "value: s is EI/(Omega^2 l I_b) at the root)\n";
  }
  out += "\nMode shapes (tip value 1)\n";
  std::vector<std::string> header{"x0"};
  for (std::size_t m = 0; m < ms.flap.size(); ++m) header.push_back(index_name("eta", m));
  for (std::size_t m = 0; m < ms.lag.size(); ++m) header.push_back(index_name("gamma", m));
  TextTable ts(header);
  for (double x : x0) {
    std::vector<std::string> row{cell(x)};
    for (const auto& s : ms.flap) row.push_back(cell(s->value(0, x)));
    for (const auto& s : ms.lag) row.push_back(cell(s->value(0, x)));
    ts.add_row(row);
  }
  out += ts.render();
  if (!all_finite) out += "  status: " + status + ": " + message + "\n";
  return out;
}

}  // namespace flaplag::cli
