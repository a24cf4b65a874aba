// The periodic equilibrium of the nonlinear equations by harmonic balance + Newton, and the
// linearization about it as harmonic sets (see periodic_equilibrium.h for the choice of method).
#include "flaplag/rotor/periodic_equilibrium.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <string>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/numerics/floquet.h"
#include "flaplag/numerics/gauss_legendre.h"
#include "flaplag/rotor/system_builder.h"

namespace flaplag {
namespace {

// Smooth pieces of [0, 2 pi]: split at the sector edges; each flagged with its region.
struct Piece {
  double a, b;
  bool reversed;
};

// (the edges from PeriodicSystem::breakpoints(), the one source of where the regions change).
std::vector<Piece> pieces(const PeriodicSystem& s) {
  std::vector<double> cuts{0.0};
  for (double b : s.breakpoints()) cuts.push_back(b);
  cuts.push_back(kTwoPi);
  std::vector<Piece> out;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    if (!(cuts[i + 1] > cuts[i])) continue;
    const int piece = s.piece_at(0.5 * (cuts[i] + cuts[i + 1]));
    out.push_back({cuts[i], cuts[i + 1], s.pieces[static_cast<std::size_t>(piece)].set != 0});
  }
  return out;
}

// Basis phi_c and its first two derivatives at psi, c = 0..2K.
void basis(int K, double psi, Eigen::VectorXd& p, Eigen::VectorXd& d1, Eigen::VectorXd& d2) {
  p.resize(2 * K + 1);
  d1.resize(2 * K + 1);
  d2.resize(2 * K + 1);
  p(0) = 1.0;
  d1(0) = d2(0) = 0.0;
  for (int k = 1; k <= K; ++k) {
    const double c = std::cos(k * psi), s = std::sin(k * psi);
    p(2 * k - 1) = c;
    p(2 * k) = s;
    d1(2 * k - 1) = -k * s;
    d1(2 * k) = k * c;
    d2(2 * k - 1) = -k * k * c;
    d2(2 * k) = -k * k * s;
  }
}

// X (n x (2K+1)) truncated or padded with zero harmonics to K2.
Eigen::MatrixXd resized(const Eigen::MatrixXd& X, int K2) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(X.rows(), 2 * K2 + 1);
  const int c = std::min<int>(static_cast<int>(X.cols()), 2 * K2 + 1);
  out.leftCols(c) = X.leftCols(c);
  return out;
}

// max_c |Xa_c - Xb_c| / max |Xb| over the coefficients of the Fourier series of q° (Xa padded
// with zero harmonics to Xb's K): the A(psi) of the linearization and the mean thrust are
// smooth functions of these coefficients.  (Not the point-wise difference of the states: q°'
// has kinks at the sector edges, so its samples converge only like 1/K near them, while the
// coefficients fall like k^-3.)
double coefficient_difference(const Eigen::MatrixXd& Xa, const Eigen::MatrixXd& Xb, int Kb) {
  const double big = Xb.cwiseAbs().maxCoeff();
  const double diff = (resized(Xa, Kb) - Xb).cwiseAbs().maxCoeff();
  return big > 0.0 ? diff / big : diff;
}

struct QuadPoint {
  double psi, weight;
  bool reversed;
};

// Composite Gauss-Legendre on each piece, sub-intervals short enough that the highest frequency
// `omega` of the integrand turns by at most 2 rad on one (8-point rule error ~ 1e-14).
std::vector<QuadPoint> quadrature(const PeriodicSystem& s, double omega) {
  const double hmax = 2.0 / std::max(1.0, omega);
  std::vector<QuadPoint> out;
  for (const Piece& pc : pieces(s)) {
    const int m = std::max(1, static_cast<int>(std::ceil((pc.b - pc.a) / hmax)));
    gauss::composite_gauss8(pc.a, pc.b, m, [&](double psi, double weight) {
      out.push_back({psi, weight, pc.reversed});
    });
  }
  return out;
}

struct Newton {
  bool converged = false, singular = false, finite = true;
  int iterations = 0;
  double step = 0.0, residual = 0.0;
};

// The harmonic balance of q'' = mass^-1 G(q, q', psi) for the coefficients X (n x (2K+1)) of
// q in the basis phi_c: the residual R, the projections onto phi_c of q'' - mass^-1 G at the
// quadrature points (fixed for the whole solve), and its Jacobian by X.
class HarmonicBalance {
 public:
  HarmonicBalance(const NonlinearSystem& sys, int M, int N, int K)
      : sys_(sys),
        M_(M),
        N_(N),
        K_(K),
        n_(M + N),
        nb_(2 * K + 1),
        // Integrand degree: residual (model order 2 plus 2K for a quadratic term) times phi_c.
        points_(quadrature(sys.sector(), 3.0 * K + 4.0)),
        P_(static_cast<int>(points_.size())) {
    tabulate_basis();
    tabulate_mass_block();
  }

  // R (n (2K+1)) and Jac (n (2K+1) square) at X, sized by the caller.
  void evaluate(const Eigen::MatrixXd& X, Eigen::VectorXd& R, Eigen::MatrixXd& Jac) {
    sample_residual(X);
    project(R, Jac);
  }

 private:
  static int harmonic_of(int c) { return (c + 1) / 2; }
  static bool is_sine(int c) { return c > 0 && c % 2 == 0; }

  // Fixed for the whole solve (the points do not move between iterations): the basis and its
  // derivatives at the points, W (nb x P) the weighted basis (the projection onto phi_c is a
  // Fourier coefficient), and H (P x (4K+1)) the weighted harmonics cos h psi (columns 0..2K)
  // and sin h psi (columns 2K+1..4K, h = 1..2K), for the Jacobian below.
  void tabulate_basis() {
    const int K = K_, P = P_;
    Pb_.resize(nb_, P);
    D1_.resize(nb_, P);
    D2_.resize(nb_, P);
    W_.resize(nb_, P);
    H_.resize(P, 4 * K + 1);
    Eigen::VectorXd p, d1, d2;
    for (int k = 0; k < P; ++k) {
      const QuadPoint& qp = points_[k];
      basis(K, qp.psi, p, d1, d2);
      Pb_.col(k) = p;
      D1_.col(k) = d1;
      D2_.col(k) = d2;
      const double w = qp.weight / kPi;
      W_.col(k) = p * w;
      W_(0, k) *= 0.5;
      // cos, sin of (K + h) psi from those of K psi and h psi (angle addition)
      const double cK = K > 0 ? p(2 * K - 1) : 1.0, sK = K > 0 ? p(2 * K) : 0.0;
      H_(k, 0) = w;
      for (int h = 1; h <= 2 * K; ++h) {
        double c, sn;
        if (h <= K) {
          c = p(2 * h - 1);
          sn = p(2 * h);
        } else {
          const double ch = p(2 * (h - K) - 1), sh = p(2 * (h - K));
          c = cK * ch - sK * sh;
          sn = sK * ch + cK * sh;
        }
        H_(k, h) = w * c;
        H_(k, 2 * K + h) = w * sn;
      }
    }
  }

  // sum W_c phi_d'' (the delta_ij term of the Jacobian).
  void tabulate_mass_block() {
    const Eigen::VectorXd unit_sums = H_.colwise().sum().transpose();
    mass_block_.resize(nb_, nb_);
    for (int c = 0; c < nb_; ++c)
      for (int d = 0; d < nb_; ++d) {
        const int l = harmonic_of(d);
        mass_block_(c, d) = -static_cast<double>(l * l) * product_sum(unit_sums, c, d);
      }
  }

  // The residual E (n x P) of q'' = mass^-1 G at each point, and S (P x 2 n^2) the
  // derivatives a_ij, b_ij of equation i's load by displacement and rate j there.
  void sample_residual(const Eigen::MatrixXd& X) {
    const int n = n_, M = M_, N = N_, P = P_;
    y_.resize(2 * n);
    E_.resize(n, P);
    S_.resize(P, 2 * n * n);
    Q_.noalias() = X * Pb_;
    Qd_.noalias() = X * D1_;
    Qdd_.noalias() = X * D2_;
    for (int k = 0; k < P; ++k) {
      const QuadPoint& qp = points_[k];
      for (int j = 0; j < n; ++j) {
        y_(model::rate_index(j, M, N)) = Qd_(j, k);
        y_(model::displacement_index(j, M, N)) = Q_(j, k);
      }
      sys_.evaluate(qp.psi, qp.reversed, y_, &F_, &J_);
      for (int i = 0; i < n; ++i) {
        const int row = model::rate_index(i, M, N);
        E_(i, k) = Qdd_(i, k) - F_(row);
        for (int j = 0; j < n; ++j) {
          S_(k, 2 * (i * n + j)) = J_(row, model::displacement_index(j, M, N));
          S_(k, 2 * (i * n + j) + 1) = J_(row, model::rate_index(j, M, N));
        }
      }
    }
  }

  // The projections onto phi_c: R from E, and the Jacobian's blocks from the harmonic sums of
  // S.  Block (i, j) is sum_k W_c(psi_k) [-a_ij phi_d - b_ij phi_d' + delta_ij phi_d''](psi_k).
  void project(Eigen::VectorXd& R, Eigen::MatrixXd& Jac) const {
    const int n = n_, nb = nb_;
    const Eigen::MatrixXd sums = H_.transpose() * S_;  // (4K+1) x 2 n^2
    for (int i = 0; i < n; ++i) {
      R.segment(i * nb, nb).noalias() = W_ * E_.row(i).transpose();
      for (int j = 0; j < n; ++j) {
        const auto sa = sums.col(2 * (i * n + j)), sb = sums.col(2 * (i * n + j) + 1);
        auto block = Jac.block(i * nb, j * nb, nb, nb);
        for (int c = 0; c < nb; ++c)
          for (int d = 0; d < nb; ++d)
            block(c, d) = -product_sum(sa, c, d) - derivative_sum(sb, c, d);
        if (i == j) block += mass_block_;
      }
    }
  }

  // The product phi_c phi_d is a sum of two harmonics of order <= 2K (cos m cos n =
  // (cos (m-n) + cos (m+n)) / 2, ...), so every block entry is a combination of the weighted
  // harmonic sums of a_ij and b_ij: O(P K) work per pair instead of O(P K^2).
  // sum_k w_k f(psi_k) phi_c(psi_k) phi_d(psi_k) / pi from f's weighted sums `s` (a column of
  // H^T f), with the factor 1/2 of the constant's projection.
  template <typename Sums>
  double product_sum(const Sums& s, int c, int d) const {
    const int K = K_;
    const auto A = [&](int h) { return s(std::abs(h)); };
    const auto B = [&](int h) { return h == 0 ? 0.0 : h > 0 ? s(2 * K + h) : -s(2 * K - h); };
    const int m = harmonic_of(c), l = harmonic_of(d);
    double v;
    if (c == 0 && d == 0)
      v = A(0);
    else if (c == 0)
      v = is_sine(d) ? B(l) : A(l);
    else if (d == 0)
      v = is_sine(c) ? B(m) : A(m);
    else if (!is_sine(c) && !is_sine(d))
      v = 0.5 * (A(m - l) + A(m + l));
    else if (is_sine(c) && is_sine(d))
      v = 0.5 * (A(m - l) - A(m + l));
    else if (!is_sine(c))
      v = 0.5 * (B(m + l) - B(m - l));  // cos m sin l
    else
      v = 0.5 * (B(m + l) + B(m - l));  // sin m cos l
    return c == 0 ? 0.5 * v : v;
  }

  // phi_d' = -l phi_{d+1} (cos l psi) or l phi_{d-1} (sin l psi); phi_d'' = -l^2 phi_d.
  template <typename Sums>
  double derivative_sum(const Sums& s, int c, int d) const {
    if (d == 0) return 0.0;
    const int l = harmonic_of(d);
    return is_sine(d) ? l * product_sum(s, c, d - 1) : -l * product_sum(s, c, d + 1);
  }

  const NonlinearSystem& sys_;
  const int M_, N_, K_, n_, nb_;
  const std::vector<QuadPoint> points_;
  const int P_;
  Eigen::MatrixXd Pb_, D1_, D2_, W_, H_, mass_block_;
  // Scratch of an evaluation.
  Eigen::VectorXd y_, F_;
  Eigen::MatrixXd J_;
  Eigen::MatrixXd E_;             // residual at each point
  Eigen::MatrixXd S_;             // a_ij, b_ij at each point
  Eigen::MatrixXd Q_, Qd_, Qdd_;  // q, q', q'' at the points
};

// Newton on the harmonic balance (HarmonicBalance) for the coefficients X (n x (2K+1)), from
// the X given.
Newton solve(const NonlinearSystem& sys, int M, int N, int K, const PeriodicEquilibriumOptions& opt,
             Eigen::MatrixXd& X) {
  const int n = M + N, nb = 2 * K + 1, unknowns = n * nb;
  HarmonicBalance balance(sys, M, N, K);
  Newton out;
  Eigen::VectorXd R(unknowns);
  Eigen::MatrixXd Jac(unknowns, unknowns);
  double previous_step = std::numeric_limits<double>::infinity();
  for (int it = 1; it <= opt.max_iterations; ++it) {
    balance.evaluate(X, R, Jac);
    out.residual = R.cwiseAbs().maxCoeff();
    if (!R.allFinite() || !Jac.allFinite()) {
      out.finite = false;
      return out;
    }
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(Jac);
    if (!(lu.rcond() > 1e-13)) {
      out.singular = true;
      return out;
    }
    const Eigen::VectorXd dx = lu.solve(-R);
    for (int i = 0; i < n; ++i) X.row(i) += dx.segment(i * nb, nb).transpose();
    out.iterations = it;
    out.step = dx.cwiseAbs().maxCoeff() / std::max(1.0, X.cwiseAbs().maxCoeff());
    if (!X.allFinite()) {
      out.finite = false;
      return out;
    }
    if (out.step <= opt.tolerance) {
      out.converged = true;
      return out;
    }
    // Not converging (no longer contracting after the first iterations, e.g. beyond a fold):
    // give up early, the continuation halves its step.
    if (it >= 6 && out.step > 0.5 * previous_step) return out;
    previous_step = out.step;
  }
  return out;
}

// Harmonic set of A(psi) = dF/dy(y°(psi), psi) in one region: exact DFT of a trigonometric
// polynomial of order <= L (L = model order + 2K covers loads up to cubic in the state).
HarmonicSet linear_set(const NonlinearSystem& sys, const PeriodicEquilibrium& eq, bool reversed,
                       int L) {
  const int ns = sys.size(), P = 2 * L + 2;
  std::vector<Eigen::MatrixXd> A(2 * L + 1, Eigen::MatrixXd::Zero(ns, ns));
  Eigen::VectorXd F;
  Eigen::MatrixXd J;
  for (int k = 0; k < P; ++k) {
    const double psi = kTwoPi * k / P;
    sys.evaluate(psi, reversed, eq.state(psi), &F, &J);
    A[0] += J / P;
    for (int h = 1; h <= L; ++h) {
      A[2 * h - 1] += J * (2.0 * std::cos(h * psi) / P);
      A[2 * h] += J * (2.0 * std::sin(h * psi) / P);
    }
  }
  // Entries at rounding level are exact zeros (the transition kernels skip constant entries).
  double scale = 0.0;
  for (const auto& a : A) scale = std::max(scale, a.cwiseAbs().maxCoeff());
  const double tiny = 1e-14 * scale;
  int top = 0;
  for (int h = 0; h <= 2 * L; ++h) {
    A[h] = A[h].unaryExpr([tiny](double v) { return std::abs(v) <= tiny ? 0.0 : v; });
    if (!A[h].isZero(0.0)) top = h;
  }
  const int H = top % 2 == 1 ? top + 2 : top + 1;  // whole harmonic orders (cos and sin)
  HarmonicSet set;
  set.A.assign(A.begin(), A.begin() + std::min(H, 2 * L + 1));
  set.f.assign(1, Eigen::VectorXd::Zero(ns));
  return set;
}

}  // namespace

NonlinearSystem::NonlinearSystem(const detail::SystemBuilder& builder, double mu)
    : builder_(&builder), mu_(mu) {
  const auto& m = builder.model();
  // The loads are integrated with the normal and the sector integrals (the exact circle would
  // be left out silently).
  if (builder.params().exact_reversed_flow) {
    throw InvalidInput("exact_reversed_flow", "true",
                       "the periodic equilibrium is built with the Appendix D sector: use the "
                       "sector (`exact_reversed_flow` = false)");
  }
  n_ = m.flap_modes + m.lag_modes;
  ns_ = 2 * n_;
  H_ = m.n_nonlinear_harmonics;
  sector_ = builder.system(mu);  // throws InvalidInput("mu", ...) for a bad mu
  normal_ = builder.normal_integrals();
  if (sector_.sets.size() > 1) reversed_ = builder.reversed_integrals(mu);
}

bool NonlinearSystem::reversed(double psi) const {
  return sector_.pieces[static_cast<std::size_t>(sector_.piece_at(psi))].set != 0;
}

void NonlinearSystem::evaluate(double psi, bool in_sector, const Eigen::VectorXd& y,
                               Eigen::VectorXd* F, Eigen::MatrixXd* J) const {
  const auto& m = builder_->model();
  const int M = m.flap_modes, N = m.lag_modes;
  // Scratch of this thread, sized once: the harmonic balance evaluates at thousands of points
  // per Newton iteration, and the allocations would cost more than the loads.
  thread_local std::vector<double> force, jac;
  thread_local Eigen::VectorXd G, acc;
  thread_local Eigen::MatrixXd Jg, D;
  force.assign(static_cast<std::size_t>(H_ * n_), 0.0);
  jac.assign(static_cast<std::size_t>(H_ * n_ * ns_), 0.0);
  builder_->nonlinear_loads(mu_, in_sector && sector_.sets.size() > 1 ? reversed_ : normal_,
                            y.data(), force.data(), jac.data());
  G.setZero(n_);
  if (J != nullptr) Jg.setZero(n_, ns_);
  for (int h = 0; h < H_; ++h) {
    const double b = harmonic_basis(h, psi);
    for (int i = 0; i < n_; ++i) {
      G(i) += b * force[h * n_ + i];
      if (J != nullptr)
        for (int c = 0; c < ns_; ++c) Jg(i, c) += b * jac[(h * n_ + i) * ns_ + c];
    }
  }
  const Eigen::MatrixXd& Minv = builder_->mass_inverse();
  F->setZero(ns_);
  acc.noalias() = Minv * G;
  for (int j = 0; j < n_; ++j) {
    (*F)(model::rate_index(j, M, N)) = acc(j);
    (*F)(model::displacement_index(j, M, N)) = y(model::rate_index(j, M, N));
  }
  if (J != nullptr) {
    J->setZero(ns_, ns_);
    D.noalias() = Minv * Jg;
    for (int j = 0; j < n_; ++j) {
      J->row(model::rate_index(j, M, N)) = D.row(j);
      (*J)(model::displacement_index(j, M, N), model::rate_index(j, M, N)) = 1.0;
    }
  }
}

double NonlinearSystem::thrust(double psi, bool in_sector, const Eigen::VectorXd& y) const {
  std::vector<double> t(H_);
  builder_->nonlinear_thrust(mu_, in_sector && sector_.sets.size() > 1 ? reversed_ : normal_,
                             y.data(), t.data(), nullptr);
  double v = 0.0;
  for (int h = 0; h < H_; ++h) v += harmonic_basis(h, psi) * t[h];
  return v;
}

std::vector<Eigen::VectorXd> NonlinearSystem::integrate(const Eigen::VectorXd& y0, int revolutions,
                                                        int steps_per_rev) const {
  if (y0.size() != ns_) throw InvalidInput("y0", std::to_string(y0.size()), "must have 2n entries");
  if (revolutions < 1)
    throw InvalidInput("revolutions", std::to_string(revolutions), "must be >= 1");
  if (steps_per_rev < 1)
    throw InvalidInput("steps_per_rev", std::to_string(steps_per_rev), "must be >= 1");
  std::vector<double> grid;
  for (int i = 0; i <= steps_per_rev; ++i) grid.push_back(kTwoPi * i / steps_per_rev);
  for (double e : sector_.breakpoints()) grid.push_back(e);
  std::sort(grid.begin(), grid.end());
  grid.erase(std::unique(grid.begin(), grid.end(),
                         [](double a, double b) { return std::abs(a - b) < 1e-13; }),
             grid.end());
  std::vector<Eigen::VectorXd> out;
  Eigen::VectorXd y = y0, k1, k2, k3, k4, stage(ns_);  // (stage: no allocation per step)
  for (int r = 0; r < revolutions; ++r) {
    for (std::size_t i = 0; i + 1 < grid.size(); ++i) {
      const double a = grid[i], b = grid[i + 1], h = b - a;
      const bool rev = reversed(0.5 * (a + b));
      evaluate(a, rev, y, &k1, nullptr);
      stage = y + 0.5 * h * k1;
      evaluate(a + 0.5 * h, rev, stage, &k2, nullptr);
      stage = y + 0.5 * h * k2;
      evaluate(a + 0.5 * h, rev, stage, &k3, nullptr);
      stage = y + h * k3;
      evaluate(b, rev, stage, &k4, nullptr);
      y += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    out.push_back(y);
  }
  return out;
}

std::optional<InvalidInput> PeriodicEquilibriumOptions::Validate() const {
  static_assert(kAutomaticHarmonics == -1, "the words of kHarmonicsRange name it");
  return Requirements()
      .InRange("harmonics", harmonics == kAutomaticHarmonics ? 1 : harmonics, kHarmonicsRange)
      .InRanges(*this)
      .Result();
}

Eigen::VectorXd PeriodicEquilibrium::state(double psi) const {
  const int n = static_cast<int>(coefficients.rows()), K = harmonics;
  const int M = flap_modes, N = n - flap_modes;
  Eigen::VectorXd p, d1, d2;
  basis(K, psi, p, d1, d2);
  const Eigen::VectorXd q = coefficients * p, qd = coefficients * d1;
  Eigen::VectorXd y(2 * n);
  for (int j = 0; j < n; ++j) {
    y(model::rate_index(j, M, N)) = qd(j);
    y(model::displacement_index(j, M, N)) = q(j);
  }
  return y;
}

namespace {

// A solution of the harmonic balance on the branch through the hover equilibrium.
struct Branch {
  int K = 0;             // harmonics
  Eigen::MatrixXd X;     // coefficients (n x (2K+1))
  double reached = 0.0;  // the mu it is the solution at
  Newton newton;         // the last solve
};

// K of the continuation: fixed, or (automatic) one below the start's accepted K.
int continuation_harmonics(const PeriodicEquilibriumOptions& opt,
                           const PeriodicEquilibrium* start) {
  if (opt.harmonics != PeriodicEquilibriumOptions::kAutomaticHarmonics) return opt.harmonics;
  if (start != nullptr && std::isfinite(start->harmonics_error))
    return std::clamp(start->harmonics / 2, PeriodicEquilibriumOptions::kFirstHarmonics,
                      PeriodicEquilibriumOptions::kMaxHarmonics / 2);
  return PeriodicEquilibriumOptions::kFirstHarmonics;
}

// The branch through the hover equilibrium: continuation in mu from hover (at mu = 0 the
// hover state solves the equations exactly), steps of at most kMaxStep, each Newton solve
// from the previous solution; a failed step, or one that moves any coefficient by more than
// kMaxChange, is halved, so that the steps shrink where the branch steepens towards a fold.
// Newton straight from the hover state at a large mu could land on another branch.
constexpr double kMaxStep = 0.1, kMaxChange = 0.01;

// The point of the branch the continuation to mu starts from, with K harmonics: `start` when
// it is corrected at its own mu (a point of the same branch, perhaps of slightly different
// parameters: a neighbouring trim iterate; one Newton iteration when nothing changed), else
// hover.
Branch start_of_branch(const detail::SystemBuilder& builder, const NonlinearSystem& sys, double mu,
                       int K, const PeriodicEquilibriumOptions& opt,
                       const PeriodicEquilibrium* start) {
  const auto& m = builder.model();
  const int M = m.flap_modes, N = m.lag_modes, n = M + N;
  Branch b;
  b.K = K;
  b.X = Eigen::MatrixXd::Zero(n, 2 * K + 1);
  b.X.col(0) = builder.hover().q0;
  if (start != nullptr && start->status != Status::Failed && start->coefficients.rows() == n &&
      start->coefficients.allFinite() && start->mu - mu <= kMaxStep) {
    const Eigen::MatrixXd given = resized(start->coefficients, K);
    Eigen::MatrixXd trial = given;
    const Newton t =
        solve(start->mu == mu ? sys : NonlinearSystem(builder, start->mu), M, N, K, opt, trial);
    if (t.finite && t.converged && (trial - given).cwiseAbs().maxCoeff() <= kMaxChange) {
      b.X = trial;
      b.reached = start->mu;
      b.newton = t;
      return b;
    }
  }
  b.newton = solve(NonlinearSystem(builder, 0.0), M, N, K, opt, b.X);
  return b;
}

// Continues b towards mu (downwards only from a start above mu) until it is reached or the
// step falls below min_continuation_step.
void continue_branch(const detail::SystemBuilder& builder, const NonlinearSystem& sys, double mu,
                     const PeriodicEquilibriumOptions& opt, Branch& b) {
  const auto& m = builder.model();
  const int M = m.flap_modes, N = m.lag_modes;
  const double dir = mu >= b.reached ? 1.0 : -1.0;
  double step = std::min(std::abs(mu - b.reached), kMaxStep);
  // (a start closer than that is a step of its own)
  const double min_step = std::min(opt.min_continuation_step, step);
  for (int tries = 0; b.newton.converged && tries < 1000 && b.reached != mu && step >= min_step;
       ++tries) {
    const double next = dir > 0.0 ? std::min(mu, b.reached + step) : std::max(mu, b.reached - step);
    Eigen::MatrixXd trial = b.X;
    const Newton t =
        solve(next == mu ? sys : NonlinearSystem(builder, next), M, N, b.K, opt, trial);
    if (!t.finite) {
      b.newton = t;
      break;
    }
    // A step that moves the solution by more than kMaxChange may have jumped to another
    // branch (beyond a fold there is no solution nearby): retry with half the step.
    if (t.converged && (trial - b.X).cwiseAbs().maxCoeff() <= kMaxChange) {
      b.X = trial;
      b.reached = next;
      b.newton = t;
      step = std::min(kMaxStep, 1.5 * step);
    } else {
      step *= 0.5;
    }
  }
}

// Automatic K: doubled at mu (Newton from the padded solution) until two successive K agree
// (out.harmonics_error), or K reaches its cap (then `k_note` says so).  false: no solution of
// the finer truncation (out is final).
bool converge_in_harmonics(const NonlinearSystem& sys, double mu,
                           const PeriodicEquilibriumOptions& opt, int M, int N, Branch& b,
                           PeriodicEquilibrium& out, std::string& k_note) {
  while (true) {
    const int K2 = 2 * b.K;
    Eigen::MatrixXd X2 = resized(b.X, K2);
    const Newton t = solve(sys, M, N, K2, opt, X2);
    if (!t.finite || !t.converged) {
      // No solution of the finer truncation near this one: the K solution is an artefact of
      // the truncation (between the folds of K and 2K the coarse branch still exists, the
      // converged one no longer), so there is no converged periodic equilibrium here.
      out.harmonics = b.K;
      out.coefficients = b.X;
      out.continued_to = b.reached;
      out.status = Status::Failed;
      out.message = "no periodic equilibrium converged in the number of harmonics at mu = " +
                    round_trip_text(mu) + ": the harmonic balance with K = " + std::to_string(b.K) +
                    " has one, but none near it with K = " + std::to_string(K2) +
                    " (typically just past the fold of the branch, which the coarser "
                    "truncation places too far out)";
      return false;
    }
    out.harmonics_error = coefficient_difference(b.X, X2, K2);
    b.X = X2;
    b.K = K2;
    b.newton = t;
    if (out.harmonics_error <= opt.harmonics_tolerance) return true;
    if (b.K >= PeriodicEquilibriumOptions::kMaxHarmonics) {
      k_note = "harmonics_error = " + short_text(out.harmonics_error) +
               " at the cap K = " + std::to_string(b.K) +
               " exceeds harmonics_tolerance = " + short_text(opt.harmonics_tolerance);
      return true;
    }
  }
}

// Why there is no periodic equilibrium at mu on the branch b, if so (then out is final).
bool branch_failed(const Branch& b, double mu, PeriodicEquilibrium& out) {
  if (!b.newton.finite) {
    out.status = Status::Failed;
    out.message = "the harmonic balance overflowed at mu = " + round_trip_text(mu);
    return true;
  }
  if (b.newton.singular && b.reached == mu) {
    out.status = Status::Failed;
    out.message = "the harmonic-balance Newton matrix is singular at mu = " + round_trip_text(mu) +
                  ": a Floquet multiplier at 1, no unique periodic equilibrium";
    return true;
  }
  if (!b.newton.converged) {
    out.status = Status::Failed;
    out.message =
        "no periodic equilibrium on the branch from hover at mu = " + round_trip_text(mu) +
        ": the continuation from hover (harmonic balance, K = " + std::to_string(b.K) +
        ") stops at mu = " + short_text(b.reached) +
        " (the branch ends there: typically a fold, where a real Floquet multiplier reaches 1)";
    return true;
  }
  return false;
}

// The last harmonic's size relative to the largest coefficient.
double truncation(const Eigen::MatrixXd& X, int K) {
  const double big = X.cwiseAbs().maxCoeff();
  double last = 0.0;
  for (int j = 0; j < X.rows(); ++j)
    last = std::max(last, std::hypot(X(j, 2 * K - 1), X(j, 2 * K)));
  return big > 0.0 ? last / big : 0.0;
}

// The mean thrust along q° (a polynomial of degree <= 2 in y°: trigonometric degree model
// order + 2K, integrated exactly by the quadrature of the harmonic balance).
double mean_thrust(const NonlinearSystem& sys, const PeriodicEquilibrium& eq) {
  double sum = 0.0;
  for (const QuadPoint& qp : quadrature(sys.sector(), 3.0 * eq.harmonics + 4.0))
    sum += qp.weight * sys.thrust(qp.psi, qp.reversed, eq.state(qp.psi));
  return sum / kTwoPi;
}

// The Floquet multipliers of the linearization: whether the equilibrium is isolated and
// stable (problems noted in `note`).
void check_multipliers(PeriodicEquilibrium& out, Outcome& note) {
  const Eigen::MatrixXd phi = transition_matrix_rk4(out.linearization, 4096);
  const FloquetResult fl = floquet_exponents(phi, out.linearization.trace_integral());
  out.min_distance_to_one = std::numeric_limits<double>::infinity();
  for (const FloquetExponent& e : fl.exponents) {
    out.multiplier_moduli.push_back(std::abs(e.multiplier));
    out.min_distance_to_one =
        std::min(out.min_distance_to_one, std::abs(e.multiplier - std::complex<double>(1.0)));
  }
  std::sort(out.multiplier_moduli.rbegin(), out.multiplier_moduli.rend());
  if (fl.status != Status::Ok) {
    note.Worsen(Status::Warning, fl.message);
  } else if (out.min_distance_to_one < 1e-8) {
    note.Worsen(Status::Warning, "a Floquet multiplier is at 1 (distance " +
                                     short_text(out.min_distance_to_one) +
                                     "): the periodic equilibrium is not isolated");
  } else if (!out.multiplier_moduli.empty() && out.multiplier_moduli[0] > 1.0) {
    note.Worsen(Status::Warning,
                "the periodic equilibrium is unstable (largest multiplier modulus " +
                    short_text(out.multiplier_moduli[0]) + "): the blade does not settle onto it");
  }
}

}  // namespace

PeriodicEquilibrium periodic_equilibrium(const detail::SystemBuilder& builder, double mu,
                                         const PeriodicEquilibriumOptions& opt,
                                         const PeriodicEquilibrium* start) {
  opt.Check();
  const NonlinearSystem sys(builder, mu);
  const auto& m = builder.model();
  const int M = m.flap_modes, N = m.lag_modes;
  const bool automatic = opt.harmonics == PeriodicEquilibriumOptions::kAutomaticHarmonics;
  PeriodicEquilibrium out;
  out.mu = mu;
  out.flap_modes = M;
  Branch b = start_of_branch(builder, sys, mu, continuation_harmonics(opt, start), opt, start);
  continue_branch(builder, sys, mu, opt, b);
  out.continued_to = b.reached;
  if (b.reached != mu) b.newton.converged = false;
  std::string k_note;
  if (automatic && b.newton.converged && !converge_in_harmonics(sys, mu, opt, M, N, b, out, k_note))
    return out;
  out.harmonics = b.K;
  out.coefficients = b.X;
  out.iterations = b.newton.iterations;
  out.step = b.newton.step;
  out.residual = b.newton.residual;
  if (branch_failed(b, mu, out)) return out;
  out.truncation = truncation(b.X, b.K);
  out.mean_thrust = mean_thrust(sys, out);

  // The linearization: model order (H_nl - 1) / 2 plus 2K.
  const int L = (m.n_nonlinear_harmonics - 1) / 2 + 2 * b.K;
  out.linearization = sys.sector();
  out.linearization.sets[0] = linear_set(sys, out, false, L);
  if (out.linearization.sets.size() > 1) out.linearization.sets[1] = linear_set(sys, out, true, L);

  Outcome note;  // the problems, in this order
  note.Worsen(Status::Warning, k_note);
  if (out.truncation > 1e-3) {
    note.Worsen(Status::Warning, "harmonic " + std::to_string(b.K) +
                                     " of the periodic equilibrium is " +
                                     short_text(out.truncation) +
                                     " of its largest coefficient; increase `harmonics`");
  }
  if (opt.check_stability) check_multipliers(out, note);
  if (!note.message.empty()) {
    out.status = Status::Warning;
    out.message = note.message;
  }
  return out;
}

}  // namespace flaplag
