#include "command_line.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/blade/imported_modes.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/core/parallel.h"
#include "flaplag/documents/plot.h"
#include "flaplag/documents/read_file.h"
#include "flaplag/documents/report.h"
#include "flaplag/limits.h"
#include "flaplag/rotor/blade_table.h"
#include "flaplag/rotor/parameter_table.h"
#include "flaplag_spec/runtime_spec.h"
#include "shard.h"

namespace flaplag::cli {

using documents::is_plot_path;
using documents::is_report_path;

using documents::kMaxCaseBytes;
using documents::read_text_file;

namespace {

// Upper limits that only keep absurd requests from running for hours or overflowing; they are
// far above anything the paper or the tests use.
constexpr int kMaxPoints = 100001;  // sweep points, Fig 9 rows, spanwise stations
constexpr int kMaxShards = 100000;  // parts of a --shard job (a map has at most 10000 lines)

const char* const kMissing = "(missing)";
const char* const kNoValue = "(no value)";

// The model of that name ("<family>" or "<family>-<M>x<N>"), or nullptr with the library's
// reason in *why (for "paper-13x1", the mode count and its reason).
const model::ModelDescriptor* compiled_model(const std::string& name, std::string* why = nullptr) {
  try {
    return &find_model(name);
  } catch (const InvalidInput& e) {
    if (why != nullptr) *why = e.name() == "model" ? e.reason() : e.what();
    return nullptr;
  }
}

std::string subcommand_list() {
  std::string s;
  for (Command c : subcommands()) s += (s.empty() ? "" : ", ") + std::string(command_name(c));
  return s;
}

// "flaplag point" / "flaplag"
std::string full_name(Command c) {
  const std::string n = command_name(c);
  return n.empty() ? "flaplag" : "flaplag " + n;
}

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// "-0.5", "-.5", "-1e3": a negative number, not an option.
bool negative_number(const std::string& a) {
  if (a.size() < 2 || a[0] != '-') return false;
  const char c = a[1];
  return (c >= '0' && c <= '9') || (c == '.' && a.size() > 2 && a[2] >= '0' && a[2] <= '9');
}

// "--" and lower-case letters, digits and inner dashes: the shape of every option of flaplag.
bool well_formed_long_option(const std::string& name) {
  if (name.size() < 3 || !starts_with(name, "--") || name[2] == '-') return false;
  for (std::size_t i = 2; i < name.size(); ++i) {
    const char c = name[i];
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-')) return false;
  }
  return true;
}

bool is_option_word(const std::string& a) {
  return a.size() > 1 && a[0] == '-' && !negative_number(a);
}

struct Range {
  double start, stop, step;
  int count;  // points start, start + step, ..., up to stop
};

// "A:B:STEP" with 0 <= A < B, STEP > 0; the whole text is the value in every message.
Range parse_range(const std::string& option, const std::string& text) {
  std::vector<std::string> parts;
  std::string::size_type from = 0;
  for (;;) {
    const auto colon = text.find(':', from);
    parts.push_back(text.substr(from, colon == std::string::npos ? colon : colon - from));
    if (colon == std::string::npos) break;
    from = colon + 1;
  }
  const std::string value = shown(text);
  if (text.empty()) throw InvalidInput(option, value, "empty range, expected START:STOP:STEP");
  if (parts.size() != 3) throw InvalidInput(option, value, "expected START:STOP:STEP");
  const char* names[3] = {"START", "STOP", "STEP"};
  double v[3];
  for (int i = 0; i < 3; ++i) {
    try {
      v[i] = parse_real(option, parts[i]);
    } catch (const InvalidInput& e) {
      // Keep the whole range as the value; say which part is wrong.
      throw InvalidInput(option, value, std::string(names[i]) + " " + e.reason());
    }
  }
  Range r{v[0], v[1], v[2], 0};
  if (r.start < 0.0) throw InvalidInput(option, value, "START must be >= 0");
  if (r.stop < r.start) throw InvalidInput(option, value, "reversed range (STOP < START)");
  if (r.stop == r.start) throw InvalidInput(option, value, "empty range (STOP = START)");
  if (!(r.step > 0.0)) throw InvalidInput(option, value, "STEP must be > 0");
  const double n = std::floor((r.stop - r.start) / r.step * (1.0 + 1e-12)) + 1.0;
  if (!(n <= kMaxPoints)) {
    throw InvalidInput(option, value,
                       "STEP too small: more than " + std::to_string(kMaxPoints) + " points");
  }
  r.count = static_cast<int>(n);
  return r;
}

// "NAME=START:STOP:STEP" or "NAME=V1,V2,...": NAME an option word of a numeric rotor parameter
// ("omega-lag") or, where allowed, "mu"; the values in the given order (a range ascending, both
// ends included).
void parse_axis(const std::string& option, const std::string& text, bool allow_mu,
                std::string& name, std::vector<double>& values) {
  const std::string value = shown(text);
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InvalidInput(option, value, "expected NAME=START:STOP:STEP or NAME=V1,V2,...");
  std::string word = text.substr(0, eq);
  std::string field = word;
  for (char& ch : field)
    if (ch == '-') ch = '_';
  if (field == "mu") {
    if (!allow_mu)
      throw InvalidInput(option, value, "mu cannot be varied here (mu_c is what a study finds)");
  } else {
    const ParameterSpec* s = find_parameter(field);
    if (s == nullptr || s->type != ParameterType::Real)
      throw InvalidInput(option, value,
                         "\"" + word +
                             "\" is not a numeric rotor parameter (e.g. omega-lag, theta, "
                             "gamma, damping-lag, droop, precone)");
  }
  name = field;
  values.clear();
  const std::string rest = text.substr(eq + 1);
  if (rest.find(':') != std::string::npos) {
    std::vector<std::string> parts;
    std::string::size_type from = 0;
    for (;;) {
      const auto colon = rest.find(':', from);
      parts.push_back(rest.substr(from, colon == std::string::npos ? colon : colon - from));
      if (colon == std::string::npos) break;
      from = colon + 1;
    }
    if (parts.size() != 3) throw InvalidInput(option, value, "expected NAME=START:STOP:STEP");
    double v[3];
    const char* names[3] = {"START", "STOP", "STEP"};
    for (int i = 0; i < 3; ++i) {
      try {
        v[i] = parse_real(option, parts[i]);
      } catch (const InvalidInput& e) {
        throw InvalidInput(option, value, std::string(names[i]) + " " + e.reason());
      }
    }
    if (!(v[2] > 0.0)) throw InvalidInput(option, value, "STEP must be > 0");
    if (!(v[1] > v[0]))
      throw InvalidInput(option, value, "empty or reversed range (STOP <= START)");
    const double n = std::floor((v[1] - v[0]) / v[2] * (1.0 + 1e-12)) + 1.0;
    if (!(n <= kMaxPoints))
      throw InvalidInput(option, value,
                         "STEP too small: more than " + std::to_string(kMaxPoints) + " points");
    // Decimal grid values (START + k STEP accumulates rounding): 12 significant digits.
    for (int k = 0; k < static_cast<int>(n); ++k) {
      char buf[40];
      std::snprintf(buf, sizeof buf, "%.12g", v[0] + k * v[2]);
      values.push_back(std::strtod(buf, nullptr));
    }
    if (values.back() < v[1] - 1e-9 * std::max(1.0, std::abs(v[1]))) values.push_back(v[1]);
  } else {
    std::string::size_type from = 0;
    for (;;) {
      const auto comma = rest.find(',', from);
      const std::string item = rest.substr(from, comma == std::string::npos ? comma : comma - from);
      try {
        values.push_back(parse_real(option, item));
      } catch (const InvalidInput& e) {
        throw InvalidInput(option, value, "value \"" + item + "\" " + e.reason());
      }
      if (values.size() > static_cast<std::size_t>(kMaxPoints))
        throw InvalidInput(option, value, "more than " + std::to_string(kMaxPoints) + " values");
      if (comma == std::string::npos) break;
      from = comma + 1;
    }
  }
  if (field == "mu") {
    for (std::size_t i = 0; i < values.size(); ++i)
      if (values[i] < 0.0 || (i > 0 && values[i] <= values[i - 1]))
        throw InvalidInput(option, value, "advance ratios must be >= 0 and increasing");
  }
}

// ---- help ------------------------------------------------------------------------------------

const char* description(Command c) {
  switch (c) {
    case Command::Typical:
      return "the paper's typical case: hover, mu_c, zeta(mu) and omega(mu) for mu = 0, 0.1, ..., "
             "1";
    case Command::Point:
      return "characteristic exponents and multipliers at one advance ratio";
    case Command::Sweep:
      return "exponents over a range of advance ratios";
    case Command::Critical:
      return "critical advance ratio mu_c: the first mu with zeta > 0";
    case Command::System:
      return "A(psi), f(psi), flow region, hover equilibrium, spanwise integrals";
    case Command::Models:
      return "compiled ordering models (one per spec, each for any M x N modes) and their specs";
    case Command::Modes:
      return "exact rotating modes: the Fig 9 frequency relation and a blade's mode shapes";
    case Command::Study:
      return "mu_c and every instability interval versus one parameter (Figs 12-17)";
    case Command::Map:
      return "stability map: the largest zeta over two parameters (one may be mu)";
    case Command::Response:
      return "periodic forced response: tip flap and lag deflections over one revolution";
    case Command::Simulate:
      return "time-domain simulation of the linear (or, --nonlinear, the nonlinear) equations "
             "from a perturbation";
    case Command::Merge:
      return "join the --shard parts of a map or study into the file one run writes";
    case Command::Plot:
      return "draw an existing sweep, study, map, response, simulate, modes or campbell result "
             "(--json output), or several sweeps in one picture";
    case Command::Trim:
      return "trim: theta0, theta1c, theta1s and lambda (eq 2.25) for a thrust coefficient";
    case Command::Campbell:
      return "Campbell diagram: every mode's frequency against the rotor speed, with the per-rev "
             "lines it crosses";
  }
  return "";
}

std::vector<std::string> examples(Command c) {
  switch (c) {
    case Command::Typical:
      return {"flaplag                                   the typical case",
              "flaplag --modes exact --json              exact modes, as JSON",
              "flaplag critical --method magnus          mu_c with the reference method",
              "flaplag point --mu 0.5                    exponents at mu = 0.5"};
    case Command::Point:
      return {"flaplag point --mu 0.5", "flaplag point --mu 0.8 --method hsu --steps 50 --json"};
    case Command::Sweep:
      return {"flaplag sweep --mu 0:1:0.05",
              "flaplag sweep --mu 0:1.5:0.01 --format csv -o sweep.csv",
              "flaplag sweep --mu 0:1.5:0.01 --damping-criterion 0.01 --plot damping.svg"};
    case Command::Critical:
      return {"flaplag critical", "flaplag critical --mu-max 1.5 --modes exact --flap-modes 2",
              "flaplag critical --modes exact --flap-modes 4 --lag-modes 2",
              "flaplag critical --trim moment --thrust-coefficient 0.004"};
    case Command::System:
      return {"flaplag system --mu 0.8 --psi 4.7", "flaplag system --mu 0.3 --json"};
    case Command::Models:
      return {"flaplag models", "flaplag models --spec paper", "flaplag models --json"};
    case Command::Campbell:
      return {"flaplag campbell --plot campbell.svg",
              "flaplag campbell --omega-lag 0.7 --speed-max 1.2 --speeds 61 --json",
              "flaplag --modes exact --flap-modes 3 --lag-modes 2 campbell --mu 0.3"};
    case Command::Modes:
      return {"flaplag modes", "flaplag modes --omega-lag 1.4 --flap-modes 2 --json",
              "flaplag modes --flap-modes 3 --lag-modes 2 --points 21 --plot shapes.svg"};
    case Command::Study:
      return {"flaplag study --vary omega-lag=0.2:2.5:0.05 --plot fig15.svg",
              "flaplag --modes exact study --vary damping-lag=0,0.01,0.02,0.03,0.05 --json",
              "flaplag study --vary omega-lag=0.2:2.5:0.01 --json --shard 1/4 -o part1.json"};
    case Command::Map:
      return {"flaplag map --x mu=0:2:0.02 --y omega-lag=0.3:2.5:0.02 --plot map.png",
              "flaplag map --x theta=0.05:0.3:0.01 --y gamma=4:16:0.5 --mu 0.6 --json",
              "flaplag map --x mu=0:2:0.01 --y omega-lag=0.3:2.5:0.01 --json --shard 3/8 -o "
              "part3.json   (then: flaplag merge part*.json -o map.json)"};
    case Command::Response:
      return {"flaplag response --mu 0.3", "flaplag response --mu 0.5 --json --plot tip.svg"};
    case Command::Simulate:
      return {"flaplag simulate --mu 0.9 --revs 50", "flaplag simulate --mu 0.3 --forced --json",
              "flaplag simulate --mu 0.6 --nonlinear --revs 40"};
    case Command::Merge:
      return {
          "flaplag map --x mu=0:2:0.02 --y omega-lag=0.3:2.5:0.02 --json --shard 2/8 -o "
          "part2.json",
          "flaplag merge part*.json -o map.json"};
    case Command::Plot:
      return {"flaplag plot map.json --plot map.png",
              "flaplag plot a.json b.json --label paper --label trimmed --max-zeta --plot z.png",
              "flaplag study --vary theta=0:0.3:0.02 --json -o s.json && flaplag plot s.json "
              "--plot s.svg"};
    case Command::Trim:
      return {"flaplag trim --mu 0.3 --thrust-coefficient 0.005",
              "flaplag critical --trim moment --thrust-coefficient 0.0042",
              "flaplag --periodic-linearization trim --mu 0.2 --trim moment"};
  }
  return {};
}

const char* const kRunDescription = "run a case file (TOML) or a --json output again";
const char* const kReportDescription =
    "a one-page HTML report of a case file (run now) or of a --json output (as computed)";

// What a subcommand's help says beyond its options.
std::string usage_notes(Command c) {
  switch (c) {
    case Command::Study:
    case Command::Map:
      return "\nOn a terminal a progress bar shows on stderr after 1 s (--quiet: none).  Ctrl-C "
             "(or SIGTERM)\nstops after the rows being computed: the rows finished are written as "
             "a "
             "valid file\nwith status \"cancelled\", and flaplag exits with code 130 (143 for "
             "SIGTERM).\n";
    case Command::Models:
      return "\nOne model per ordering spec, listed at the spec's mode counts.  Each model also "
             "exists for\nM flap x N lag exact modes, 1 <= M, N <= " +
             std::to_string(model::kMaxModes) +
             ": <model>-<M>x<N> (e.g. paper-4x2), which the\noptions --modes exact --flap-modes "
             "M --lag-modes N select (at most --basis modes per\ndirection).  Every model has "
             "the cyclic pitch, the rotor thrust and the nonlinear loads\n(trim, periodic "
             "linearization, simulate --nonlinear).\n";
    case Command::Merge:
      return "\nThe parts are the --json outputs of one command line run with --shard 1/N .. "
             "N/N.\nThe result is byte for byte the file the command writes without --shard.  "
             "Parts of\nanother case, missing or repeated parts and files that are not "
             "flaplag parts are\nrefused (exit 2).\n";
    case Command::Plot:
      return "\nThe same picture as --plot on the command that wrote DATA.json.  Several sweep "
             "results\nare drawn in one picture, each curve labelled by its file's case (model, "
             "trim,\nperiodic linearization) or by --label (one per file, in order); --max-zeta "
             "draws\nonly the largest zeta of each, --mode NAME only that mode's curves.  "
             "Without\ngnuplot (Debian: gnuplot-nox) one line says so and flaplag exits with "
             "code 3.\n";
    default:
      return "";
  }
}

constexpr char kNoBreak = '\x01';

// Words of `text` wrapped to `width` columns, continuation lines indented by `indent`.
std::string wrap(const std::string& text, std::size_t first_column, std::size_t indent,
                 std::size_t width = 100) {
  std::string out, word;
  std::size_t column = first_column;
  auto flush = [&]() {
    if (word.empty()) return;
    if (column > indent && column + 1 + word.size() > width) {
      out += "\n" + std::string(indent, ' ');
      column = indent;
    } else if (column > indent || !out.empty()) {
      out += ' ';
      ++column;
    }
    out += word;
    column += word.size();
    word.clear();
  };
  for (char ch : text) {
    if (ch == ' ') {
      flush();
    } else {
      word += ch == kNoBreak ? ' ' : ch;
    }
  }
  flush();
  return out;
}

// A phrase wrap() keeps on one line ("in (0, 1000]").
std::string unbroken(std::string s) {
  std::replace(s.begin(), s.end(), ' ', kNoBreak);
  return s;
}

std::string option_help(const OptionSpec& o) {
  std::string h = o.help;
  std::vector<std::string> detail;
  if (o.rotor != nullptr &&
      (o.rotor->type == ParameterType::Real || o.rotor->type == ParameterType::Integer)) {
    std::string symbol = o.rotor->symbol;
    if (std::string(o.rotor->units) != "-") {
      symbol += (symbol.empty() ? "" : ", ") + std::string(o.rotor->units);
    }
    if (!symbol.empty()) detail.push_back(unbroken(symbol));
    detail.push_back(unbroken(o.rotor->requirement));
  }
  if (!o.default_text.empty()) detail.push_back(unbroken("default " + o.default_text));
  if (detail.empty()) return h;
  std::string d;
  for (const std::string& s : detail) d += (d.empty() ? "" : "; ") + s;
  return h + " (" + d + ")";
}

std::string options_block(const std::vector<OptionSpec>& options) {
  constexpr std::size_t kColumn = 30;
  std::string out;
  for (const OptionSpec& o : options) {
    std::string left = "  " + o.name + (o.alias.empty() ? "" : ", " + o.alias);
    if (o.takes_value) left += " " + o.metavar;
    if (left.size() + 2 > kColumn) {
      out += left + "\n" + std::string(kColumn, ' ');
    } else {
      out += left + std::string(kColumn - left.size(), ' ');
    }
    out += wrap(option_help(o), kColumn, kColumn) + "\n";
  }
  return out;
}

}  // namespace

namespace {

// The memory a run will take, from the request alone (limits.h), against --memory-limit.  The
// error names the option that sets the size (the larger axis of a map); a --shard part is
// estimated for its own block.
void check_run_memory(const Request& r) {
  const model::ModelDescriptor* m = compiled_model(r.params.model);
  const int state = m != nullptr ? 2 * (m->flap_modes + m->lag_modes) : 4;
  const std::uint64_t limit = r.memory_limit;
  switch (r.command) {
    case Command::Map: {
      const Request part = shard_request(r);
      const bool y = part.y_values.size() >= part.x_values.size();
      check_memory(map_memory(part.x_values.size(), part.y_values.size()), limit, y ? "y" : "x",
                   std::to_string((y ? part.y_values : part.x_values).size()) + " values");
      break;
    }
    case Command::Study: {
      const Request part = shard_request(r);
      check_memory(study_memory(part.vary_values.size(), state), limit, "values",
                   std::to_string(part.vary_values.size()) + " values");
      break;
    }
    case Command::Sweep: {
      // The points of parse_range (the grid may add the stop: one more).
      const double n =
          std::floor((r.sweep_stop - r.sweep_start) / r.sweep_step * (1.0 + 1e-12)) + 1.0;
      check_memory(sweep_memory(static_cast<std::size_t>(std::min(n, 1e15)), state), limit, "step",
                   round_trip_text(r.sweep_step));
      break;
    }
    case Command::Response:
      check_memory(response_memory(r.response.samples, state), limit, "samples",
                   std::to_string(r.response.samples));
      break;
    case Command::Simulate:
      check_memory(simulation_memory(r.simulation.revolutions, r.simulation.samples_per_rev, state,
                                     r.simulation.nonlinear),
                   limit, "revolutions", round_trip_text(r.simulation.revolutions));
      break;
    default:
      break;
  }
}

}  // namespace

void check_merged_output(const Request& r, const nlohmann::ordered_json& merged) {
  documents::check_merged_size(r.inputs, r.memory_limit, merged);
}

CommandLine::CommandLine(const std::vector<std::string>& args) {
  bool have_command = false;
  bool options_done = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (!options_done && a == "--") {
      options_done = true;
      continue;
    }
    if (options_done || !is_option_word(a)) {
      read_word(i, a, !have_command);
      have_command = true;
      continue;
    }
    i = read_option(args, i);
  }
  refuse_options_of_other_commands();
}

// A word that is no option: the subcommand (the first), a file of merge or plot, or a stray.
void CommandLine::read_word(std::size_t i, const std::string& word, bool first) {
  if (first) {
    if (word == "run" || word == "report") {  // main.cc expands them before this parser runs
      problem(i, InvalidInput("subcommand", word,
                              "must be the first word: flaplag " + word + " CASE [OPTIONS]"));
    } else if (!command_from_name(word, &command_)) {
      problem(i, InvalidInput("subcommand", shown(word),
                              "unknown (one of " + subcommand_list() +
                                  ", run, report; see flaplag --help)"));
    }
  } else if (command_ == Command::Merge || command_ == Command::Plot) {
    inputs_.push_back(word);
  } else {
    const std::string cmd = full_name(command_);
    problem(i, InvalidInput("argument", shown(word),
                            "unexpected: " + cmd + " takes options only (see " + cmd + " --help)"));
  }
}

// The option args[i] with its value, attached or the next word; the index of the last word used.
std::size_t CommandLine::read_option(const std::vector<std::string>& args, std::size_t i) {
  const std::string& a = args[i];
  // --name[=value], -o[VALUE]
  std::string name = a;
  std::optional<std::string> attached;
  if (starts_with(a, "--")) {
    const auto eq = a.find('=');
    if (eq != std::string::npos) {
      name = a.substr(0, eq);
      attached = a.substr(eq + 1);
    }
  } else if (a.size() > 2 && starts_with(a, "-o")) {
    name = "-o";  // -oFILE, as getopt
    attached = a.substr(2);
  }
  if (name == "--help" || name == "-h") {
    help_ = true;
    return i;
  }
  if (name == "--version") {
    version_ = true;
    return i;
  }
  const OptionSpec* spec = find_any_option(name);
  if (spec == nullptr && !well_formed_long_option(name)) {
    // "-q", "--Gamma", "---x": not an option name at all, so the word itself is the value.
    problem(i, InvalidInput("argument", shown(a), "unknown option (see flaplag --help)"));
    return i;
  }
  if (spec == nullptr) {
    // Show what the user meant as its value, if anything: "--bogus 1" -> "--bogus = 1".
    std::string value = kNoValue;
    Command c;
    if (attached) {
      value = shown(*attached);
    } else if (i + 1 < args.size() && !is_option_word(args[i + 1]) &&
               !command_from_name(args[i + 1], &c)) {
      value = shown(args[i + 1]);
    }
    problem(i, InvalidInput(name, value, "unknown option (see flaplag --help)"));
    return i;
  }
  Given g{spec->name, name, "", i};
  if (spec->takes_value) {
    if (attached) {
      g.text = *attached;
    } else if (i + 1 < args.size() && !starts_with(args[i + 1], "--")) {
      g.text = args[++i];
    } else {
      problem(i, InvalidInput(name, kMissing, "needs a value (" + spec->metavar + ")"));
      return i;
    }
  } else if (attached) {
    problem(i, InvalidInput(name, shown(*attached), "takes no value"));
    return i;
  }
  given_.push_back(g);
  return i;
}

// Options are shared by several subcommands and may come before the subcommand, so whether
// this one takes an option is known only after the whole command line.
void CommandLine::refuse_options_of_other_commands() {
  for (const Given& g : given_) {
    if (find_option(command_, g.name) == nullptr) {
      const std::string cmd = full_name(command_);
      const OptionSpec* spec = find_any_option(g.name);
      problem(g.position, InvalidInput(g.spelling, spec->takes_value ? shown(g.text) : kNoValue,
                                       "not an option of " + cmd + " (see " + cmd + " --help)"));
    }
  }
}

void CommandLine::problem(std::size_t position, InvalidInput e) {
  if (!problem_ || position < problem_->position) problem_ = Problem{position, std::move(e)};
}

void CommandLine::check() const {
  if (problem_) throw problem_->error;
}

const CommandLine::Given* CommandLine::given(const std::string& name) const {
  for (auto it = given_.rbegin(); it != given_.rend(); ++it) {
    if (it->name == name) return &*it;
  }
  return nullptr;
}

namespace {
// "<option> <where>" for an error inside a table given by an option ("--blade-table t.csv:4:
// m"); the text options' tables are named by the option already ("--blade-csv:4: m").
std::string option_named(const std::string& spelling, const std::string& name) {
  return name.rfind(spelling, 0) == 0 ? name : spelling + " " + name;
}
}  // namespace

// --blade-table FILE / --blade-csv TEXT: the blade table into r.params.  The fields the table
// sets may not be given as well.
void CommandLine::apply_blade(Request& r) const {
  const Given* file = given("--blade-table");
  const Given* text = given("--blade-csv");
  if (file == nullptr && text == nullptr) return;
  if (file != nullptr && text != nullptr)
    throw InvalidInput(text->spelling, "...", "not with --blade-table (one blade table)");
  const Given* g = file != nullptr ? file : text;
  std::string source = "--blade-csv";
  if (file != nullptr) {
    if (file->text.empty()) throw InvalidInput(file->spelling, "\"\"", "empty file name");
    r.blade_csv =
        read_text_file(file->text, kMaxCaseBytes, "blade table", "blade table cannot be read");
    source = file->text;
  } else {
    r.blade_csv = text->text;
  }
  BladeTable table;
  try {
    table = parse_blade_table(r.blade_csv, source);
  } catch (const InvalidInput& e) {
    throw InvalidInput(option_named(g->spelling, e.name()), e.value(), e.reason());
  }
  for (const std::string& field : blade_table_fields(table.dimensional)) {
    const OptionSpec* o = option_for_library_name(r.command, field);
    if (o == nullptr) continue;
    if (const Given* also = given(o->name)) {
      throw InvalidInput(also->spelling, shown(also->text),
                         std::string("not with ") + (table.dimensional ? "a dimensional " : "a ") +
                             "blade table (" + g->spelling + " " + shown(g->text.substr(0, 60)) +
                             " sets it)");
    }
  }
  try {
    apply_blade_table(table, r.params);
  } catch (const InvalidInput& e) {
    throw InvalidInput(option_named(g->spelling, e.name()), e.value(), e.reason());
  }
}

// --mode-shapes FILE / --mode-shapes-csv TEXT: imported mode shapes into r.params.
void CommandLine::apply_mode_shapes(Request& r) const {
  const Given* file = given("--mode-shapes");
  const Given* text = given("--mode-shapes-csv");
  if (file == nullptr && text == nullptr) return;
  if (file != nullptr && text != nullptr)
    throw InvalidInput(text->spelling, "...", "not with --mode-shapes (one mode file)");
  const Given* g = file != nullptr ? file : text;
  std::string source = "--mode-shapes-csv";
  if (file != nullptr) {
    if (file->text.empty()) throw InvalidInput(file->spelling, "\"\"", "empty file name");
    r.mode_shapes_csv =
        read_text_file(file->text, kMaxCaseBytes, "mode file", "mode file cannot be read");
    source = file->text;
  } else {
    r.mode_shapes_csv = text->text;
  }
  try {
    r.params.mode_shapes =
        std::make_shared<const ImportedModes>(parse_mode_table(r.mode_shapes_csv, source));
  } catch (const InvalidInput& e) {
    throw InvalidInput(option_named(g->spelling, e.name()), e.value(), e.reason());
  }
}

// The options are read in a fixed order (rotor, transition, output, model, the subcommand's own,
// trim, run-wide), so that of several bad options the same one is always named first.
Request CommandLine::interpret() const {
  check();
  Request r;
  r.command = command_;
  interpret_rotor(r);
  const ModeCounts modes = interpret_mode_counts();
  interpret_tables(r);
  interpret_transition(r);
  interpret_output(r);
  if (command_ != Command::Models && command_ != Command::Modes) interpret_model(r, modes);
  interpret_subcommand(r, modes);
  interpret_trim(r);
  if (command_ == Command::Study || command_ == Command::Map) interpret_batch(r);
  interpret_run_options(r);
  check_run_memory(r);
  return r;
}

const CommandLine::Given& CommandLine::required(const char* name) const {
  const Given* g = given(name);
  if (g == nullptr) throw InvalidInput(name, kMissing, "required by " + full_name(command_));
  return *g;
}

// Rotor parameters, in table order, then the blade table and the mode file over them.
void CommandLine::interpret_rotor(Request& r) const {
  const Command c = command_;
  for (const OptionSpec& o : options_of(c)) {
    if (o.rotor == nullptr) continue;
    if (const Given* g = given(o.name)) set_parameter(r.params, o, g->text);
  }
  apply_blade(r);
  apply_mode_shapes(r);
  if (c != Command::Models && c != Command::Modes) validate(r.params);
}

CommandLine::ModeCounts CommandLine::interpret_mode_counts() const {
  ModeCounts m;
  m.flap_given = given("--flap-modes");
  m.lag_given = given("--lag-modes");
  if (m.flap_given)
    m.flap = parse_int(m.flap_given->spelling, m.flap_given->text, 1, model::kMaxModes);
  if (m.lag_given) m.lag = parse_int(m.lag_given->spelling, m.lag_given->text, 1, model::kMaxModes);
  return m;
}

// The options made from the options structs' tables (options.h), in help order.
void CommandLine::interpret_tables(Request& r) const {
  for (const OptionSpec& o : options_of(command_)) {
    if (!o.set) continue;
    if (const Given* g = given(o.name)) o.set(r, g->spelling, g->text);
  }
}

// --steps (N or auto; --method, --terms and --zeta-tolerance are table options).
void CommandLine::interpret_transition(Request& r) const {
  if (const Given* g = given("--steps")) {
    r.transition.steps = g->text == "auto"
                             ? TransitionOptions::kAutomatic
                             : parse_int(g->spelling, g->text, 1, TransitionOptions::kMaxSteps);
  }
}

// --json, -o.
void CommandLine::interpret_output(Request& r) const {
  r.json = given("--json") != nullptr;
  if (const Given* g = given("-o")) {
    if (g->text.empty()) throw InvalidInput(g->spelling, shown(g->text), "empty file name");
    r.output = g->text == "-" ? "" : g->text;
  }
}

// The model of an analysis: --spec (and its --audit), and --flap-modes M --lag-modes N, which
// select the model "<model>-<M>x<N>" (1x1 is <model> itself).
void CommandLine::interpret_model(Request& r, const ModeCounts& modes) const {
  // --spec FILE.toml: the model is derived from the file now (runtime_spec.h).
  if (const Given* g = given("--spec")) {
    if (const Given* m = given("--model"))
      throw InvalidInput(m->spelling, shown(m->text), "not with --spec (the spec is the model)");
    try {
      r.params.model = spec::load_spec(g->text).name;
    } catch (const InvalidInput& e) {
      throw InvalidInput(g->spelling, shown(g->text), e.reason());
    }
  }
  if (const Given* g = given("--audit")) {
    if (given("--spec") == nullptr)
      throw InvalidInput(g->spelling, shown(g->text),
                         "needs --spec (the report of a compiled model is generated/<model>.md)");
    if (g->text.empty()) throw InvalidInput(g->spelling, shown(g->text), "empty file name");
    r.audit = g->text;
  }
  if (modes.flap_given || modes.lag_given) {
    if ((modes.flap > 1 || modes.lag > 1) && r.params.modes == ModeKind::Assumed) {
      const Given* many = modes.flap > 1 ? modes.flap_given : modes.lag_given;
      throw InvalidInput(many->spelling, shown(many->text),
                         "more than one mode needs --modes exact (the assumed mode of eq 4.1 "
                         "is one flap and one lag mode)");
    }
    std::string why;
    const model::ModelDescriptor* named = compiled_model(r.params.model, &why);
    if (named == nullptr) {
      const Given* g = given("--model");
      throw InvalidInput(g != nullptr ? g->spelling : "--model", shown(r.params.model), why);
    }
    r.params.model = find_model(named->base, modes.flap, modes.lag).name;
    // Galerkin's method gives at most --basis rotating modes per direction: the converged
    // basis (the default, 12) holds every mode count; with --basis N the library refuses a
    // basis below them, naming --basis.
  } else if (std::string why; compiled_model(r.params.model, &why) == nullptr) {
    const Given* g = given("--model");
    throw InvalidInput(g != nullptr ? g->spelling : "--model", shown(r.params.model), why);
  }
}

// The options of the subcommand itself.
void CommandLine::interpret_subcommand(Request& r, const ModeCounts& modes) const {
  const Command c = command_;
  switch (c) {
    case Command::Point:
    case Command::System: {
      const Given& mu = required("--mu");
      // The range (0..kMaxAdvanceRatio) is the library's to check; its error names `mu`.
      r.mu = parse_real(mu.spelling, mu.text);
      if (c == Command::System) {
        if (const Given* g = given("--psi")) r.psi = parse_real(g->spelling, g->text);
      }
      if (const Given* g = given("--scan-step")) r.scan_step = parse_real(g->spelling, g->text);
      break;
    }
    case Command::Sweep:
      interpret_sweep(r);
      break;
    case Command::Critical:  // --mu-max, --scan-step: table options
      break;
    case Command::Models:
      if (const Given* g = given("--spec")) {
        if (std::string why; compiled_model(g->text, &why) == nullptr)
          throw InvalidInput(g->spelling, shown(g->text), why);
        r.spec = g->text;
      }
      break;
    case Command::Modes:
      interpret_modes(r, modes);
      break;
    case Command::Study: {
      const Given& v = required("--vary");
      parse_axis(v.spelling, v.text, false, r.vary, r.vary_values);
      break;
    }
    case Command::Map:
      interpret_map(r);
      break;
    case Command::Response: {
      const Given& mu = required("--mu");
      r.mu = parse_real(mu.spelling, mu.text);
      if (const Given* g = given("--samples"))
        r.response.samples = parse_int(g->spelling, g->text, 12, 100000);
      break;
    }
    case Command::Simulate:
      interpret_simulate(r);
      break;
    case Command::Merge:
      if (inputs_.empty())
        throw InvalidInput("argument", kMissing,
                           "flaplag merge needs the parts: flaplag merge PART.json... -o OUT.json");
      r.inputs = inputs_;
      break;
    case Command::Plot:
      interpret_plot(r);
      break;
    case Command::Trim: {
      const Given& mu = required("--mu");
      r.mu = parse_real(mu.spelling, mu.text);
      r.trim.kind = TrimKind::Thrust;
      break;
    }
    case Command::Campbell:
      interpret_campbell(r);
      break;
    case Command::Typical:
      break;
  }
}

// sweep: --mu A:B:STEP, --format.
void CommandLine::interpret_sweep(Request& r) const {
  const Given& mu = required("--mu");
  const Range range = parse_range(mu.spelling, mu.text);
  r.sweep_start = range.start;
  r.sweep_stop = range.stop;
  r.sweep_step = range.step;
  if (const Given* g = given("--format")) {
    if (g->text == "csv")
      r.csv = true;
    else if (g->text != "table")
      throw InvalidInput(g->spelling, shown(g->text), "must be table or csv");
    if (r.csv && r.json)
      throw InvalidInput(g->spelling, shown(g->text), "cannot be combined with --json");
  }
}

// modes: the basis and the mode counts it holds, --nonrotating, --points, --export-shapes.
void CommandLine::interpret_modes(Request& r, const ModeCounts& modes) const {
  // Every rotor option is accepted (one option string serves every subcommand) and checked;
  // the modes use the blade's.
  validate(r.params);
  if (r.params.basis == kElementBasis) {
    const Given* b = given("--basis");
    throw InvalidInput(b ? b->spelling : "--basis", b ? shown(b->text) : "elements",
                       "flaplag modes shows the Galerkin modes and their Fig 9 relation "
                       "(--basis 1..12, converged or paper); the finite elements' "
                       "frequencies are in every analysis result's hover exponents");
  }
  const int basis = galerkin_basis(r.params);
  if (modes.flap > basis) {
    throw InvalidInput(modes.flap_given->spelling, shown(modes.flap_given->text),
                       "must not exceed --basis = " + std::to_string(basis));
  }
  if (modes.lag > basis) {
    throw InvalidInput(modes.lag_given->spelling, shown(modes.lag_given->text),
                       "must not exceed --basis = " + std::to_string(basis));
  }
  const Given* nr = given("--nonrotating");
  const std::string spelling = nr ? nr->spelling : "--nonrotating";
  const std::string text = nr ? nr->text : "0:2.5:0.1";
  const Range range = parse_range(spelling, text);
  if (range.count < 2) {
    throw InvalidInput(spelling, shown(text), "STEP exceeds the range: need 2 points or more");
  }
  r.fig9_from = range.start;
  r.fig9_to = range.stop;
  r.fig9_step = range.step;
  r.fig9_points = range.count;
  if (const Given* g = given("--points")) {
    r.shape_points = parse_int(g->spelling, g->text, 2, kMaxPoints);
  }
  if (const Given* g = given("--export-shapes")) {
    if (g->text.empty()) throw InvalidInput(g->spelling, shown(g->text), "empty file name");
    if (g->text == "-")
      throw InvalidInput(g->spelling, shown(g->text),
                         "needs a file (standard output carries the modes' table)");
    r.export_shapes = g->text;
  }
  r.flap_modes = modes.flap;
  r.lag_modes = modes.lag;
}

// map: --x, --y, --mu, --scan-step.
void CommandLine::interpret_map(Request& r) const {
  const Given& x = required("--x");
  const Given& y = required("--y");
  parse_axis(x.spelling, x.text, true, r.x_name, r.x_values);
  parse_axis(y.spelling, y.text, true, r.y_name, r.y_values);
  if (r.x_name == r.y_name)
    throw InvalidInput(y.spelling, shown(y.text), "must vary another quantity than --x");
  if (const Given* g = given("--mu")) {
    if (r.x_name == "mu" || r.y_name == "mu")
      throw InvalidInput(g->spelling, shown(g->text), "mu is already an axis");
    r.mu = parse_real(g->spelling, g->text);
  }
  if (const Given* g = given("--scan-step")) r.scan_step = parse_real(g->spelling, g->text);
}

// simulate: --mu, --perturbation, --forced, --nonlinear (--revs, --samples: table options).
void CommandLine::interpret_simulate(Request& r) const {
  const Given& mu = required("--mu");
  r.mu = parse_real(mu.spelling, mu.text);
  if (const Given* g = given("--perturbation")) r.perturbation = parse_real(g->spelling, g->text);
  r.forced = given("--forced") != nullptr;
  r.simulation.nonlinear = given("--nonlinear") != nullptr;
}

// plot: the data files, --plot, --label per file, --max-zeta, --mode.
void CommandLine::interpret_plot(Request& r) const {
  if (inputs_.empty())
    throw InvalidInput("argument", kMissing,
                       "flaplag plot needs the data: flaplag plot DATA.json... --plot "
                       "FILE.svg");
  required("--plot");
  r.inputs = inputs_;
  // --label may be repeated: one per data file, in order.
  for (const Given& g : given_)
    if (g.name == "--label") r.labels.push_back(g.text);
  if (!r.labels.empty() && r.labels.size() != r.inputs.size())
    throw InvalidInput("--label", shown(r.labels.back()),
                       std::to_string(r.labels.size()) + " given for " +
                           std::to_string(r.inputs.size()) +
                           " data files (one --label per file, in order)");
  r.max_zeta = given("--max-zeta") != nullptr;
  if (const Given* g = given("--mode")) {
    if (r.max_zeta) throw InvalidInput(g->spelling, shown(g->text), "does not go with --max-zeta");
    r.mode = g->text;
  }
}

// campbell: --speed-max, --speeds, --mu, --harmonics, --scan-step (table options) checked.
void CommandLine::interpret_campbell(Request& r) const {
  r.campbell.Check();  // errors name the option's field
}

// --trim, --thrust-coefficient, --shaft-angle.
void CommandLine::interpret_trim(Request& r) const {
  const Command c = command_;
  if (const Given* g = given("--trim")) {
    if (!trim_kind_from_name(g->text, &r.trim.kind) ||
        (c == Command::Trim && r.trim.kind == TrimKind::None)) {
      throw InvalidInput(
          g->spelling, shown(g->text),
          c == Command::Trim ? "must be thrust or moment" : "must be none, thrust or moment");
    }
  }
  if (r.trim.kind != TrimKind::None) r.trim.Check();  // errors name the option's field
  interpret_inflow(r);
  // Without a trim or the momentum inflow they would be ignored: an answer for another rotor
  // than the one described.
  if (r.trim.kind == TrimKind::None && r.inflow.kind != InflowKind::Momentum) {
    const bool takes_trim = find_option(c, "--trim") != nullptr;
    for (const char* name : {"--thrust-coefficient", "--shaft-angle"}) {
      if (const Given* g = given(name))
        throw InvalidInput(g->spelling, shown(g->text),
                           takes_trim
                               ? "applies only with --trim thrust|moment or --inflow momentum"
                               : "applies only with --inflow momentum");
    }
  }
}

// --inflow (after the trim, which it must not be given with): the momentum inflow of eq 2.25
// for --thrust-coefficient and --shaft-angle.
void CommandLine::interpret_inflow(Request& r) const {
  const Given* g = given("--inflow");
  if (g == nullptr) return;
  InflowKind kind = InflowKind::Uniform;
  if (!enum_from_name(g->text, &kind) || kind == InflowKind::Given)
    throw InvalidInput(g->spelling, shown(g->text), "must be one of " + inflow_kind_names(", "));
  if (kind != InflowKind::Momentum) return;
  if (r.trim.kind != TrimKind::None)
    throw InvalidInput(g->spelling, shown(g->text),
                       std::string("not with --trim ") + trim_kind_name(r.trim.kind) +
                           " (the trim solves eq 2.25 itself, with its own inflow at every mu)");
  if (given("--thrust-coefficient") == nullptr)
    throw InvalidInput(g->spelling, shown(g->text),
                       "needs --thrust-coefficient (the C_T of eq 2.25, not C_T/sigma)");
  r.inflow = InflowModel::Momentum(r.trim.thrust_coefficient, r.trim.shaft_angle);
  r.inflow.Check();  // errors name the option's field (thrust_coefficient, shaft_angle)
}

// The options of any run: --threads, --plot, --report, --damping-criterion, --plot-quantity,
// --memory-limit.
void CommandLine::interpret_run_options(Request& r) const {
  if (const Given* g = given("--threads"))
    r.threads = parse_int(g->spelling, g->text, 0, kMaxThreads);
  if (const Given* g = given("--plot")) {
    if (!is_plot_path(g->text))
      throw InvalidInput(g->spelling, shown(g->text), "must end in .svg or .png");
    r.plot = g->text;
  }
  if (const Given* g = given("--report")) {
    if (!is_report_path(g->text))
      throw InvalidInput(g->spelling, shown(g->text), "must end in .html or .htm");
    if (r.shard_count > 0)
      throw InvalidInput(g->spelling, shown(g->text),
                         "a report covers the whole job, not one --shard part: flaplag merge the "
                         "parts, then flaplag report MERGED.json");
    r.report = g->text;
  }
  if (const Given* g = given("--damping-criterion")) {
    const double v = parse_real(g->spelling, g->text);
    if (!kDampingCriterionRange.interval.Contains(v))
      throw InvalidInput(g->spelling, shown(g->text),
                         std::string("must be ") + kDampingCriterionRange.words);
    r.damping_criterion = v;
  }
  if (const Given* g = given("--plot-quantity")) {
    if (g->text != "damping-ratio" && g->text != "zeta")
      throw InvalidInput(g->spelling, shown(g->text), "must be damping-ratio or zeta");
    if (r.max_zeta)
      throw InvalidInput(g->spelling, shown(g->text), "does not go with --max-zeta (zeta)");
    r.plot_zeta = g->text == "zeta";
  }
  if (const Given* g = given("--memory-limit"))
    r.memory_limit = parse_memory_size(g->spelling, g->text);
}

std::optional<std::string> CommandLine::error_line(const InvalidInput& e) const {
  // Raised by the CLI itself: already named by the option as typed.
  if (!e.name().empty() && e.name()[0] == '-') {
    return e.name() + " = " + e.value() + ": " + vocabulary(e.reason());
  }
  if (e.name() == "subcommand" || e.name() == "argument") return std::string(e.what());
  const OptionSpec* o = option_for_library_name(command_, e.name());
  if (o == nullptr) return std::nullopt;
  const Given* g = given(o->name);
  std::string value = e.value();
  if (g != nullptr && o->takes_value) value = shown(g->text);
  // A flag of the run (not a rotor flag, whose option may turn its field off) is on as given.
  if (g != nullptr && !o->takes_value && o->rotor == nullptr) value = "true";
  return (g != nullptr ? g->spelling : o->name) + " = " + value + ": " + vocabulary(e.reason());
}

std::string CommandLine::vocabulary(const std::string& message) const {
  return in_cli_vocabulary(command_, message);
}

std::string CommandLine::help_text() const {
  const Command c = command_;
  std::string out;
  if (c == Command::Typical) {
    out +=
        "flaplag: coupled flap-lag stability of a hingeless rotor blade in forward flight\n"
        "(Friedmann & Silverthorn, NASA CR-132431, 1974)\n\n"
        "Usage: flaplag [SUBCOMMAND] [OPTIONS]   (options before or after the subcommand)\n\n";
    out += wrap("Without a subcommand: " + std::string(description(c)) + ".", 0, 0) +
           "\n\nSubcommands (flaplag SUBCOMMAND --help):\n";
    for (Command s : subcommands()) {
      const std::string n = command_name(s);
      out += "  " + n + std::string(12 - n.size(), ' ') + description(s) + "\n";
    }
    out += "  run         " + std::string(kRunDescription) + "\n";
    out += "  report      " + std::string(kReportDescription) + "\n";
  } else {
    std::string usage = full_name(c);
    if (c == Command::Point || c == Command::System || c == Command::Trim) usage += " --mu REAL";
    if (c == Command::Sweep) usage += " --mu A:B:STEP";
    if (c == Command::Study) usage += " --vary NAME=...";
    if (c == Command::Map) usage += " --x NAME=... --y NAME=...";
    if (c == Command::Merge) usage += " PART.json...";
    if (c == Command::Plot) usage += " DATA.json... --plot FILE.svg|FILE.png";
    out += "Usage: " + usage + " [OPTIONS]\n\n" + description(c) + "\n";
    out += usage_notes(c);
  }
  out += "\nOptions:\n" + options_block(options_of(c));
  out += "  -h, --help                  this help\n";
  out += "  --version                   the version\n";
  out += "\nExamples:\n";
  for (const std::string& x : examples(c)) out += "  " + x + "\n";
  out +=
      "\nExit codes: 0 a result (an unstable blade or an unresolved computation is a result with a "
      "status);\n2 bad input, one line on stderr: flaplag: error: <option> = <value>: <reason>\n";
  if (c == Command::Study || c == Command::Map)
    out +=
        "130 interrupted (Ctrl-C), 143 stopped by SIGTERM: the rows finished are written, status "
        "\"cancelled\"\n";
  if (c == Command::Plot) out += "3 gnuplot is missing or failed: no picture written\n";
  return out;
}

std::string CommandLine::run_help_text() {
  return "Usage: flaplag run CASE [OPTIONS]\n\n" + std::string(kRunDescription) +
         ".\n\nCASE is a TOML file whose keys are the option names without \"--\" (command = "
         "\"study\",\nvary = \"omega-lag=0.2:2.5:0.05\", theta = 0.1, json = true; tables "
         "such as [parameters]\nonly group keys), or any --json output of flaplag: its \"case\" "
         "object reproduces it byte\nfor byte.  Options typed after CASE override the file; they "
         "are the options of the\ncase's subcommand (flaplag SUBCOMMAND --help lists them).\n"
         "\nOptions:\n  -h, --help                  this help\n"
         "\nExamples:\n"
         "  flaplag run examples/fig15.toml\n"
         "  flaplag run examples/fig12.toml --json -o fig12.json\n"
         "  flaplag run fig12.json                    the same bytes again\n"
         "\nExit codes: those of the case's subcommand; 2 also for a case file that cannot be read "
         "or\nhas an unknown key, a wrong type or a bad value (named by file, line and key).\n";
}

std::string CommandLine::report_help_text() {
  return "Usage: flaplag report CASE [OPTIONS] [-o FILE.html]\n\n" +
         std::string(kReportDescription) +
         ".\n\nA self-contained page (inline SVG pictures, no script, no network) with the "
         "outcome and\nevery warning in plain words, the model and its assumptions, the inputs "
         "with their\nsymbols and units, the results with their status and error estimates, the "
         "convergence\nevidence, the pictures, and the flaplag version, commit and command that "
         "reproduce it.\n\nCASE is a TOML case file (flaplag run --help): it is run now, with "
         "the options typed\nafter it overriding the file's.  Or CASE is a --json output of "
         "flaplag: its result is\nreported as it was computed (nothing is recomputed; its "
         "strings are shown as text,\nnever run); only -o and --memory-limit apply then.  Any "
         "analysis command also takes\n--report FILE.html to write the report beside its usual "
         "output.\n"
         "\nOptions:\n  -o, --output FILE.html      the page (default: standard output)\n"
         "  -h, --help                  this help\n"
         "\nExamples:\n"
         "  flaplag report examples/fig03.toml -o fig03.html\n"
         "  flaplag report study.json -o study.html   a result computed elsewhere\n"
         "  flaplag critical --theta 0.1 --report critical.html\n"
         "\nExit codes: those of the case's subcommand; 2 also for a file that is neither a case "
         "nor\na flaplag result, and for -o that does not end in .html or .htm.\n";
}

void CommandLine::interpret_batch(Request& r) const {
  r.quiet = given("--quiet") != nullptr;
  const Given* g = given("--shard");
  if (g == nullptr) return;
  const std::string value = shown(g->text);
  const auto slash = g->text.find('/');
  if (slash == std::string::npos)
    throw InvalidInput(g->spelling, value, "expected I/N: part I of N, 1 <= I <= N (e.g. 2/8)");
  int count = 0;
  try {
    count = parse_int(g->spelling, g->text.substr(slash + 1), 1, kMaxShards);
    r.shard_index = parse_int(g->spelling, g->text.substr(0, slash), 1, count);
  } catch (const InvalidInput& e) {
    throw InvalidInput(g->spelling, value,
                       std::string(count == 0 ? "N " : "I ") + e.reason() + " (expected I/N)");
  }
  r.shard_count = count;
  if (!r.json)
    throw InvalidInput(g->spelling, value,
                       "needs --json: the parts are JSON files that flaplag merge joins");
}

}  // namespace flaplag::cli
