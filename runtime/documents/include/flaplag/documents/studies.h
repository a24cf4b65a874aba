// flaplag documents — the documents of a study and a map: the header, what was run (as plain
// data from the front end), the rows or grids, the status; JSON and text.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/documents/json_fields.h"
#include "flaplag/study.h"

namespace flaplag::documents {

// What a study document says about its run.
struct StudyRun {
  std::string vary;  // the field varied ("omega_lag")
  double mu_max = 0.0, scan_step = 0.0;
  std::optional<double> damping_criterion;  // each row's damping crossings when set
  bool trimmed = false;                     // each row's trim at its mu_c
};

// What a map document says about its run: the axes (fields and the values computed) and, when
// neither axis is mu, the mu of every cell.
struct MapRun {
  std::string x_name, y_name;
  std::vector<double> x_values, y_values;
  double mu = 0.0;
};

// `message` shows the library's messages in the front end's vocabulary.
Json study_json(const StudyRun& r, const Analysis& base, const StudyResult& s,
                const MessageText& message);
std::string study_text(const StudyRun& r, const Analysis& base, const StudyResult& s,
                       const MessageText& message);
Json map_json(const MapRun& r, const Analysis& base, const MapResult& m,
              const MessageText& message);
std::string map_text(const MapRun& r, const Analysis& base, const MapResult& m,
                     const MessageText& message);

}  // namespace flaplag::documents
