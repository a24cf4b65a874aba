// Accuracy experiment (not a timing; bench/README.md, "The 151-point sweep against 1 ms"): how
// many steps per period each candidate transition method needs for the analysis's default
// resolution on the typical case, with the estimate the analysis would use.
//
// For mu = 0, 0.1, ..., 1.5 and each candidate, the smallest even K >= K0 at which the
// Richardson estimate |zeta(K) - zeta(K/2)| / (2^p - 1) resolves every exponent (1e-5 per rev,
// relative 1e-3 for damped modes, as analysis.h), and against a converged reference (Magnus4 +
// Richardson, 1000 steps) the worst ratio of actual error to estimate.  "boundary" counts the mu
// where that smallest K is accepted while an actual error exceeds its allowance (and by how
// much); the ratio to the estimate is given for the other mu.
//
// The Magnus candidates are written here plainly (Eigen, 4 x 4) on the library's grid rule: equal
// steps split at the sector edges, the harmonics of the region of each substep.
//   hsu:     the library's Hsu (transition_matrix_hsu), J = 4 Taylor terms (p = 2);
//   m4-tJ:   fourth-order Magnus from the exact moments, Omega = B0 + [B1, B0] with
//            B1 = (1/h) int (psi - c) A (p = 4), exp(Omega) by J Taylor terms;
//   m4-exp:  the same with an accurate exponential (Eigen's scaling and squaring, the
//            library's matrix_exponential).
// Output: one line per candidate, K at each mu, the sum of K + K/2 and the two counts.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/core/constants.h"
#include "flaplag/numerics/dense.h"
#include "flaplag/numerics/floquet.h"

namespace {

using flaplag::kTwoPi;
using Mat = Eigen::Matrix4d;

double sinc(double x) { return std::abs(x) < 1e-4 ? 1.0 - x * x / 6.0 : std::sin(x) / x; }

// 3 (sin x - x cos x) / x^3: the first moment of a harmonic relative to its small-x limit.
double first_moment_factor(double x) {
  if (std::abs(x) < 2e-2) {
    const double x2 = x * x;
    return 1.0 - x2 / 10.0 * (1.0 - x2 / 28.0);
  }
  return 3.0 * (std::sin(x) - x * std::cos(x)) / (x * x * x);
}

Mat taylor(const Mat& X, int J) {
  Mat E = Mat::Identity(), T = Mat::Identity();
  for (int j = 1; j <= J; ++j) {
    T = T * X / j;
    E += T;
  }
  return E;
}

struct Candidate {
  const char* name;
  bool magnus;    // B0 + [B1, B0] instead of B0
  int terms;      // Taylor terms of the exponential; 0: accurate exponential
  int min_steps;  // K0
  int order;      // p of the estimate
};

Mat transition(const flaplag::PeriodicSystem& s, int K, const Candidate& c) {
  if (!c.magnus) return flaplag::transition_matrix_hsu(s, K, c.terms);  // the library's Hsu
  const std::vector<double> edges = s.breakpoints();
  Mat phi = Mat::Identity();
  const double d = kTwoPi / K;
  auto substep = [&](double a, double b) {
    const double h = b - a, mid = 0.5 * (a + b);
    const flaplag::HarmonicSet& g =
        s.sets[static_cast<std::size_t>(s.pieces[static_cast<std::size_t>(s.piece_at(mid))].set)];
    Mat B0 = h * Mat(g.A[0]), B1 = Mat::Zero();
    for (std::size_t j = 1; j < g.A.size(); ++j) {
      const int k = static_cast<int>(j + 1) / 2;
      const bool cosine = j % 2 == 1;
      const double cs = std::cos(k * mid), sn = std::sin(k * mid);
      B0 += (cosine ? cs : sn) * h * sinc(0.5 * k * h) * Mat(g.A[j]);
      B1 += (cosine ? -sn : cs) * h * h / 12.0 * k * first_moment_factor(0.5 * k * h) * Mat(g.A[j]);
    }
    const Mat omega = B0 + B1 * B0 - B0 * B1;
    phi = (c.terms > 0 ? taylor(omega, c.terms) : flaplag::matrix_exponential<4>(omega)) * phi;
  };
  for (int i = 0; i < K; ++i) {
    const double a = i * d, b = i + 1 == K ? kTwoPi : (i + 1) * d;
    double lo = a;
    for (double e : edges) {
      if (e > a + 1e-12 * kTwoPi && e < b - 1e-12 * kTwoPi) {
        substep(lo, e);
        lo = e;
      }
    }
    substep(lo, b);
  }
  return phi;
}

std::vector<double> zetas(const Eigen::MatrixXd& phi) {
  // Eigen::EigenSolver<Eigen::MatrixXd>, compiled once in the library
  const Eigen::VectorXcd values =
      flaplag::real_eigen_system(phi, false, flaplag::EigenStorage::Dynamic).values;
  std::vector<double> z;
  for (Eigen::Index i = 0; i < values.size(); ++i)
    z.push_back(std::log(std::abs(values(i))) / kTwoPi);
  std::sort(z.begin(), z.end());
  return z;
}

}  // namespace

int main() {
  const flaplag::Analysis an(flaplag::RotorParameters{}, {});
  const double tolerance = flaplag::TransitionOptions{}.zeta_tolerance;
  const Candidate candidates[] = {{"hsu, K >= 50 (the default)", false, 4, 50, 2},
                                  {"m4-t4, K >= 8", true, 4, 8, 4},
                                  {"m4-t6, K >= 8", true, 6, 8, 4},
                                  {"m4-t6, K >= 32", true, 6, 32, 4},
                                  {"m4-exp, K >= 8", true, 0, 8, 4},
                                  {"m4-exp, K >= 24", true, 0, 24, 4},
                                  {"m4-exp, K >= 32", true, 0, 32, 4}};
  std::vector<flaplag::PeriodicSystem> systems;
  std::vector<std::vector<double>> references;
  for (int m = 0; m <= 15; ++m) {
    systems.push_back(an.system(0.1 * m));
    references.push_back(zetas(flaplag::transition_matrix_magnus4(systems.back(), 1000).phi));
  }
  for (const Candidate& c : candidates) {
    long total = 0;
    int boundary = 0;
    double worst = 0.0, overshoot = 0.0;  // worst actual/estimate; worst actual/allowed
    std::printf("%-28s K:", c.name);
    for (std::size_t m = 0; m < systems.size(); ++m) {
      const double divisor = std::pow(2.0, c.order) - 1.0;
      for (int K = c.min_steps; K <= 4000; K += 2) {
        const std::vector<double> z = zetas(transition(systems[m], K, c));
        const std::vector<double> zc = zetas(transition(systems[m], K / 2, c));
        bool resolved = true, over = false;
        double ratio = 0.0, excess = 0.0;
        for (std::size_t i = 0; i < z.size(); ++i) {
          const double estimate = std::abs(z[i] - zc[i]) / divisor;
          const double actual = std::abs(z[i] - references[m][i]);
          const double allowed = tolerance * std::max(1.0, 100.0 * std::abs(z[i]));
          resolved = resolved && estimate <= allowed;
          over = over || actual > allowed;
          ratio = std::max(ratio, actual / std::max(estimate, 1e-14));
          excess = std::max(excess, actual / allowed);
        }
        if (!resolved) continue;
        total += K + K / 2;
        if (over) {
          ++boundary;
          overshoot = std::max(overshoot, excess);
        } else {
          worst = std::max(worst, ratio);
        }
        std::printf(" %d", K);
        break;
      }
    }
    std::printf(
        "\n%-28s sum of K + K/2 %ld, boundary %d of 16 (actual up to %.2f x the allowance), "
        "worst actual/estimate elsewhere %.2f\n",
        "", total, boundary, overshoot, worst);
  }
}
