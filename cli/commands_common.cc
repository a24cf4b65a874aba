// flaplag CLI — what every subcommand's output shares beyond the documents' header
// (documents/header.h): messages in this command line's vocabulary, the operating condition of a
// request, the picture a command draws.
#include <optional>
#include <string>
#include <vector>

#include "commands_internal.h"
#include "flaplag/documents/plot.h"
#include "flaplag/trim.h"
#include "options.h"

namespace flaplag::cli::cmd {

std::string vocab(const Request& r, const std::string& message) {
  return in_cli_vocabulary(r.command, message);
}

OperatingCondition fixed_controls(const Request& r) {
  OperatingCondition c;
  c.inflow = r.inflow;
  c.linearization = r.linearization;
  return c;
}

std::string notes_text(const Request& r, const std::vector<std::string>& notes) {
  std::string out;
  for (const std::string& n : notes) out += "  note: " + vocab(r, n) + "\n";
  return out;
}

// A plot, if asked for: "" or a warning line for stderr (the data is written in any case).
std::string plot_if_asked(const Request& r, Json result) {
  if (r.plot.empty()) return "";
  // What the picture reads of the "case" object run_command adds (commands.cc): the trim.
  if (trimmed(r)) result["case"] = Json{{"trim", trim_kind_name(r.trim.kind)}};
  const std::optional<std::string> script = result_plot_script(
      result, r.plot, r.plot_zeta ? SweepQuantity::Zeta : SweepQuantity::DampingRatio);
  return script ? render_plot(*script, r.plot) : "";
}

}  // namespace flaplag::cli::cmd
