// flaplag — parametric studies and stability maps on a pool of threads.
#include "flaplag/study.h"

#include <algorithm>
#include <cmath>

#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/core/parallel.h"
#include "flaplag/rotor/parameter_table.h"

namespace flaplag {
namespace {

// A study's or map's operating condition: trimmed with its trim options, else fixed controls at
// its inflow model (OperatingCondition::Validate refuses a non-uniform one with a trim); either
// linearized about its linearization.
template <class Options>
OperatingCondition condition_of(const Options& o) {
  OperatingCondition c =
      o.trim.kind != TrimKind::None ? OperatingCondition::Trimmed(o.trim) : OperatingCondition{};
  c.inflow = o.inflow;
  c.linearization = o.linearization;
  return c;
}

std::optional<InvalidInput> bad(const char* name, const std::string& value,
                                const std::string& reason) {
  return InvalidInput(name, value, reason);
}

std::optional<InvalidInput> check_values(const char* name, const std::vector<double>& v,
                                         std::size_t max_count) {
  if (v.empty()) return bad(name, "[]", "need at least one value");
  if (v.size() > max_count)
    return bad(name, std::to_string(v.size()) + " values",
               "at most " + std::to_string(max_count) + " values");
  for (double x : v)
    if (!std::isfinite(x)) return bad(name, round_trip_text(x), "values must be finite");
  return std::nullopt;
}

std::optional<InvalidInput> study_problem(const StudyOptions& o) {
  if (o.parameter == "mu" || !is_study_parameter(o.parameter))
    return bad("parameter", o.parameter.empty() ? "\"\"" : o.parameter,
               "must name a numeric rotor parameter (not mu: mu_c is what a study finds)");
  if (auto p = check_values("values", o.values, kMaxStudyValues)) return p;
  return Requirements()
      .InRanges(o, "damping_criterion")
      .Include(o.critical.Validate())
      .Include(o.trim.Validate())
      .Include(condition_of(o).Validate())
      .InRanges(o, "threads")
      .Result();
}

std::optional<InvalidInput> map_problem(const MapOptions& o) {
  for (const MapAxis* a : {&o.x, &o.y}) {
    const char* name = a == &o.x ? "x" : "y";
    if (a->parameter != "mu" && !is_study_parameter(a->parameter))
      return bad(name, a->parameter.empty() ? "\"\"" : a->parameter,
                 "must be mu or a numeric rotor parameter");
    if (auto p = check_values(name, a->values, kMaxMapValues)) return p;
    if (a->parameter == "mu") {
      for (std::size_t i = 0; i < a->values.size(); ++i) {
        const double mu = a->values[i];
        if (mu < 0.0 || mu > kMaxAdvanceRatio)
          return bad(name, round_trip_text(mu), "advance ratios must be in [0, 1000]");
        if (i > 0 && mu <= a->values[i - 1])
          return bad(name, round_trip_text(mu), "advance ratios must be increasing");
      }
    }
  }
  if (o.x.parameter == o.y.parameter) return bad("y", o.y.parameter, "must differ from the x axis");
  return Requirements()
      .InRanges(o, "mu")
      .InRanges(o, "scan_step")
      .Include(o.trim.Validate())
      .Include(condition_of(o).Validate())
      .InRanges(o, "threads")
      .Result();
}

// The least stable exponent of a point as a map cell.
MapCell cell_of(const PointResult& p) {
  MapCell c;
  c.computed = true;
  c.status = p.status;
  c.message = p.message;
  if (p.exponents.empty() || p.status == Status::Failed) return c;
  const LabelledExponent* best = &p.exponents.front();
  for (const LabelledExponent& e : p.exponents)
    if (e.zeta > best->zeta || (e.zeta == best->zeta && e.omega >= 0.0 && best->omega < 0.0))
      best = &e;
  c.max_zeta = best->zeta;
  c.mode = best->label;
  c.omega = std::abs(best->omega);
  c.kind = classify_crossing(best->omega);
  return c;
}

// The crossings of the damping criterion along a row's sweep, per mode (the labels of its first
// point, sorted as a point's exponents are).
std::vector<DampingCrossing> crossings_along(const SweepResult& s, double criterion) {
  std::vector<std::string> labels;
  if (!s.points.empty())
    for (const LabelledExponent& e : s.points.front().exponents) labels.push_back(e.label);
  return damping_crossings(s, distinct_labels(labels), criterion);
}

MapCell failed_cell(const std::string& why) {
  MapCell c;
  c.computed = true;
  c.status = Status::Failed;
  c.message = why;
  return c;
}

}  // namespace

bool is_study_parameter(const std::string& name) {
  const ParameterSpec* s = find_parameter(name);
  return s != nullptr && s->type == ParameterType::Real;
}

RotorParameters with_parameter(RotorParameters p, const std::string& name, double v) {
  const ParameterSpec* s = find_parameter(name);
  if (s == nullptr || s->type != ParameterType::Real)
    throw InvalidInput("parameter", name.empty() ? "\"\"" : name, "not a numeric rotor parameter");
  p.*(s->real) = v;
  return p;
}

std::optional<InvalidInput> StudyOptions::Validate() const { return study_problem(*this); }

std::optional<InvalidInput> MapOptions::Validate() const { return map_problem(*this); }

StudyResult run_study(const RotorParameters& base, const TransitionOptions& transition,
                      const StudyOptions& options, const std::atomic<bool>* cancel,
                      const ProgressFunction& progress) {
  options.Check();
  transition.Check();
  CriticalOptions crit = options.critical;
  crit.all_intervals = true;
  StudyResult out;
  out.rows.resize(options.values.size());
  out.rows_done =
      parallel_for(options.values.size(), options.threads, cancel, progress, [&](std::size_t i) {
        StudyRow& row = out.rows[i];
        row.value = options.values[i];
        try {
          const RotorParameters p = with_parameter(base, options.parameter, row.value);
          const Analysis an(p, transition, condition_of(options));
          // (the rows are the parallel work: one thread each)
          RotorCritical c = an.critical(crit, 1);
          row.trim = std::move(c.trim);
          row.critical = std::move(c);
          if (options.damping_criterion)
            row.damping_crossings = crossings_along(an.sweep(0.0, crit.mu_max, crit.scan_step, 1),
                                                    *options.damping_criterion);
        } catch (const InvalidInput& e) {
          row.critical = CriticalResult{};
          row.critical.mu_max = crit.mu_max;
          row.critical.status = Status::Failed;
          row.critical.message = e.what();
        }
      });
  out.cancelled = out.rows_done < out.rows.size();
  out.rows.resize(out.rows_done);
  for (const StudyRow& r : out.rows)
    out.Include(r.critical, options.parameter + " = " + round_trip_text(r.value) + ": ");
  return out;
}

MapResult run_map(const RotorParameters& base, const TransitionOptions& transition,
                  const MapOptions& options, const std::atomic<bool>* cancel,
                  const ProgressFunction& progress) {
  options.Check();
  transition.Check();
  const std::size_t nx = options.x.values.size(), ny = options.y.values.size();
  MapResult out;
  out.cells.assign(ny, std::vector<MapCell>(nx));
  const bool mu_x = options.x.parameter == "mu", mu_y = options.y.parameter == "mu";
  // A line: one value of the non-mu parameter, continued along mu; without a mu axis, a row.
  const std::size_t lines = mu_x ? ny : (mu_y ? nx : ny);
  out.lines_done = parallel_for(lines, options.threads, cancel, progress, [&](std::size_t l) {
    if (mu_x || mu_y) {
      const MapAxis& other = mu_x ? options.y : options.x;
      const std::vector<double>& mus = mu_x ? options.x.values : options.y.values;
      auto put = [&](std::size_t k, MapCell c) {
        (mu_x ? out.cells[l][k] : out.cells[k][l]) = std::move(c);
      };
      try {
        const RotorParameters p = with_parameter(base, other.parameter, other.values[l]);
        const SweepResult s =
            Analysis(p, transition, condition_of(options)).track(mus, options.scan_step, 1);
        for (std::size_t k = 0; k < mus.size(); ++k)
          put(k, k < s.points.size() ? cell_of(s.points[k])
                                     : failed_cell("continuation stopped: " + s.message));
      } catch (const InvalidInput& e) {
        for (std::size_t k = 0; k < mus.size(); ++k) put(k, failed_cell(e.what()));
      }
      return;
    }
    for (std::size_t j = 0; j < nx; ++j) {
      try {
        const RotorParameters p =
            with_parameter(with_parameter(base, options.y.parameter, options.y.values[l]),
                           options.x.parameter, options.x.values[j]);
        out.cells[l][j] = cell_of(
            Analysis(p, transition, condition_of(options)).point(options.mu, options.scan_step));
      } catch (const InvalidInput& e) {
        out.cells[l][j] = failed_cell(e.what());
      }
    }
  });
  out.cancelled = out.lines_done < lines;
  // In line order, so that the first problem of a map split into blocks of lines (flaplag map
  // --shard) is the first problem of the first block that has one.
  const std::size_t along = mu_y ? ny : nx;
  for (std::size_t l = 0; l < lines; ++l)
    for (std::size_t k = 0; k < along; ++k) {
      const MapCell& c = mu_y ? out.cells[k][l] : out.cells[l][k];
      if (c.computed) out.Include(c);
    }
  return out;
}

}  // namespace flaplag
