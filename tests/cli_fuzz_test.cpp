// Fuzzing the `flaplag` command line (issue 8): generated argument vectors, run as a user runs
// them, each checked against the output contract of docs/cli.md:
//   - no signal, exit code 0 or 2 (1 is an internal error: a bug);
//   - exit 2: exactly one stderr line "flaplag: error: <option> = <value>: <reason>", nothing on
//     stdout, no output file created or changed;
//   - exit 0: nothing on stderr; no "nan"/"inf" token in the output (the zeta of a zero
//     multiplier is "-inf"); JSON parses, has no null outside the documented nullable keys
//     unless a status above it is not "ok", and `stable` is null only with a status that is not
//     "ok".
//
// Deterministic: a fixed seed (FLAPLAG_FUZZ_SEED overrides it) and a bounded budget:
// FLAPLAG_FUZZ_VECTORS vectors (default 1000), FLAPLAG_FUZZ_JOBS at a time (default 2), each
// killed after FLAPLAG_FUZZ_TIMEOUT seconds (default 60; a kill is a violation: a hang).  The
// generator keeps the number of Floquet evaluations of each run small (the continuation step
// follows mu), so the budget holds for the extreme but legal physics it draws: mu up to 1000,
// gamma up to 1e4, damping up to 10, frequencies 1e-3..100, every model, method, explicit
// steps 1..2000 and terms 1..8.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "flaplag/analysis.h"
#include "options.h"
#include "process.h"

#ifndef FLAPLAG_EXE
#error "FLAPLAG_EXE must name the flaplag binary"
#endif

extern char** environ;

namespace cli_fuzz_test {

namespace {

using Json = nlohmann::json;
namespace cli = flaplag::cli;
namespace fs = std::filesystem;

using flaplag::testing::env_long;
using flaplag::testing::slurp;

std::string shell_quoted(const std::vector<std::string>& args) {
  std::string s = "flaplag";
  for (const std::string& a : args) {
    bool plain = !a.empty();
    for (char c : a) {
      plain = plain && (std::isalnum(static_cast<unsigned char>(c)) || std::strchr("-_.:/=+,", c));
    }
    if (plain) {
      s += " " + a;
    } else {
      std::string q = " '";
      for (char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
      s += q + "'";
    }
  }
  return s;
}

// ---- the generator ---------------------------------------------------------------------------

class Generator {
 public:
  explicit Generator(std::uint64_t seed) : rng_(seed) {
    // One model per spec, each also named for other mode counts ("<model>-<M>x<N>").
    for (const flaplag::model::ModelDescriptor* m : flaplag::compiled_models()) {
      base_models_.push_back(m->name);
      for (const char* size : {"-2x1", "-1x3", "-2x2", "-4x2"})
        all_models_.push_back(std::string(m->base) + size);
    }
    all_models_.insert(all_models_.end(), base_models_.begin(), base_models_.end());
  }

  struct Vector {
    std::vector<std::string> args;
    bool output = false;    // -o into a fresh directory (appended by the runner)
    bool existing = false;  // ... over an existing file
    std::string kind;       // "legal", "mixed", "garbage"
  };

  Vector next() {
    Vector v;
    const double r = uniform(0, 1);
    v.kind = r < 0.45 ? "legal" : r < 0.9 ? "mixed" : "garbage";
    if (v.kind == "garbage") {
      garbage(v.args);
    } else {
      legal(v.args);
      if (v.kind == "mixed") {
        const int n = integer(1, 2);
        for (int i = 0; i < n; ++i) corrupt(v.args);
      }
    }
    v.output = chance(0.15);
    v.existing = v.output && chance(0.5);
    return v;
  }

  // Every option of every command must have a legal value here: the fuzzer covers them all.
  bool knows(const std::string& option) const {
    static const std::set<std::string> known = {"--model",
                                                "--gamma",
                                                "--sigma",
                                                "--lift-slope",
                                                "--cdo",
                                                "--theta",
                                                "--precone",
                                                "--droop",
                                                "--omega-flap",
                                                "--omega-lag",
                                                "--damping-flap",
                                                "--damping-lag",
                                                "--length-ratio",
                                                "--tip-loss-a",
                                                "--tip-loss-b",
                                                "--root-offset",
                                                "--no-reversed-flow",
                                                "--exact-reversed-flow",
                                                "--modes",
                                                "--no-elastic-coupling",
                                                "--paper-1974-shapes",
                                                "--periodic-linearization",
                                                "--method",
                                                "--steps",
                                                "--terms",
                                                "--zeta-tolerance",
                                                "--flap-modes",
                                                "--lag-modes",
                                                "--json",
                                                "-o",
                                                "--mu",
                                                "--scan-step",
                                                "--format",
                                                "--mu-max",
                                                "--psi",
                                                "--spec",
                                                "--audit",
                                                "--export-shapes",
                                                "--blade-table",
                                                "--blade-csv",
                                                "--mode-shapes",
                                                "--mode-shapes-csv",
                                                "--basis",
                                                "--nonrotating",
                                                "--points",
                                                "--vary",
                                                "--x",
                                                "--y",
                                                "--threads",
                                                "--plot",
                                                "--report",
                                                "--label",
                                                "--max-zeta",
                                                "--mode",
                                                "--damping-criterion",
                                                "--plot-quantity",
                                                "--samples",
                                                "--revs",
                                                "--perturbation",
                                                "--forced",
                                                "--nonlinear",
                                                "--shard",
                                                "--quiet",
                                                "--theta1c",
                                                "--theta1s",
                                                "--trim",
                                                "--thrust-coefficient",
                                                "--shaft-angle",
                                                "--inflow",
                                                "--memory-limit",
                                                "--speed-max",
                                                "--speeds",
                                                "--harmonics"};
    return known.count(option) == 1;
  }

 private:
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  bool chance(double p) { return uniform(0, 1) < p; }
  template <typename T>
  const T& pick(const std::vector<T>& v) {
    return v[static_cast<std::size_t>(integer(0, static_cast<int>(v.size()) - 1))];
  }

  // A number as users type it: short, full precision, exponent form, a leading '+'.
  std::string text(double v) {
    char buf[64];
    switch (integer(0, 3)) {
      case 0:
        std::snprintf(buf, sizeof buf, "%.6g", v);
        break;
      case 1:
        std::snprintf(buf, sizeof buf, "%.17g", v);
        break;
      case 2:
        std::snprintf(buf, sizeof buf, "%.3e", v);
        break;
      default:
        std::snprintf(buf, sizeof buf, "%s%.4g", v >= 0 ? "+" : "", v);
        break;
    }
    return buf;
  }

  // Legal physics at the extremes: each range's ends are drawn often.
  std::string in(double lo, double hi, bool log_scale = false) {
    const double r = uniform(0, 1);
    if (r < 0.1) return text(lo);
    if (r < 0.2) return text(hi);
    return text(log_scale ? log_uniform(lo, hi) : uniform(lo, hi));
  }

  std::string legal_value(const std::string& option, cli::Command c) {
    if (option == "--model")
      return c == cli::Command::Models ? pick(all_models_) : pick(base_models_);
    if (option == "--spec") return pick(all_models_);
    if (option == "--gamma") return in(1e-3, 1e4, true);
    if (option == "--sigma") return in(1e-4, 1.0, true);
    if (option == "--lift-slope") return in(1e-2, 100.0, true);
    if (option == "--cdo") return in(0.0, 1.0);
    // Below -sigma a / 24 eq 2.24 has no inflow (refused): mostly above.
    if (option == "--theta") return chance(0.1) ? in(-1.5, 1.5) : in(-0.01, 1.5);
    if (option == "--precone" || option == "--droop") return in(-1.5, 1.5);
    // Every model has the cyclic pitch.
    if (option == "--theta1c" || option == "--theta1s") return in(-0.3, 0.3);
    // A trim costs a few periodic responses per Floquet evaluation: rarely asked.
    if (option == "--trim")
      return chance(0.9) ? "none" : pick(std::vector<std::string>{"thrust", "moment"});
    if (option == "--thrust-coefficient") return in(1e-4, 0.1, true);
    if (option == "--shaft-angle") return in(-0.5, 0.5);
    // The momentum inflow needs --thrust-coefficient (refused without it) and no trim.
    if (option == "--inflow") return chance(0.8) ? "uniform" : "momentum";
    if (option == "--omega-flap" || option == "--omega-lag") {
      return chance(0.05) ? "1000" : in(1e-3, 100.0, true);
    }
    if (option == "--damping-flap" || option == "--damping-lag") return in(0.0, 10.0);
    if (option == "--length-ratio") return in(1e-3, 1.0, true);
    // Mostly ordered (A < B), sometimes not (refused).
    if (option == "--tip-loss-a") return chance(0.1) ? in(0.0, 0.99) : in(0.0, 0.5);
    if (option == "--tip-loss-b") return chance(0.1) ? in(0.01, 1.0) : in(0.5, 1.0);
    if (option == "--root-offset") return in(0.0, 0.999);
    if (option == "--modes") return chance(0.5) ? "assumed" : "exact";
    if (option == "--method") return pick(std::vector<std::string>{"rk4", "hsu", "magnus"});
    if (option == "--steps")
      return chance(0.2) ? "auto" : std::to_string(integer(1, 2000));  // corrupt()
    if (option == "--terms") return std::to_string(integer(1, 8));
    if (option == "--zeta-tolerance") return in(1e-7, 1e-1, true);
    if (option == "--flap-modes" || option == "--lag-modes") {
      // Any count 1..12 has a model; more than --basis (5 by default) is refused.  Many modes
      // are slow: mostly one or two.
      return std::to_string(c == cli::Command::Modes || chance(0.1) ? integer(1, 6)
                                                                    : integer(1, 2));
    }
    if (option == "--format") return chance(0.5) ? "table" : "csv";
    if (option == "--psi") return chance(0.2) ? text(chance(0.5) ? 1e308 : -1e308) : in(-50, 50);
    if (option == "--basis") return std::to_string(integer(1, 12));
    if (option == "--points") return std::to_string(integer(2, 50));
    if (option == "--nonrotating") {
      const double a = uniform(0, 5), b = a + uniform(0.01, 10);
      return text(a) + ":" + text(b) + ":" + text((b - a) / integer(1, 30));
    }
    if (option == "--vary") return axis(false);
    if (option == "--x" || option == "--y") return axis(true);
    if (option == "--threads") return std::to_string(integer(0, 3));
    if (option == "--memory-limit")  // 1M refuses most runs (exit 2, one line)
      return pick(
          std::vector<std::string>{"2G", "512M", "1M", "64G", "0.5G", "8GiB", "3000000000"});
    if (option == "--plot") return chance(0.5) ? "plot.svg" : "plot.png";
    if (option == "--audit") return "audit.md";
    if (option == "--export-shapes") return "shapes.csv";
    if (option == "--report") return "report.html";
    if (option == "--label") return pick(std::vector<std::string>{"(a) paper", "", "x\"y"});
    if (option == "--mode") return pick(std::vector<std::string>{"lag", "flap", "lag2"});
    // A fraction of critical, 0 <= C < 1.
    if (option == "--damping-criterion") return chance(0.3) ? in(1e-5, 0.5, true) : in(0.0, 0.1);
    if (option == "--plot-quantity") return pick(std::vector<std::string>{"damping-ratio", "zeta"});
    if (option == "--shard") {  // part I of N; now and then I > N (refused)
      const int n = integer(1, 4);
      return std::to_string(chance(0.9) ? integer(1, n) : n + 1) + "/" + std::to_string(n);
    }
    if (option == "--samples") return std::to_string(integer(12, 100));
    if (option == "--revs") return text(log_uniform(0.1, 30));
    if (option == "--perturbation") return text(log_uniform(1e-6, 10));
    if (option == "--mu") return text(uniform(0, 2));
    if (option == "--scan-step") return text(log_uniform(0.005, 0.5));
    if (option == "--mu-max") return text(uniform(0.01, 3));
    if (option == "--speed-max") return in(1e-2, 10.0, true);
    if (option == "--harmonics") return std::to_string(integer(1, 100));
    return "1";
  }

  // mu and the continuation step together: at most ~40 Floquet evaluations per run, with mu
  // up to kMaxAdvanceRatio.
  void add_advance_ratio(std::vector<std::string>& a, cli::Command c, int max_evaluations) {
    const double r = uniform(0, 1);
    const double mu_max = flaplag::kMaxAdvanceRatio;
    const double mu = r < 0.6   ? uniform(0, 2)
                      : r < 0.9 ? log_uniform(2, mu_max)
                                : (chance(0.5) ? 0.0 : mu_max);
    const int evaluations = integer(2, max_evaluations);
    const double step = std::max(mu / evaluations, 0.01);
    switch (c) {
      case cli::Command::Point:
        a.insert(a.end(), {"--mu", text(mu)});
        if (mu > 0.6 || chance(0.3)) a.insert(a.end(), {"--scan-step", text(step)});
        break;
      case cli::Command::System:
        a.insert(a.end(), {"--mu", text(mu)});
        if (chance(0.7)) a.insert(a.end(), {"--psi", legal_value("--psi", c)});
        break;
      case cli::Command::Sweep: {
        const double start = chance(0.5) ? 0.0 : uniform(0, mu);
        const double stop = std::max(mu, start + 0.01);
        const double s = std::max(stop / evaluations, 0.01);
        a.insert(a.end(), {"--mu", text(start) + ":" + text(stop) + ":" + text(s)});
        if (chance(0.3)) a.insert(a.end(), {"--format", legal_value("--format", c)});
        break;
      }
      case cli::Command::Study:
        a.insert(a.end(), {"--vary", axis(false)});
        a.insert(a.end(), {"--mu-max", text(uniform(0.05, 1.5)), "--scan-step", text(0.1)});
        break;
      case cli::Command::Map:
        a.insert(a.end(), {"--x", axis(true), "--y", axis(chance(0.5))});
        if (chance(0.5)) a.insert(a.end(), {"--mu", text(uniform(0, 1.5))});
        a.insert(a.end(), {"--scan-step", text(0.1)});
        break;
      case cli::Command::Response:
        a.insert(a.end(), {"--mu", text(r < 0.8 ? uniform(0, 2) : mu)});
        if (chance(0.5)) a.insert(a.end(), {"--samples", std::to_string(integer(12, 200))});
        break;
      case cli::Command::Simulate:
        a.insert(a.end(), {"--mu", text(r < 0.8 ? uniform(0, 2) : mu)});
        a.insert(a.end(), {"--revs", text(log_uniform(0.1, 30))});
        if (chance(0.5)) a.insert(a.end(), {"--samples", std::to_string(integer(12, 72))});
        if (chance(0.5)) a.insert(a.end(), {"--perturbation", text(log_uniform(1e-6, 10))});
        if (chance(0.3)) a.push_back("--forced");
        // (at the cost of a periodic equilibrium)
        if (chance(0.1)) a.push_back("--nonlinear");
        break;
      case cli::Command::Campbell:
        // A point at each of a few speeds: hover mostly, else a continuation to mu.
        a.insert(a.end(), {"--speeds", std::to_string(integer(2, 6))});
        if (chance(0.4)) a.insert(a.end(), {"--mu", text(uniform(0, 1)), "--scan-step", "0.1"});
        break;
      case cli::Command::Critical: {
        const double m = std::max(mu, 0.01);
        a.insert(a.end(), {"--mu-max", text(m)});
        if (m > 0.6 || chance(0.3))
          a.insert(a.end(), {"--scan-step", text(std::max(m / evaluations, 0.01))});
        break;
      }
      default:
        break;
    }
  }

  cli::Command command() {
    const double r = uniform(0, 1);
    if (r < 0.06) return cli::Command::Typical;
    if (r < 0.26) return cli::Command::Point;
    if (r < 0.42) return cli::Command::Sweep;
    if (r < 0.54) return cli::Command::Critical;
    if (r < 0.70) return cli::Command::System;
    if (r < 0.76) return cli::Command::Models;
    if (r < 0.82) return cli::Command::Modes;
    if (r < 0.87) return cli::Command::Study;
    if (r < 0.92) return cli::Command::Map;
    if (r < 0.96) return cli::Command::Response;
    if (r < 0.975) return cli::Command::Simulate;
    if (r < 0.985) return cli::Command::Campbell;
    return r < 0.99 ? cli::Command::Merge : cli::Command::Plot;
  }

  // A parameter axis of study / map: NAME=START:STOP:STEP or NAME=V1,V2,... with few values.
  std::string axis(bool allow_mu) {
    std::vector<const flaplag::ParameterSpec*> reals;
    for (const flaplag::ParameterSpec& s : flaplag::parameter_table()) {
      if (s.type == flaplag::ParameterType::Real) reals.push_back(&s);
    }
    if (allow_mu && chance(0.4)) {
      const double hi = uniform(0.05, 2.0);
      return "mu=0:" + text(hi) + ":" + text(hi / integer(1, 3));
    }
    const flaplag::ParameterSpec& s = *pick(reals);
    const std::string name = cli::json_key(s);
    const std::string option = "--" + name;
    if (chance(0.5)) {
      std::string list;
      for (int i = integer(1, 3); i > 0; --i) {
        list += (list.empty() ? "" : ",") + legal_value(option, cli::Command::Point);
      }
      return name + "=" + list;
    }
    const double lo = s.range.lo, hi = s.range.hi;
    const double a = uniform(lo, lo + (hi - lo) * 0.5), b = uniform(a, hi);
    return name + "=" + text(a) + ":" + text(b) + ":" + text((b - a) / integer(1, 3) + 1e-9);
  }

  void legal(std::vector<std::string>& a) {
    const cli::Command c = command();
    command_ = c;
    const bool subcommand_first = chance(0.7);
    if (c != cli::Command::Typical && subcommand_first) a.push_back(cli::command_name(c));
    // The cost of a run is (Floquet evaluations) x (steps per evaluation).  Automatic steps
    // reach 65536 for a stiff blade, so those runs get fewer evaluations (and no first-order
    // Hsu); the bare command (a critical search and a 101-point sweep) has explicit steps.
    const bool heavy = c == cli::Command::Typical || c == cli::Command::Study ||
                       c == cli::Command::Map || c == cli::Command::Campbell;
    const bool explicit_steps = heavy ? chance(0.95) : chance(0.45);
    add_advance_ratio(a, c, explicit_steps ? 40 : 15);
    const double p = heavy ? 0.15 : 0.3;
    for (const cli::OptionSpec& o : cli::options_of(c)) {
      if (o.name == "-o" || o.name == "--mu" || o.name == "--scan-step" || o.name == "--psi" ||
          o.name == "--mu-max" || o.name == "--format" || o.name == "--steps" ||
          o.name == "--vary" || o.name == "--x" || o.name == "--y" || o.name == "--samples" ||
          o.name == "--revs" || o.name == "--perturbation" || o.name == "--forced" ||
          o.name == "--speeds" || o.name == "--nonlinear" ||
          (o.name == "--spec" && c != cli::Command::Models) || o.name == "--audit" ||
          o.name == "--export-shapes" || o.name == "--blade-table" || o.name == "--blade-csv" ||
          o.name == "--mode-shapes" || o.name == "--mode-shapes-csv") {
        // (--spec FILE.toml derives a model: tests/cli_spec_test.cpp; --export-shapes writes a
        // side file: tests/cli_test.cpp, CliGood.ModesExportShapes; blade tables and mode files
        // are files of their own: tests/cli_blade_test.cpp)
        continue;
      }
      // gnuplot is slow to start: few pictures.  A periodic equilibrium (harmonic balance
      // continued from hover) at every mu is the costliest switch: rarely, and in the heavy
      // commands very rarely (about as often as when only two models in six had it).
      const double q = o.name == "--json"                           ? 0.5
                       : o.name == "--plot" || o.name == "--report" ? 0.05
                       : o.name == "--periodic-linearization"       ? (heavy ? 0.01 : 0.03)
                                                                    : p;
      if (!chance(q)) continue;
      if (o.takes_value) {
        std::string v = legal_value(o.name, c);
        if (o.name == "--terms" && !explicit_steps) v = std::to_string(integer(2, 8));
        if (chance(0.15)) {
          a.push_back(o.name + "=" + v);
        } else {
          a.insert(a.end(), {o.name, v});
        }
      } else {
        a.push_back(o.name);
      }
    }
    // merge and plot read files: here never a part or a result (refused, one line each).
    if (c == cli::Command::Merge || c == cli::Command::Plot) {
      for (int i = integer(c == cli::Command::Plot ? 1 : 0, 2); i > 0; --i)
        a.push_back(pick(std::vector<std::string>{"/dev/null", "/etc/hostname", "missing.json",
                                                  FLAPLAG_EXE, "/"}));
      if (c == cli::Command::Plot) a.insert(a.end(), {"--plot", legal_value("--plot", c)});
    }
    const bool analysis = c != cli::Command::Models && c != cli::Command::Modes;
    if (analysis && cli::find_option(c, "--steps") != nullptr) {
      if (explicit_steps) {
        const int hi = heavy ? 200 : 2000;
        a.insert(a.end(), {"--steps", std::to_string(integer(1, hi))});
      } else if (chance(0.2)) {
        a.insert(a.end(), {"--steps", "auto"});
      }
    }
    // More than one mode needs exact modes (else refused): mostly given.
    for (std::size_t i = 0; analysis && i + 1 < a.size(); ++i) {
      if ((a[i] == "--flap-modes" || a[i] == "--lag-modes") && a[i + 1] != "1" && chance(0.8)) {
        a.insert(a.end(), {"--modes", "exact"});
        break;
      }
    }
    // Every model trims now; a trim is tens of Floquet evaluations per point, and on a
    // multi-mode exact model with a stiff blade (a 100/rev lag mode) a trimmed point at high mu
    // takes minutes: legitimate work, not a contract question, and beyond the per-run limit
    // under the sanitizers.  Such vectors keep their options but do not trim (changed in place,
    // so that the random draws of every other vector stay the same; trims of many modes are
    // tested in cli_test.cpp).
    bool many_modes = false;
    for (std::size_t i = 0; i + 1 < a.size(); ++i)
      if ((a[i] == "--flap-modes" || a[i] == "--lag-modes") && a[i + 1] != "1") many_modes = true;
    for (std::size_t i = 0; many_modes && i < a.size(); ++i) {
      if (a[i] == "--trim=thrust" || a[i] == "--trim=moment") a[i] = "--trim=none";
      if (a[i] == "--trim" && i + 1 < a.size() && (a[i + 1] == "thrust" || a[i + 1] == "moment"))
        a[i + 1] = "none";
    }
    if (c != cli::Command::Typical && !subcommand_first) {
      // Between two options (never between an option and its value).
      std::vector<int> at{0, static_cast<int>(a.size())};
      for (std::size_t i = 0; i < a.size(); ++i) {
        if (a[i].rfind("--", 0) == 0) at.push_back(static_cast<int>(i));
      }
      a.insert(a.begin() + pick(at), cli::command_name(c));
    }
    // Some of the flags, once in a while, for the bare command and the subcommands alike.
    if (chance(0.02)) a.push_back(chance(0.5) ? "--help" : "--version");
  }

  std::string malformed() {
    static const std::vector<std::string> bad = {
        "",         "nan",   "NaN",      "-nan",       "inf",
        "-inf",     "+inf",  "infinity", "0x1p3",      "0x",
        "0x1p9999", "1e999", "-1e999",   "1e-999",     "1e308",
        "-1e308",   "abc",   "1.5x",     " 1",         "1 ",
        "1,5",      "--",    "-",        "1e",         ".",
        "+",        "0:1",   "1:0:0.1",  "0:1:0",      "0:1:-1",
        ":::",      "\t",    "\n",       "\xc3\xa9",   std::string(400, '1'),
        "-0",       "0",     "-5",       "2147483648", "99999999999999999999",
        "1e30",     "3e7",   "1e300",    "-1",         "0.0000001",
        "auto",     "exact", "csv",      "paper-2x2",  "=",
        "'1'"};
    return pick(bad);
  }

  std::string any_option() {
    const double r = uniform(0, 1);
    if (r < 0.15) {
      return pick(std::vector<std::string>{"--bogus", "-x", "--gamma-x", "---gamma", "--Gamma", "-",
                                           "--mu-", "-gamma", "--output-file", "--no-json"});
    }
    // Any option of any command (so some of another subcommand).
    std::vector<cli::Command> all = cli::subcommands();
    all.push_back(cli::Command::Typical);
    // (Blade tables and mode files are left to tests/cli_blade_test.cpp, malformed ones too.)
    std::vector<cli::OptionSpec> opts;
    for (const cli::OptionSpec& o : cli::options_of(pick(all)))
      if (o.name != "--blade-table" && o.name != "--blade-csv" && o.name != "--mode-shapes" &&
          o.name != "--mode-shapes-csv")
        opts.push_back(o);
    const cli::OptionSpec& o = pick(opts);
    return o.alias.empty() || chance(0.5) ? o.name : o.alias;
  }

  void corrupt(std::vector<std::string>& a) {
    const int where = integer(0, static_cast<int>(a.size()));
    switch (integer(0, 7)) {
      case 0: {  // a value replaced by a malformed one
        std::vector<int> values;
        for (std::size_t i = 1; i < a.size(); ++i) {
          if (!a[i - 1].empty() && a[i - 1][0] == '-' && (a[i].empty() || a[i][0] != '-')) {
            values.push_back(static_cast<int>(i));
          }
        }
        if (!values.empty()) {
          a[static_cast<std::size_t>(pick(values))] = malformed();
          break;
        }
        [[fallthrough]];
      }
      case 1:  // an option with a malformed value
        a.insert(a.begin() + where, {any_option(), malformed()});
        break;
      case 2:  // an option whose value is missing (at the end or before another option)
        if (chance(0.5)) {
          a.push_back(any_option());
        } else {
          a.insert(a.begin() + where, any_option());
        }
        break;
      case 3:  // --opt= and --opt=malformed
        a.insert(a.begin() + where, any_option() + "=" + (chance(0.5) ? "" : malformed()));
        break;
      case 4:  // a duplicated option (the last one wins)
        if (!a.empty()) {
          const std::size_t i =
              static_cast<std::size_t>(integer(0, static_cast<int>(a.size()) - 1));
          if (!a[i].empty() && a[i][0] == '-' && i + 1 < a.size()) {
            a.insert(a.end(), {a[i], chance(0.5) ? a[i + 1] : malformed()});
            break;
          }
        }
        a.insert(a.end(), {"--gamma", legal_value("--gamma", command_), "--gamma", malformed()});
        break;
      case 5:  // a stray word: unknown subcommand, second subcommand, positional
        a.insert(a.begin() + where,
                 pick(std::vector<std::string>{"bogus", "point", "sweep", "models", "0.5", "", "--",
                                               "-", "help"}));
        break;
      case 6:  // an option of another subcommand with a legal value
        a.insert(a.begin() + where,
                 {pick(std::vector<std::string>{"--psi", "--mu", "--mu-max", "--spec", "--basis",
                                                "--format", "--points", "--scan-step"}),
                  "1"});
        break;
      default:  // an unknown option, possibly with a value
        a.insert(a.begin() + where, pick(std::vector<std::string>{"--bogus", "--x=1", "-q", "--"}));
        break;
    }
  }

  void garbage(std::vector<std::string>& a) {
    const int n = integer(0, 6);
    for (int i = 0; i < n; ++i) {
      const double r = uniform(0, 1);
      a.push_back(r < 0.4   ? any_option()
                  : r < 0.8 ? malformed()
                            : std::string(cli::command_name(command())));
    }
  }

  std::mt19937_64 rng_;
  std::vector<std::string> base_models_, all_models_;
  cli::Command command_ = cli::Command::Typical;
};

// ---- running and judging ---------------------------------------------------------------------

struct Result {
  Generator::Vector vector;
  std::vector<std::string> args;  // as run (with -o)
  int exit_code = -1;
  int signal = 0;
  bool timed_out = false;
  double seconds = 0.0;
  std::string out, err;
  std::vector<std::string> dir_entries;  // output directory after the run
  std::string output_text;               // the output file, if any
};

const char* const kPrevious = "previous result\n";

Result run_one(const Generator::Vector& v, std::chrono::seconds limit) {
  Result r;
  r.vector = v;
  char tmpl[] = "/tmp/flaplag_fuzz.XXXXXX";
  const char* d = ::mkdtemp(tmpl);
  if (d == nullptr) {
    r.err = "mkdtemp failed";
    return r;
  }
  const std::string dir = d;
  const std::string out_dir = dir + "/out";
  ::mkdir(out_dir.c_str(), 0700);
  const std::string target = out_dir + "/result";
  r.args = v.args;
  if (v.output) {
    if (v.existing) std::ofstream(target) << kPrevious;
    // -o first: after the vector's arguments it could become the missing value of its last
    // option, which would hide a case the fuzzer wants.
    r.args.insert(r.args.begin(), {"-o", target});
  }
  const std::string out = dir + "/stdout", err = dir + "/stderr";
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  // A generated "-o NAME" must not write into the build tree.
  posix_spawn_file_actions_addchdir_np(&fa, dir.c_str());
  std::string exe = FLAPLAG_EXE;
  std::vector<std::string> copy = r.args;
  std::vector<char*> argv{exe.data()};
  for (std::string& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int rc = ::posix_spawn(&pid, exe.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) {
    r.err = "posix_spawn failed";
    fs::remove_all(dir);
    return r;
  }
  const flaplag::testing::ChildEnd end = flaplag::testing::wait_for_child(pid, start, limit);
  r.exit_code = end.exit_code;
  r.signal = end.signal;
  r.timed_out = end.timed_out;
  r.seconds = end.seconds;
  r.out = slurp(out);
  r.err = slurp(err);
  for (const auto& e : fs::directory_iterator(out_dir)) {
    r.dir_entries.push_back(e.path().filename().string());
  }
  if (fs::exists(target)) r.output_text = slurp(target);
  fs::remove_all(dir);
  return r;
}

const std::regex kErrorLine(
    R"(flaplag: error: (--[a-z0-9][a-z0-9-]*|-o|subcommand|argument) = [^\n]+: [^\n]+\n)");
const std::regex kBadToken(R"((^|[^A-Za-z_-])[+]?(nan|inf|infinity)([^A-Za-z_]|$))",
                           std::regex::icase);

void check_json(const Json& j, const std::string& key, bool lenient,
                std::vector<std::string>& problems) {
  // docs/cli.md: what a null means under each of these keys.
  // "trim": a trimmed critical search without a mu_c (e.g. unstable in hover) has no trim at
  // mu_c (commands_point.cc); the same for a study row.  An interval's end and error estimates
  // (docs/json.md, Interval) are null while unknown.
  static const std::set<std::string> kNullable = {"trim",
                                                  "stable",
                                                  "error_estimate",
                                                  "liouville_residual",
                                                  "mu_c",
                                                  "mu_c_error",
                                                  "omega",
                                                  "mode",
                                                  "kind",
                                                  "max_liouville_residual",
                                                  "flap_growth_rate",
                                                  "lag_growth_rate",
                                                  "intervals",
                                                  "end",
                                                  "onset_error",
                                                  "end_error",
                                                  "damping_ratio",
                                                  "basis",
                                                  "basis_error"};
  if (problems.size() > 5) return;
  if (j.is_object()) {
    const bool not_ok = j.contains("status") && j["status"] != "ok";
    // Unknown stability (a failed analysis, or a largest zeta within its own error of zero)
    // is never "ok".
    if (j.contains("stable") && j["stable"].is_null() &&
        !(j.contains("status") && j["status"] != "ok")) {
      problems.push_back("\"stable\": null with status ok");
    }
    // A result's "basis" is null for the assumed mode; with exact modes an ok point, or an ok
    // critical search with a mu_c, carries its basis error (one not estimated is a warning).
    if (!not_ok && j.contains("status") && j.contains("exponents") && j.contains("basis") &&
        j["basis"].is_number() && !(j.contains("mu_c") && j["mu_c"].is_null()) &&
        !(j.contains("basis_error") && j["basis_error"].is_number())) {
      problems.push_back("\"basis_error\": missing or null with exact modes and status ok");
    }
    for (auto it = j.begin(); it != j.end(); ++it) {
      check_json(it.value(), it.key(), lenient || not_ok, problems);
    }
  } else if (j.is_array()) {
    for (const Json& e : j) check_json(e, key, lenient, problems);
  } else if (j.is_null()) {
    if (!lenient && kNullable.count(key) == 0) problems.push_back("null under \"" + key + "\"");
  } else if (j.is_number_float()) {
    if (!std::isfinite(j.get<double>())) problems.push_back("non-finite number under " + key);
  } else if (j.is_string()) {
    const std::string s = j.get<std::string>();
    if (s == "-inf" && key != "zeta") problems.push_back("\"-inf\" under \"" + key + "\"");
    if (s == "nan" || s == "inf" || s == "-nan" || s == "+inf" || s == "NaN") {
      problems.push_back("\"" + s + "\" under \"" + key + "\"");
    }
  }
}

// Non-finite numbers inside the library's status messages, reported to the library's owner
// with reproducers (cli_test: CliLibraryBugs.DISABLED_*); the CLI passes messages on verbatim.
// Each is cut out of the text before the check, so only these exact phrases are tolerated.
// (none open: the rounding-floor and error-estimate messages are finite since the fix that
// enabled CliLibraryBugs.*)
const std::vector<std::regex> kKnownLibraryIssues = {};
std::atomic<int> known_library_issues{0};

std::string without_known_issues(std::string text) {
  const std::string before = text;
  for (const std::regex& re : kKnownLibraryIssues) text = std::regex_replace(text, re, "<known>");
  if (text != before) ++known_library_issues;
  return text;
}

bool has(const std::vector<std::string>& args, const char* word) {
  return std::find(args.begin(), args.end(), word) != args.end();
}

// The contract violations of one run (empty: none).
std::vector<std::string> judge(const Result& r) {
  std::vector<std::string> p;
  if (r.timed_out) return {"timed out after " + std::to_string(r.seconds) + " s"};
  if (r.signal != 0) return {"killed by signal " + std::to_string(r.signal)};
  if (r.exit_code != 0 && r.exit_code != 2) {
    return {"exit code " + std::to_string(r.exit_code) + ", stderr: " + r.err};
  }
  const bool out_file = r.vector.output;
  // A generated -o after the runner's wins: the output went elsewhere (the scratch directory).
  bool user_output = false;
  for (std::size_t i = out_file ? 2 : 0; i < r.args.size(); ++i) {
    const std::string& a = r.args[i];
    user_output = user_output || a.rfind("-o", 0) == 0 || a.rfind("--output", 0) == 0;
  }
  if (r.exit_code == 2) {
    if (!std::regex_match(r.err, kErrorLine)) p.push_back("malformed error line: [" + r.err + "]");
    if (!r.out.empty()) p.push_back("stdout on exit 2");
    if (out_file) {
      const std::vector<std::string> expected =
          r.vector.existing ? std::vector<std::string>{"result"} : std::vector<std::string>{};
      if (r.dir_entries != expected) p.push_back("output directory changed on exit 2");
      if (r.vector.existing && r.output_text != kPrevious) p.push_back("output file changed");
    }
    return p;
  }
  // At most one warning line (a --plot without gnuplot).
  static const std::regex kWarning(R"(flaplag: warning: [^\n]+\n)");
  if (!r.err.empty() && !std::regex_match(r.err, kWarning)) {
    p.push_back("stderr on exit 0: " + r.err);
  }
  const bool info = has(r.args, "--help") || has(r.args, "-h") || has(r.args, "--version");
  std::string text = r.out;
  if (user_output) {
    if (r.out.empty()) return p;  // written where the generated -o said
  } else if (out_file && !info) {
    if (!r.out.empty()) p.push_back("stdout written although -o was given");
    if (r.dir_entries != std::vector<std::string>{"result"}) {
      p.push_back("output directory holds other files than the result");
    }
    text = r.output_text;
  }
  if (text.empty()) p.push_back("no output");
  if (info) return p;
  text = without_known_issues(text);
  if (!text.empty() && text[0] == '{') {
    try {
      const Json j = Json::parse(text);
      check_json(j, "", false, p);
    } catch (const std::exception& e) {
      p.push_back(std::string("malformed JSON: ") + e.what());
    }
  } else {
    if (has(r.args, "--json")) p.push_back("--json gave no JSON");
    std::smatch m;
    if (std::regex_search(text, m, kBadToken)) p.push_back("\"" + m.str(0) + "\" in the output");
  }
  return p;
}

TEST(CliFuzz, ContractHoldsForGeneratedCommandLines) {
  const long vectors = env_long("FLAPLAG_FUZZ_VECTORS", 1000);
  const long jobs = env_long("FLAPLAG_FUZZ_JOBS", 2);
  const std::uint64_t seed = static_cast<std::uint64_t>(env_long("FLAPLAG_FUZZ_SEED", 19740601));
  const std::chrono::seconds limit(env_long("FLAPLAG_FUZZ_TIMEOUT", 60));

  Generator gen(seed);
  // The fuzzer knows a legal value for every option of every command.
  std::vector<cli::Command> commands = cli::subcommands();
  commands.push_back(cli::Command::Typical);
  for (cli::Command c : commands) {
    for (const cli::OptionSpec& o : cli::options_of(c)) {
      EXPECT_TRUE(gen.knows(o.name)) << "the fuzzer has no values for " << o.name;
    }
  }
  std::vector<Generator::Vector> all;
  for (long i = 0; i < vectors; ++i) all.push_back(gen.next());

  std::vector<Result> results(all.size());
  std::atomic<std::size_t> next{0};
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> workers;
  for (long w = 0; w < jobs; ++w) {
    workers.emplace_back([&] {
      for (std::size_t i = next++; i < all.size(); i = next++) results[i] = run_one(all[i], limit);
    });
  }
  for (std::thread& t : workers) t.join();
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::map<int, int> exits;
  std::map<std::string, int> kinds;
  int violations = 0;
  for (const Result& r : results) {
    ++exits[r.timed_out ? -2 : r.signal != 0 ? -1 : r.exit_code];
    ++kinds[r.vector.kind + " exit " + std::to_string(r.exit_code)];
    const std::vector<std::string> problems = judge(r);
    if (problems.empty()) continue;
    ++violations;
    std::string all_problems;
    for (const std::string& s : problems) all_problems += "\n    " + s;
    ADD_FAILURE() << shell_quoted(r.args) << all_problems;
  }
  // FLAPLAG_FUZZ_VERBOSE=1: why legal vectors were refused (to tune the generator).
  if (env_long("FLAPLAG_FUZZ_VERBOSE", 0) > 0) {
    for (const Result& r : results) {
      if (r.vector.kind == "legal" && r.exit_code == 2) std::printf("  refused: %s", r.err.c_str());
    }
  }
  std::vector<const Result*> slowest;
  for (const Result& r : results) slowest.push_back(&r);
  std::sort(slowest.begin(), slowest.end(),
            [](const Result* a, const Result* b) { return a->seconds > b->seconds; });
  std::printf(
      "fuzz: seed %llu, %ld vectors, %ld jobs, %.1f s wall; %d violations; %d outputs with a "
      "known library message issue\n",
      static_cast<unsigned long long>(seed), vectors, jobs, wall, violations,
      known_library_issues.load());
  for (const auto& [code, n] : exits) std::printf("  exit %d: %d\n", code, n);
  for (const auto& [k, n] : kinds) std::printf("  %s: %d\n", k.c_str(), n);
  for (std::size_t i = 0; i < std::min<std::size_t>(5, slowest.size()); ++i) {
    std::printf("  slow: %.2f s  %s\n", slowest[i]->seconds,
                shell_quoted(slowest[i]->args).c_str());
  }
  EXPECT_GT(exits[0], vectors / 10) << "too few vectors reached an analysis";
  EXPECT_GT(exits[2], vectors / 10) << "too few vectors were refused";
}

}  // namespace

}  // namespace cli_fuzz_test
