// flaplag documents — the one-page HTML report of a result, for a design review.
//
// A report is made from a result's JSON document (what --json writes, or a file of it) and
// nothing else, so that `flaplag report RESULT.json` shows exactly what the run that wrote it
// found.  The page is self-contained: inline CSS and inline SVG pictures (drawn by gnuplot
// through plot.h's builders, the pictures of --plot), no script, no network; a
// Content-Security-Policy forbids both, so that nothing a hostile result file holds can run or
// reach out.  Every text of the document is HTML-escaped; numbers are shown to six significant
// digits (the JSON has them in full).
//
// Sections: the outcome (the worst status anywhere in the document, with its message), the key
// results, the model and its assumptions (ordering spec, modes, reversed flow, linearization,
// trim, Floquet method), the inputs (each rotor parameter with the paper's symbol, units and
// meaning), the convergence evidence (every error estimate and residual the result holds),
// the pictures, every warning in plain words, the result's tables, and the provenance (flaplag
// version and commit, and the command that reproduces it).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "flaplag/documents/names.h"

namespace flaplag::documents {

struct ReportSource {
  std::string title;  // what the report is of: "case file examples/fig03.toml", "result a.json"
  std::string input;  // the file as typed, which refusals name ("" for a run's own result)
  std::vector<std::string> warnings;  // what the run said on stderr, one line each
  bool with_date = true;              // the UTC time the page was made
  // The front end's spelling of its options named on the page and in refusals (plot, json).
  Spelling option;
  // The spelling of a key of the result's case ("omega-lag") in the command line that
  // reproduces it (the case is a flaplag command line); none: no such line on the page.
  Spelling case_option;
};

// The HTML page.  Throws InvalidInput("argument", source, reason) for a document that is not a
// flaplag result (as `flaplag plot` refuses one); a picture that gnuplot cannot draw is left
// out with a warning on the page (and in *warning, when given).
std::string html_report(const nlohmann::ordered_json& result, const ReportSource& source,
                        std::string* warning = nullptr);

// The page of a result file: `text` as read from `path` (as typed; read_file.h bounds the
// reading), spelled as html_report's source.option and source.case_option.  Throws
// InvalidInput("argument", path, reason) for text that is not a flaplag result.
std::string html_report_of_text(const std::string& path, const std::string& text,
                                const Spelling& option, const Spelling& case_option,
                                std::string* warning = nullptr);

// True when `text` is JSON rather than TOML (its first character other than a blank is '{').
bool is_json_text(const std::string& text);

// True when `path` names a page: it ends in .html or .htm.
bool is_report_path(const std::string& path);

}  // namespace flaplag::documents
