#include "command_line.h"

#include <cmath>
#include <string>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/rotor/parameter_table.h"

namespace flaplag::cli {

namespace {

// Upper limits that only keep absurd requests from running for hours or overflowing; they are
// far above anything the paper or the tests use.
constexpr int kMaxSteps = 1000000;
constexpr int kMaxTerms = 50;
constexpr int kMaxModes = 12;  // exact modes: at most the Galerkin basis (rotating_modes.h)
constexpr int kMaxBasis = 12;
constexpr int kMaxPoints = 100001;  // sweep points, Fig 9 rows, spanwise stations

std::string quoted_if_empty(const std::string& s) { return s.empty() ? "\"\"" : s; }

std::string join_model_names() {
  std::string names;
  for (const model::ModelDescriptor* m : compiled_models()) {
    if (!names.empty()) names += ", ";
    names += m->name;
  }
  return names.empty() ? "none" : names;
}

const model::ModelDescriptor* compiled_model(const std::string& name) {
  for (const model::ModelDescriptor* m : compiled_models()) {
    if (name == m->name) return m;
  }
  return nullptr;
}

struct Range {
  double start, stop, step;
  int count;  // points start, start + step, ..., up to stop
};

// "A:B:STEP" with A <= ... ; `what` names the quantity in messages.
Range parse_range(const std::string& option, const std::string& text, double min_start) {
  std::vector<std::string> parts;
  std::string::size_type from = 0;
  for (;;) {
    const auto colon = text.find(':', from);
    parts.push_back(text.substr(from, colon == std::string::npos ? colon : colon - from));
    if (colon == std::string::npos) break;
    from = colon + 1;
  }
  const std::string shown = quoted_if_empty(text);
  if (text.empty()) throw InvalidInput(option, shown, "empty range, expected START:STOP:STEP");
  if (parts.size() != 3) throw InvalidInput(option, shown, "expected START:STOP:STEP");
  const char* names[3] = {"START", "STOP", "STEP"};
  double v[3];
  for (int i = 0; i < 3; ++i) {
    try {
      v[i] = parse_real(option, parts[i]);
    } catch (const InvalidInput& e) {
      // Keep the whole range as the value; say which part is wrong.
      throw InvalidInput(option, shown, std::string(names[i]) + " " + reason_of(e));
    }
  }
  Range r{v[0], v[1], v[2], 0};
  if (r.start < min_start) {
    throw InvalidInput(option, shown, "START must be >= " + round_trip_text(min_start));
  }
  if (r.stop < r.start) throw InvalidInput(option, shown, "reversed range (STOP < START)");
  if (r.stop == r.start) throw InvalidInput(option, shown, "empty range (STOP = START)");
  if (!(r.step > 0.0)) throw InvalidInput(option, shown, "STEP must be > 0");
  const double n = std::floor((r.stop - r.start) / r.step * (1.0 + 1e-12)) + 1.0;
  if (!(n <= kMaxPoints)) {
    throw InvalidInput(option, shown,
                       "STEP too small: more than " + std::to_string(kMaxPoints) + " points");
  }
  r.count = static_cast<int>(n);
  return r;
}

double parse_at_least(const std::string& option, const std::string& text, double lo, bool open) {
  const double v = parse_real(option, text);
  if (open ? !(v > lo) : !(v >= lo)) {
    throw InvalidInput(option, text,
                       std::string("must be ") + (open ? "> " : ">= ") + round_trip_text(lo));
  }
  return v;
}

std::string rotor_help(const ParameterSpec& s) {
  std::string h = s.help;
  std::string detail;
  if (*s.symbol != '\0') detail += s.symbol;
  if (std::string(s.units) != "-") detail += (detail.empty() ? "" : ", ") + std::string(s.units);
  if (*s.requirement != '\0' && s.type == ParameterType::Real) {
    detail += (detail.empty() ? "" : "; ") + std::string(s.requirement);
  }
  return detail.empty() ? h : h + " (" + detail + ")";
}

}  // namespace

std::string reason_of(const InvalidInput& e) {
  const std::string what = e.what();
  const std::size_t prefix = e.name().size() + 3 + e.value().size() + 2;  // "name = value: "
  return prefix <= what.size() ? what.substr(prefix) : what;
}

CommandLine::CommandLine() : app_(std::make_unique<CLI::App>()) {
  CLI::App& a = *app_;
  a.name("flaplag");
  a.description(
      "Coupled flap-lag stability of a hingeless rotor blade in forward flight\n"
      "(Friedmann & Silverthorn, NASA CR-132431, 1974).\n"
      "Without a subcommand: the paper's typical case (hover, mu_c, zeta(mu) table).");
  a.footer(
      "Examples:\n"
      "  flaplag                                  typical case, Hsu K = 50, J = 4\n"
      "  flaplag critical --method magnus         mu_c with the reference method\n"
      "  flaplag point --mu 0.5 --json            exponents at mu = 0.5 as JSON\n"
      "  flaplag sweep --mu 0:1:0.05 --format csv -o sweep.csv\n"
      "  flaplag system --mu 0.8 --psi 4.7        A(psi), f(psi) and the spanwise integrals\n"
      "  flaplag --modes exact critical           exact rotating modes with elastic coupling\n"
      "Bad input: one line on stderr, exit code 2.");
  a.set_version_flag("--version", "flaplag 0.1.0");
  a.get_formatter()->column_width(34);
  a.require_subcommand(0, 1);
  add_rotor_options(&a);
  add_analysis_options(&a);
  add_output_options(&a);

  CLI::App* point = a.add_subcommand("point", "characteristic exponents at one advance ratio");
  add_value(point, "--mu", "--mu", "advance ratio (>= 0)", "REAL", "", true);
  CLI::App* sweep = a.add_subcommand("sweep", "exponents over a range of advance ratios");
  add_value(sweep, "--mu", "--mu",
            "advance ratios START:STOP:STEP (0 <= START < STOP, STEP > 0, STOP included)",
            "A:B:STEP", "", true);
  add_value(sweep, "--format", "--format", "table or csv (--json for JSON)", "table|csv", "table");
  CLI::App* critical =
      a.add_subcommand("critical", "critical advance ratio mu_c: the first mu with zeta > 0");
  add_value(critical, "--mu-max", "--mu-max", "scan limit (> 0)", "REAL", "2");
  CLI::App* system =
      a.add_subcommand("system", "A(psi), f(psi), flow region, hover equilibrium, integrals");
  add_value(system, "--mu", "--mu", "advance ratio (>= 0)", "REAL", "", true);
  add_value(system, "--psi", "--psi", "azimuth [rad] (any finite value; reduced to [0, 2 pi))",
            "REAL", "0");
  for (CLI::App* sub : {point, sweep, critical, system}) {
    add_rotor_options(sub);
    add_analysis_options(sub);
    add_output_options(sub);
  }
  CLI::App* models = a.add_subcommand("models", "compiled ordering models and their specs");
  add_value(models, "--spec", "--spec", "print the spec of this model", "NAME", "");
  add_output_options(models);
  CLI::App* modes = a.add_subcommand(
      "modes", "exact rotating modes: Fig 9 frequency relation and the mode shapes of a blade");
  add_modes_options(modes);
  add_output_options(modes);

  commands_ = {{"point", point},   {"sweep", sweep},   {"critical", critical},
               {"system", system}, {"models", models}, {"modes", modes}};
}

CommandLine::~CommandLine() = default;

void CommandLine::add_value(CLI::App* app, const std::string& names, const std::string& key,
                            const std::string& help, const std::string& type,
                            const std::string& default_text, bool required) {
  Slot* s = &slot(key);
  // Values arrive as text and are converted by interpret(), so that every bad value gets the
  // same one-line message naming the option and the value as typed.
  CLI::Option* o = app->add_option_function<std::string>(
      names,
      [s](const std::string& text) {
        s->text = text;
        s->given = true;
      },
      help);
  o->type_name(type);
  o->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  if (!default_text.empty()) o->default_str(default_text);
  if (required) o->required();
}

void CommandLine::add_flag(CLI::App* app, const std::string& names, const std::string& key,
                           const std::string& help) {
  Slot* s = &slot(key);
  app->add_flag_callback(
      names, [s]() { s->given = true; }, help);
}

void CommandLine::add_rotor_options(CLI::App* app) {
  const RotorParameters defaults;
  for (const ParameterSpec& spec : parameter_table()) {
    if (spec.type == ParameterType::Flag) {
      add_flag(app, spec.option, spec.option, rotor_help(spec));
    } else {
      const char* type = spec.type == ParameterType::Real   ? "REAL"
                         : spec.type == ParameterType::Text ? "NAME"
                                                            : spec.choices;
      add_value(app, spec.option, spec.option, rotor_help(spec), type,
                parameter_text(defaults, spec));
    }
  }
}

void CommandLine::add_analysis_options(CLI::App* app) {
  const TransitionOptions defaults;
  add_value(app, "--method", "--method",
            "transition matrix: rk4 (paper 3.3.2), hsu (eqs 3.21-3.28) or magnus (4th-order "
            "Magnus with Richardson error estimate)",
            "rk4|hsu|magnus", method_name(defaults.method));
  add_value(app, "--steps", "--steps", "RK4 steps, Hsu intervals K or Magnus steps per period", "N",
            std::to_string(defaults.steps));
  add_value(app, "--terms", "--terms", "Hsu Taylor terms J", "J", std::to_string(defaults.terms));
  add_value(app, "--flap-modes", "--flap-modes",
            "flap modes M: selects model <model>-<M>x<N> (<model> itself for 1x1)", "M", "1");
  add_value(app, "--lag-modes", "--lag-modes", "lag modes N (see --flap-modes)", "N", "1");
}

void CommandLine::add_output_options(CLI::App* app) {
  add_flag(app, "--json", "--json", "write JSON instead of text");
  add_value(app, "-o,--output", "-o", "write to FILE (atomically replaced) instead of stdout",
            "FILE", "");
}

void CommandLine::add_modes_options(CLI::App* app) {
  for (const char* field : {"omega_flap", "omega_lag", "length_ratio", "e1", "paper_1974_shapes"}) {
    const ParameterSpec& spec = *find_parameter(field);
    if (spec.type == ParameterType::Flag) {
      add_flag(app, spec.option, spec.option, rotor_help(spec));
    } else {
      add_value(app, spec.option, spec.option, rotor_help(spec), "REAL",
                parameter_text(RotorParameters{}, spec));
    }
  }
  add_value(app, "--flap-modes", "--flap-modes", "rotating flap modes shown (1..basis)", "M", "1");
  add_value(app, "--lag-modes", "--lag-modes", "rotating lag modes shown (1..basis)", "N", "1");
  add_value(app, "--basis", "--basis", "nonrotating cantilever functions per direction", "N", "5");
  add_value(app, "--nonrotating", "--nonrotating",
            "Fig 9 table: first nonrotating frequencies START:STOP:STEP (>= 0)", "A:B:STEP",
            "0:2.5:0.1");
  add_value(app, "--points", "--points", "spanwise stations of the mode-shape table (>= 2)", "K",
            "11");
}

const std::string* CommandLine::typed(const std::string& option) const {
  const Slot* s = given(option);
  return s != nullptr ? &s->text : nullptr;
}

const CommandLine::Slot* CommandLine::given(const std::string& key) const {
  const auto it = slots_.find(key);
  return it != slots_.end() && it->second.given ? &it->second : nullptr;
}

Request CommandLine::interpret() const {
  Request r;
  std::string command;
  for (const auto& [name, sub] : commands_) {
    if (sub->parsed()) command = name;
  }
  if (command.empty())
    r.command = Command::Typical;
  else if (command == "point")
    r.command = Command::Point;
  else if (command == "sweep")
    r.command = Command::Sweep;
  else if (command == "critical")
    r.command = Command::Critical;
  else if (command == "system")
    r.command = Command::System;
  else if (command == "models")
    r.command = Command::Models;
  else
    r.command = Command::Modes;

  // Rotor parameters, in table order.
  for (const ParameterSpec& spec : parameter_table()) {
    if (const Slot* s = given(spec.option)) set_parameter(r.params, spec, s->text);
  }
  try {
    validate(r.params);
  } catch (const InvalidInput& e) {
    // validate() shows the stored double; show what the user typed instead.
    const Slot* s = given(e.name());
    if (s == nullptr) throw;
    throw InvalidInput(e.name(), quoted_if_empty(s->text), reason_of(e));
  }

  int flap_modes = 1, lag_modes = 1;
  const Slot* flap_given = given("--flap-modes");
  const Slot* lag_given = given("--lag-modes");
  if (flap_given) flap_modes = parse_int("--flap-modes", flap_given->text, 1, kMaxModes);
  if (lag_given) lag_modes = parse_int("--lag-modes", lag_given->text, 1, kMaxModes);

  if (const Slot* s = given("--method")) {
    if (s->text == "rk4")
      r.transition.method = TransitionMethod::RK4;
    else if (s->text == "hsu")
      r.transition.method = TransitionMethod::Hsu;
    else if (s->text == "magnus")
      r.transition.method = TransitionMethod::Magnus4;
    else
      throw InvalidInput("--method", quoted_if_empty(s->text), "must be one of rk4, hsu, magnus");
  }
  if (const Slot* s = given("--steps"))
    r.transition.steps = parse_int("--steps", s->text, 1, kMaxSteps);
  if (const Slot* s = given("--terms"))
    r.transition.terms = parse_int("--terms", s->text, 1, kMaxTerms);

  if (const Slot* s = given("--json")) r.json = s->given;
  if (const Slot* s = given("-o")) {
    if (s->text.empty()) throw InvalidInput("-o", "\"\"", "empty file name");
    r.output = s->text;
  }

  const bool analysis = r.command != Command::Models && r.command != Command::Modes;
  if (analysis) {
    // --flap-modes M --lag-modes N select the model "<model>-<M>x<N>"; 1x1 is <model> itself.
    if (flap_given || lag_given) {
      const std::string base = r.params.model;
      if (flap_modes != 1 || lag_modes != 1) {
        r.params.model = base + "-" + std::to_string(flap_modes) + "x" + std::to_string(lag_modes);
      }
      const std::string option = flap_given ? "--flap-modes" : "--lag-modes";
      const std::string value = flap_given ? flap_given->text : lag_given->text;
      const model::ModelDescriptor* m = compiled_model(r.params.model);
      if (m == nullptr) {
        throw InvalidInput(option, value,
                           "no compiled model \"" + r.params.model + "\" for " +
                               std::to_string(flap_modes) + " flap x " + std::to_string(lag_modes) +
                               " lag modes (compiled: " + join_model_names() + ")");
      }
      if (m->flap_modes != flap_modes || m->lag_modes != lag_modes) {
        throw InvalidInput(option, value,
                           "model \"" + r.params.model + "\" has " + std::to_string(m->flap_modes) +
                               " flap x " + std::to_string(m->lag_modes) + " lag modes");
      }
    } else if (compiled_model(r.params.model) == nullptr) {
      throw InvalidInput("--model", r.params.model,
                         "unknown model (compiled: " + join_model_names() + ")");
    }
  }

  switch (r.command) {
    case Command::Point:
    case Command::System:
      r.mu = parse_at_least("--mu", slots_.at("--mu").text, 0.0, false);
      if (r.command == Command::System) {
        if (const Slot* s = given("--psi")) r.psi = parse_real("--psi", s->text);
      }
      break;
    case Command::Sweep: {
      const Range range = parse_range("--mu", slots_.at("--mu").text, 0.0);
      r.sweep_start = range.start;
      r.sweep_stop = range.stop;
      r.sweep_step = range.step;
      if (const Slot* s = given("--format")) {
        if (s->text == "csv")
          r.csv = true;
        else if (s->text != "table") {
          throw InvalidInput("--format", quoted_if_empty(s->text), "must be table or csv");
        }
        if (r.csv && r.json)
          throw InvalidInput("--format", s->text, "cannot be combined with --json");
      }
      break;
    }
    case Command::Critical:
      if (const Slot* s = given("--mu-max"))
        r.mu_max = parse_at_least("--mu-max", s->text, 0.0, true);
      break;
    case Command::Models:
      if (const Slot* s = given("--spec")) {
        if (compiled_model(s->text) == nullptr) {
          throw InvalidInput("--spec", quoted_if_empty(s->text),
                             "unknown model (compiled: " + join_model_names() + ")");
        }
        r.spec = s->text;
      }
      break;
    case Command::Modes: {
      int basis = 5;
      if (const Slot* s = given("--basis")) basis = parse_int("--basis", s->text, 1, kMaxBasis);
      if (flap_modes > basis) {
        throw InvalidInput("--flap-modes", flap_given->text,
                           "must not exceed --basis = " + std::to_string(basis));
      }
      if (lag_modes > basis) {
        throw InvalidInput("--lag-modes", lag_given->text,
                           "must not exceed --basis = " + std::to_string(basis));
      }
      const Slot* nr = given("--nonrotating");
      const std::string text = nr ? nr->text : "0:2.5:0.1";
      const Range range = parse_range("--nonrotating", text, 0.0);
      if (range.count < 2) {
        throw InvalidInput("--nonrotating", text, "STEP exceeds the range: need 2 points or more");
      }
      r.fig9_from = range.start;
      r.fig9_to = range.stop;
      r.fig9_step = range.step;
      r.fig9_points = range.count;
      if (const Slot* s = given("--points")) {
        r.shape_points = parse_int("--points", s->text, 2, kMaxPoints);
      }
      r.basis = basis;
      r.flap_modes = flap_modes;
      r.lag_modes = lag_modes;
      break;
    }
    case Command::Typical:
      break;
  }
  return r;
}

}  // namespace flaplag::cli
