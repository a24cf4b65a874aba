#include "flaplag/campbell.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>

#include "flaplag/blade/blade.h"
#include "flaplag/blade/imported_modes.h"
#include "flaplag/blade/rotating_modes.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/core/parallel.h"
#include "flaplag/model_api.h"
#include "flaplag/numerics/continuation.h"

namespace flaplag {

namespace {

// The blade's bending stiffness by Omega_0^2 (fixed as the speed changes; with a blade table the
// scale of its stiffness columns, rotating_modes.h) and the modes the analysis labels.
struct Blade {
  ExactModeOptions shape;
  double stiffness[model::kDirectionCount] = {};  // per direction, model::index(d)
  double of(BendingDirection d) const { return stiffness[model::index(d)]; }
};

Blade blade_of(const RotorParameters& p) {
  // The speeds' frequencies come from the Galerkin basis (rotating_modes.h).
  if (p.basis == kElementBasis) {
    throw InvalidInput("basis", "elements",
                       "the Campbell diagram uses the Galerkin basis (1..12, converged or "
                       "paper); finite elements are not implemented for it");
  }
  Blade b;
  b.shape.n_basis = galerkin_basis(p);
  b.shape.e1_over_l = p.root_offset / p.length_ratio;
  b.shape.blade = p.blade;
  const double first[model::kDirectionCount] = {p.omega_flap, p.omega_lag};
  for (const BendingDirection d : model::kDirections)
    b.stiffness[model::index(d)] = stiffness_for_frequency(d, first[model::index(d)], b.shape);
  return b;
}

// Mode k of a label (model_api.h: "flap" and "lag" are mode 1; "flap2" mode 2) and its
// direction.
BendingDirection direction_of(const std::string& label) {
  std::string direction;
  int k = 1;
  model::parse_mode_label(label, &direction, &k);
  for (const BendingDirection d : model::kDirections)
    if (direction == model::kDirectionNames[model::index(d)]) return d;
  return BendingDirection::Flap;
}
int mode_number(const std::string& label) {
  std::string direction;
  int k = 1;
  model::parse_mode_label(label, &direction, &k);
  return k;
}

// Omega = 0: the nonrotating cantilever, omega_k / Omega_0 = sqrt(k / mbar) beta_k^2 (a blade
// table: its k-th nonrotating frequency at the nominal scale).
CampbellPoint at_rest(const Blade& b, const std::vector<std::string>& labels) {
  std::vector<double> frequencies[model::kDirectionCount];
  for (const BendingDirection d : model::kDirections)
    frequencies[model::index(d)] = nonrotating_frequencies(d, b.of(d), b.shape);
  auto nonrotating = [&](BendingDirection d, int k) {
    return frequencies[model::index(d)].at(static_cast<std::size_t>(k - 1));
  };
  CampbellPoint pt;
  pt.omega_flap = nonrotating(BendingDirection::Flap, 1);
  pt.omega_lag = nonrotating(BendingDirection::Lag, 1);
  for (const std::string& l : labels) {
    const double f = nonrotating(direction_of(l), mode_number(l));
    pt.modes.push_back({l, f, f, std::nullopt});
  }
  pt.Note(
      "Omega = 0: the nonrotating structural frequencies (no centrifugal or aerodynamic "
      "loads)");
  return pt;
}

// Speed s > 0: the blade's first rotating frequencies by Omega with stiffness k / s^2, and the
// exponents of the rotor with them at mu.
CampbellPoint at_speed(double s, const RotorParameters& params, const TransitionOptions& transition,
                       const CampbellOptions& options, const Blade& b,
                       const std::vector<std::string>& labels) {
  CampbellPoint pt;
  pt.speed = s;
  pt.omega_flap =
      rotating_frequencies(BendingDirection::Flap, b.of(BendingDirection::Flap) / (s * s), b.shape)
          .front();
  pt.omega_lag =
      rotating_frequencies(BendingDirection::Lag, b.of(BendingDirection::Lag) / (s * s), b.shape)
          .front();
  RotorParameters p = params;
  p.omega_flap = pt.omega_flap;
  p.omega_lag = pt.omega_lag;
  const PointResult r = Analysis(p, transition).point(options.mu, options.scan_step);
  pt.Merge(r);
  if (!r.IsUsable()) return pt;
  for (const std::string& l : labels) {
    const LabelledExponent* e = dominant_exponent(r, l);
    if (e == nullptr) {
      pt.Worsen(Status::Failed, "no exponent of mode " + l);
      pt.modes.clear();
      return pt;
    }
    pt.modes.push_back({l, s * e->omega, e->omega, damping_ratio(e->zeta, e->omega)});
  }
  return pt;
}

// Every crossing of frequency - n speed through zero between neighbouring usable points.
std::vector<CampbellCrossing> crossings_of(const CampbellResult& c) {
  std::vector<CampbellCrossing> out;
  for (std::size_t m = 0; m < c.labels.size(); ++m) {
    for (int n = 1; n <= c.harmonics; ++n) {
      for (std::size_t i = 0; i + 1 < c.points.size(); ++i) {
        const CampbellPoint &a = c.points[i], &b = c.points[i + 1];
        if (a.modes.size() != c.labels.size() || b.modes.size() != c.labels.size()) continue;
        const double ga = a.modes[m].frequency - n * a.speed;
        const double gb = b.modes[m].frequency - n * b.speed;
        if ((ga > 0.0) == (gb > 0.0)) continue;
        const double s = a.speed + (b.speed - a.speed) * ga / (ga - gb);
        out.push_back({c.labels[m], n, s, n * s});
      }
    }
  }
  return out;
}

}  // namespace

std::optional<InvalidInput> CampbellOptions::Validate() const {
  return Requirements().InRanges(*this).Include(threads_problem(threads)).Result();
}

CampbellResult campbell_diagram(const RotorParameters& params, const TransitionOptions& transition,
                                const CampbellOptions& options) {
  options.Check();
  // Imported shapes and frequencies hold at one rotor speed: the blade behind them (its
  // stiffness) is not known, so neither are its frequencies at another speed.
  if (params.mode_shapes) {
    throw InvalidInput("mode_shapes", params.mode_shapes->source,
                       "the Campbell diagram needs the blade's frequencies at every rotor speed; "
                       "imported mode shapes give them at one speed only (a blade table, or the "
                       "uniform blade, without `mode_shapes` gives them)");
  }
  const Analysis nominal(params, transition);  // checks the rotor at Omega_0
  const Blade blade = blade_of(params);
  CampbellResult c;
  c.mu = options.mu;
  c.harmonics = options.harmonics;
  c.labels = distinct_labels(nominal.hover().labels);
  // Flap modes, then lag modes, each in order of their number.
  std::sort(c.labels.begin(), c.labels.end(), [](const std::string& a, const std::string& b) {
    const bool a_lag = direction_of(a) == BendingDirection::Lag;
    const bool b_lag = direction_of(b) == BendingDirection::Lag;
    return a_lag != b_lag ? b_lag : mode_number(a) < mode_number(b);
  });
  c.points.resize(static_cast<std::size_t>(options.points));
  parallel_for(c.points.size(), options.threads, nullptr, {}, [&](std::size_t i) {
    const double s =
        options.speed_max * static_cast<double>(i) / static_cast<double>(c.points.size() - 1);
    CampbellPoint& pt = c.points[i];
    try {
      pt = i == 0 ? at_rest(blade, c.labels)
                  : at_speed(s, params, transition, options, blade, c.labels);
    } catch (const std::exception& e) {  // InvalidInput: e.g. a frequency the basis cannot reach
      pt = CampbellPoint{};
      pt.Worsen(Status::Failed, e.what());
    }
    pt.speed = s;
  });
  for (const CampbellPoint& pt : c.points)
    c.Include(pt, "at Omega/Omega_0 = " + round_trip_text(pt.speed) + ": ");
  c.crossings = crossings_of(c);
  return c;
}

}  // namespace flaplag
