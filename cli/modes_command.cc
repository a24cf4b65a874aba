// `flaplag modes`: the Fig 9 relation between first rotating and nonrotating frequencies, and
// the exact rotating modes of one blade (frequencies, stiffnesses, shapes, Rayleigh checks): the
// uniform blade, or a blade table's (its stiffness columns scaled, rotating_modes.h).
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "commands_internal.h"
#include "flaplag/blade/imported_modes.h"
#include "flaplag/blade/rotating_modes.h"
#include "flaplag/documents/output.h"
#include "flaplag/documents/plot.h"
#include "flaplag/rotor/parameter_table.h"
#include "options.h"

namespace flaplag::cli {

using documents::render_plot;
using documents::result_plot_script;

using documents::num;
using documents::OutputTarget;
using documents::TextTable;

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
  // The directions (model_api.h) with their first rotating frequencies as given.
  std::vector<model::DirectionBlock> directions;
  std::vector<double> given;
  // Per direction, in the order of `directions`: the Fig 9 relation and the Rayleigh quotients
  // of the shapes.
  std::vector<std::vector<FrequencyPair>> fig9;
  std::vector<std::vector<double>> rayleigh;
  ExactModes ex;
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
  bool all_finite = std::isfinite(m.opt.e1_over_l);
  auto check = [&](double x) { all_finite = all_finite && std::isfinite(x); };
  for (std::size_t i = 0; i < m.directions.size(); ++i) {
    const model::Direction d = m.directions[i].direction;
    const DirectionModes& modes = m.ex.modes[d];
    check(m.ex[d].omega_nonrotating);
    check(modes.stiffness);
    for (const FrequencyPair& f : m.fig9[i]) {
      check(f.nonrotating);
      check(f.rotating);
    }
    for (const std::vector<double>* v : {&m.ex[d].omega_all, &modes.omega, &m.rayleigh[i]})
      for (double x : *v) check(x);
    for (const auto& shape : modes.shapes)
      for (int der = 0; der <= 3; ++der)
        for (double x : m.x0) check(shape->value(der, x));
  }
  return all_finite;
}

ModesShown compute_modes(const Request& r) {
  const RotorParameters& p = r.params;
  ModesShown m;
  m.table = p.blade != nullptr;
  m.opt = mode_options(r);
  m.directions = model::direction_blocks(m.opt.flap_modes, m.opt.lag_modes);
  m.given = {p.omega_flap, p.omega_lag};  // the paper's parameters, in direction order
  // fig9_table spaces n points evenly on [lo, hi]: hi is the last multiple of STEP in the range
  // (the command line guarantees at least two points).
  const double hi9 = r.fig9_from + (r.fig9_points - 1) * r.fig9_step;
  for (const model::DirectionBlock& b : m.directions)
    m.fig9.push_back(fig9_table(b.direction, r.fig9_from, hi9, r.fig9_points, m.opt));

  m.ex = exact_rotating_modes(p.omega_flap, p.omega_lag, m.opt);
  // The Rayleigh quotients with the blade's own distributions (the table's, with its tip mass).
  auto rayleigh_of = [&](BendingDirection dir, const ModeShape& shape, double k) {
    return m.table ? rayleigh_frequency(dir, shape, k, m.opt.e1_over_l, *p.blade)
                   : rayleigh_frequency(dir, shape, k, m.opt.e1_over_l, m.opt.mbar);
  };
  for (const model::DirectionBlock& b : m.directions) {
    const DirectionModes& modes = m.ex.modes[b.direction];
    std::vector<double> rayleigh;
    for (const auto& s : modes.shapes)
      rayleigh.push_back(rayleigh_of(b.direction, *s, modes.stiffness));
    m.rayleigh.push_back(rayleigh);
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

// Direction i's frequencies, stiffness and mode shapes (values and derivatives 1..3 at x0).
Json direction_json(const ModesShown& m, std::size_t i) {
  const model::DirectionBlock& b = m.directions[i];
  const DirectionModes& dm = m.ex.modes[b.direction];
  const std::vector<std::shared_ptr<const ModeShape>>& shapes = dm.shapes;
  const std::vector<double>& returned = dm.omega;
  const std::vector<double>& rayleigh = m.rayleigh[i];
  Json d;
  d["rotating_first"] = m.given[i];
  d["nonrotating_first"] = jnum(m.ex[b.direction].omega_nonrotating);
  d[m.table ? "stiffness_scale" : "stiffness"] = jnum(dm.stiffness);
  d["rotating_all"] = jnums(m.ex[b.direction].omega_all);
  Json modes = Json::array();
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    Json mode;
    mode["name"] = index_name(b.shape, k);
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
  // The rows of the first direction's relation, each with every direction's rotating frequency
  // ("flap_rotating", "lag_rotating").
  Json fig9 = Json::array();
  for (std::size_t i = 0; i < m.fig9.front().size(); ++i) {
    Json row{{"nonrotating", jnum(m.fig9.front()[i].nonrotating)}};
    for (std::size_t d = 0; d < m.directions.size(); ++d) {
      row[std::string(m.directions[d].name) + "_rotating"] =
          i < m.fig9[d].size() ? jnum(m.fig9[d][i].rotating) : Json();
    }
    fig9.push_back(row);
  }
  j["fig9"] = fig9;
  j["x0"] = m.x0;
  for (std::size_t d = 0; d < m.directions.size(); ++d)
    j[m.directions[d].name] = direction_json(m, d);
  j["status"] = m.status;
  j["message"] = m.message;
  return j;
}

std::string fig9_text(const Request& r, const ModesShown& m) {
  std::string out = "Fig 9: first rotating vs first nonrotating frequency, by Omega\n(" +
                    std::to_string(galerkin_basis(r.params)) +
                    " cantilever functions per direction, e1/l = " + cell(m.opt.e1_over_l) + ")\n";
  if (m.table) out += "blade table " + cmd::blade_table_text(*r.params.blade, r.params) + "\n";
  std::vector<std::string> header{"nonrotating"};
  for (const model::DirectionBlock& b : m.directions)
    header.push_back(b.name + std::string(" rotating"));
  TextTable t9(header);
  for (std::size_t i = 0; i < m.fig9.front().size(); ++i) {
    std::vector<std::string> row{cell(m.fig9.front()[i].nonrotating)};
    for (const std::vector<FrequencyPair>& f : m.fig9)
      row.push_back(i < f.size() ? cell(f[i].rotating) : "-");
    t9.add_row(row);
  }
  return out + t9.render() + "\n";
}

// One row of the frequency table: a heading and a cell per direction (i: the direction's index
// in m.directions), "-" where value(i) gives none.
template <class Value>
std::vector<std::string> direction_row(const ModesShown& m, const std::string& heading,
                                       const Value& value) {
  std::vector<std::string> row{heading};
  for (std::size_t i = 0; i < m.directions.size(); ++i) {
    const std::optional<double> v = value(i);
    row.push_back(v ? cell(*v) : "-");
  }
  return row;
}

// The k-th entry of list(i) of each direction, or none past its end.
template <class List>
auto entry(std::size_t k, const List& list) {
  return [k, &list](std::size_t i) -> std::optional<double> {
    const std::vector<double>& v = list(i);
    return k < v.size() ? std::optional<double>(v[k]) : std::nullopt;
  };
}

// Frequencies, stiffnesses and the Rayleigh check of each shape.
std::string exact_modes_text(const RotorParameters& p, const ModesShown& m) {
  const ExactModes& ex = m.ex;
  std::string out = "Exact rotating modes of the blade";
  if (m.opt.paper_1974_shapes)
    out += "\n(1974 sign convention: the shapes are NOT modes of the blade)";
  out += "\n";
  std::vector<std::string> header{""};
  for (const model::DirectionBlock& b : m.directions) header.push_back(b.name);
  TextTable tb(header);
  auto dir = [&](std::size_t i) { return m.directions[i].direction; };
  tb.add_row(direction_row(m, "first rotating frequency",
                           [&](std::size_t i) { return std::optional<double>(m.given[i]); }));
  tb.add_row(direction_row(m, "first nonrotating frequency", [&](std::size_t i) {
    return std::optional<double>(ex[dir(i)].omega_nonrotating);
  }));
  tb.add_row(direction_row(
      m, m.table ? "stiffness scale s of the table's EI" : "stiffness EI/(Omega^2 l I_b)",
      [&](std::size_t i) { return std::optional<double>(ex.modes[dir(i)].stiffness); }));
  auto all = [&](std::size_t i) -> const std::vector<double>& { return ex[dir(i)].omega_all; };
  std::size_t n_all = 0;
  for (std::size_t i = 0; i < m.directions.size(); ++i) n_all = std::max(n_all, all(i).size());
  for (std::size_t k = 0; k < n_all; ++k)
    tb.add_row(direction_row(m, "rotating frequency " + std::to_string(k + 1), entry(k, all)));
  // The Rayleigh quotient of a true mode is its frequency; a wrong shape shows up here.
  auto rayleigh = [&](std::size_t i) -> const std::vector<double>& { return m.rayleigh[i]; };
  std::size_t n_shapes = 0;
  for (const std::vector<double>& v : m.rayleigh) n_shapes = std::max(n_shapes, v.size());
  for (std::size_t k = 0; k < n_shapes; ++k) {
    tb.add_row(direction_row(m, "Rayleigh frequency of shape " + std::to_string(k + 1),
                             entry(k, rayleigh)));
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
  for (const model::DirectionBlock& b : m.directions)
    for (int k = 0; k < ms[b.direction].count(); ++k)
      header.push_back(index_name(b.shape, static_cast<std::size_t>(k)));
  TextTable ts(header);
  for (double x : m.x0) {
    std::vector<std::string> row{cell(x)};
    for (const model::DirectionBlock& b : m.directions)
      for (const auto& s : ms.shapes(b.direction)) row.push_back(cell(s->value(0, x)));
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
