// flaplag CLI — the command line: the subcommand, its options and their interpretation into a
// Request.  No analysis happens here.
//
// The parser is our own (not CLI11's) because the error contract is ours: every refused input
// is ONE line "<option> = <value>: <reason>" naming the option as the user typed it and the
// value as typed.  Grammar: at most one subcommand; options before or after it; "--name value"
// or "--name=value", "-o FILE" or "-oFILE"; a value may start with '-' ("--theta -0.1",
// "-o -") but not with "--" (then the value is missing); "--" ends the options; the last of a
// repeated option wins.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "flaplag/campbell.h"
#include "flaplag/core/errors.h"
#include "flaplag/limits.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/numerics/floquet.h"
#include "flaplag/numerics/response.h"
#include "flaplag/rotor/inflow.h"
#include "flaplag/rotor/parameters.h"
#include "flaplag/trim.h"
#include "options.h"

namespace flaplag::cli {

struct Request {
  Command command = Command::Typical;
  RotorParameters params;
  TransitionOptions transition;  // automatic steps unless --steps N
  bool json = false;
  std::string output;  // -o FILE; empty: stdout (also for "-o -")
  // point, system: --mu; system: --psi; point, map: --scan-step
  double mu = 0.0;
  double psi = 0.0;
  double scan_step = 0.01;
  // critical, study: --mu-max, --scan-step
  CriticalOptions critical;
  // sweep: --mu A:B:STEP, --format
  double sweep_start = 0.0, sweep_stop = 0.0, sweep_step = 0.0;
  bool csv = false;
  // models: --spec NAME ("" lists the models)
  std::string spec;
  // analysis commands: --audit FILE.md, the audit report of the --spec model ("": none)
  std::string audit;
  // modes: the Fig 9 table over nonrotating first frequencies START:STOP:STEP (fig9_points of
  // them), and M flap / N lag rotating mode shapes from params.basis cantilever functions,
  // tabulated at shape_points stations
  double fig9_from = 0.0, fig9_to = 0.0, fig9_step = 0.0;
  int fig9_points = 0;
  int flap_modes = 1, lag_modes = 1;  // the basis size: params.basis
  int shape_points = 11;
  // modes: --export-shapes FILE.csv, the mode file of the shapes (kExportedModeStations
  // stations; "": none)
  std::string export_shapes;
  // --blade-table / --blade-csv: the text of the blade table ("": the uniform blade); the case
  // of a JSON output records the text, not the file.
  std::string blade_csv;
  // --mode-shapes / --mode-shapes-csv: the text of the mode file ("": computed modes).
  std::string mode_shapes_csv;
  // study: --vary NAME=...; map: --x, --y (field names, "mu" for the advance ratio)
  std::string vary;
  std::vector<double> vary_values;
  std::string x_name, y_name;
  std::vector<double> x_values, y_values;
  // campbell: --speed-max, --speeds, --mu, --harmonics, --scan-step (its threads: threads)
  CampbellOptions campbell;
  int threads = 0;
  std::string plot;  // --plot FILE (.svg or .png)
  // --report FILE.html: also the HTML report of the result (report.h); "-": standard output
  // (flaplag report, which writes nothing else); "": none
  std::string report;
  // sweep, study: --damping-criterion C (a fraction of critical, kDampingCriterionRange): the
  // first mu where each mode's damping ratio falls below C; nullopt: not asked
  std::optional<double> damping_criterion;
  // sweep, plot: --plot-quantity, the y quantity of a sweep picture: the damping ratio in % of
  // critical (default) or zeta
  bool plot_zeta = false;
  // study, map: --shard I/N (1 <= I <= N; N = 0: the whole job) and --quiet (no progress bar)
  int shard_index = 0, shard_count = 0;
  bool quiet = false;
  // merge: the part files; plot: the data files (as typed), --label per file (in order; empty:
  // labels from each result's case), --max-zeta (the largest zeta of each sweep only) and --mode
  std::vector<std::string> inputs;
  std::vector<std::string> labels;
  bool max_zeta = false;
  std::string mode;  // plot --mode NAME: only that mode's curves ("": all)
  // response: --samples
  ResponseOptions response;
  // simulate: --revs, --samples, --nonlinear; --perturbation, --forced
  SimulationOptions simulation;
  double perturbation = 0.01;
  bool forced = false;
  // point, sweep, critical, study, map, trim: --trim, --thrust-coefficient, --shaft-angle
  TrimOptions trim;
  // The analyses at fixed controls (point, sweep, critical, study, map, system, response,
  // simulate, the typical case): --inflow; momentum takes C_T and alpha_R from
  // --thrust-coefficient and --shaft-angle (trim's fields).  Uniform (eq 2.24) by default.
  InflowModel inflow;
  // Every analysis: --periodic-linearization, about q°(psi) instead of hover (the paper).
  Linearization linearization = Linearization::HoverEquilibrium;
  // sweep, study, map, response, simulate, merge: --memory-limit (limits.h), checked against
  // the run's estimate by interpret() (merge: by check_merged_output)
  std::uint64_t memory_limit = kDefaultMemoryLimit;
  // The arguments as given (after a case file is expanded), for the "case" of JSON outputs.
  std::vector<std::string> arguments;
};

// flaplag merge, before the text is made: throws InvalidInput("--memory-limit", ...) when the
// JSON text of `merged` (dump(2), computed exactly without making it) and the documents behind
// it need more than r.memory_limit (limits.h json_output_memory), saying how large the parts
// r.inputs are: a part that grows a thousandfold when written out was not written by flaplag.
void check_merged_output(const Request& r, const nlohmann::ordered_json& merged);

class CommandLine {
 public:
  // Splits args (argv[1..]) into the subcommand and its options.  Never throws: problems are
  // kept for check(), so that --help works on any command line.
  explicit CommandLine(const std::vector<std::string>& args);

  Command command() const { return command_; }
  bool wants_help() const { return help_; }
  bool wants_version() const { return version_; }

  // Throws InvalidInput for the first problem of the command line itself, in argument order:
  // an unknown option (name = the option when it is shaped like one, "--bogus"; else name =
  // "argument" and the word is the value, "-q", "--Gamma"), an unknown subcommand (name =
  // "subcommand"), a stray argument (name = "argument"), a missing value (value "(missing)"), a
  // value given to a flag, an option the subcommand does not take.
  void check() const;

  // After check(): the request, every value checked.  Throws InvalidInput(option as typed,
  // value as typed, reason).
  Request interpret() const;

  // An InvalidInput from the runtime (named by field or argument, "omega_lag", "mu1") or from
  // the CLI itself (named by option) as "<option> = <value>: <reason>" in this command line's
  // vocabulary: the option as typed, the value as typed (the runtime's value for options not
  // given), field names in the reason translated.  nullopt when no option of the subcommand
  // answers for the name (a quantity derived inside the analysis: a bug, not bad input).
  std::optional<std::string> error_line(const InvalidInput& e) const;

  // A library message in this command's vocabulary (see in_cli_vocabulary).
  std::string vocabulary(const std::string& message) const;

  // The help of the subcommand (or of flaplag itself).
  std::string help_text() const;

  // The help of `flaplag run CASE [OPTIONS]` (run is expanded before the command line is read).
  static std::string run_help_text();
  // The help of `flaplag report CASE [OPTIONS]` (expanded as run is).
  static std::string report_help_text();

 private:
  struct Given {
    std::string name;      // OptionSpec::name
    std::string spelling;  // as typed ("--output" or "-o")
    std::string text;      // the value ("" for flags)
    std::size_t position;  // index in args
  };
  struct Problem {
    std::size_t position;
    InvalidInput error;
  };
  struct ModeCounts {  // --flap-modes, --lag-modes (1 when not given)
    int flap = 1, lag = 1;
    const Given* flap_given = nullptr;
    const Given* lag_given = nullptr;
  };
  const Given* given(const std::string& name) const;
  // The option, or InvalidInput(name, "(missing)", "required by <subcommand>").
  const Given& required(const char* name) const;
  void problem(std::size_t position, InvalidInput e);
  // The steps of the constructor.
  void read_word(std::size_t i, const std::string& word, bool first);
  std::size_t read_option(const std::vector<std::string>& args, std::size_t i);
  void refuse_options_of_other_commands();
  // The steps of interpret(); interpret_sweep .. interpret_campbell are those of one subcommand.
  void interpret_rotor(Request& r) const;
  ModeCounts interpret_mode_counts() const;
  void interpret_tables(Request& r) const;  // the options of the options structs' tables
  void interpret_transition(Request& r) const;
  void interpret_output(Request& r) const;
  void interpret_model(Request& r, const ModeCounts& modes) const;
  void interpret_subcommand(Request& r, const ModeCounts& modes) const;
  void interpret_sweep(Request& r) const;
  void interpret_modes(Request& r, const ModeCounts& modes) const;
  void interpret_map(Request& r) const;
  void interpret_simulate(Request& r) const;
  void interpret_plot(Request& r) const;
  void interpret_campbell(Request& r) const;
  void interpret_trim(Request& r) const;
  void interpret_inflow(Request& r) const;
  void interpret_batch(Request& r) const;  // --shard, --quiet
  void interpret_run_options(Request& r) const;
  void apply_blade(Request& r) const;        // --blade-table, --blade-csv
  void apply_mode_shapes(Request& r) const;  // --mode-shapes, --mode-shapes-csv

  Command command_ = Command::Typical;
  std::vector<Given> given_;         // in argument order; the last of a name wins
  std::vector<std::string> inputs_;  // merge, plot: the file arguments
  std::optional<Problem> problem_;
  bool help_ = false, version_ = false;
};

}  // namespace flaplag::cli
