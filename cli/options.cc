#include "options.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <system_error>
#include <type_traits>

#include "command_line.h"
#include "flaplag/campbell.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/fields.h"
#include "flaplag/core/format.h"
#include "flaplag/limits.h"
#include "flaplag/model_api.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/numerics/floquet.h"
#include "flaplag/rotor/inflow.h"
#include "flaplag/study.h"
#include "flaplag/trim.h"

namespace flaplag::cli {

namespace {

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v'; }

// An option's word is the field's JSON key.
std::string kebab(std::string_view field) { return documents::json_word(field); }

OptionSpec value_option(std::string name, std::string metavar, std::string help,
                        std::string default_text, std::vector<std::string> library_names) {
  OptionSpec o;
  o.name = std::move(name);
  o.takes_value = true;
  o.metavar = std::move(metavar);
  o.help = std::move(help);
  o.default_text = std::move(default_text);
  o.library_names = std::move(library_names);
  return o;
}

OptionSpec flag_option(std::string name, std::string help) {
  OptionSpec o;
  o.name = std::move(name);
  o.help = std::move(help);
  return o;
}

// ---- options of the options structs' tables (core/fields.h) ----------------------------------

template <class V>
V parse_value(const std::string& spelling, const std::string& text, const Range* range) {
  if constexpr (std::is_same_v<V, double>) {
    return parse_real(spelling, text);
  } else if constexpr (std::is_same_v<V, int>) {
    if (range == nullptr)
      return parse_int(spelling, text, std::numeric_limits<int>::min(),
                       std::numeric_limits<int>::max());
    return parse_int(spelling, text, static_cast<int>(range->interval.lo),
                     static_cast<int>(range->interval.hi));
  } else {
    static_assert(is_described_enum_v<V>, "an option of a type the command line cannot read");
    V v{};
    if (!enum_from_name(text, &v))
      throw InvalidInput(spelling, shown(text), "must be one of " + enum_names<V>(", "));
    return v;
  }
}

template <class V>
std::string value_text(const V& v) {
  if constexpr (std::is_same_v<V, double>) {
    return round_trip_text(v);
  } else if constexpr (std::is_same_v<V, int>) {
    return std::to_string(v);
  } else {
    return enum_name(v);
  }
}

// The option of the row `field` of O's table, which sets (r.*owner).field: "--" + kebab of the
// field unless `name` is given; metavar REAL, N or the enum's names unless `metavar` is given;
// help from the row's doc, units and range; default from O{}.  owner nullptr: the help of an
// option read by hand (a Request member of its own, shared with other subcommands), no setter.
template <class O>
OptionSpec table_option(O Request::*owner, std::string_view field, const char* name = nullptr,
                        const char* metavar = nullptr) {
  OptionSpec o;
  const bool found = visit_row<O>(field, [&](const auto& row) {
    using V = typename std::decay_t<decltype(row)>::value_type;
    o.name = name != nullptr ? name : kebab_option(row.name);
    o.library_names = {row.name};
    // "doc (units; range words)", as the rotor parameters' help.
    std::string note = row.units;
    if (note == "-") note.clear();
    o.help = row.doc;
    if constexpr (std::is_same_v<V, bool>) {
      if (!note.empty()) o.help += " (" + note + ")";
      if (owner != nullptr) {
        o.set = [owner, row](Request& r, const std::string&, const std::string&) {
          row.get(r.*owner) = true;
        };
      }
    } else if constexpr (std::is_same_v<V, std::optional<double>>) {
      // Help only: an optional number is off by default.
      const Range* range = row_range(row);
      o.takes_value = true;
      o.metavar = metavar != nullptr ? metavar : "REAL";
      if (range != nullptr) note += (note.empty() ? "" : "; ") + std::string(range->words);
      if (!note.empty()) o.help += " (" + note + ")";
    } else if constexpr (std::is_same_v<V, double> || std::is_same_v<V, int> ||
                         is_described_enum_v<V>) {
      const Range* range = row_range(row);
      o.takes_value = true;
      if (metavar != nullptr) {
        o.metavar = metavar;
      } else if constexpr (std::is_same_v<V, double>) {
        o.metavar = "REAL";
      } else if constexpr (std::is_same_v<V, int>) {
        o.metavar = "N";
      } else {
        o.metavar = enum_names<V>("|");
      }
      if (range != nullptr) note += (note.empty() ? "" : "; ") + std::string(range->words);
      if (!note.empty()) o.help += " (" + note + ")";
      o.default_text = value_text(row.get(O{}));
      if (owner != nullptr) {
        o.set = [owner, row, range](Request& r, const std::string& spelling,
                                    const std::string& text) {
          row.get(r.*owner) = parse_value<V>(spelling, text, range);
        };
      }
    }
  });
  if (!found || (owner != nullptr && !o.set))
    throw std::logic_error("no option row " + std::string(field));
  return o;
}

// One option per row of the runtime table.  A bool field gets the option that changes its
// default: "--no-<field>" for a field that is on by default, "--<field>" for one that is off.
OptionSpec rotor_option(const ParameterSpec& s) {
  const RotorParameters defaults;
  OptionSpec o;
  o.rotor = &s;
  o.library_names = {s.field};
  switch (s.type) {
    case ParameterType::Real:
    case ParameterType::Integer:
    case ParameterType::Text:
    case ParameterType::Choice:
      o.name = kebab_option(s.field);
      o.takes_value = true;
      o.metavar = s.type == ParameterType::Real      ? "REAL"
                  : s.type == ParameterType::Integer ? (s.names != nullptr ? "N|NAME" : "N")
                  : s.type == ParameterType::Text    ? "NAME"
                                                     : s.choices;
      o.help = s.description;
      o.default_text = parameter_text(defaults, s);
      break;
    case ParameterType::Flag: {
      const bool on_by_default = defaults.*s.flag;
      o.name = on_by_default ? "--no-" + kebab(s.field) : kebab_option(s.field);
      o.flag_value = !on_by_default;
      o.help = std::string(on_by_default ? "without " : "with ") + s.description;
      break;
    }
  }
  // The basis row is ExactModeOptions::n_basis, which the blade layer names in its messages.
  if (s.type == ParameterType::Integer && s.integer == &RotorParameters::basis)
    o.library_names.push_back("n_basis");
  return o;
}

std::vector<OptionSpec> rotor_options() {
  std::vector<OptionSpec> v;
  for (const ParameterSpec& s : parameter_table()) v.push_back(rotor_option(s));
  // Part of the operating condition (OperatingCondition::linearization), not of the rotor; the
  // option every command takes, as the rotor's.
  OptionSpec periodic = flag_option(
      "--periodic-linearization",
      "with the linearization about the periodic equilibrium of the nonlinear equations instead "
      "of hover");
  periodic.library_names = {"linearization"};
  periodic.set = [](Request& r, const std::string&, const std::string&) {
    r.linearization = Linearization::PeriodicEquilibrium;
  };
  v.push_back(std::move(periodic));
  // A nonuniform blade: the table's file, or its text (what a JSON result's case records).
  v.push_back(value_option(
      "--blade-table", "TABLE.csv",
      "a blade property table (columns x or r, m, EI_flap, EI_lag, chord, twist_deg; "
      "docs/your-blade.md): the blade's mass, stiffness, chord and twist along the span; sets "
      "--modes exact, --root-offset and --length-ratio (and, for a dimensional table, --gamma, "
      "--sigma, --omega-flap, --omega-lag); relative to the case file in a case",
      "", {"blade"}));
  v.push_back(value_option(
      "--mode-shapes", "MODES.csv",
      "flap and lag mode shapes and rotating frequencies from a mode file (e.g. an FE model; "
      "columns x0, flap1.., lag1.., an omega row; docs/your-blade.md) instead of computed ones; "
      "needs --modes exact; relative to the case file in a case",
      "", {"mode_shapes"}));
  v.push_back(value_option("--mode-shapes-csv", "TEXT",
                           "the text of a mode file (as --mode-shapes; what a JSON result records "
                           "of it)",
                           "", {}));
  v.push_back(value_option("--blade-csv", "TEXT",
                           "the text of a blade table (as --blade-table; what a JSON result "
                           "records of it)",
                           "", {}));
  return v;
}

std::vector<OptionSpec> transition_options() {
  return {
      table_option(&Request::transition, "method"),
      value_option(
          "--steps", "N|auto",
          "RK4 steps, Hsu intervals K or Magnus steps per period, 1.." +
              std::to_string(TransitionOptions::kMaxSteps) +
              "; auto: raised from the error estimates until the exponents meet --zeta-tolerance",
          "auto", {"steps"}),
      table_option(&Request::transition, "terms", nullptr, "J"),
      table_option(&Request::transition, "zeta_tolerance"),
  };
}

std::vector<OptionSpec> mode_count_options() {
  return {
      value_option("--flap-modes", "M",
                   "flap modes M, 1.." + std::to_string(model::kMaxModes) +
                       ": selects the model <model>-<M>x<N> (<model> itself for 1x1; more than "
                       "one mode needs --modes exact and at most --basis modes per direction)",
                   "1", {"flap_modes"}),
      value_option("--lag-modes", "N", "lag modes N (see --flap-modes)", "1", {"lag_modes"}),
  };
}

// A model derived at run time from an ordering spec file (runtime_spec/): no build needed.
std::vector<OptionSpec> spec_options() {
  return {
      value_option("--spec", "SPEC.toml",
                   "derive the model of this ordering spec file now (GiNaC) instead of using a "
                   "compiled one: the model spec:<name>, any --flap-modes/--lag-modes; a `base` "
                   "is looked up in the file's directory; not with --model",
                   "", {"spec"}),
      value_option("--audit", "FILE.md",
                   "with --spec: also write the spec's audit report (every term with its eps "
                   "order, origin and paper name) to FILE.md",
                   "", {"audit"}),
  };
}

// Trim (runtime/analysis trim.h): a trimmed rotor at every mu (point, sweep, critical, trim).
std::vector<OptionSpec> trim_options(bool for_trim_command) {
  OptionSpec ct = table_option(&Request::trim, "thrust_coefficient");
  OptionSpec alpha = table_option(&Request::trim, "shaft_angle");
  if (!for_trim_command) {
    ct.help += "; with --inflow momentum the C_T of its eq 2.25 (then required)";
    alpha.help += "; also of --inflow momentum";
  }
  return {
      value_option("--trim", for_trim_command ? "thrust|moment" : "none|thrust|moment",
                   "trim at each mu: thrust (theta0, lambda of eq 2.25 for --thrust-coefficient) "
                   "or moment (also theta1c, theta1s: no first flap harmonic); with "
                   "--periodic-linearization the periodic equilibrium is trimmed",
                   for_trim_command ? "thrust" : "none", {"trim"}),
      ct,
      alpha,
  };
}

// The commands that analyse fixed controls through an Analysis of the case's rotor: --inflow,
// and (those without --trim) the C_T and alpha_R of its eq 2.25.
std::vector<OptionSpec> inflow_options(bool with_trim) {
  std::vector<OptionSpec> v = {value_option(
      "--inflow", inflow_kind_names("|"),
      "the inflow at fixed controls: uniform (eq 2.24, the paper: the hover inflow at --theta, "
      "held at every mu) or momentum (eq 2.25 at every mu for --thrust-coefficient and "
      "--shaft-angle: sqrt(C_T/2) in hover); not with --trim thrust|moment, which solves eq "
      "2.25 itself",
      "uniform", {"inflow"})};
  if (!with_trim) {
    // The trim's rows, read as eq 2.25's inputs: no trim here, and no default C_T (required).
    OptionSpec ct = table_option(&Request::trim, "thrust_coefficient");
    ct.help =
        "with --inflow momentum (required): the thrust coefficient C_T of eq 2.25 (in (0, "
        "0.1], C_T, not C_T/sigma)";
    ct.default_text.clear();
    OptionSpec alpha = table_option(&Request::trim, "shaft_angle");
    alpha.help =
        "with --inflow momentum: the shaft angle alpha_R of eq 2.25 (rad; in (-pi/2, "
        "pi/2))";
    v.push_back(ct);
    v.push_back(alpha);
  }
  return v;
}

std::vector<OptionSpec> output_options() {
  OptionSpec o = value_option("-o", "FILE",
                              "write to FILE instead of stdout (- is stdout; a file is replaced "
                              "atomically, a device or FIFO written through)",
                              "", {"output"});
  o.alias = "--output";
  return {flag_option("--json", "write JSON instead of text"), o};
}

// Every command with a result (not models, merge, plot): the page of the result (report.h).
OptionSpec report_option() {
  return value_option("--report", "FILE.html",
                      "also write a one-page HTML report of the result: outcome, model, inputs, "
                      "results with status and error estimates, convergence, pictures, warnings, "
                      "provenance",
                      "", {"report"});
}

void append(std::vector<OptionSpec>& to, const std::vector<OptionSpec>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

// The long runs (study, map): one part of a batch job, and the progress bar.
std::vector<OptionSpec> batch_options() {
  return {
      value_option("--shard", "I/N",
                   "compute part I of N (I = 1..N, e.g. $SLURM_ARRAY_TASK_ID/N): a contiguous "
                   "block of the rows (of the columns when --y is mu); needs --json; "
                   "flaplag merge joins the parts",
                   "", {"shard"}),
      flag_option("--quiet", "no progress bar on stderr (shown only on a terminal, after 1 s)")};
}

// The runs whose size the user chooses (cells, values, points, samples): their memory is
// estimated before they start and checked against this budget (limits.h).
OptionSpec memory_limit_option() {
  return value_option("--memory-limit", "SIZE",
                      "the memory this run may take, e.g. 512M, 8G (units K, M, G, T: powers of "
                      "1024); a larger run is refused before it starts, naming its estimate",
                      memory_text(kDefaultMemoryLimit), {"memory_limit"});
}

// The y quantity of a sweep picture: sweep --plot and flaplag plot of a sweep's file.
OptionSpec plot_quantity_option() {
  return value_option("--plot-quantity", "damping-ratio|zeta",
                      "y quantity of a sweep picture: the damping ratio -zeta/|lambda| in % of "
                      "critical (with the damping criterion's line) or the exponent zeta [1/rev]",
                      "damping-ratio", {"plot_quantity"});
}

// flaplag merge and flaplag plot read files given as arguments.
std::vector<OptionSpec> file_tool_options(Command c) {
  if (c == Command::Merge) return {output_options()[1], memory_limit_option()};  // -o: JSON
  return {
      memory_limit_option(),
      value_option("--plot", "FILE.svg|FILE.png", "the picture to draw (gnuplot)", "", {"plot"}),
      value_option("--label", "TEXT",
                   "the label of a data file's curves (repeated: one per file, in order; "
                   "default: from the file's case)",
                   "", {"label"}),
      flag_option("--max-zeta", "sweeps: only the largest zeta over the modes at each mu"),
      value_option("--mode", "NAME",
                   "sweeps: only the curves of this mode, by its label (flap, lag, lag2, ...; "
                   "lag1 of older M x N files is lag)",
                   "", {"mode"}),
      plot_quantity_option()};
}

std::vector<OptionSpec> build(Command c) {
  std::vector<OptionSpec> v;
  const OptionSpec mu = value_option(
      "--mu", "REAL", "advance ratio (0.." + round_trip_text(kMaxAdvanceRatio) + ")", "", {"mu"});
  const OptionSpec scan_step = value_option(
      "--scan-step", "REAL", "continuation step in mu from hover (> 0)", "0.01", {"scan_step"});
  const OptionSpec threads = value_option(
      "--threads", "N", "worker threads (0: all cores; the answer does not depend on it)", "0",
      {"threads"});
  const OptionSpec damping_criterion = value_option(
      "--damping-criterion", "C",
      "damping ratio asked of every mode, a fraction of critical (0.01: 1 %), >= 0 and < 1: "
      "report the first mu where each mode's damping ratio -zeta/|lambda| falls below it",
      "", {"damping_criterion"});
  const OptionSpec plot_quantity = plot_quantity_option();
  switch (c) {
    case Command::Point:
      v.push_back(mu);
      v.push_back(scan_step);
      break;
    case Command::Sweep:
      v.push_back(value_option("--mu", "A:B:STEP",
                               "advance ratios A, A + STEP, ..., B (0 <= A < B <= " +
                                   round_trip_text(kMaxAdvanceRatio) + ", STEP > 0, B included)",
                               "", {"mu0", "mu1", "step", "mu"}));
      v.push_back(value_option("--format", "table|csv", "text layout (--json for JSON)", "table",
                               {"format"}));
      v.push_back(threads);
      v.push_back(value_option("--plot", "FILE.svg|FILE.png",
                               "also draw the damping ratio (or zeta) and omega of each mode "
                               "against mu (gnuplot)",
                               "", {"plot"}));
      v.push_back(plot_quantity);
      v.push_back(damping_criterion);
      break;
    case Command::Critical:
      v.push_back(table_option(&Request::critical, "mu_max"));
      v.push_back(table_option(&Request::critical, "scan_step"));
      v.push_back(threads);
      break;
    case Command::System:
      v.push_back(mu);
      v.push_back(value_option("--psi", "REAL", "azimuth [rad], any finite value", "0", {"psi"}));
      break;
    case Command::Models:
      v.push_back(
          value_option("--spec", "NAME", "print the ordering spec of this model", "", {"model"}));
      append(v, output_options());
      return v;
    case Command::Modes:
      // Every rotor option, so that one option string serves every subcommand; the modes use
      // omega-flap, omega-lag, length-ratio, root-offset, basis and paper-1974-shapes.
      append(v, rotor_options());
      v.push_back(value_option("--flap-modes", "M", "rotating flap modes shown (1..--basis)", "1",
                               {"flap_modes"}));
      v.push_back(value_option("--lag-modes", "N", "rotating lag modes shown (1..--basis)", "1",
                               {"lag_modes"}));
      v.push_back(value_option("--nonrotating", "A:B:STEP",
                               "Fig 9 table: first nonrotating frequencies (0 <= A < B, STEP > 0)",
                               "0:2.5:0.1", {"omega_nonrotating_lo", "omega_nonrotating_hi"}));
      v.push_back(value_option("--points", "K", "spanwise stations of the mode-shape table (>= 2)",
                               "11", {"n_points"}));
      v.push_back(value_option("--plot", "FILE.svg|FILE.png",
                               "also draw the flap and lag mode shapes and their slopes at the "
                               "--points stations (gnuplot)",
                               "", {"plot"}));
      v.push_back(value_option(
          "--export-shapes", "FILE.csv",
          "also write the --flap-modes x --lag-modes rotating mode shapes and frequencies as a "
          "mode file (CSV at " +
              std::to_string(kExportedModeStations) +
              " stations), the format a finite-element model's modes are imported in",
          "", {"export_shapes"}));
      append(v, output_options());
      v.push_back(report_option());
      return v;
    case Command::Study: {
      v.push_back(value_option("--vary", "NAME=START:STOP:STEP|NAME=V1,V2,...",
                               "the parameter varied (any numeric rotor parameter, e.g. "
                               "omega-lag, theta, damping-lag) and its values",
                               "", {"parameter", "values"}));
      v.push_back(table_option(&Request::critical, "mu_max"));
      v.push_back(table_option(&Request::critical, "scan_step"));
      // --threads and --damping-criterion are read for every subcommand (interpret_run_options).
      v.push_back(table_option<StudyOptions>(nullptr, "threads"));
      v.push_back(value_option("--plot", "FILE.svg|FILE.png",
                               "also draw mu_c and the instability intervals (gnuplot)", "",
                               {"plot"}));
      v.push_back(table_option<StudyOptions>(nullptr, "damping_criterion", nullptr, "C"));
      break;
    }
    case Command::Map:
      v.push_back(value_option("--x", "NAME=START:STOP:STEP|NAME=V1,...",
                               "x axis: mu or a numeric rotor parameter", "", {"x"}));
      v.push_back(value_option("--y", "NAME=START:STOP:STEP|NAME=V1,...",
                               "y axis: mu or a numeric rotor parameter", "", {"y"}));
      // Read in interpret_map (--mu only without a mu axis) and interpret_run_options.
      v.push_back(table_option<MapOptions>(nullptr, "mu"));
      v.push_back(table_option<MapOptions>(nullptr, "scan_step"));
      v.push_back(table_option<MapOptions>(nullptr, "threads"));
      v.push_back(value_option("--plot", "FILE.svg|FILE.png",
                               "also draw the max-zeta map with the zeta = 0 boundary (gnuplot)",
                               "", {"plot"}));
      break;
    case Command::Response:
      v.push_back(mu);
      v.push_back(value_option("--samples", "N", "azimuth samples over one revolution (>= 12)",
                               "72", {"samples"}));
      v.push_back(value_option("--plot", "FILE.svg|FILE.png",
                               "also draw the tip deflections over one revolution (gnuplot)", "",
                               {"plot"}));
      break;
    case Command::Simulate:
      v.push_back(mu);
      v.push_back(table_option(&Request::simulation, "revolutions", "--revs"));
      v.push_back(value_option("--perturbation", "REAL",
                               "initial perturbation of every state (free response)", "0.01",
                               {"perturbation"}));
      {
        OptionSpec forced =
            flag_option("--forced", "include the forcing f(psi) (default: free response)");
        forced.library_names = {"forced"};
        v.push_back(forced);
        OptionSpec nonlinear = flag_option(
            "--nonlinear",
            "integrate the nonlinear equations (full state, from the periodic equilibrium plus "
            "the perturbation; the tip response is the deviation from it; not with --forced)");
        nonlinear.library_names = {"nonlinear"};
        v.push_back(nonlinear);
      }
      v.push_back(table_option(&Request::simulation, "samples_per_rev", "--samples"));
      v.push_back(value_option("--plot", "FILE.svg|FILE.png",
                               "also draw the tip response (gnuplot)", "", {"plot"}));
      break;
    case Command::Merge:
    case Command::Plot:
      return file_tool_options(c);
    case Command::Trim:
      v.push_back(mu);
      append(v, trim_options(true));
      break;
    case Command::Campbell: {
      v.push_back(table_option(&Request::campbell, "speed_max", nullptr, "S"));
      v.push_back(table_option(&Request::campbell, "points", "--speeds"));
      v.push_back(table_option(&Request::campbell, "mu"));
      v.push_back(table_option(&Request::campbell, "harmonics"));
      v.push_back(table_option(&Request::campbell, "scan_step"));
      v.push_back(threads);
      v.push_back(value_option("--plot", "FILE.svg|FILE.png",
                               "also draw the Campbell diagram with the per-rev lines (gnuplot)",
                               "", {"plot"}));
      break;
    }
    case Command::Typical:
      break;
  }
  const bool with_trim = c == Command::Point || c == Command::Sweep || c == Command::Critical ||
                         c == Command::Study || c == Command::Map;
  if (with_trim) append(v, trim_options(false));
  if (with_trim || c == Command::System || c == Command::Response || c == Command::Simulate ||
      c == Command::Typical)
    append(v, inflow_options(with_trim));
  if (c == Command::Study || c == Command::Map) append(v, batch_options());
  if (c == Command::Sweep || c == Command::Study || c == Command::Map || c == Command::Response ||
      c == Command::Simulate)
    v.push_back(memory_limit_option());
  append(v, rotor_options());
  if (c != Command::System && c != Command::Response && c != Command::Simulate &&
      c != Command::Trim)
    append(v, transition_options());
  append(v, mode_count_options());
  append(v, spec_options());
  append(v, output_options());
  if (c != Command::Models) v.push_back(report_option());
  return v;
}

}  // namespace

// The inflow model at fixed controls (rotor/inflow.h): its kinds but `given` (a given lambda is
// a trim's, OperatingCondition::At, not an option).
std::string inflow_kind_names(const char* sep) {
  std::string s;
  for (const EnumName<InflowKind>& e : describe(Tag<InflowKind>{}))
    if (e.value != InflowKind::Given) s += (s.empty() ? "" : sep) + std::string(e.name);
  return s;
}

const char* command_name(Command c) {
  switch (c) {
    case Command::Typical:
      return "";
    case Command::Point:
      return "point";
    case Command::Sweep:
      return "sweep";
    case Command::Critical:
      return "critical";
    case Command::System:
      return "system";
    case Command::Models:
      return "models";
    case Command::Modes:
      return "modes";
    case Command::Study:
      return "study";
    case Command::Map:
      return "map";
    case Command::Response:
      return "response";
    case Command::Simulate:
      return "simulate";
    case Command::Merge:
      return "merge";
    case Command::Plot:
      return "plot";
    case Command::Trim:
      return "trim";
    case Command::Campbell:
      return "campbell";
  }
  return "";
}

const std::vector<Command>& subcommands() {
  static const std::vector<Command> all = {
      Command::Point,  Command::Sweep,    Command::Critical, Command::Study, Command::Map,
      Command::System, Command::Response, Command::Simulate, Command::Trim,  Command::Campbell,
      Command::Models, Command::Modes,    Command::Merge,    Command::Plot};
  return all;
}

bool command_from_name(std::string_view name, Command* c) {
  for (Command k : subcommands()) {
    if (name == command_name(k)) {
      *c = k;
      return true;
    }
  }
  return false;
}

const std::vector<OptionSpec>& options_of(Command c) {
  static const std::map<Command, std::vector<OptionSpec>> all = [] {
    std::map<Command, std::vector<OptionSpec>> m;
    m[Command::Typical] = build(Command::Typical);
    for (Command k : subcommands()) m[k] = build(k);
    return m;
  }();
  return all.at(c);
}

const OptionSpec* find_option(Command c, std::string_view name) {
  for (const OptionSpec& o : options_of(c)) {
    if (name == o.name || (!o.alias.empty() && name == o.alias)) return &o;
  }
  return nullptr;
}

const OptionSpec* find_any_option(std::string_view name) {
  if (const OptionSpec* o = find_option(Command::Typical, name)) return o;
  for (Command c : subcommands()) {
    if (const OptionSpec* o = find_option(c, name)) return o;
  }
  return nullptr;
}

const OptionSpec* option_for_library_name(Command c, std::string_view library_name) {
  for (const OptionSpec& o : options_of(c)) {
    for (const std::string& n : o.library_names) {
      if (library_name == n) return &o;
    }
  }
  return nullptr;
}

std::string kebab_option(std::string_view field) { return "--" + kebab(field); }

std::string case_option(std::string_view key) { return "--" + std::string(key); }

std::string in_cli_vocabulary(Command c, const std::string& message) {
  std::string out;
  std::size_t i = 0;
  while (i < message.size()) {
    const std::size_t open = message.find('`', i);
    const std::size_t close = open == std::string::npos ? open : message.find('`', open + 1);
    if (close == std::string::npos) {
      out += message.substr(i);
      break;
    }
    out += message.substr(i, open - i);
    const std::string name = message.substr(open + 1, close - open - 1);
    const OptionSpec* o = option_for_library_name(c, name);
    i = close + 1;
    if (o == nullptr) {
      out += "`" + name + "`";
      continue;
    }
    out += o->name;
    if (o->takes_value && message.compare(i, 3, " = ") == 0) {
      out += "=";
      i += 3;
    }
  }
  return out;
}

double parse_real(const std::string& option, const std::string& text) {
  if (text.empty() || is_blank(text.front()) || is_blank(text.back())) {
    throw InvalidInput(option, shown(text), "not a number");
  }
  // strtod also accepts "nan", "inf" and hexadecimal; the first two are rejected below with a
  // clearer reason than "not a number".  errno distinguishes overflow (1e999) from a valid 0.
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if (end == begin || *end != '\0' || text.size() != std::char_traits<char>::length(begin)) {
    throw InvalidInput(option, shown(text), "not a number");
  }
  if (!std::isfinite(v)) {
    const bool overflow = errno == ERANGE;
    throw InvalidInput(option, shown(text),
                       overflow ? "out of the range of double" : "must be a finite number");
  }
  return v;
}

int parse_int(const std::string& option, const std::string& text, int lo, int hi) {
  long long v = 0;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+') ++first;  // from_chars takes no '+', users do type it
  const auto res = std::from_chars(first, last, v);
  if (text.empty() || res.ec == std::errc::invalid_argument || res.ptr != last) {
    throw InvalidInput(option, shown(text), "not a whole number");
  }
  if (res.ec == std::errc::result_out_of_range || v < lo || v > hi) {
    throw InvalidInput(option, shown(text),
                       "must be between " + std::to_string(lo) + " and " + std::to_string(hi));
  }
  return static_cast<int>(v);
}

void set_parameter(RotorParameters& p, const OptionSpec& option, const std::string& text) {
  const ParameterSpec& spec = *option.rotor;
  switch (spec.type) {
    case ParameterType::Real:
      p.*spec.real = parse_real(option.name, text);
      return;
    case ParameterType::Integer:
      if (integer_from_name(spec, text, &(p.*spec.integer))) return;  // --basis paper
      // The range is validate()'s, as for reals; a whole number beyond int is out of it too.
      try {
        p.*spec.integer = parse_int(option.name, text, std::numeric_limits<int>::min(),
                                    std::numeric_limits<int>::max());
      } catch (const InvalidInput&) {
        const std::size_t digits = text.find_first_not_of("+-") == 1 ? 1 : 0;
        if (text.size() <= digits ||
            text.find_first_not_of("0123456789", digits) != std::string::npos)
          throw;  // not a whole number
        throw InvalidInput(option.name, shown(text), std::string("must be ") + spec.requirement);
      }
      // A number must be in the range (the named values only by name: --basis 0 is refused).
      if (!in_range(spec, p.*spec.integer))
        throw InvalidInput(option.name, shown(text), std::string("must be ") + spec.requirement);
      return;
    case ParameterType::Flag:
      p.*spec.flag = option.flag_value;
      return;
    case ParameterType::Choice:
      if (!mode_kind_from_name(text, &p.modes)) {
        throw InvalidInput(option.name, shown(text), "must be one of assumed, exact");
      }
      return;
    case ParameterType::Text:
      p.model = text;
      return;
  }
}

}  // namespace flaplag::cli
