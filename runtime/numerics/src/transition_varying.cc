// flaplag — transition matrices with a varying region (exact reversed flow): the methods of
// transition.cc on dynamic matrices, with A(psi) from the harmonics outside the varying region
// and from its evaluator inside.
//
// Hsu (eqs 3.21-3.28) needs the mean of A over each substep: exact for the harmonic parts
// (eqs 4.2-4.5), a 3-point Gauss-Legendre mean inside the varying region (its error O(h^6) is
// far below Hsu's own O(h^2)).  Every substep lies inside one
// smooth piece (the grid is split at all breakpoints), so RK4 keeps its fourth and Magnus its
// fourth (Richardson: sixth) order.
#include "transition_varying.h"

#include <cmath>
#include <vector>

#include "flaplag/core/constants.h"
#include "flaplag/numerics/dense.h"

namespace flaplag::detail {
namespace {

struct Piece {
  double a, b;
  bool varying;              // inside the varying region (by the midpoint)
  bool after_break = false;  // a starts at a breakpoint (A may jump or kink there)
};

// N equal steps over [0, 2 pi]; a step containing a breakpoint strictly inside is split there
// (a breakpoint within rounding of a grid point needs no split, as in transition.cc).
std::vector<Piece> make_grid(const PeriodicSystem& sys, int steps) {
  const std::vector<double> edges = sys.breakpoints();
  const double d = kTwoPi / steps;
  const double slack = 1e-12 * kTwoPi;
  std::vector<Piece> out;
  out.reserve(static_cast<std::size_t>(steps) + edges.size());
  std::size_t k = 0;
  for (int i = 0; i < steps; ++i) {
    const double a = i * d;
    const double b = (i + 1 == steps) ? kTwoPi : (i + 1) * d;
    double lo = a;
    bool at_break = false;
    while (k < edges.size() && edges[k] <= a + slack) at_break |= edges[k++] >= a - slack;
    while (k < edges.size() && edges[k] < b - slack) {
      out.push_back({lo, edges[k], sys.in_varying(0.5 * (lo + edges[k])), at_break});
      lo = edges[k++];
      at_break = true;
    }
    out.push_back({lo, b, sys.in_varying(0.5 * (lo + b)), at_break});
  }
  return out;
}

// A at psi on piece p: the evaluator inside the varying region (psi may be a piece end on the
// region's edge: the one-sided value), else the harmonics of the region of p's midpoint.
class Evaluator {
 public:
  explicit Evaluator(const PeriodicSystem& sys) : sys_(sys) {}
  void at(const Piece& p, double psi, Eigen::MatrixXd& out) {
    if (p.varying) {
      sys_.varying(psi, out, f_);
      return;
    }
    const HarmonicSet& set = sys_.region(0.5 * (p.a + p.b));
    out = set.A[0];
    // cos k psi, sin k psi by the rotation recurrence from one sin/cos pair
    const double c1 = std::cos(psi), s1 = std::sin(psi);
    double ck = c1, sk = s1;
    for (std::size_t h = 1; h < set.A.size(); h += 2) {
      out += ck * set.A[h];
      if (h + 1 < set.A.size()) out += sk * set.A[h + 1];
      const double cn = ck * c1 - sk * s1;
      sk = sk * c1 + ck * s1;
      ck = cn;
    }
  }

 private:
  const PeriodicSystem& sys_;
  Eigen::VectorXd f_;
};

// T = sum_{j=0}^{J} X^j / j! by Horner (eq 3.27): I + X/1 (I + X/2 (... (I + X/J))); Y is
// workspace.
void taylor(const Eigen::MatrixXd& X, int J, Eigen::MatrixXd& Y, Eigen::MatrixXd& T) {
  T = X / static_cast<double>(J);
  T.diagonal().array() += 1.0;
  for (int j = J - 1; j >= 1; --j) {
    Y.noalias() = X * T;
    T = Y / static_cast<double>(j);
    T.diagonal().array() += 1.0;
  }
}

Eigen::MatrixXd magnus(const PeriodicSystem& sys, const std::vector<Piece>& grid) {
  const double g = std::sqrt(3.0) / 6.0;
  Evaluator ev(sys);
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Identity(sys.n, sys.n), A1, A2;
  for (const Piece& p : grid) {
    const double h = p.b - p.a;
    ev.at(p, p.a + (0.5 - g) * h, A1);
    ev.at(p, p.a + (0.5 + g) * h, A2);
    Eigen::MatrixXd Om = (0.5 * h) * (A1 + A2);
    Om += (std::sqrt(3.0) / 12.0 * h * h) * (A2 * A1 - A1 * A2);
    const Eigen::MatrixXd E = matrix_exponential(Om);
    Phi = E * Phi;
  }
  return Phi;
}

}  // namespace

Eigen::MatrixXd varying_rk4(const PeriodicSystem& sys, int steps) {
  Evaluator ev(sys);
  const int n = sys.n;
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Identity(n, n), Aa(n, n), Am(n, n), Ab(n, n), Y(n, n),
                  k1(n, n), k2(n, n), k3(n, n), k4(n, n);
  const std::vector<Piece> grid = make_grid(sys, steps);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const Piece& p = grid[i];
    const double h = p.b - p.a;
    // A at the start is the previous end unless a breakpoint lies between (A may jump there)
    if (i > 0 && !p.after_break) {
      Aa.swap(Ab);
    } else {
      ev.at(p, p.a, Aa);
    }
    ev.at(p, 0.5 * (p.a + p.b), Am);
    ev.at(p, p.b, Ab);
    k1.noalias() = Aa * Phi;
    Y = Phi + (0.5 * h) * k1;
    k2.noalias() = Am * Y;
    Y = Phi + (0.5 * h) * k2;
    k3.noalias() = Am * Y;
    Y = Phi + h * k3;
    k4.noalias() = Ab * Y;
    Phi += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return Phi;
}

Eigen::MatrixXd varying_hsu(const PeriodicSystem& sys, int intervals, int terms) {
  // 3-point Gauss-Legendre on [-1, 1]
  const double gx = std::sqrt(0.6), gw[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  Evaluator ev(sys);
  const int n = sys.n;
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Identity(n, n), C(n, n), X(n, n), E(n, n), P(n, n);
  for (const Piece& p : make_grid(sys, intervals)) {
    // C_k = mean of A over the substep (eq 3.22): exact for the harmonic regions; in the
    // varying region 3-point Gauss (error O(h^6), far below Hsu's own O(h^2)).
    if (p.varying) {
      const double m = 0.5 * (p.a + p.b), r = 0.5 * (p.b - p.a);
      C.setZero(sys.n, sys.n);
      for (int i = 0; i < 3; ++i) {
        ev.at(p, m + (i - 1) * gx * r, X);
        C += gw[i] * X;
      }
    } else {
      C = sys.A_mean(p.a, p.b);
    }
    C *= p.b - p.a;
    taylor(C, terms, X, E);
    P.noalias() = E * Phi;
    Phi.swap(P);
  }
  return Phi;
}

// As transition_matrix_magnus4: Phi_h and Phi_{h/2} (every piece bisected), Richardson.
TransitionResult varying_magnus4(const PeriodicSystem& sys, int steps) {
  const std::vector<Piece> coarse = make_grid(sys, steps);
  std::vector<Piece> fine;
  fine.reserve(2 * coarse.size());
  for (const Piece& p : coarse) {
    const double m = 0.5 * (p.a + p.b);
    fine.push_back({p.a, m, p.varying});
    fine.push_back({m, p.b, p.varying});
  }
  const Eigen::MatrixXd ph = magnus(sys, coarse);
  const Eigen::MatrixXd ph2 = magnus(sys, fine);
  TransitionResult out;
  out.phi = (16.0 * ph2 - ph) / 15.0;
  out.error_estimate = (ph2 - ph).cwiseAbs().maxCoeff() / 15.0;
  return out;
}

}  // namespace flaplag::detail
