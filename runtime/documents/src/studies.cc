// flaplag documents — the documents of a study (mu_c against one parameter) and a map (the
// largest zeta over two), as JSON and as text.
#include "flaplag/documents/studies.h"

#include <string>
#include <vector>

#include "flaplag/core/format.h"
#include "flaplag/documents/header.h"
#include "flaplag/documents/json_fields.h"
#include "flaplag/documents/output.h"

namespace flaplag::documents {

namespace {

// One line of the study's table (the trimmed columns: the trim at mu_c [rad; lambda of eq
// 2.25]).
std::vector<std::string> study_row_cells(const StudyRun& r, const StudyRow& row) {
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
  if (r.trimmed) {
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

}  // namespace

Json study_json(const StudyRun& r, const Analysis& base, const StudyResult& s,
                const MessageText& message) {
  Json j = header_json("study", base);
  j["vary"] = json_word(r.vary);
  j["mu_max"] = r.mu_max;
  j["scan_step"] = r.scan_step;
  if (r.damping_criterion) j["damping_criterion"] = jnum(*r.damping_criterion);
  // A row by StudyRow's table; a trimmed study reports each row's trim at its mu_c (the trim
  // the row's search made there, whose problems are in the row's status), null without one.
  std::vector<std::string> present;
  if (r.trimmed) present.push_back("trim");
  if (r.damping_criterion) present.push_back("damping_crossings");
  Json rows = Json::array();
  for (const StudyRow& row : s.rows) rows.push_back(to_json(row, message, present));
  j["rows"] = rows;
  return status_json(j, s.status, message(s.message));
}

std::string study_text(const StudyRun& r, const Analysis& base, const StudyResult& s,
                       const MessageText& message) {
  std::string out = header_text(base) + "\n";
  out += "mu_c and instability intervals versus " + json_word(r.vary) + " (mu up to " +
         num(r.mu_max) + ")\n";
  std::vector<std::string> head = {json_word(r.vary), "mu_c", "mode",
                                   "omega",           "kind", "unstable for mu in"};
  if (r.trimmed) head.insert(head.end(), {"theta0", "theta1c", "theta1s", "lambda"});
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
      out += "  " + json_word(r.vary) + " = " + num(row.value) + ": " +
             status_name(row.critical.status) + ": " + message(row.critical.message) + "\n";
  return out;
}

Json map_json(const MapRun& r, const Analysis& base, const MapResult& m,
              const MessageText& message) {
  Json j = header_json("map", base);
  j["x"] = Json{{"name", json_word(r.x_name)}, {"values", r.x_values}};
  j["y"] = Json{{"name", json_word(r.y_name)}, {"values", r.y_values}};
  if (r.x_name != "mu" && r.y_name != "mu") j["mu"] = r.mu;
  // One grid per row of kMapGridRows, written by the row's type; null where the cell's
  // exponent is unknown (no max_zeta).
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
  return status_json(j, m.status, message(m.message));
}

std::string map_text(const MapRun& r, const Analysis& base, const MapResult& m,
                     const MessageText& message) {
  std::string out = header_text(base) + "\n";
  out += "Largest zeta (per rev) over " + json_word(r.y_name) + " (rows) x " + json_word(r.x_name) +
         " (columns); * marks an unstable point\n";
  std::vector<std::string> header{json_word(r.y_name) + " \\ " + json_word(r.x_name)};
  for (double x : r.x_values) header.push_back(short_text(x));
  TextTable t(header);
  for (std::size_t i = 0; i < m.cells.size(); ++i) {
    std::vector<std::string> row{short_text(r.y_values[i])};
    for (const MapCell& c : m.cells[i])
      row.push_back(c.max_zeta ? short_text(*c.max_zeta) + (*c.max_zeta > 0 ? "*" : " ") : "-");
    t.add_row(row);
  }
  return out + t.render() + status_text(m.status, message(m.message));
}

}  // namespace flaplag::documents
