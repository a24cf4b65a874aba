// flaplag — command-line front end of the flap-lag stability analysis (NASA CR-132431).
//
// Exit codes: 0 success (numerical outcomes such as an unstable hover or no mu_c below the scan
// limit are results, not errors); 2 bad input, reported as ONE line on stderr
// "flaplag: error: <option> = <value>: <reason>", with no output file created or changed (an
// output that cannot be written, standard output included, is such an error too); 1 an
// internal failure (a bug), also one line on stderr; 3 (flaplag plot) gnuplot is missing or
// failed; a study or map stopped by a signal writes the rows finished as a valid output with
// status "cancelled", says so in one line on stderr and exits with 128 + the signal's number,
// as a shell reports a job the signal ended: 130 for Ctrl-C (SIGINT), 143 for SIGTERM (what a
// batch scheduler sends at the time limit), so that a script can tell them apart.
#include <signal.h>

#include <atomic>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "case_file.h"
#include "command_line.h"
#include "commands.h"
#include "flaplag/core/errors.h"
#include "flaplag/documents/output.h"
#include "flaplag/documents/plot.h"
#include "flaplag/documents/read_file.h"
#include "flaplag/documents/report.h"
#include "flaplag/limits.h"
#include "flaplag/version.h"
#include "flaplag_spec/runtime_spec.h"
#include "progress.h"

namespace {

constexpr int kBadInput = 2;
constexpr int kInternalError = 1;
constexpr int kRendererMissing = 3;
// Set by SIGINT or SIGTERM; the study and map poll it between rows.  Lock-free atomics are what
// a signal handler may touch.
std::atomic<bool> interrupted{false};
std::atomic<int> stop_signal{0};  // the signal that set it
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free);

extern "C" void on_interrupt(int signal) {
  stop_signal.store(signal);
  interrupted.store(true);
}

// Ctrl-C (SIGINT) or SIGTERM during a study or map stops it after the rows being computed; a
// second one of the same signal (its handler is reset by the first) ends flaplag at once.
void catch_interrupt() {
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND | SA_RESTART;  // no EINTR for the writes of the output
  ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);
}

// 128 + the signal, as a shell reports a job ended by it: 130 (SIGINT), 143 (SIGTERM).
int interrupted_exit_code() {
  const int signal = stop_signal.load();
  return 128 + (signal > 0 ? signal : SIGINT);
}

// Standard output that cannot be written (a full disk) is an output error; a pipe whose reader
// went away ends flaplag by SIGPIPE, as any filter.
int write_stdout(const std::string& text) {
  const std::string reason = flaplag::documents::write_descriptor(1, text, false);
  if (reason.empty()) return 0;
  std::cerr << "flaplag: error: standard output: " << reason << std::endl;
  return kBadInput;
}

const char* const kVersion = "flaplag " FLAPLAG_VERSION;

// One line, whatever the message contains.
std::string one_line(std::string s) {
  for (char& c : s) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

int report(const std::string& message, int code) {
  std::cerr << (code == kBadInput ? "flaplag: error: " : "flaplag: internal error: ")
            << one_line(message) << std::endl;
  return code;
}

// `flaplag run CASE [options]`: the case file's arguments, then the options typed after it
// (the last of a repeated option wins, so the command line overrides the file).
// `flaplag report CASE [options] [-o PAGE.html]` is the same run with the result's page as its
// only output; `flaplag report RESULT.json [-o PAGE.html]` is the page of a result as it is.
struct Expanded {
  std::vector<std::string> args;
  flaplag::cli::CaseArguments from_file;
  std::vector<std::string> typed;  // the options given after the file
  bool run_help = false;           // flaplag run --help
  bool report = false;             // flaplag report
  bool report_help = false;        // flaplag report --help
  std::string file;                // the case or result file, as typed
  std::string page;                // flaplag report: -o ("": standard output)
  bool of_result = false;          // flaplag report RESULT.json: report `result` as it is
  std::string result;              // its text
};

// The --memory-limit typed after `flaplag run FILE` (the last one; the default without one): it
// bounds the reading of the file itself, before the file's own options are known.
std::uint64_t typed_memory_limit(const std::vector<std::string>& args) {
  std::uint64_t limit = flaplag::kDefaultMemoryLimit;
  const std::string name = "--memory-limit";
  for (std::size_t i = 2; i < args.size(); ++i) {
    if (args[i] == name && i + 1 < args.size()) {
      limit = flaplag::parse_memory_size(name, args[i + 1]);
      ++i;
    } else if (args[i].rfind(name + "=", 0) == 0) {
      limit = flaplag::parse_memory_size(name, args[i].substr(name.size() + 1));
    }
  }
  return limit;
}

// flaplag report: takes -o PAGE out of the options typed after the file (the page is the only
// output; a case file's own -o is not written).
std::string take_page(std::vector<std::string>& typed) {
  std::string page;
  for (std::size_t i = 0; i < typed.size();) {
    const std::string& a = typed[i];
    std::string value;
    std::size_t used = 0;
    if (a == "-o" || a == "--output") {
      if (i + 1 >= typed.size() || typed[i + 1].rfind("--", 0) == 0)
        throw flaplag::InvalidInput(a, "(missing)", "expected a file name");
      value = typed[i + 1];
      used = 2;
    } else if (a.rfind("--output=", 0) == 0) {
      value = a.substr(9);
      used = 1;
    } else if (a.rfind("-o", 0) == 0 && a.size() > 2 && a.rfind("--", 0) != 0) {
      value = a.substr(2);
      used = 1;
    } else {
      ++i;
      continue;
    }
    if (value != "-" && !flaplag::documents::is_report_path(value))
      throw flaplag::InvalidInput(a.rfind("--", 0) == 0 ? "--output" : "-o",
                                  flaplag::cli::shown(value),
                                  "must end in .html or .htm (flaplag report writes a page)");
    page = value == "-" ? "" : value;
    typed.erase(typed.begin() + static_cast<std::ptrdiff_t>(i),
                typed.begin() + static_cast<std::ptrdiff_t>(i + used));
  }
  return page;
}

Expanded expand(const std::vector<std::string>& args) {
  Expanded e;
  if (args.empty() || (args[0] != "run" && args[0] != "report")) {
    e.args = args;
    return e;
  }
  const std::string word = args[0];
  e.report = word == "report";
  if (args.size() >= 2 && (args[1] == "--help" || args[1] == "-h")) {
    (e.report ? e.report_help : e.run_help) = true;
    return e;
  }
  if (args.size() < 2 || args[1].empty() || args[1][0] == '-')
    throw flaplag::InvalidInput("argument", args.size() < 2 ? "(missing)" : args[1],
                                "flaplag " + word + " needs a case file: flaplag " + word +
                                    " CASE.toml (or a --json output of flaplag)");
  e.file = args[1];
  if (e.report) {
    e.typed.assign(args.begin() + 2, args.end());
    e.page = take_page(e.typed);
    const std::string text =
        flaplag::documents::read_json_file(e.file, typed_memory_limit(args), "case file",
                                           "case file cannot be read", flaplag::cli::kebab_option);
    if (flaplag::documents::is_json_text(text)) {
      // A result is shown as computed: nothing here would change it but the memory to read it.
      for (std::size_t i = 0; i < e.typed.size(); ++i) {
        const std::string& a = e.typed[i];
        if (a == "--memory-limit") {
          ++i;
        } else if (a.rfind("--memory-limit=", 0) != 0) {
          throw flaplag::InvalidInput(
              "argument", flaplag::cli::shown(a),
              "flaplag report of a --json output shows its result as computed (only -o and "
              "--memory-limit apply); to compute it again: flaplag run " +
                  e.file + " --report PAGE.html");
        }
      }
      e.of_result = true;
      e.result = text;
      return e;
    }
    e.from_file = flaplag::cli::parse_case_text(e.file, text);
    e.args = e.from_file.args;
    e.args.insert(e.args.end(), e.typed.begin(), e.typed.end());
    return e;
  }
  e.from_file = flaplag::cli::read_case_file(args[1], typed_memory_limit(args));
  e.args = e.from_file.args;
  e.typed.assign(args.begin() + 2, args.end());
  e.args.insert(e.args.end(), e.typed.begin(), e.typed.end());
  return e;
}

// An error about an option that came from the case file names the file, line and key.
std::string with_origin(const Expanded& e, const std::string& line) {
  for (const auto& [option, where] : e.from_file.origin) {
    if (line.rfind(option + " = ", 0) != 0 && line.rfind(option + "=", 0) != 0) continue;
    bool typed = false;
    for (const std::string& t : e.typed)
      typed = typed || t == option || t.rfind(option + "=", 0) == 0;
    if (!typed) return where + line.substr(option.size());
  }
  return line;
}

// flaplag report RESULT.json: the page of a result as it was computed.
int report_of_result(const Expanded& e) {
  try {
    const flaplag::documents::OutputTarget page(e.page, "output");
    std::string warning;
    const std::string html = flaplag::documents::html_report_of_text(
        e.file, e.result, flaplag::cli::kebab_option, flaplag::cli::case_option, &warning);
    if (e.page.empty()) {
      if (const int code = write_stdout(html); code != 0) return code;
    } else {
      page.write(html);
    }
    if (!warning.empty()) std::cerr << "flaplag: warning: " << one_line(warning) << std::endl;
    return 0;
  } catch (const flaplag::InvalidInput& error) {
    return report(error.name() == "output" ? "-o = " + error.value() + ": " + error.reason()
                                           : std::string(error.what()),
                  kBadInput);
  }
}

// The request of the command line; for `flaplag report CASE`, the same run with the page as its
// only output: the result is made as JSON for it, and nothing else is written but what the case
// asks to draw (--plot).
flaplag::cli::Request request_of(const Expanded& e, const flaplag::cli::CommandLine& cl) {
  flaplag::cli::Request request = cl.interpret();
  request.arguments = e.args;
  if (!e.report) return request;
  using flaplag::cli::Command;
  if (request.command == Command::Models || request.command == Command::Merge ||
      request.command == Command::Plot)
    throw flaplag::InvalidInput("argument", flaplag::cli::shown(e.file),
                                std::string("a flaplag ") +
                                    flaplag::cli::command_name(request.command) +
                                    " case makes no result to report on");
  if (request.shard_count > 0)
    throw flaplag::InvalidInput("argument", flaplag::cli::shown(e.file),
                                "a report covers the whole job, not one --shard part: "
                                "flaplag merge the parts, then flaplag report MERGED.json");
  request.json = true;
  request.output.clear();
  request.report = e.page.empty() ? "-" : e.page;
  return request;
}

// Every output path, checked (in this order) before a possibly long analysis: nothing is left
// behind.
struct Outputs {
  Outputs(const Expanded& e, const flaplag::cli::Request& r)
      : target(e.report ? "" : r.output, "output"),
        picture(r.plot, "plot"),
        audit(r.audit, "audit"),
        page(r.report == "-" ? "" : r.report, e.report ? "output" : "report") {}
  const flaplag::documents::OutputTarget target, picture, audit, page;
};

// The command's output text (and *document, its JSON).  A study or map stops at SIGINT or
// SIGTERM (control->cancelled) and shows its progress on a terminal.
std::string compute(const flaplag::cli::Request& request, std::string* warning,
                    flaplag::cli::RunControl* control, nlohmann::ordered_json* document) {
  using flaplag::cli::Command;
  const bool long_run = request.command == Command::Study || request.command == Command::Map;
  if (long_run) catch_interrupt();
  flaplag::cli::ProgressBar bar(
      long_run && !request.quiet && flaplag::cli::stderr_is_terminal(),
      std::string("flaplag ") + flaplag::cli::command_name(request.command),
      request.command == Command::Study ? "values"
      : request.y_name == "mu"          ? "columns"
                                        : "rows");
  control->cancel = &interrupted;
  control->progress = bar.function();
  const std::string text = flaplag::cli::run_command(request, warning, control, document);
  bar.finish();
  return text;
}

// The page of the result for --report ("" without): made before anything is written, so that a
// failure leaves nothing.  Its warnings join *warning.
std::string report_page(const Expanded& e, const flaplag::cli::Request& request,
                        const nlohmann::ordered_json& document, std::string* warning) {
  if (request.report.empty()) return "";
  flaplag::documents::ReportSource source;
  source.title = e.file.empty() ? "command line" : "case file " + e.file;
  source.option = flaplag::cli::kebab_option;
  source.case_option = flaplag::cli::case_option;
  source.warnings = e.from_file.warnings;
  if (!warning->empty()) source.warnings.push_back(*warning);
  std::string page_warning;
  std::string html = flaplag::documents::html_report(document, source, &page_warning);
  if (!page_warning.empty()) *warning += (warning->empty() ? "" : "; ") + page_warning;
  return html;
}

// The output, or for `flaplag report` the page alone; then the page of --report.  The exit code
// of a standard output that cannot be written, else 0.
int write_outputs(const Expanded& e, const flaplag::cli::Request& request, const Outputs& out,
                  const std::string& text, const std::string& html) {
  if (e.report) {
    if (request.report == "-") return write_stdout(html);
    out.page.write(html);
    return 0;
  }
  if (request.output.empty()) {
    if (const int code = write_stdout(text); code != 0) return code;
  } else {
    out.target.write(text);
  }
  if (!request.report.empty()) out.page.write(html);
  return 0;
}

// At most one warning line: what the case file left out, then what the run says.
void print_warnings(const Expanded& e, const std::string& warning) {
  std::vector<std::string> warnings = e.from_file.warnings;
  if (!warning.empty()) warnings.push_back(warning);
  std::string joined;
  for (const std::string& w : warnings) joined += (joined.empty() ? "" : "; ") + w;
  if (!joined.empty()) std::cerr << "flaplag: warning: " << one_line(joined) << std::endl;
}

int run_request(const Expanded& e, const flaplag::cli::CommandLine& cl) {
  const flaplag::cli::Request request = request_of(e, cl);
  const Outputs out(e, request);
  // The picture is written after the output, so that a run that fails leaves none.
  flaplag::documents::DeferredPictures pictures;
  std::string warning;
  flaplag::cli::RunControl control;
  nlohmann::ordered_json document;
  const std::string text = compute(request, &warning, &control, &document);
  const std::string html = report_page(e, request, document, &warning);
  if (const int code = write_outputs(e, request, out, text, html); code != 0) return code;
  pictures.commit();
  // The audit report of a --spec model, after the result (a failed run writes none).
  if (!request.audit.empty())
    out.audit.write(flaplag::spec::audit_report(flaplag::find_model(request.params.model).base));
  print_warnings(e, warning);
  if (control.cancelled) {
    std::cerr << "flaplag: " << one_line(control.message) << std::endl;
    return interrupted_exit_code();
  }
  return 0;
}

int run(const std::vector<std::string>& raw) {
  Expanded e;
  try {
    e = expand(raw);
  } catch (const flaplag::InvalidInput& error) {
    return report(error.what(), kBadInput);
  }
  if (e.run_help || e.report_help) {
    return write_stdout(e.run_help ? flaplag::cli::CommandLine::run_help_text()
                                   : flaplag::cli::CommandLine::report_help_text());
  }
  if (e.of_result) return report_of_result(e);
  const flaplag::cli::CommandLine cl(e.args);
  if (cl.wants_help() || cl.wants_version()) {
    return write_stdout(cl.wants_help() ? cl.help_text() : std::string(kVersion) + "\n");
  }
  try {
    return run_request(e, cl);
  } catch (const flaplag::documents::RendererUnavailable& error) {
    std::cerr << "flaplag: error: " << one_line(error.what()) << std::endl;
    return kRendererMissing;
  } catch (const flaplag::InvalidInput& error) {
    // The runtime names fields ("omega_lag"); users know options ("--omega-lag").
    if (const std::optional<std::string> line = cl.error_line(error))
      return report(with_origin(e, *line), kBadInput);
    // A name no option answers for is a quantity the analysis derived from valid input (say a
    // non-finite coefficient): the inputs were checked, so this is a bug to report.
    return report(std::string("invalid derived quantity ") + error.what(), kInternalError);
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(std::vector<std::string>(argv + (argc > 0 ? 1 : 0), argv + argc));
  } catch (const std::exception& e) {
    return report(e.what(), kInternalError);
  } catch (...) {
    return report("unknown exception", kInternalError);
  }
}
