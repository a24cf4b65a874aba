// flaplag — transition matrices of a system with an evaluator piece (exact reversed flow): the
// methods of transition.cc on dynamic matrices, with A(psi) from the harmonics of the harmonic
// pieces and from the evaluator inside its piece.
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
#include "flaplag/numerics/gauss_legendre.h"
#include "grid.h"

namespace flaplag::detail {
namespace {

using Piece = Segment;

// A at psi on piece p: the evaluator inside the varying region (psi may be a piece end on the
// region's edge: the one-sided value), else the harmonics of the region of p's midpoint.
class Evaluator {
 public:
  explicit Evaluator(const PeriodicSystem& sys) : sys_(sys) {}
  void at(const Piece& p, double psi, Eigen::MatrixXd& out) {
    if (p.set < 0) {
      evaluator(sys_, p)(psi, out, f_);
      return;
    }
    const HarmonicSet& set = harmonic_set(sys_, p.set);
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

// Fourth-order Magnus (gauss::magnus4_step) on the given grid.
Eigen::MatrixXd magnus(const PeriodicSystem& sys, const std::vector<Piece>& grid) {
  Evaluator ev(sys);
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Identity(sys.n, sys.n), A1, A2;
  for (const Piece& p : grid) {
    const gauss::Magnus4Step st = gauss::magnus4_step(p.a, p.b);
    ev.at(p, st.psi1, A1);
    ev.at(p, st.psi2, A2);
    Eigen::MatrixXd Om = st.c1 * (A1 + A2);
    Om += st.c2 * (A2 * A1 - A1 * A2);
    const Eigen::MatrixXd E = matrix_exponential(Om);
    Phi = E * Phi;
  }
  return Phi;
}

}  // namespace

Eigen::MatrixXd varying_rk4(const PeriodicSystem& sys, int steps) {
  Evaluator ev(sys);
  const int n = sys.n;
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Identity(n, n), Aa(n, n), Am(n, n), Ab(n, n);
  Rk4<Eigen::MatrixXd> rk;
  const std::vector<Piece> grid = equal_grid(sys, steps);
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
    rk.step(h, Phi, [&](int stage, const Eigen::MatrixXd& y, Eigen::MatrixXd& k) {
      k.noalias() = (stage == 0 ? Aa : stage == 3 ? Ab : Am) * y;
    });
  }
  return Phi;
}

Eigen::MatrixXd varying_hsu(const PeriodicSystem& sys, int intervals, int terms) {
  Evaluator ev(sys);
  const int n = sys.n;
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Identity(n, n), C(n, n), X(n, n), E(n, n), P(n, n);
  for (const Piece& p : equal_grid(sys, intervals)) {
    // C_k = mean of A over the substep (eq 3.22): exact for the harmonic regions; in the
    // varying region 3-point Gauss (error O(h^6), far below Hsu's own O(h^2)).
    if (p.set < 0) {
      const double m = 0.5 * (p.a + p.b), r = 0.5 * (p.b - p.a);
      C.setZero(sys.n, sys.n);
      for (int i = 0; i < 3; ++i) {
        ev.at(p, m + gauss::kX3[i] * r, X);
        C += gauss::kHalfW3[i] * X;
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
  const std::vector<Piece> coarse = equal_grid(sys, steps);
  const std::vector<Piece> fine = bisect(coarse);
  const Eigen::MatrixXd ph = magnus(sys, coarse);
  const Eigen::MatrixXd ph2 = magnus(sys, fine);
  TransitionResult out;
  out.phi = (16.0 * ph2 - ph) / 15.0;
  out.error_estimate = (ph2 - ph).cwiseAbs().maxCoeff() / 15.0;
  return out;
}

}  // namespace flaplag::detail
