// flaplag CLI — run_command: the dispatcher from a Request to the command that computes it
// (commands_*.cc, one file per area), and the provenance every JSON output carries.
#include "commands.h"

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "commands_internal.h"
#include "flaplag/analysis.h"
#include "flaplag/core/format.h"
#include "flaplag/documents/plot.h"
#include "flaplag/trim.h"
#include "flaplag/version.h"
#include "options.h"
#include "shard.h"

namespace flaplag::cli {

namespace {

using cmd::Json;
using cmd::Output;

// The command line behind a result, as the "case" object of JSON outputs: `flaplag run` takes
// it back (case_file.h).
Json case_json(const Request& r) {
  // Keys in a canonical order (command, then alphabetical), so that a case read back from a
  // file in any key order reproduces the same bytes.
  std::map<std::string, Json> options;
  const std::vector<std::string>& a = r.arguments;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string& s = a[i];
    if (s.rfind("-", 0) != 0 || s == "-") continue;  // the subcommand
    std::string name = s, value;
    bool attached = false;
    const auto eq = s.find('=');
    if (s.rfind("--", 0) == 0 && eq != std::string::npos) {
      name = s.substr(0, eq);
      value = s.substr(eq + 1);
      attached = true;
    } else if (s.rfind("-o", 0) == 0 && s.size() > 2 && s.rfind("--", 0) != 0) {
      name = "-o";
      value = s.substr(2);
      attached = true;
    }
    const OptionSpec* o = find_option(r.command, name);
    if (o == nullptr) continue;
    // Where the result goes is not part of it: the same run to stdout and to -o FILE writes
    // the same bytes.
    if (o->name == "-o" || o->name == "--audit" || o->name == "--export-shapes") {
      if (!attached) ++i;
      continue;
    }
    if (o->name == "--quiet") continue;  // how the run looked, not what it computed
    // A blade table is recorded by its text: a result names no file to read.
    if (o->name == "--blade-table" || o->name == "--blade-csv") {
      if (!attached) ++i;
      options["blade-csv"] = r.blade_csv;
      continue;
    }
    if (o->name == "--mode-shapes" || o->name == "--mode-shapes-csv") {
      if (!attached) ++i;
      options["mode-shapes-csv"] = r.mode_shapes_csv;
      continue;
    }
    const std::string key = o->name.substr(2);
    if (!o->takes_value) {
      options[key] = true;
    } else {
      if (!attached && i + 1 < a.size()) value = a[++i];
      options[key] = value;
    }
  }
  Json c = Json::object();
  c["command"] = command_name(r.command);
  for (const auto& [key, value] : options) c[key] = value;
  return c;
}

// The commands that do not rest on one Analysis of the case's rotor.
std::optional<Output> run_standalone(const Request& r, std::string& w, RunControl* control) {
  switch (r.command) {
    case Command::Models:
      return cmd::models(r);
    case Command::Modes:
      return Output(run_modes(r, &w));
    case Command::Study:
      return cmd::study(r, w, control);
    case Command::Map:
      return cmd::map(r, w, control);
    case Command::Merge:
      return Output(merge_parts(r));
    case Command::Plot:
      return Output(documents::plot_data_files(
          {r.inputs, r.labels, r.max_zeta, r.mode, r.plot, r.memory_limit,
           r.plot_zeta ? documents::SweepQuantity::Zeta : documents::SweepQuantity::DampingRatio},
          kebab_option));
    case Command::Trim:
      return cmd::trim_command(r);
    default:
      return std::nullopt;
  }
}

// Point, sweep and critical of a trimmed rotor.  The header shows the rotor trimmed in hover (its
// theta0 and eq 2.25 lambda); each mu of the analysis is trimmed on its own.
// (Any other command of a trimmed rotor: nullopt, after the same check of the hover trim.)
std::optional<Output> run_trimmed(const Request& r, std::string& w) {
  const Analysis an(r.params, r.transition,
                    OperatingCondition::Trimmed(r.trim).About(r.linearization));
  switch (r.command) {
    case Command::Point:
      return cmd::point(r, an);
    case Command::Sweep:
      return cmd::sweep(r, an, w);
    case Command::Critical:
      return cmd::critical(r, an);
    default:
      return std::nullopt;
  }
}

Output run(const Request& r, std::string* warning, RunControl* control) {
  std::string ignored;
  std::string& w = warning != nullptr ? *warning : ignored;
  if (std::optional<Output> out = run_standalone(r, w, control)) return std::move(*out);
  if (cmd::trimmed(r)) {
    if (std::optional<Output> out = run_trimmed(r, w)) return std::move(*out);
  }
  // Fixed controls, at the inflow model of --inflow (eq 2.24 by default).
  const Analysis an(r.params, r.transition, cmd::fixed_controls(r));
  switch (r.command) {
    case Command::Point:
      return cmd::point(r, an);
    case Command::Sweep:
      return cmd::sweep(r, an, w);
    case Command::Critical:
      return cmd::critical(r, an);
    case Command::System:
      return cmd::system_snapshot(r, an);
    case Command::Response:
      return cmd::response(r, an, w);
    case Command::Simulate:
      return cmd::simulate_command(r, an, w);
    case Command::Campbell:
      return cmd::campbell(r, an, w);
    default:
      return cmd::typical(r, an);
  }
}

// Provenance in every JSON output: the flaplag version and commit, and the case that
// reproduces it (`flaplag run FILE.json`).
void complete(const Request& r, Json& j, const RunControl* control) {
  const bool cancelled = control != nullptr && control->cancelled;
  if (cancelled) {
    const std::string before = j.value("message", "");
    j["status"] = "cancelled";
    j["message"] = control->message + (before.empty() ? "" : "; " + before);
  }
  if (r.shard_count > 0) j["shard"] = shard_json(r);  // which part of a --shard job
  j["flaplag"] = Json{{"version", FLAPLAG_VERSION}, {"commit", FLAPLAG_GIT_COMMIT}};
  j["case"] = case_json(r);
  if (r.shard_count > 0) seal_part(j);  // last: the digest covers everything above
}

}  // namespace

std::string run_command(const Request& r, std::string* warning, RunControl* control,
                        Json* document) {
  Output out = run(r, warning, control);
  const bool cancelled = control != nullptr && control->cancelled;
  if (!out.json && r.json && !out.text.empty() && out.text[0] == '{')
    out.json = Json::parse(out.text);  // modes and merge (modes_command.cc, shard.cc) give JSON
  if (!out.json && !r.json && !r.report.empty() && r.command == Command::Modes) {
    // The modes command makes one form; its JSON for the report is made again (milliseconds).
    Request rj = r;
    rj.json = true;
    rj.plot.clear();
    out.json = Json::parse(run_modes(rj, nullptr));
  }
  if (out.json) complete(r, *out.json, control);
  std::string text = std::move(out.text);
  if (r.json && out.json) {
    text = out.json->dump(2) + "\n";
  } else if (cancelled) {
    text += "  status: cancelled: " + control->message + "\n";
  }
  // The document for the report (a command keeps it only when a report asks for it).
  if (document != nullptr && out.json) *document = std::move(*out.json);
  return text;
}

}  // namespace flaplag::cli
