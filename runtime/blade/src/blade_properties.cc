// flaplag — the spanwise distributions of a nonuniform blade: interpolation and checks.
#include "flaplag/blade/blade_properties.h"

#include <algorithm>
#include <cmath>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"

namespace flaplag {

double BladeProperties::at(const std::vector<double>& column, double s) const {
  if (x0.size() < 2 || column.size() != x0.size()) return column.empty() ? 0.0 : column.front();
  s = std::clamp(s, x0.front(), x0.back());
  // The interval [x0[i], x0[i+1]] that holds s (the last one for s = 1).
  const auto it = std::upper_bound(x0.begin(), x0.end(), s);
  std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - x0.begin() - 1, 0));
  i = std::min(i, x0.size() - 2);
  const double t = (s - x0[i]) / (x0[i + 1] - x0[i]);
  return column[i] + t * (column[i + 1] - column[i]);
}

std::vector<double> BladeProperties::corners() const {
  std::vector<double> c;
  for (std::size_t i = 1; i + 1 < x0.size(); ++i) c.push_back(x0[i]);
  return c;
}

namespace {

std::string station_name(const BladeProperties& b, const char* column, std::size_t i) {
  return std::string(column) + " at x0 = " + round_trip_text(b.x0[i]) +
         (b.source.empty() ? "" : " (" + b.source + ", station " + std::to_string(i + 1) + ")");
}

void check_column(const BladeProperties& b, const std::vector<double>& v, const char* column,
                  double lo, bool lo_open, double hi) {
  if (v.size() != b.x0.size()) {
    throw InvalidInput(column, std::to_string(v.size()) + " values",
                       "needs one value per station (" + std::to_string(b.x0.size()) + ")");
  }
  for (std::size_t i = 0; i < v.size(); ++i) {
    const bool ok = std::isfinite(v[i]) && (lo_open ? v[i] > lo : v[i] >= lo) && v[i] < hi;
    if (!ok) {
      throw InvalidInput(station_name(b, column, i), round_trip_text(v[i]),
                         std::string("must be finite and ") + (lo_open ? "> " : ">= ") +
                             round_trip_text(lo) +
                             (std::isfinite(hi) ? " and < " + round_trip_text(hi) : ""));
    }
  }
}

// int_0^1 mbar x0^2 dx0 of the piecewise-linear mass, exactly (Simpson is exact for the cubic
// on each interval).
double mass_moment(const BladeProperties& b) {
  double s = 0.0;
  for (std::size_t i = 0; i + 1 < b.x0.size(); ++i) {
    const double a = b.x0[i], c = b.x0[i + 1], m = 0.5 * (a + c);
    const double fa = b.mass[i] * a * a, fc = b.mass[i + 1] * c * c;
    const double fm = 0.5 * (b.mass[i] + b.mass[i + 1]) * m * m;
    s += (c - a) / 6.0 * (fa + 4.0 * fm + fc);
  }
  return s;
}

void validate_shape(const BladeProperties& b) {
  if (b.x0.size() < 2) {
    throw InvalidInput("stations", std::to_string(b.x0.size()),
                       "a blade table needs at least 2 stations (root and tip)");
  }
  for (std::size_t i = 0; i < b.x0.size(); ++i) {
    if (!std::isfinite(b.x0[i]) || (i > 0 && !(b.x0[i] > b.x0[i - 1]))) {
      throw InvalidInput(
          std::string("x0") + (b.source.empty()
                                   ? ""
                                   : " (" + b.source + ", station " + std::to_string(i + 1) + ")"),
          round_trip_text(b.x0[i]), "stations must be finite and strictly increasing");
    }
  }
  if (b.x0.front() != 0.0 || b.x0.back() != 1.0) {
    throw InvalidInput("x0", round_trip_text(b.x0.front()) + ".." + round_trip_text(b.x0.back()),
                       "the stations must run from 0 (root of the elastic blade) to 1 (tip)");
  }
  check_column(b, b.mass, "mass", 0.0, true, INFINITY);
  check_column(b, b.stiffness_flap, "EI_flap", 0.0, true, INFINITY);
  check_column(b, b.stiffness_lag, "EI_lag", 0.0, true, INFINITY);
  check_column(b, b.chord, "chord", 0.0, true, INFINITY);
  check_column(b, b.twist, "twist", -kPi / 2, true, kPi / 2);
  if (!std::isfinite(b.tip_mass) || b.tip_mass < 0.0) {
    throw InvalidInput("tip_mass", round_trip_text(b.tip_mass), "must be finite and >= 0");
  }
}

}  // namespace

void validate(const BladeProperties& b) {
  validate_shape(b);
  const double total = mass_moment(b) + b.tip_mass;
  if (!(std::abs(total - 1.0) <= 1e-12)) {
    throw InvalidInput("mass", round_trip_text(total),
                       "int mbar x0^2 dx0 + tip_mass must be 1 (mass by I_b)");
  }
}

BladeProperties normalised_mass(BladeProperties b) {
  validate_shape(b);
  const double total = mass_moment(b) + b.tip_mass;
  for (double& m : b.mass) m /= total;
  b.tip_mass /= total;
  return b;
}

BladeProperties uniform_blade(double stiffness_flap, double stiffness_lag) {
  BladeProperties b;
  b.x0 = {0.0, 1.0};
  b.mass = {3.0, 3.0};
  b.stiffness_flap = {stiffness_flap, stiffness_flap};
  b.stiffness_lag = {stiffness_lag, stiffness_lag};
  b.chord = {1.0, 1.0};
  b.twist = {0.0, 0.0};
  b.source = "uniform blade";
  return b;
}

}  // namespace flaplag
