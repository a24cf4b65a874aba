// flaplag CLI — the command line: options (built from the parameter table), subcommands and
// their interpretation into a Request.  No analysis happens here.
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <memory>
#include <string>

#include "flaplag/core/errors.h"
#include "flaplag/numerics/floquet.h"
#include "flaplag/rotor/parameters.h"

namespace flaplag::cli {

enum class Command { Typical, Point, Sweep, Critical, System, Models, Modes };

struct Request {
  Command command = Command::Typical;
  RotorParameters params;
  TransitionOptions transition;
  bool json = false;
  std::string output;  // -o FILE; empty: stdout
  // point, system: --mu; system: --psi
  double mu = 0.0;
  double psi = 0.0;
  // critical: --mu-max
  double mu_max = 2.0;
  // sweep: --mu A:B:STEP, --format
  double sweep_start = 0.0, sweep_stop = 0.0, sweep_step = 0.0;
  bool csv = false;
  // models: --spec NAME ("" lists the models)
  std::string spec;
  // modes: the Fig 9 table over nonrotating first frequencies START:STOP:STEP (fig9_points of
  // them), and M flap / N lag rotating mode shapes from `basis` cantilever functions, tabulated
  // at shape_points stations
  double fig9_from = 0.0, fig9_to = 0.0, fig9_step = 0.0;
  int fig9_points = 0;
  int flap_modes = 1, lag_modes = 1, basis = 5;
  int shape_points = 11;
};

// The reason part of an InvalidInput message ("name = value: reason").
std::string reason_of(const InvalidInput& e);

class CommandLine {
 public:
  CommandLine();
  ~CommandLine();
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  CLI::App& app() { return *app_; }

  // After app().parse(): the request, every value checked.  Throws InvalidInput naming the
  // option and the value as typed.
  Request interpret() const;

  // The text typed for an option, or nullptr when it was not given: error messages about a
  // value the runtime rejected quote the user's spelling, not the stored double.
  const std::string* typed(const std::string& option) const;

 private:
  struct Slot {
    std::string text;
    bool given = false;
  };
  Slot& slot(const std::string& key) { return slots_[key]; }
  const Slot* given(const std::string& key) const;
  void add_value(CLI::App* app, const std::string& names, const std::string& key,
                 const std::string& help, const std::string& type, const std::string& default_text,
                 bool required = false);
  void add_flag(CLI::App* app, const std::string& names, const std::string& key,
                const std::string& help);
  void add_rotor_options(CLI::App* app);
  void add_analysis_options(CLI::App* app);
  void add_output_options(CLI::App* app);
  void add_modes_options(CLI::App* app);

  std::unique_ptr<CLI::App> app_;
  std::map<std::string, CLI::App*> commands_;
  std::map<std::string, Slot> slots_;  // keyed by long option name; node-stable for callbacks
};

}  // namespace flaplag::cli
