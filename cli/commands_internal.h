// flaplag CLI — what the files of the subcommands share (commands_*.cc); not part of the CLI's
// interface (commands.h).  Each command returns its Output: the text to write, or the JSON
// document that run_command completes (version, commit, case, shard) and writes once.
#pragma once

#include <complex>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "command_line.h"
#include "commands.h"
#include "flaplag/analysis.h"
#include "flaplag/documents/header.h"
#include "flaplag/documents/numbers.h"
#include "flaplag/documents/output.h"
#include "flaplag/documents/plot.h"
#include "flaplag/documents/table_fields.h"
#include "flaplag/study.h"
#include "flaplag/trim.h"

namespace flaplag::cli::cmd {

using documents::Json;
// The printers and writers of the documents layer (documents/numbers.h, output.h,
// json_fields.h, table_fields.h, header.h).
using documents::blade_table_json;
using documents::blade_table_text;
using documents::cell;
using documents::header_json;
using documents::header_text;
using documents::inflow_at;
using documents::inflow_json;
using documents::model_json;
using documents::render_plot;
using documents::result_plot_script;
using documents::status_json;
using documents::status_text;
using documents::SweepQuantity;
using documents::warnings_text;

using documents::CellStyle;
using documents::Column;
using documents::complex_json;
using documents::complex_text;
using documents::csv_field;
using documents::csv_fields;
using documents::described_cells;
using documents::described_heading;
using documents::described_table;
using documents::exact_num;
using documents::exact_zeta_text;
using documents::finite;
using documents::jnum;
using documents::KeyValues;
using documents::locked_text;
using documents::MessageText;
using documents::num;
using documents::optional_json;
using documents::optional_text;
using documents::ratio_cell;
using documents::ratio_json;
using documents::rows_json;
using documents::stable_json;
using documents::stable_text;
using documents::TextTable;
using documents::to_json;
using documents::zeta_cell;
using documents::zeta_json;
using documents::zeta_ok;
using documents::zeta_text;

// What a command produced: a JSON document (json set; the command's `return j;`) or text (the
// command's `return out;`), taken as they are.  A text output carries the JSON document along
// when a --report needs it (text_output).
struct Output {
  Output(std::string t) : text(std::move(t)) {}
  Output(Json j) : json(std::move(j)) {}
  Output(std::string t, std::optional<Json> j) : json(std::move(j)), text(std::move(t)) {}
  std::optional<Json> json;
  std::string text;
};

// ---- the parts every output shares (commands_common.cc) ----------------------------------------

// A runtime message in this command line's vocabulary.
std::string vocab(const Request& r, const std::string& message);
// Messages in the request's vocabulary (vocab()), for the documents' writers; r must outlive
// the function.
inline MessageText in_vocabulary(const Request& r) {
  return [&r](const std::string& m) { return vocab(r, m); };
}
// The word of a field in this command line's vocabulary ("omega_lag" -> "omega-lag"): its JSON
// key.
inline std::string word(const std::string& field) { return documents::json_word(field); }
// The operating condition of fixed controls at the request's inflow model (--inflow).
OperatingCondition fixed_controls(const Request& r);
// One "  note: ..." line per note of a result (Outcome::notes), in the request's vocabulary.
std::string notes_text(const Request& r, const std::vector<std::string>& notes);
// A plot, if asked for: "" or a warning line for stderr (the data is written in any case).  The
// picture is `flaplag plot`'s of `result` (the command's --json output: result_plot_script in
// plot.h), with the case's trim, so that --plot and `flaplag plot DATA.json` draw the same.
std::string plot_if_asked(const Request& r, Json result);

// The JSON document of a result, made once and only when something needs it: the output
// (--json), the picture (--plot: drawn here from the document, as `flaplag plot` draws it, when
// `warning` is given; nullptr for a command without a picture, or a result that has none) or
// the report (--report).
template <class MakeJson>
std::optional<Json> result_document(const Request& r, MakeJson&& make_json, std::string* warning) {
  const bool picture = warning != nullptr && !r.plot.empty();
  if (!r.json && !picture && r.report.empty()) return std::nullopt;
  Json j = make_json();
  if (picture) *warning = plot_if_asked(r, j);
  return j;
}

// A text output, with the document along only when a report needs it.
inline Output text_output(const Request& r, std::string text, std::optional<Json> document) {
  if (r.report.empty()) document.reset();
  return Output(std::move(text), std::move(document));
}

// ---- hover and the stability of one rotor (commands_point.cc) ----------------------------------

Json hover_json(const Request& r, const Analysis& an);
std::string hover_text(const Request& r, const Analysis& an);
Output typical(const Request& r, const Analysis& an);
Output point(const Request& r, const Analysis& an);
Output sweep(const Request& r, const Analysis& an, std::string& warning);
Output critical(const Request& r, const Analysis& an);

// ---- trim (commands_trim.cc) --------------------------------------------------------------------

bool trimmed(const Request& r);  // --trim given
Json trim_json(const Request& r, const TrimResult& t);
// The periodic equilibrium q° a result at fixed controls rests on (--periodic-linearization): its
// K and truncation, as a trim's `equilibrium`; null where there is none (beyond the fold).
Json equilibrium_json(const Request& r, const PeriodicEquilibrium& q);
std::string trim_text(const Request& r, const TrimResult& t);
Output trim_command(const Request& r);

// ---- the equations: system and models (commands_model.cc) ---------------------------------------

Output system_snapshot(const Request& r, const Analysis& an);
Output models(const Request& r);

// ---- studies and maps (commands_studies.cc) -----------------------------------------------------

Output study(const Request& request, std::string& warning, RunControl* control);
Output map(const Request& request, std::string& warning, RunControl* control);

// ---- response and simulation (commands_time.cc) -------------------------------------------------

Output response(const Request& r, const Analysis& an, std::string& warning);
Output simulate_command(const Request& r, const Analysis& an, std::string& warning);

// ---- the Campbell diagram (commands_campbell.cc) ----------------------------------------------

Output campbell(const Request& r, const Analysis& an, std::string& warning);

}  // namespace flaplag::cli::cmd
