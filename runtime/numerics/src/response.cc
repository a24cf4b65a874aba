// flaplag — periodic forced response and time-domain simulation (RK4 on the grid split at the piece
// edges).
#include "flaplag/numerics/response.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/numerics/dense.h"
#include "grid.h"

namespace flaplag {
namespace {

constexpr int kMinSteps = 200;
constexpr int kMaxSteps = 1 << 20;

using detail::Segment;

// Equal steps over [0, 2 pi], split at the breakpoints; each piece in its own region.
std::vector<Segment> grid(const PeriodicSystem& sys, int steps) {
  std::vector<Segment> out;
  detail::sampled_grid(sys, 0.0, kTwoPi, steps, out);
  return out;
}

// A and f of one region at psi (no region lookup: the segment decides).
void eval(const HarmonicSet& set, double psi, int n, Eigen::MatrixXd& A, Eigen::VectorXd& f) {
  A.setZero(n, n);
  f.setZero(n);
  for (std::size_t h = 0; h < set.A.size(); ++h) {
    const double phi = harmonic_basis(static_cast<int>(h), psi);
    A += phi * set.A[h];
    if (h < set.f.size() && set.f[h].size() == n) f += phi * set.f[h];
  }
}

// One RK4 step of z' = A z + c f (c = 1 forced, 0 free) for the columns of Z (n x m).  The
// stage matrices are kept between steps (no allocation once sized), and A, f at a step's end
// serve as the next step's start when that step continues in the same region: the same
// values as evaluating them again, at two thirds of the evaluations.
struct Stepper {
  Stepper(const PeriodicSystem* system, int size) : sys(system), n(size) {}
  const PeriodicSystem* sys;
  int n;
  Eigen::MatrixXd A0, A1, A2;
  Eigen::VectorXd f0, f1, f2;
  detail::Rk4<Eigen::MatrixXd> rk;  // the stages and the states they are taken at
  bool have_end = false;            // A2, f2 hold A, f at end_psi in end_set
  double end_psi = 0.0;
  int end_set = -1;

  void at(const Segment& s, double psi, Eigen::MatrixXd& A, Eigen::VectorXd& f) const {
    if (s.set < 0) {
      detail::evaluator(*sys, s)(psi, A, f);
    } else {
      eval(detail::harmonic_set(*sys, s.set), psi, n, A, f);
    }
  }
  // A, f at the start, middle and end of s into A0 .. A2, f0 .. f2.
  void coefficients(const Segment& s) {
    if (have_end && s.set >= 0 && end_set == s.set && end_psi == s.a) {
      A0.swap(A2);
      f0.swap(f2);
    } else {
      at(s, s.a, A0, f0);
    }
    at(s, 0.5 * (s.a + s.b), A1, f1);
    at(s, s.b, A2, f2);
    have_end = s.set >= 0;
    end_psi = s.b;
    end_set = s.set;
  }
  // The four stages of the step from Y over s (rk.k1 .. k4, and rk.y2 .. y4 the states of
  // stages 2-4).
  void stages(const Segment& s, const Eigen::MatrixXd& Y, const Eigen::RowVectorXd& c) {
    coefficients(s);
    rk.stages(s.b - s.a, Y, [&](int stage, const Eigen::MatrixXd& y, Eigen::MatrixXd& k) {
      const Eigen::MatrixXd& A = stage == 0 ? A0 : stage == 3 ? A2 : A1;
      const Eigen::VectorXd& f = stage == 0 ? f0 : stage == 3 ? f2 : f1;
      k.noalias() = A * y;
      k.noalias() += f * c;
    });
  }
  void step(const Segment& s, Eigen::MatrixXd& Y, const Eigen::RowVectorXd& c) {
    stages(s, Y, c);
    rk.advance(s.b - s.a, Y);
  }
};

// Automatic starting steps: |lambda| h <= 1/2 for the largest eigenvalue of A at a few azimuths.
int automatic_steps(const PeriodicSystem& sys) {
  double rho = 0.0;
  for (int k = 0; k < 8; ++k) {
    rho = std::max(rho, spectral_radius(sys.A((k + 0.5) * kTwoPi / 8.0), EigenStorage::Dynamic));
  }
  const double k = std::ceil(rho * kTwoPi / 0.5);
  if (!(k <= kMaxSteps / 4)) return kMaxSteps / 4;
  return std::max(kMinSteps, static_cast<int>(k));
}

// Phi and g (the state at 2 pi from y(0) = 0) by RK4 with `steps`.
void monodromy(const PeriodicSystem& sys, int steps, Eigen::MatrixXd& phi, Eigen::VectorXd& g) {
  const int n = sys.n;
  Eigen::MatrixXd Y(n, n + 1);
  Y.setZero();
  Y.leftCols(n).setIdentity();
  Eigen::RowVectorXd c = Eigen::RowVectorXd::Zero(n + 1);
  c(n) = 1.0;  // the last column is the forced solution from 0
  Stepper st{&sys, n};
  for (const Segment& s : grid(sys, steps)) st.step(s, Y, c);
  phi = Y.leftCols(n);
  g = Y.col(n);
}

// The start y0 = (I - Phi)^-1 g of the periodic solution by RK4 with `steps`; dist the distance
// of the nearest multiplier to 1 and rho the largest |multiplier| (0: the eigen-solve failed).
// false when Phi or g overflowed (dist and rho then unchanged) or y0 is not finite.
bool periodic_start(const PeriodicSystem& sys, int steps, Eigen::VectorXd& y0, double& dist,
                    double& rho) {
  const int n = sys.n;
  Eigen::MatrixXd phi;
  Eigen::VectorXd g;
  monodromy(sys, steps, phi, g);
  if (!phi.allFinite() || !g.allFinite()) return false;
  const RealEigenSystem es = real_eigen_system(phi, false, EigenStorage::Dynamic);
  dist = HUGE_VAL;
  rho = 0.0;
  if (es.ok) {
    for (Eigen::Index i = 0; i < n; ++i)
      dist = std::min(dist, std::abs(es.values(i) - std::complex<double>(1.0, 0.0)));
    rho = es.values.cwiseAbs().maxCoeff();
  }
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  y0 = (I - phi).fullPivLu().solve(g);
  return y0.allFinite();
}

// y0 at the steps of the integration and what its solve tells.
struct ResolvedStart {
  bool ok = false;
  Eigen::VectorXd y0;
  int steps = 0;
  double dist = 0.0;            // of the nearest multiplier to 1
  double rho = 0.0;             // the largest |multiplier|
  std::optional<double> error;  // Richardson estimate of y0's error (relative)
};

// y0 with `steps`, and at half the steps for its error; with automatic steps doubled until the
// error meets `tolerance` (or the steps their cap).
ResolvedStart resolve_start(const PeriodicSystem& sys, int steps, bool automatic,
                            double tolerance) {
  ResolvedStart r;
  double rho = 0.0;  // largest |multiplier| of the last solve (0: the eigen-solve failed)
  Eigen::VectorXd coarse;
  double dist_coarse = 0.0;
  r.ok = periodic_start(sys, steps, r.y0, r.dist, rho);
  r.rho = rho;
  if (r.ok && steps >= 2) {
    const bool ok_coarse = periodic_start(sys, steps / 2, coarse, dist_coarse, rho);
    while (r.ok && ok_coarse) {
      const double scale = std::max(1e-300, r.y0.cwiseAbs().maxCoeff());
      // RK4: error(N) ~ (error(N/2) - error(N)) / 15
      r.error = (r.y0 - coarse).cwiseAbs().maxCoeff() / scale / 15.0;
      if (!automatic || *r.error <= tolerance || 2 * steps > kMaxSteps) break;
      coarse = r.y0;
      steps *= 2;
      r.ok = periodic_start(sys, steps, r.y0, r.dist, rho);
      r.rho = rho;
    }
  }
  r.steps = steps;
  return r;
}

// The response over one period, sampled at psi_k = 2 pi k / samples, integrated from y0 on
// the same grid (refined so that every sample is a grid point); returns the state at 2 pi.
Eigen::VectorXd sample_period(const PeriodicSystem& sys, const Eigen::VectorXd& y0, int steps,
                              int samples, PeriodicResponse& out) {
  const int per = std::max(1, (steps + samples - 1) / samples);
  Stepper st{&sys, sys.n};
  Eigen::MatrixXd Y = y0;
  const Eigen::RowVectorXd c = Eigen::RowVectorXd::Ones(1);
  std::vector<double> cuts;
  for (int k = 0; k <= samples; ++k) cuts.push_back(kTwoPi * k / samples);
  std::vector<Segment> segments;
  for (int k = 0; k < samples; ++k) {
    out.psi.push_back(cuts[k]);
    out.y.push_back(Y.col(0));
    segments.clear();
    detail::sampled_grid(sys, cuts[k], cuts[k + 1], per, segments);
    for (const Segment& s : segments) st.step(s, Y, c);
  }
  return Y.col(0);
}

// Whether the samples close onto y0 (out.closure) as well as the integration's error allows;
// false: they cannot be the periodic solution (out is final).  rho: the largest |multiplier|.
bool check_closure(PeriodicResponse& out, double rho) {
  // The samples are integrated forward from y0, so a strongly unstable system amplifies the
  // rounding of y0 by up to its largest multiplier over the period, and the samples no longer
  // close: the typical rotor at mu = 20 (|Lambda| = 2.7e14) missed y0 by 79 times |y0| and at
  // mu = 50 by 1e27, reported with a warning only.  Beyond the integration's own error such
  // samples are not the periodic solution.
  const double expected = std::max(1e-8, 100.0 * out.error.value_or(0.0));
  if (!(out.closure <= std::max(1e-3, expected))) {
    out.status = Status::Failed;
    out.message =
        "the periodic solution cannot be sampled in double precision: integrated from "
        "y0 over one revolution the state misses y0 by " +
        short_text(out.closure) + " (relative; the largest |multiplier|, " + short_text(rho) +
        ", amplifies the rounding of y0)";
    out.psi.clear();
    out.y.clear();
    return false;
  }
  if (out.closure > expected) {
    out.status = Status::Warning;
    out.message = "periodicity error " + short_text(out.closure) +
                  " (relative) above what the integration's error implies: the largest "
                  "|multiplier|, " +
                  short_text(rho) + ", amplifies the rounding of y0";
  }
  return true;
}

}  // namespace

std::optional<InvalidInput> ResponseOptions::Validate() const {
  return Requirements().InRanges(*this).Result();
}

std::optional<InvalidInput> SimulationOptions::Validate() const {
  return Requirements().InRanges(*this).Result();
}

PeriodicResponse periodic_response(const PeriodicSystem& sys, const ResponseOptions& options) {
  sys.validate();
  options.Check();
  PeriodicResponse out;
  const bool automatic = options.steps == 0;
  const ResolvedStart start = resolve_start(sys, automatic ? automatic_steps(sys) : options.steps,
                                            automatic, options.tolerance);
  out.error = start.error;
  out.steps = start.steps;
  out.min_distance_to_one = start.dist;
  if (!start.ok) {
    out.status = Status::Failed;
    out.message = "the transition matrix overflowed or I - Phi is singular: no periodic response";
    return out;
  }
  // A multiplier at 1 makes I - Phi singular: the forced problem has no unique periodic
  // solution (resonance with the forcing's period).
  if (start.dist < 1e-8) {
    out.status = Status::Failed;
    out.message = "a characteristic multiplier is at 1 (distance " + short_text(start.dist) +
                  "): no unique periodic response";
    return out;
  }
  out.y0 = start.y0;
  const Eigen::VectorXd end = sample_period(sys, start.y0, start.steps, options.samples, out);
  out.closure =
      (end - start.y0).cwiseAbs().maxCoeff() / std::max(1.0, start.y0.cwiseAbs().maxCoeff());
  if (!check_closure(out, start.rho)) return out;
  // Some |Lambda| > 1 means the blade does not settle onto this solution.
  if (start.rho > 1.0) {
    out.Worsen(Status::Warning,
               "the system is unstable (largest |multiplier| " + short_text(start.rho) +
                   ", zeta = " + short_text(std::log(start.rho) / kTwoPi) +
                   " per rev): the periodic solution exists but the blade does not settle onto "
                   "it");
  }
  if (automatic && out.error && *out.error > options.tolerance) {
    out.Worsen(Status::Warning,
               "not resolved to the tolerance: estimated error " + short_text(*out.error));
  }
  return out;
}

namespace {

// The sampled RK4 run shared by simulate() and simulate_nonlinear(): equal steps per
// revolution (a whole multiple of the samples, so that samples fall on grid points), split at
// the sector edges of `sys`; step(segment, y) advances y over one segment.
template <typename Step>
Simulation sampled_run(const PeriodicSystem& sys, const Eigen::VectorXd& y0,
                       const SimulationOptions& options, Step step) {
  if (y0.size() != sys.n || !y0.allFinite())
    throw InvalidInput("y0", std::to_string(y0.size()) + " values",
                       "must be " + std::to_string(sys.n) + " finite values");
  Simulation out;
  int steps = options.steps_per_rev > 0 ? options.steps_per_rev : automatic_steps(sys);
  steps =
      ((steps + options.samples_per_rev - 1) / options.samples_per_rev) * options.samples_per_rev;
  out.steps_per_rev = steps;
  const int per = steps / options.samples_per_rev;
  const long total_samples =
      static_cast<long>(std::ceil(options.revolutions * options.samples_per_rev - 1e-9));
  Eigen::VectorXd y = y0;
  out.psi.push_back(0.0);
  out.y.push_back(y0);
  std::vector<Segment> segments;
  for (long k = 0; k < total_samples; ++k) {
    const int j = static_cast<int>(k % options.samples_per_rev);
    const double base = kTwoPi * static_cast<double>(k / options.samples_per_rev);
    const double a = kTwoPi * j / options.samples_per_rev,
                 b = kTwoPi * (j + 1) / options.samples_per_rev;
    segments.clear();
    detail::sampled_grid(sys, a, b, per, segments);
    for (const Segment& s : segments) step(s, y);
    if (!y.allFinite()) {
      out.status = Status::Failed;
      out.message = "the state overflowed after " +
                    short_text(base / kTwoPi + (j + 1.0) / options.samples_per_rev) +
                    " revolutions";
      return out;
    }
    out.psi.push_back(base + b);
    out.y.push_back(y);
  }
  return out;
}

}  // namespace

Simulation simulate(const PeriodicSystem& sys, const Eigen::VectorXd& y0, bool forced,
                    const SimulationOptions& options) {
  sys.validate();
  options.Check();
  Stepper st{&sys, sys.n};
  const Eigen::RowVectorXd c = Eigen::RowVectorXd::Constant(1, forced ? 1.0 : 0.0);
  Eigen::MatrixXd Y;
  return sampled_run(sys, y0, options, [&](const Segment& s, Eigen::VectorXd& y) {
    Y = y;
    st.step(s, Y, c);
    y = Y.col(0);
  });
}

Simulation simulate_nonlinear(const PeriodicSystem& grid, const NonlinearRhs& rhs,
                              const Eigen::VectorXd& y0, const SimulationOptions& options) {
  grid.validate();
  options.Check();
  if (!rhs) throw InvalidInput("rhs", "(empty)", "a right-hand side is required");
  detail::Rk4<Eigen::VectorXd> rk;
  return sampled_run(grid, y0, options, [&](const Segment& s, Eigen::VectorXd& y) {
    // The region of the whole segment (its midpoint): a step never straddles a sector edge.
    const double mid = 0.5 * (s.a + s.b);
    const bool reversed = s.set != 0;
    rk.step(s.b - s.a, y, [&](int stage, const Eigen::VectorXd& x, Eigen::VectorXd& k) {
      rhs(stage == 0 ? s.a : stage == 3 ? s.b : mid, reversed, x, k);
    });
  });
}

double periodic_mean(const PeriodicSystem& sys, const Eigen::VectorXd& y0, int steps,
                     const PeriodicQuantity& quantity) {
  sys.validate();
  if (steps < 1) throw InvalidInput("steps", std::to_string(steps), "must be >= 1");
  if (y0.size() != sys.n || !y0.allFinite())
    throw InvalidInput("y0", std::to_string(y0.size()) + " values",
                       "must be " + std::to_string(sys.n) + " finite values");
  if (!quantity) throw InvalidInput("quantity", "(empty)", "a quantity is required");
  Stepper st{&sys, sys.n};
  const Eigen::RowVectorXd c = Eigen::RowVectorXd::Ones(1);
  Eigen::MatrixXd Y = y0;
  double integral = 0.0;
  for (const Segment& s : grid(sys, steps)) {
    const double mid = 0.5 * (s.a + s.b), h = s.b - s.a;
    const bool reversed = s.set != 0;
    // the stages of Stepper::step, with the quantity at each stage's state
    st.stages(s, Y, c);
    const double t1 = quantity(s.a, reversed, Y.col(0)),
                 t2 = quantity(mid, reversed, st.rk.y2.col(0)),
                 t3 = quantity(mid, reversed, st.rk.y3.col(0)),
                 t4 = quantity(s.b, reversed, st.rk.y4.col(0));
    st.rk.advance(h, Y);
    integral += h / 6.0 * (t1 + 2.0 * t2 + 2.0 * t3 + t4);
  }
  return std::isfinite(integral) && Y.allFinite() ? integral / kTwoPi
                                                  : std::numeric_limits<double>::quiet_NaN();
}

std::optional<double> envelope_growth_rate(const std::vector<double>& psi,
                                           const std::vector<double>& signal, double skip_revs) {
  if (psi.size() != signal.size() || psi.empty()) return std::nullopt;
  // max |s| per whole revolution after skip_revs
  std::vector<double> revs, logs;
  const long first = static_cast<long>(std::ceil(skip_revs));
  const long last = static_cast<long>(std::floor(psi.back() / kTwoPi + 1e-9));
  for (long r = first; r < last; ++r) {
    double m = 0.0;
    for (std::size_t i = 0; i < psi.size(); ++i)
      if (psi[i] >= kTwoPi * static_cast<double>(r) - 1e-12 &&
          psi[i] < kTwoPi * static_cast<double>(r + 1) - 1e-12)
        m = std::max(m, std::abs(signal[i]));
    if (!(m > 0.0) || !std::isfinite(m)) return std::nullopt;
    revs.push_back(static_cast<double>(r));
    logs.push_back(std::log(m));
  }
  if (revs.size() < 3) return std::nullopt;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(revs.size());
  for (std::size_t i = 0; i < revs.size(); ++i) {
    sx += revs[i];
    sy += logs[i];
    sxx += revs[i] * revs[i];
    sxy += revs[i] * logs[i];
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);  // ln growth per revolution
  return slope / kTwoPi;  // per radian of psi: the unit of zeta
}

}  // namespace flaplag
