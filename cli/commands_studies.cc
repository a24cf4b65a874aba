// flaplag CLI — runs over a grid: `flaplag study` (mu_c versus one parameter) and `flaplag map`
// (the largest zeta over two), with --shard parts, progress and cancellation.
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "commands_internal.h"
#include "flaplag/core/format.h"
#include "flaplag/documents/output.h"
#include "flaplag/documents/studies.h"
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

// What the study and map documents say about their run, from the request.
documents::StudyRun study_run(const Request& r) {
  return {r.vary, r.critical.mu_max, r.critical.scan_step, r.damping_criterion, trimmed(r)};
}

documents::MapRun map_run(const Request& r) {
  return {r.x_name, r.y_name, r.x_values, r.y_values, r.mu};
}

}  // namespace

Output study(const Request& request, std::string& warning, RunControl* control) {
  const Request r = shard_request(request);  // --shard: this part's values only
  const Analysis base(r.params, r.transition,
                      fixed_controls(r));  // the header, and the base parameters checked
  const StudyResult s = run_study_part(r, control);
  std::optional<Json> j = result_document(
      r, [&] { return documents::study_json(study_run(r), base, s, in_vocabulary(r)); }, &warning);
  if (r.json) return std::move(*j);
  return text_output(r, documents::study_text(study_run(r), base, s, in_vocabulary(r)),
                     std::move(j));
}

Output map(const Request& request, std::string& warning, RunControl* control) {
  Request r = shard_request(request);  // --shard: this part's lines only
  const Analysis base(r.params, r.transition, fixed_controls(r));
  const MapResult m = run_map_part(r, control);
  std::optional<Json> j = result_document(
      r, [&] { return documents::map_json(map_run(r), base, m, in_vocabulary(r)); }, &warning);
  if (r.json) return std::move(*j);
  return text_output(r, documents::map_text(map_run(r), base, m, in_vocabulary(r)), std::move(j));
}

}  // namespace flaplag::cli::cmd
