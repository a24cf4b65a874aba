// flaplag — the periodic system y' = A(psi) y + f(psi): harmonic evaluation, exact interval
// means (eqs 4.2-4.5 generalised to any harmonic) and the exact trace integral used by the
// Liouville check det Phi(2 pi) = exp(int_0^{2 pi} tr A).
#include "flaplag/numerics/periodic_system.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/numerics/gauss_legendre.h"

namespace flaplag {
namespace {

// Local formatting so that this library does not depend on errors.cc (another library).
std::string fmt(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// sin(x)/x, accurate near 0 (the series keeps full precision where the quotient cancels).
double sinc(double x) {
  if (std::abs(x) < 1e-4) {
    const double x2 = x * x;
    return 1.0 - x2 / 6.0 * (1.0 - x2 / 20.0);
  }
  return std::sin(x) / x;
}

// Harmonic order k of basis index h: 0 -> 0, 2k-1 and 2k -> k.
int order(int h) { return (h + 1) / 2; }

using gauss::kW8;
using gauss::kX8;

// 0 when every entry is finite, NaN otherwise (x * 0 is NaN exactly for inf and NaN): one
// vectorizable pass, since validate() runs on every transition-matrix call.
double nonfinite_probe(const double* x, Eigen::Index count) {
  double acc = 0.0;
  for (Eigen::Index i = 0; i < count; ++i) acc += x[i] * 0.0;
  return acc;
}

void check_harmonics(const HarmonicSet& set, int n, const char* region) {
  if (set.A.empty())
    throw InvalidInput(std::string(region) + ".A.size()", "0",
                       "at least the constant harmonic is required");
  for (std::size_t h = 0; h < set.A.size(); ++h) {
    const Eigen::MatrixXd& a = set.A[h];
    if (a.rows() != n || a.cols() != n)
      throw InvalidInput(std::string(region) + ".A[" + std::to_string(h) + "]",
                         std::to_string(a.rows()) + "x" + std::to_string(a.cols()),
                         "must be n x n with n = " + std::to_string(n));
    if (nonfinite_probe(a.data(), a.size()) != 0.0)
      throw InvalidInput(std::string(region) + ".A[" + std::to_string(h) + "]", "non-finite",
                         "coefficients must be finite");
  }
  for (std::size_t h = 0; h < set.f.size(); ++h) {
    if (set.f[h].size() != n)
      throw InvalidInput(std::string(region) + ".f[" + std::to_string(h) + "]",
                         std::to_string(set.f[h].size()),
                         "must have n = " + std::to_string(n) + " entries");
  }
}

}  // namespace

double harmonic_basis(int h, double psi) {
  if (h < 0) throw InvalidInput("h", std::to_string(h), "harmonic index must be >= 0");
  if (h == 0) return 1.0;
  const double k = order(h);
  return (h % 2 == 1) ? std::cos(k * psi) : std::sin(k * psi);
}

std::string harmonic_name(int h) {
  if (h < 0) throw InvalidInput("h", std::to_string(h), "harmonic index must be >= 0");
  if (h == 0) return "const";
  const int k = order(h);
  return std::string(h % 2 == 1 ? "cos " : "sin ") + (k == 1 ? "" : std::to_string(k)) + "psi";
}

double harmonic_mean(int h, double a, double b) {
  if (h < 0) throw InvalidInput("h", std::to_string(h), "harmonic index must be >= 0");
  if (!(std::isfinite(a) && std::isfinite(b)))
    throw InvalidInput("interval", "[" + fmt(a) + ", " + fmt(b) + "]", "must be finite");
  if (h == 0) return 1.0;
  // (1/(b-a)) int_a^b cos(k psi) = cos(k m) sin(k d)/(k d), m the midpoint, d the half width;
  // the same with sin.  For k = 1, 2 these are eqs 4.2-4.5.  b == a gives the point value.
  const double k = order(h);
  const double mid = 0.5 * (a + b);
  const double s = sinc(k * 0.5 * (b - a));
  return ((h % 2 == 1) ? std::cos(k * mid) : std::sin(k * mid)) * s;
}

void PeriodicSystem::validate() const {
  if (n < 1) throw InvalidInput("n", std::to_string(n), "state dimension must be >= 1");
  check_harmonics(normal, n, "normal");
  if (has_sector) {
    check_harmonics(reversed, n, "reversed");
    if (!(sector_begin >= 0.0 && sector_begin < sector_end && sector_end <= kTwoPi))
      throw InvalidInput("sector", "[" + fmt(sector_begin) + ", " + fmt(sector_end) + ")",
                         "need 0 <= sector_begin < sector_end <= 2 pi");
  }
  if (has_varying) {
    if (has_sector)
      throw InvalidInput("varying", "with a sector",
                         "a varying region replaces the sector; both cannot be set");
    if (!varying) throw InvalidInput("varying", "empty", "the varying region needs an evaluator");
    if (!(varying_begin >= 0.0 && varying_begin < varying_end && varying_end <= kTwoPi))
      throw InvalidInput("varying", "[" + fmt(varying_begin) + ", " + fmt(varying_end) + ")",
                         "need 0 <= varying_begin < varying_end <= 2 pi");
    double last = varying_begin;
    for (double b : varying_breaks) {
      if (!(b > last && b < varying_end))
        throw InvalidInput("varying_breaks", fmt(b),
                           "breaks must be sorted and inside (varying_begin, varying_end)");
      last = b;
    }
  }
}

double reduce_azimuth(double psi) {
  double p = std::fmod(psi, kTwoPi);
  if (p < 0.0) p += kTwoPi;
  if (p >= kTwoPi) p = 0.0;  // fmod of a tiny negative number rounds up to 2 pi
  return p;
}

bool PeriodicSystem::in_sector(double psi) const {
  if (!has_sector) return false;
  const double p = reduce_azimuth(psi);
  return p >= sector_begin && p < sector_end;
}

bool PeriodicSystem::in_varying(double psi) const {
  if (!has_varying) return false;
  const double p = reduce_azimuth(psi);
  return p >= varying_begin && p < varying_end;
}

const HarmonicSet& PeriodicSystem::region(double psi) const {
  return in_sector(psi) ? reversed : normal;
}

Eigen::MatrixXd PeriodicSystem::A(double psi) const {
  // Reduced first: cos(k psi) of a huge psi is NaN (k psi overflows) or meaningless.
  psi = reduce_azimuth(psi);
  if (in_varying(psi)) {
    Eigen::MatrixXd a;
    Eigen::VectorXd f;
    varying(psi, a, f);
    return a;
  }
  const HarmonicSet& set = region(psi);
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t h = 0; h < set.A.size(); ++h)
    out += harmonic_basis(static_cast<int>(h), psi) * set.A[h];
  return out;
}

Eigen::VectorXd PeriodicSystem::f(double psi) const {
  psi = reduce_azimuth(psi);
  if (in_varying(psi)) {
    Eigen::MatrixXd a;
    Eigen::VectorXd f;
    varying(psi, a, f);
    return f;
  }
  const HarmonicSet& set = region(psi);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
  for (std::size_t h = 0; h < set.f.size(); ++h)
    out += harmonic_basis(static_cast<int>(h), psi) * set.f[h];
  return out;
}

Eigen::MatrixXd PeriodicSystem::A_mean(double a, double b) const {
  // The interval lies inside one region by contract; its midpoint decides which (robust to an
  // endpoint sitting exactly on a sector edge).
  if (in_varying(0.5 * (a + b))) {
    Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, n), x;
    Eigen::VectorXd f;
    for (int i = 0; i < 8; ++i) {
      varying(0.5 * (a + b) + 0.5 * (b - a) * kX8[i], x, f);
      out += (0.5 * kW8[i]) * x;
    }
    return out;
  }
  const HarmonicSet& set = region(0.5 * (a + b));
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t h = 0; h < set.A.size(); ++h)
    out += harmonic_mean(static_cast<int>(h), a, b) * set.A[h];
  return out;
}

std::vector<double> PeriodicSystem::breakpoints() const {
  std::vector<double> out;
  if (has_varying) {
    if (varying_begin > 0.0) out.push_back(varying_begin);
    for (double b : varying_breaks) out.push_back(b);
    if (varying_end < kTwoPi) out.push_back(varying_end);
    return out;
  }
  if (!has_sector) return out;
  if (sector_begin > 0.0 && sector_begin < kTwoPi) out.push_back(sector_begin);
  if (sector_end > 0.0 && sector_end < kTwoPi) out.push_back(sector_end);
  return out;
}

double PeriodicSystem::trace_integral() const {
  // int_0^{2pi} phi_h = 2 pi for h = 0 and 0 otherwise; the sector replaces the normal
  // harmonics by the reversed ones over [begin, end):
  //   int tr A = sum_h tr(N_h) (int_0^{2pi} phi_h - int_sec phi_h) + sum_h tr(R_h) int_sec phi_h.
  double total = kTwoPi * normal.A.at(0).trace();
  if (has_varying) {
    // Inside the varying region the normal harmonics are replaced by the evaluator: subtract
    // their exact integral and add the evaluator's by composite Gauss-Legendre, 8 points on
    // panels of at most pi/16 on each smooth piece (between breaks), where the integrand is
    // analytic (checked against closed forms in tests/periodic_system_test.cpp, and through
    // the rotor's Liouville residual below 1e-10 in tests/analysis_test.cpp).
    const double width = varying_end - varying_begin;
    for (std::size_t h = 0; h < normal.A.size(); ++h)
      total -= normal.A[h].trace() *
               harmonic_mean(static_cast<int>(h), varying_begin, varying_end) * width;
    std::vector<double> cuts = {varying_begin};
    for (double b : varying_breaks) cuts.push_back(b);
    cuts.push_back(varying_end);
    Eigen::MatrixXd x;
    Eigen::VectorXd f;
    for (std::size_t k = 1; k < cuts.size(); ++k) {
      const double lo = cuts[k - 1], hi = cuts[k];
      const int panels = std::max(2, static_cast<int>(std::ceil((hi - lo) / (kPi / 16.0))));
      const double hp = (hi - lo) / panels;
      for (int p = 0; p < panels; ++p) {
        const double c = lo + (p + 0.5) * hp;
        for (int i = 0; i < 8; ++i) {
          varying(c + 0.5 * hp * kX8[i], x, f);
          total += 0.5 * hp * kW8[i] * x.trace();
        }
      }
    }
    return total;
  }
  if (!has_sector) return total;
  const double width = sector_end - sector_begin;
  for (std::size_t h = 0; h < normal.A.size(); ++h)
    total -=
        normal.A[h].trace() * harmonic_mean(static_cast<int>(h), sector_begin, sector_end) * width;
  for (std::size_t h = 0; h < reversed.A.size(); ++h)
    total += reversed.A[h].trace() * harmonic_mean(static_cast<int>(h), sector_begin, sector_end) *
             width;
  return total;
}

}  // namespace flaplag
