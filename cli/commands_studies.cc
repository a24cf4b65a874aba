// flaplag CLI — runs over a grid: `flaplag study` (mu_c versus one parameter) and `flaplag map`
// (the largest zeta over two), with --shard parts, progress and cancellation.
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "commands_internal.h"
#include "flaplag/core/format.h"
#include "flaplag/documents/output.h"
#include "shard.h"

namespace flaplag::cli::cmd {

namespace {

// A run stopped by RunControl::cancel: what the output holds.
void note_cancelled(RunControl* control, std::size_t done, std::size_t all,
                    const std::string& lines) {
  if (control == nullptr) return;
  control->cancelled = true;
  control->message = "interrupted: " + std::to_string(done) + " of " + std::to_string(all) + " " +
                     lines + " finished; the output holds those";
}

// The study's rows: run_study on this part's values (none: an empty part of a job with more
// parts than values).
StudyResult run_study_part(const Request& r, RunControl* control) {
  StudyOptions so;
  so.parameter = r.vary;
  so.values = r.vary_values;
  so.critical = r.critical;
  so.threads = r.threads;
  so.trim = r.trim;
  so.linearization = r.linearization;
  so.inflow = r.inflow;
  so.damping_criterion = r.damping_criterion;
  StudyResult s;
  if (!so.values.empty()) {
    s = run_study(r.params, r.transition, so, control ? control->cancel : nullptr,
                  control ? control->progress : ProgressFunction{});
  }
  if (s.cancelled)
    note_cancelled(control, s.rows_done, so.values.size(), "values (" + word(r.vary) + ")");
  return s;
}

Json study_json(const Request& r, const Analysis& base, const StudyResult& s) {
  Json j = header_json("study", base);
  j["vary"] = word(r.vary);
  j["mu_max"] = r.critical.mu_max;
  j["scan_step"] = r.critical.scan_step;
  if (r.damping_criterion) j["damping_criterion"] = jnum(*r.damping_criterion);
  // A row by StudyRow's table; a trimmed study reports each row's trim at its mu_c (the trim
  // the row's search made there, whose problems are in the row's status), null without one.
  std::vector<std::string> present;
  if (trimmed(r)) present.push_back("trim");
  if (r.damping_criterion) present.push_back("damping_crossings");
  Json rows = Json::array();
  for (const StudyRow& row : s.rows) rows.push_back(to_json(row, in_vocabulary(r), present));
  j["rows"] = rows;
  return status_json(j, s.status, vocab(r, s.message));
}

// One line of the study's table (the trimmed columns: the trim at mu_c [rad; lambda of eq
// 2.25]).
std::vector<std::string> study_row_cells(const Request& r, const StudyRow& row) {
  const CriticalResult& c = row.critical;
  std::string ivs;
  for (const InstabilityInterval& i : c.intervals)
    ivs += (ivs.empty() ? "" : " ") + std::string("(") + short_text(i.onset) + ", " +
           (i.end ? short_text(*i.end) : std::string("mu-max")) + ")";
  std::vector<std::string> cells = {
      num(row.value),
      c.mu_c ? short_text(*c.mu_c) : (c.hover_unstable ? "hover" : "-"),
      c.mu_c ? c.mode : "-",
      c.mu_c ? short_text(c.omega) : "-",
      c.mu_c ? kind_name(c.kind) : "-",
      ivs.empty() ? "-" : ivs};
  if (trimmed(r)) {
    const std::optional<TrimResult>& x = row.trim;
    for (double v :
         {x ? x->theta0 : 0.0, x ? x->theta1c : 0.0, x ? x->theta1s : 0.0, x ? x->inflow : 0.0})
      cells.push_back(x ? short_text(v) : "-");
  }
  if (r.damping_criterion) {
    // "lag 0.603" per mode that crosses, its status when not crossed cleanly.
    std::string below;
    for (const DampingCrossing& d : row.damping_crossings) {
      if (d.status == CrossingStatus::NotCrossed) continue;
      below += (below.empty() ? "" : ", ") + d.mode + " " + (d.mu ? short_text(*d.mu) : "-");
      if (d.status != CrossingStatus::Crossed)
        below += std::string(" (") + enum_name(d.status) + ")";
    }
    cells.push_back(below.empty() ? "-" : below);
  }
  cells.push_back(status_name(c.status));
  return cells;
}

std::string study_text(const Request& r, const Analysis& base, const StudyResult& s) {
  std::string out = header_text(base) + "\n";
  out += "mu_c and instability intervals versus " + word(r.vary) + " (mu up to " +
         num(r.critical.mu_max) + ")\n";
  std::vector<std::string> head = {word(r.vary), "mu_c", "mode",
                                   "omega",      "kind", "unstable for mu in"};
  if (trimmed(r)) head.insert(head.end(), {"theta0", "theta1c", "theta1s", "lambda"});
  if (r.damping_criterion)
    head.push_back("damping < " + num(100.0 * *r.damping_criterion) + " % from mu");
  head.push_back("status");
  TextTable t(head);
  t.left_align(head.size() - 1);
  t.left_align(5);
  for (const StudyRow& row : s.rows) t.add_row(study_row_cells(r, row));
  out += t.render();
  for (const StudyRow& row : s.rows)
    if (row.critical.status != Status::Ok)
      out += "  " + word(r.vary) + " = " + num(row.value) + ": " +
             status_name(row.critical.status) + ": " + vocab(r, row.critical.message) + "\n";
  return out;
}

// The map's cells: run_map on this part's lines (none: an empty part).  A cancelled run keeps
// the lines finished, and r's values on the cut axis are cut to them.
MapResult run_map_part(Request& r, RunControl* control) {
  MapOptions mo;
  mo.x = {r.x_name, r.x_values};
  mo.y = {r.y_name, r.y_values};
  mo.mu = r.mu;
  mo.scan_step = r.scan_step;
  mo.threads = r.threads;
  mo.trim = r.trim;
  mo.linearization = r.linearization;
  mo.inflow = r.inflow;
  MapResult m;
  m.cells.assign(r.y_values.size(), {});
  if (!r.x_values.empty() && !r.y_values.empty()) {
    m = run_map(r.params, r.transition, mo, control ? control->cancel : nullptr,
                control ? control->progress : ProgressFunction{});
  }
  if (m.cancelled) {
    // The output is the map of the lines finished: rows, or columns when y is mu.
    const bool columns = r.y_name == "mu";
    note_cancelled(control, m.lines_done, columns ? r.x_values.size() : r.y_values.size(),
                   (columns ? "columns (" + word(r.x_name) : "rows (" + word(r.y_name)) + ")");
    if (columns) {
      r.x_values.resize(m.lines_done);
      for (auto& row : m.cells) row.resize(m.lines_done);
    } else {
      r.y_values.resize(m.lines_done);
      m.cells.resize(m.lines_done);
    }
  }
  return m;
}

Json map_json(const Request& r, const Analysis& base, const MapResult& m) {
  Json j = header_json("map", base);
  j["x"] = Json{{"name", word(r.x_name)}, {"values", r.x_values}};
  j["y"] = Json{{"name", word(r.y_name)}, {"values", r.y_values}};
  if (r.x_name != "mu" && r.y_name != "mu") j["mu"] = r.mu;
  // One grid per row of kMapGridRows, written by the row's type; null where the cell's
  // exponent is unknown (no max_zeta).
  const MessageText message = in_vocabulary(r);
  for (const char* key : kMapGridRows) {
    visit_row<MapCell>(key, [&](const auto& field) {
      Json grid = Json::array();
      for (const auto& row : m.cells) {
        Json line = Json::array();
        for (const MapCell& cell : row)
          line.push_back(cell.max_zeta
                             ? documents::json_detail::value(field.get(cell), field.flags, message)
                             : Json(nullptr));
        grid.push_back(line);
      }
      j[key] = grid;
    });
  }
  return status_json(j, m.status, vocab(r, m.message));
}

std::string map_text(const Request& r, const Analysis& base, const MapResult& m) {
  std::string out = header_text(base) + "\n";
  out += "Largest zeta (per rev) over " + word(r.y_name) + " (rows) x " + word(r.x_name) +
         " (columns); * marks an unstable point\n";
  std::vector<std::string> header{word(r.y_name) + " \\ " + word(r.x_name)};
  for (double x : r.x_values) header.push_back(short_text(x));
  TextTable t(header);
  for (std::size_t i = 0; i < m.cells.size(); ++i) {
    std::vector<std::string> row{short_text(r.y_values[i])};
    for (const MapCell& c : m.cells[i])
      row.push_back(c.max_zeta ? short_text(*c.max_zeta) + (*c.max_zeta > 0 ? "*" : " ") : "-");
    t.add_row(row);
  }
  return out + t.render() + status_text(m.status, vocab(r, m.message));
}

}  // namespace

Output study(const Request& request, std::string& warning, RunControl* control) {
  const Request r = shard_request(request);  // --shard: this part's values only
  const Analysis base(r.params, r.transition,
                      fixed_controls(r));  // the header, and the base parameters checked
  const StudyResult s = run_study_part(r, control);
  std::optional<Json> j = result_document(
      r, [&] { return study_json(r, base, s); }, &warning);
  if (r.json) return std::move(*j);
  return text_output(r, study_text(r, base, s), std::move(j));
}

Output map(const Request& request, std::string& warning, RunControl* control) {
  Request r = shard_request(request);  // --shard: this part's lines only
  const Analysis base(r.params, r.transition, fixed_controls(r));
  const MapResult m = run_map_part(r, control);
  std::optional<Json> j = result_document(
      r, [&] { return map_json(r, base, m); }, &warning);
  if (r.json) return std::move(*j);
  return text_output(r, map_text(r, base, m), std::move(j));
}

}  // namespace flaplag::cli::cmd
