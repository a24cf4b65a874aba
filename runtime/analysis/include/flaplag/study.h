// flaplag — parametric studies: mu_c (and every instability interval) versus one parameter, and
// stability maps over two parameters, one of which may be the advance ratio.
//
// Each row of a study or a map is independent: rows run on a pool of threads and every row's
// result depends only on its own inputs, so the result is identical, bit for bit, for any
// number of threads.  A cancel flag is polled between rows; rows already started finish, so
// the finished rows are always a prefix of the full result.
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/core/fields.h"
#include "flaplag/core/parallel.h"
#include "flaplag/core/validation.h"
#include "flaplag/trim.h"

namespace flaplag {

// Progress: ProgressFunction (core/parallel.h), called after each finished row with (rows
// finished, rows in all).

// The name of an axis: "mu" or a Real field of the parameter table (rotor/parameter_table.h),
// e.g. "omega_lag", "theta", "damping_lag".
bool is_study_parameter(const std::string& name);
// p with field `name` set to v (InvalidInput("parameter", name) for an unknown name; the value
// itself is checked when an Analysis is built from p).
RotorParameters with_parameter(RotorParameters p, const std::string& name, double v);

// Worker threads of a study or a map: threads_problem's (core/parallel.h) words as a Range.
inline constexpr Range kThreadsRange{{0.0, static_cast<double>(kMaxThreads), false, false},
                                     "0 (all cores) or 1..256"};
static_assert(kMaxThreads == 256, "kThreadsRange's words name kMaxThreads");

struct StudyOptions {
  std::string parameter;       // the varied field (not "mu")
  std::vector<double> values;  // 1..kMaxStudyValues values
  CriticalOptions critical;    // the search at each value (all_intervals is always on)
  // kind != None: each row is trimmed at every mu of its search (trim.h, Analysis with
  // OperatingCondition::Trimmed): mu_c at fixed C_T.  The trim replaces theta (and, moment trim,
  // theta1c, theta1s).
  TrimOptions trim;
  // Untrimmed rows: the inflow at every mu (rotor/inflow.h; the default eq 2.24).  Not with a
  // trim (InvalidInput "inflow"): a trim has its own.
  InflowModel inflow;
  // What every row is linearized about (OperatingCondition::linearization, trimmed or not).
  Linearization linearization = Linearization::HoverEquilibrium;
  int threads = 0;  // 0: as many as the hardware has; else 1..kMaxThreads (core/parallel.h)
  // Given (kDampingCriterionRange, numerics/continuation.h): each row also sweeps mu = 0,
  // scan_step, ..., mu_max (trimmed when the row is) and reports, per mode, the first mu where
  // its damping ratio falls below it (StudyRow::damping_crossings).  The sweep is a second
  // continuation at the exponents' full accuracy: it about doubles a row's cost.
  std::optional<double> damping_criterion;

  std::optional<InvalidInput> Validate() const;
  bool IsValid(std::string* error) const { return IsValidReport(Validate(), error); }
  void Check() const { ThrowIfInvalid(Validate()); }
};

// The scalar options (the axis, the search and the condition are checked by hand in Validate(),
// in the order of the checks before the table, which the ranged rows keep).
constexpr auto describe(Tag<StudyOptions>) {
  using O = StudyOptions;
  return std::make_tuple(
      Option{"damping_criterion", &O::damping_criterion, "-",
             "damping ratio asked of every mode: report the first mu where each mode's damping "
             "ratio -zeta/|lambda| falls below it",
             &kDampingCriterionRange},
      Option{"threads", &O::threads, "",
             "worker threads; the answer does not depend on their number", &kThreadsRange});
}

inline constexpr std::size_t kMaxStudyValues = 100000;

struct StudyRow {
  double value = 0.0;
  // mu_c, its mode/omega/kind, hover_unstable, every instability interval, status and message.
  // An InvalidInput at this value (e.g. an exact-mode frequency the basis cannot reach) gives
  // status Failed with the reason as message.
  CriticalResult critical;
  // Trimmed studies: the trim at mu_c that the row's result rests on (RotorCritical::trim; its
  // problems are in critical's status and message); nullopt without mu_c or without a trim.
  std::optional<TrimResult> trim;
  // With StudyOptions::damping_criterion: one crossing per mode (labels in the order of the
  // sweep's exponents: sorted); empty otherwise or when the row failed before its sweep.
  std::vector<DampingCrossing> damping_crossings;
};

// A row as a study document holds it (`flaplag study --json`, docs/json.md): the value, the part
// of its search's CriticalResult that a table of mu_c shows, the trim and the crossings.  A
// front end writes trim and damping_crossings when the study asked for them (null or [] when a
// row has none), and basis_error with exact modes only.
constexpr auto describe(Tag<StudyRow>) {
  using R = StudyRow;
  using Number = std::optional<double>;
  return std::make_tuple(
      Field{"value", &R::value, "", "the value of the varied parameter (in its units)"},
      Computed{"hover_unstable", +[](const R& r) { return r.critical.hover_unstable; }, "",
               "unstable already in hover (then no mu_c)"},
      Computed{"mu_c", +[](const R& r) { return r.critical.mu_c; }, "-",
               "the first mu with zeta > 0; null: stable up to mu_max, unstable in hover, or "
               "the search failed"},
      Computed{"mu_c_error", +[](const R& r) { return r.critical.mu_c_error; }, "-",
               "estimated |mu_c error| (CriticalResult's)"},
      Computed{"basis_error",
               +[](const R& r) {
                 return r.critical.basis ? std::optional<Number>(r.critical.basis_error)
                                         : std::nullopt;
               },
               "-",
               "exact modes: the part of mu_c_error that is the Galerkin basis's; null when not "
               "estimated (the message says why); absent for the assumed mode",
               kFieldOmitWhenEmpty},
      Computed{"mode",
               +[](const R& r) {
                 return r.critical.mu_c ? std::optional<std::string>(r.critical.mode)
                                        : std::nullopt;
               },
               "", "the mode that crosses at mu_c; null without mu_c"},
      Computed{"omega",
               +[](const R& r) { return r.critical.mu_c ? Number(r.critical.omega) : Number(); },
               "per rev", "its omega at mu_c, >= 0; null without mu_c"},
      Computed{"kind",
               +[](const R& r) {
                 return r.critical.mu_c ? std::optional<InstabilityKind>(r.critical.kind)
                                        : std::nullopt;
               },
               "", "flutter or periodic (omega locked to 0, 1/2 or 1 per rev); null without mu_c"},
      Computed{"intervals",
               +[](const R& r) {
                 std::vector<std::vector<Number>> pairs;
                 for (const InstabilityInterval& i : r.critical.intervals)
                   pairs.push_back({i.onset, i.end});
                 return pairs;
               },
               "",
               "every interval of instability up to mu_max as [onset, end]; end null when still "
               "unstable at mu_max"},
      Field{"trim", &R::trim, "",
            "trimmed studies: the trim at mu_c (RotorCritical::trim); null without mu_c (absent "
            "untrimmed)",
            kFieldOmitWhenEmpty},
      Field{"damping_crossings", &R::damping_crossings, "",
            "with a damping criterion: one crossing per mode (absent without)",
            kFieldOmitWhenEmpty},
      Computed{"status", +[](const R& r) { return r.critical.status; }, "",
               "the search's status at this value; failed when the value is refused"},
      Computed{"message", +[](const R& r) { return r.critical.message; }, "",
               "the search's message (the reason when the value is refused)", kFieldMessage});
}

struct StudyResult : Outcome {
  std::vector<StudyRow> rows;  // rows_done of them when cancelled
  std::size_t rows_done = 0;
  bool cancelled = false;
  // Outcome: the worst row's status, and the first problem met (Outcome::Include)
};

// Options are checked (Check()); so is every value (rows with invalid values are Failed rows,
// not exceptions).  base and transition are as for Analysis.
StudyResult run_study(const RotorParameters& base, const TransitionOptions& transition,
                      const StudyOptions& options, const std::atomic<bool>* cancel = nullptr,
                      const ProgressFunction& progress = {});

struct MapAxis {
  std::string parameter;       // "mu" or a study parameter
  std::vector<double> values;  // ascending for "mu"
};

struct MapOptions {
  static constexpr Range kMuRange{{0.0, kMaxAdvanceRatio, false, false}, "in [0, 1000]"};
  static_assert(kMaxAdvanceRatio == 1000.0, "kMuRange's words name kMaxAdvanceRatio");

  MapAxis x, y;             // at most one of them "mu"; each with 1..kMaxMapValues values
  double mu = 0.0;          // the advance ratio when neither axis is "mu"
  double scan_step = 0.01;  // continuation step in mu
  TrimOptions trim;         // kind != None: every cell trimmed at its mu (trim.h)
  InflowModel inflow;       // untrimmed cells: the inflow model, as StudyOptions::inflow
  Linearization linearization = Linearization::HoverEquilibrium;  // as StudyOptions's
  int threads = 0;

  std::optional<InvalidInput> Validate() const;
  bool IsValid(std::string* error) const { return IsValidReport(Validate(), error); }
  void Check() const { ThrowIfInvalid(Validate()); }
};

constexpr auto describe(Tag<MapOptions>) {
  using O = MapOptions;
  return std::make_tuple(
      Option{"mu", &O::mu, "-", "advance ratio when neither axis is mu", &O::kMuRange},
      Option{"scan_step", &O::scan_step, "-", "continuation step in mu from hover", &kPositive},
      Option{"threads", &O::threads, "",
             "worker threads; the answer does not depend on their number", &kThreadsRange});
}

inline constexpr std::size_t kMaxMapValues = 10000;

struct MapCell : Outcome {
  bool computed = false;           // false: not reached (cancelled run)
  std::optional<double> max_zeta;  // largest zeta, per rev; nullopt when unknown (Failed)
  std::string mode;                // label of the least stable exponent
  double omega = 0.0;              // its omega, per rev
  InstabilityKind kind = InstabilityKind::Flutter;  // periodic when omega is locked (0, 1/2, 1)
};

// The JSON documents (flaplag map --json) write the exponent's rows as grids (kMapGridRows, null
// where unknown); Python has every row as an array of the map's shape.
constexpr auto describe(Tag<MapCell>) {
  return std::tuple_cat(
      std::make_tuple(
          Field{"computed", &MapCell::computed, "", "false: not reached (a cancelled run)"},
          Field{"max_zeta", &MapCell::max_zeta, "per rev",
                "the largest zeta at the cell; null when unknown (failed)", kFieldNegativeInfinity},
          Field{"mode", &MapCell::mode, "", "the label of the least stable exponent"},
          Field{"omega", &MapCell::omega, "per rev", "its omega, >= 0"},
          Field{"kind", &MapCell::kind, "",
                "flutter (omega not locked) or periodic (omega locked to 0, 1/2 or 1 per rev)"}),
      describe(Tag<Outcome>{}));
}

// The rows of MapCell a map document holds, each as a grid (rows y, columns x).
inline constexpr const char* kMapGridRows[] = {"max_zeta", "mode", "kind"};

struct MapResult : Outcome {
  // cells[i][j]: y.values[i], x.values[j].  The work is done in lines along the "mu" axis (one
  // continuation in mu per value of the other parameter) or, without a "mu" axis, in rows; a
  // cancelled run has the first lines_done lines computed (MapCell::computed).
  std::vector<std::vector<MapCell>> cells;
  std::size_t lines_done = 0;
  bool cancelled = false;
  // Outcome: the worst computed cell's status, and the first problem met in line order
};

MapResult run_map(const RotorParameters& base, const TransitionOptions& transition,
                  const MapOptions& options, const std::atomic<bool>* cancel = nullptr,
                  const ProgressFunction& progress = {});

}  // namespace flaplag
