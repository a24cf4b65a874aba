// flaplag analysis — helpers shared by the sources of the analysis library (not installed).
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "flaplag/blade/blade.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/model_api.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/rotor/periodic_equilibrium.h"
#include "flaplag/rotor/system_builder.h"
#include "flaplag/rotor/validity.h"

namespace flaplag::internal {

// mu in [0, kMaxAdvanceRatio], else InvalidInput(name, ...).
inline void check_mu(double mu, const char* name) {
  if (!std::isfinite(mu) || mu < 0.0 || mu > kMaxAdvanceRatio) {
    throw InvalidInput(name, round_trip_text(mu),
                       "advance ratio must be >= 0 and <= " + round_trip_text(kMaxAdvanceRatio));
  }
}

// Sorted by label, then omega descending: the order in which results are shown.  Stable (an
// insertion sort: a handful of exponents, no temporary buffer).
inline void sort_for_output(std::vector<LabelledExponent>& v) {
  auto before = [](const LabelledExponent& a, const LabelledExponent& b) {
    return a.label != b.label ? a.label < b.label : a.omega > b.omega;
  };
  for (std::size_t i = 1; i < v.size(); ++i)
    for (std::size_t j = i; j > 0 && before(v[j], v[j - 1]); --j) std::swap(v[j], v[j - 1]);
}

// The harmonic balance behind periodic_linearization, for the analysis and the trim alike (the
// stability comes from the analysis' own Floquet evaluation, so none here).
inline PeriodicEquilibriumOptions equilibrium_options() {
  PeriodicEquilibriumOptions o;
  o.check_stability = false;
  return o;
}

// Tip deflections w/l (flap) and v/l (lag) of the modal displacements q0 + y, y a state in the
// order of model_api.h and q0 (M + N values: flap then lag) the hover equilibrium, or none.
struct TipDeflection {
  double flap = 0.0, lag = 0.0;
};
inline TipDeflection tip_deflection(const ModeSet& modes, int M, int N, const Eigen::VectorXd& y,
                                    const Eigen::VectorXd* q0 = nullptr) {
  TipDeflection t;
  for (int k = 0; k < M; ++k) {
    const double g = y(model::flap_displacement_index(k, M, N));
    t.flap += modes.flap[k]->value(0, 1.0) * (q0 != nullptr ? (*q0)(k) + g : g);
  }
  for (int r = 0; r < N; ++r) {
    const double h = y(model::lag_displacement_index(r, M, N));
    t.lag += modes.lag[r]->value(0, 1.0) * (q0 != nullptr ? (*q0)(M + r) + h : h);
  }
  return t;
}

// The validity envelope (rotor/validity.h) of the operating point a builder describes: its
// pitch, inflow and the flap tip deflection of its hover equilibrium.
inline std::string validity_of(const detail::SystemBuilder& b) {
  const model::ModelDescriptor& m = b.model();
  double flap_tip = std::numeric_limits<double>::quiet_NaN();
  if (b.hover().q0.size() == m.flap_modes + m.lag_modes) {
    flap_tip = 0.0;
    for (int k = 0; k < m.flap_modes; ++k)
      flap_tip += b.modes().flap[k]->value(0, 1.0) * b.hover().q0(k);
  }
  return validity_warning(b.params(), b.inflow(), flap_tip);
}

// A result is never better than what it rests on: `status` and `message` take the worse of
// their own and (s, m), the messages joined.
inline void combine(Status* status, std::string* message, Status s, const std::string& m) {
  if (s == Status::Ok && m.empty()) return;
  if (static_cast<int>(s) > static_cast<int>(*status)) *status = s;
  if (!m.empty()) *message = message->empty() ? m : *message + "; " + m;
}

}  // namespace flaplag::internal
