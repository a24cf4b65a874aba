// flaplag — continuation of Floquet exponents in mu, hover labels, critical advance ratio.
#include "flaplag/numerics/continuation.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"

namespace flaplag {
namespace {

constexpr double kAmbiguousSimilarity = 0.5;

std::string fmt(double v) { return short_text(v); }

void require(bool ok, const char* name, double value, const char* reason) {
  if (!ok) throw InvalidInput(name, round_trip_text(value), reason);
}

Status worse(Status a, Status b) { return static_cast<int>(a) >= static_cast<int>(b) ? a : b; }

// Minimum-cost assignment of rows (tracked modes) to columns (new exponents).
class Assignment {
 public:
  explicit Assignment(const Eigen::MatrixXd& cost)
      : cost_(cost), n_(static_cast<int>(cost.rows())) {}

  std::vector<int> solve() {
    perm_.assign(static_cast<std::size_t>(n_), -1);
    if (n_ <= 8) {
      used_.assign(static_cast<std::size_t>(n_), false);
      best_cost_ = std::numeric_limits<double>::infinity();
      best_ = perm_;
      search(0, 0.0);
      return best_;
    }
    // Greedy: repeatedly take the cheapest remaining pair.
    std::vector<bool> row_done(static_cast<std::size_t>(n_), false), col_done = row_done;
    for (int step = 0; step < n_; ++step) {
      double c = std::numeric_limits<double>::infinity();
      int bi = 0, bj = 0;
      for (int i = 0; i < n_; ++i)
        for (int j = 0; j < n_; ++j)
          if (!row_done[i] && !col_done[j] && cost_(i, j) < c) {
            c = cost_(i, j);
            bi = i;
            bj = j;
          }
      row_done[bi] = col_done[bj] = true;
      perm_[bi] = bj;
    }
    return perm_;
  }

 private:
  // Depth-first over permutations with the partial cost as bound (costs are >= 0).
  void search(int row, double partial) {
    if (partial >= best_cost_) return;
    if (row == n_) {
      best_cost_ = partial;
      best_ = perm_;
      return;
    }
    for (int j = 0; j < n_; ++j) {
      if (used_[j]) continue;
      used_[j] = true;
      perm_[row] = j;
      search(row + 1, partial + cost_(row, j));
      used_[j] = false;
    }
  }

  const Eigen::MatrixXd& cost_;
  int n_;
  std::vector<int> perm_, best_;
  std::vector<bool> used_;
  double best_cost_ = 0.0;
};

// Everything the search needs at one trial mu.
struct Trial {
  double mu = 0.0;
  double f = 0.0;  // max zeta - zeta_tolerance
  ExponentTracker tracker;
  TrackReport report;
};

}  // namespace

InstabilityKind classify_crossing(double omega, double tolerance) {
  const double twice = 2.0 * omega;
  return std::abs(twice - std::round(twice)) <= 2.0 * tolerance ? InstabilityKind::Periodic
                                                                : InstabilityKind::Flutter;
}

ExponentTracker::ExponentTracker(const HoverModes& hover) {
  if (hover.eigenvalues.empty() || hover.eigenvectors.size() != hover.eigenvalues.size() ||
      hover.labels.size() != hover.eigenvalues.size())
    throw InvalidInput("hover", std::to_string(hover.eigenvalues.size()) + " eigenvalues",
                       "need matching, non-empty eigenvalues, eigenvectors and labels");
  for (std::size_t k = 0; k < hover.eigenvalues.size(); ++k) {
    const std::complex<double> lam = hover.eigenvalues[k];
    LabelledExponent e;
    e.label = hover.labels[k];
    e.zeta = lam.real();
    e.omega = lam.imag();  // exact at mu = 0, integer part included
    e.multiplier = std::exp(kTwoPi * lam);
    exponents_.push_back(std::move(e));
    vectors_.push_back(hover.eigenvectors[k]);
  }
}

TrackReport ExponentTracker::advance(const FloquetResult& next, double mu) {
  const int n = static_cast<int>(exponents_.size());
  if (static_cast<int>(next.exponents.size()) != n)
    throw InvalidInput("exponents", std::to_string(next.exponents.size()),
                       "expected " + std::to_string(n) + " as tracked");
  TrackReport report;
  for (const FloquetExponent& e : next.exponents) {
    if (!std::isfinite(e.multiplier.real()) || !std::isfinite(e.multiplier.imag()) ||
        e.eigenvector.size() != vectors_[0].size() || !e.eigenvector.allFinite()) {
      report.status = Status::Failed;
      report.message = "non-finite multipliers or eigenvectors; tracking state unchanged";
      report.min_similarity = 0.0;
      return report;
    }
  }

  // Predicted exponents at mu: linear in mu through the last two states.
  const bool extrapolate =
      std::isfinite(mu) && has_previous_ && mu_ != previous_mu_ && std::isfinite(mu_);
  const double t = extrapolate ? (mu - mu_) / (mu_ - previous_mu_) : 0.0;
  double predicted_zeta[64], predicted_omega[64];
  std::vector<double> big_zeta, big_omega;
  double* pz = predicted_zeta;
  double* pw = predicted_omega;
  if (n > 64) {
    big_zeta.resize(static_cast<std::size_t>(n));
    big_omega.resize(static_cast<std::size_t>(n));
    pz = big_zeta.data();
    pw = big_omega.data();
  }
  for (int i = 0; i < n; ++i) {
    const LabelledExponent& e = exponents_[i];
    pz[i] = e.zeta + (extrapolate ? t * (e.zeta - previous_[i].real()) : 0.0);
    pw[i] = e.omega + (extrapolate ? t * (e.omega - previous_[i].imag()) : 0.0);
  }

  // Cost of assigning tracked mode i to new exponent j: eigenvector dissimilarity plus the
  // distance of the new exponent from the prediction (omega modulo integers), times 2 pi so
  // that it is the relative change of the multiplier for small steps.  Both terms are O(1)
  // for a wrong match.
  Eigen::MatrixXd cost(n, n), sim(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const FloquetExponent& e = next.exponents[j];
      sim(i, j) = std::abs(vectors_[i].dot(e.eigenvector));  // dot() conjugates the left side
      const double dw = e.omega - pw[i];
      const double dz = std::isfinite(e.zeta) ? e.zeta - pz[i] : 1e3;
      cost(i, j) = (1.0 - sim(i, j)) + kTwoPi * std::hypot(dz, dw - std::round(dw));
    }
  }
  const std::vector<int> match = Assignment(cost).solve();

  previous_.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const FloquetExponent& e = next.exponents[match[i]];
    LabelledExponent& x = exponents_[i];
    previous_[i] = {x.zeta, x.omega};
    // omega = principal + k with the integer k that puts omega closest to its prediction.
    x.omega = e.omega + std::round(pw[i] - e.omega);
    x.zeta = e.zeta;
    x.multiplier = e.multiplier;
    vectors_[i] = e.eigenvector;
    report.min_similarity = std::min(report.min_similarity, sim(i, match[i]));
  }
  previous_mu_ = mu_;
  mu_ = mu;
  has_previous_ = std::isfinite(mu);
  if (report.min_similarity < kAmbiguousSimilarity) {
    report.status = Status::Warning;
    report.message = "ambiguous mode identification (eigenvector similarity " +
                     fmt(report.min_similarity) + "); consider a smaller step";
  }
  return report;
}

int ExponentTracker::most_unstable() const {
  int best = 0;
  for (int i = 1; i < static_cast<int>(exponents_.size()); ++i)
    if (exponents_[i].zeta > exponents_[best].zeta) best = i;
  return best;
}

double ExponentTracker::max_zeta() const { return exponents_[most_unstable()].zeta; }

CriticalSearchResult find_critical(const HoverModes& hover, const FloquetFunction& floquet,
                                   const CriticalSearchOptions& opt) {
  require(std::isfinite(opt.mu_max) && opt.mu_max > 0.0, "mu_max", opt.mu_max, "must be > 0");
  require(std::isfinite(opt.step) && opt.step > 0.0, "step", opt.step, "must be > 0");
  require(std::isfinite(opt.tolerance) && opt.tolerance > 0.0, "tolerance", opt.tolerance,
          "must be > 0");
  require(std::isfinite(opt.zeta_tolerance) && opt.zeta_tolerance >= 0.0, "zeta_tolerance",
          opt.zeta_tolerance, "must be >= 0");
  require(std::isfinite(opt.periodic_omega_tolerance) && opt.periodic_omega_tolerance >= 0.0,
          "periodic_omega_tolerance", opt.periodic_omega_tolerance, "must be >= 0");
  if (!floquet) throw InvalidInput("floquet", "empty", "a FloquetFunction is required");

  CriticalSearchResult out;
  out.mu_max = opt.mu_max;
  if (hover.status == Status::Failed) {
    out.status = Status::Failed;
    out.message = "hover modes unavailable: " + hover.message;
    return out;
  }
  std::string warnings;
  auto note = [&](const std::string& m) {
    if (warnings.empty()) warnings = m;
  };
  auto crossing = [&](const ExponentTracker& t, double mu) {
    const LabelledExponent& e = t.exponents()[t.most_unstable()];
    out.found = true;
    out.mu_c = mu;
    out.label = e.label;
    out.omega = e.omega;
    out.kind = classify_crossing(e.omega, opt.periodic_omega_tolerance);
    out.exponents = t.exponents();
  };

  ExponentTracker tracker(hover);
  if (tracker.max_zeta() > opt.zeta_tolerance) {
    crossing(tracker, 0.0);
    out.status = Status::Warning;
    out.message = "unstable in hover (" + out.label + ", zeta = " + fmt(tracker.max_zeta()) + ")";
    return out;
  }

  auto evaluate = [&](const ExponentTracker& from, double mu) {
    Trial t{mu, 0.0, from, {}};
    t.report = t.tracker.advance(floquet(mu), mu);
    ++out.evaluations;
    t.f = t.tracker.max_zeta() - opt.zeta_tolerance;
    return t;
  };
  auto failed = [&](const Trial& t) {
    out.status = Status::Failed;
    out.message = "at mu = " + fmt(t.mu) + ": " + t.report.message;
    out.exponents = t.tracker.exponents();
    return out;
  };

  const int steps = static_cast<int>(std::ceil(opt.mu_max / opt.step - 1e-9));
  double prev_mu = 0.0;
  for (int i = 1; i <= steps; ++i) {
    const double mu = std::min(i * opt.step, opt.mu_max);
    Trial hi = evaluate(tracker, mu);
    if (hi.report.status == Status::Failed) return failed(hi);
    if (hi.report.status == Status::Warning) note("at mu = " + fmt(mu) + ": " + hi.report.message);
    if (hi.f <= 0.0) {
      tracker = std::move(hi.tracker);
      prev_mu = mu;
      continue;
    }

    // Brent's method (zeroin) on f(mu) = max zeta - zeta_tolerance over [prev_mu, mu], every
    // trial continued from the tracker at the last stable grid point.
    Trial a{prev_mu, tracker.max_zeta() - opt.zeta_tolerance, tracker, {}};
    Trial b = std::move(hi);
    Trial c = a;
    double d = b.mu - a.mu, e = d;
    const double eps = std::numeric_limits<double>::epsilon();
    for (int iter = 0; iter < 200; ++iter) {
      if ((b.f > 0.0) == (c.f > 0.0)) {
        c = a;
        d = e = b.mu - a.mu;
      }
      if (std::abs(c.f) < std::abs(b.f)) {
        a = b;
        b = c;
        c = a;
      }
      const double tol1 = 2.0 * eps * std::abs(b.mu) + 0.5 * opt.tolerance;
      const double xm = 0.5 * (c.mu - b.mu);
      if (std::abs(xm) <= tol1 || b.f == 0.0) break;
      if (std::abs(e) >= tol1 && std::abs(a.f) > std::abs(b.f)) {
        // Inverse quadratic interpolation (secant when a == c).
        const double s = b.f / a.f;
        double p, q;
        if (a.mu == c.mu) {
          p = 2.0 * xm * s;
          q = 1.0 - s;
        } else {
          const double qa = a.f / c.f, r = b.f / c.f;
          p = s * (2.0 * xm * qa * (qa - r) - (b.mu - a.mu) * (r - 1.0));
          q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
        }
        if (p > 0.0) q = -q;
        p = std::abs(p);
        if (2.0 * p < std::min(3.0 * xm * q - std::abs(tol1 * q), std::abs(e * q))) {
          e = d;
          d = p / q;
        } else {
          d = e = xm;
        }
      } else {
        d = e = xm;
      }
      a = b;
      const double next = b.mu + (std::abs(d) > tol1 ? d : (xm > 0.0 ? tol1 : -tol1));
      b = evaluate(tracker, next);
      if (b.report.status == Status::Failed) return failed(b);
      if (b.report.status == Status::Warning)
        note("at mu = " + fmt(next) + ": " + b.report.message);
    }
    // b is the estimate of mu_c; the mode that crossed is the most unstable one on the
    // unstable side of the final bracket [b, c].
    const Trial& unstable = b.f > 0.0 ? b : c;
    crossing(unstable.tracker, b.mu);
    out.status = warnings.empty() ? Status::Ok : Status::Warning;
    out.message = "unstable above mu_c = " + fmt(b.mu) + " (" + out.label + ", " +
                  kind_name(out.kind) + ", omega = " + fmt(out.omega) + ")";
    if (!warnings.empty()) out.message += "; " + warnings;
    return out;
  }
  out.exponents = tracker.exponents();
  out.status = warnings.empty() ? Status::Ok : Status::Warning;
  out.message = "stable up to mu_max = " + fmt(opt.mu_max);
  if (!warnings.empty()) out.message += "; " + warnings;
  return out;
}

ExponentSweep sweep_exponents(const HoverModes& hover, const FloquetFunction& floquet, double mu0,
                              double mu1, double step) {
  require(std::isfinite(mu0) && mu0 >= 0.0, "mu0", mu0, "must be >= 0");
  require(std::isfinite(mu1) && mu1 >= mu0, "mu1", mu1, "must be >= mu0");
  require(std::isfinite(step) && step > 0.0, "step", step, "must be > 0");
  if (!floquet) throw InvalidInput("floquet", "empty", "a FloquetFunction is required");

  ExponentSweep out;
  if (hover.status == Status::Failed) {
    out.status = Status::Failed;
    out.message = "hover modes unavailable: " + hover.message;
    return out;
  }
  ExponentTracker tracker(hover);
  // Reach mu0 from hover in equal steps no longer than `step`.
  const int pre = static_cast<int>(std::ceil(mu0 / step - 1e-9));
  for (int i = 1; i < pre; ++i) {
    const double mu = mu0 * i / pre;
    const TrackReport r = tracker.advance(floquet(mu), mu);
    if (r.status == Status::Failed) {
      out.status = Status::Failed;
      out.message = "continuation to mu0 failed at mu = " + fmt(mu) + ": " + r.message;
      return out;
    }
    if (r.status == Status::Warning && out.message.empty()) {
      out.status = Status::Warning;
      out.message = "at mu = " + fmt(mu) + ": " + r.message;
    }
  }

  std::vector<double> mus;
  const int m = static_cast<int>(std::floor((mu1 - mu0) / step + 1e-9));
  for (int i = 0; i <= m; ++i) mus.push_back(mu0 + i * step);
  if (mus.back() < mu1 - 1e-12 * std::max(1.0, mu1))
    mus.push_back(mu1);
  else
    mus.back() = std::min(mus.back(), mu1);

  for (double mu : mus) {
    const FloquetResult fr = floquet(mu);
    const TrackReport r = tracker.advance(fr, mu);
    SweepPoint p;
    p.mu = mu;
    p.status = r.status;
    p.message = r.message;
    p.liouville_residual = fr.liouville_residual;
    if (r.status == Status::Failed) {
      out.points.push_back(std::move(p));
      out.status = Status::Failed;
      out.message = "at mu = " + fmt(mu) + ": " + r.message;
      return out;
    }
    p.exponents = tracker.exponents();
    p.stable = tracker.max_zeta() <= 0.0;
    if (r.status == Status::Warning && out.message.empty())
      out.message = "at mu = " + fmt(mu) + ": " + r.message;
    out.status = worse(out.status, r.status);
    out.points.push_back(std::move(p));
  }
  return out;
}

}  // namespace flaplag
