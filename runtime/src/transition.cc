// flaplag — transition matrix Phi(2 pi, 0) of y' = A(psi) y (paper Section 3.3).
//
// Three methods share one grid rule: the period is cut into equal steps, and a step that
// contains a reversed-flow sector edge is split there into two substeps, so that A(psi) is
// smooth (a trigonometric polynomial of one region) on every substep.  Each substep uses the
// harmonics of the region that contains its midpoint; at a substep end that lies on an edge
// that is the one-sided limit, which is what the integrators need.
//
// Speed: the dimension is a template parameter (fixed-size, stack-allocated Eigen matrices for
// n = 2, 4, 6, 8; dynamic matrices with preallocated temporaries otherwise), and the harmonic
// basis on the equal grid comes from a rotation recurrence e^{i(j+1)d} = e^{ijd} e^{id} instead
// of sin/cos calls (re-seeded exactly every kReseed points so rounding cannot accumulate).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "flaplag/errors.h"
#include "flaplag/floquet.h"

namespace flaplag {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr int kReseed = 32;

double sinc(double x) {
  if (std::abs(x) < 1e-4) {
    const double x2 = x * x;
    return 1.0 - x2 / 6.0 * (1.0 - x2 / 20.0);
  }
  return std::sin(x) / x;
}

void check_count(const char* name, int value) {
  if (value < 1) throw InvalidInput(name, std::to_string(value), "must be >= 1");
}

// One substep of the grid.  `node` >= 0 marks an unsplit equal step number `node` (its ends
// are grid points node and node + 1); split substeps have node = -1.
struct Segment {
  double a, b;
  bool reversed;
  int node;
};

// N equal steps over [0, 2 pi]; a step containing a sector edge strictly inside is split.
std::vector<Segment> make_grid(const PeriodicSystem& sys, int steps) {
  const std::vector<double> edges = sys.breakpoints();
  const double d = kTwoPi / steps;
  std::vector<Segment> out;
  out.reserve(static_cast<std::size_t>(steps) + 2 * edges.size());
  for (int i = 0; i < steps; ++i) {
    const double a = i * d;
    const double b = (i + 1 == steps) ? kTwoPi : (i + 1) * d;
    // An edge within rounding of a grid point needs no split: the midpoint rule picks the
    // region of each neighbouring step correctly.
    const double slack = 1e-12 * kTwoPi;
    std::vector<double> cuts;
    for (double e : edges)
      if (e > a + slack && e < b - slack) cuts.push_back(e);
    if (cuts.empty()) {
      out.push_back({a, b, sys.in_sector(0.5 * (a + b)), i});
      continue;
    }
    double lo = a;
    cuts.push_back(b);
    for (double c : cuts) {
      out.push_back({lo, c, sys.in_sector(0.5 * (lo + c)), -1});
      lo = c;
    }
  }
  return out;
}

// Harmonic basis values (point values, or interval means when scaled by sinc factors) for
// H harmonics from z = e^{i psi}: c[2k-1] = Re z^k = cos k psi, c[2k] = Im z^k = sin k psi.
void basis_from_rotor(std::complex<double> z, int H, double* c) {
  c[0] = 1.0;
  std::complex<double> w = z;
  for (int h = 1; h < H; h += 2) {
    c[h] = w.real();
    if (h + 1 < H) c[h + 1] = w.imag();
    w *= z;
  }
}

// Rotation recurrence over the points psi_j = j * d, reseeded exactly every kReseed points.
class Rotor {
 public:
  explicit Rotor(double d) : d_(d), step_(std::polar(1.0, d)) {}
  std::complex<double> at(int j) {
    if (j != next_) {
      seed(j);
    } else if (j % kReseed == 0) {
      seed(j);
    } else {
      z_ *= step_;
    }
    next_ = j + 1;
    return z_;
  }

 private:
  void seed(int j) { z_ = std::polar(1.0, j * d_); }
  double d_;
  std::complex<double> step_;
  std::complex<double> z_{1.0, 0.0};
  int next_ = -1;
};

template <int N>
class Kernel {
 public:
  using Mat = Eigen::Matrix<double, N, N>;

  explicit Kernel(const PeriodicSystem& sys) : sys_(sys), n_(sys.n) {
    copy(sys.normal, normal_);
    if (sys.has_sector) copy(sys.reversed, reversed_);
    const std::size_t hmax = std::max(normal_.size(), reversed_.size());
    basis_.resize(hmax);
  }

  Mat identity() const { return Mat::Identity(n_, n_); }

  // out = sum_h c[h] A_h of the region.
  void combine(bool reversed, const double* c, Mat& out) const {
    const std::vector<Mat>& set = reversed ? reversed_ : normal_;
    out = c[0] * set[0];
    for (std::size_t h = 1; h < set.size(); ++h) out += c[h] * set[h];
  }
  int harmonics(bool reversed) const {
    return static_cast<int>(reversed ? reversed_.size() : normal_.size());
  }

  // A at psi with the harmonics of the given region (one-sided value at an edge).
  void point(bool reversed, double psi, Mat& out) {
    basis_from_rotor(std::polar(1.0, psi), harmonics(reversed), basis_.data());
    combine(reversed, basis_.data(), out);
  }
  void point(bool reversed, std::complex<double> z, Mat& out) {
    basis_from_rotor(z, harmonics(reversed), basis_.data());
    combine(reversed, basis_.data(), out);
  }
  // Exact mean of A over [a, b] inside one region (eqs 4.2-4.5 generalised).
  void mean(bool reversed, double a, double b, Mat& out) {
    const int H = harmonics(reversed);
    for (int h = 0; h < H; ++h) basis_[h] = harmonic_mean(h, a, b);
    combine(reversed, basis_.data(), out);
  }

  // Hsu, eqs 3.21-3.28: constant C_k = exact interval mean of A, exp(Delta C_k) by J Taylor
  // terms, H(K) = prod exp(Delta_k C_k) with later intervals multiplied from the left (3.25).
  Mat hsu(int K, int J) {
    const std::vector<Segment> grid = make_grid(sys_, K);
    const double d = kTwoPi / K;
    // Means of cos k psi, sin k psi over an equal interval are the midpoint values times
    // sinc(k d / 2) (eqs 4.2-4.5): one table for the whole grid.
    const int H = std::max(harmonics(false), harmonics(true));
    std::vector<double> damp(static_cast<std::size_t>(H), 1.0);
    for (int h = 1; h < H; ++h) damp[h] = sinc(((h + 1) / 2) * 0.5 * d);
    Rotor mid(d);
    const std::complex<double> half = std::polar(1.0, 0.5 * d);

    Mat Phi = identity();
    Mat C(n_, n_), X(n_, n_), X2(n_, n_), T(n_, n_), E(n_, n_), P(n_, n_);
    for (const Segment& s : grid) {
      if (s.node >= 0) {
        basis_from_rotor(mid.at(s.node) * half, harmonics(s.reversed), basis_.data());
        for (int h = 1; h < harmonics(s.reversed); ++h) basis_[h] *= damp[h];
        combine(s.reversed, basis_.data(), C);
      } else {
        mean(s.reversed, s.a, s.b, C);
      }
      X = (s.b - s.a) * C;
      taylor(X, J, X2, T, E);
      P.noalias() = E * Phi;
      Phi = P;
    }
    return Phi;
  }

  // Classical RK4 on the matrix ODE Phi' = A Phi (paper 3.3.2, all columns at once).
  Mat rk4(int steps) {
    const std::vector<Segment> grid = make_grid(sys_, steps);
    Rotor rot(0.5 * kTwoPi / steps);  // grid points and step midpoints: psi_j = j * d / 2
    Mat Phi = identity();
    Mat Aa(n_, n_), Am(n_, n_), Ab(n_, n_), Y(n_, n_), k1(n_, n_), k2(n_, n_), k3(n_, n_),
        k4(n_, n_);
    bool have_end = false;
    bool end_reversed = false;
    for (const Segment& s : grid) {
      const double h = s.b - s.a;
      // A at the start: reuse the previous end value when the region is the same.
      if (have_end && end_reversed == s.reversed) {
        Aa = Ab;
      } else if (s.node >= 0) {
        point(s.reversed, rot.at(2 * s.node), Aa);
      } else {
        point(s.reversed, s.a, Aa);
      }
      if (s.node >= 0) {
        point(s.reversed, rot.at(2 * s.node + 1), Am);
        point(s.reversed, rot.at(2 * s.node + 2), Ab);
      } else {
        point(s.reversed, 0.5 * (s.a + s.b), Am);
        point(s.reversed, s.b, Ab);
      }
      have_end = true;
      end_reversed = s.reversed;

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

  // Fourth-order Magnus with two-point Gauss nodes on every substep:
  //   Omega = h/2 (A1 + A2) + sqrt(3) h^2 / 12 [A2, A1],  Phi <- exp(Omega) Phi.
  // The method is symmetric, so its global error expands in h^4, h^6, ...
  Mat magnus(const std::vector<Segment>& grid) {
    const double g = std::sqrt(3.0) / 6.0;
    Mat Phi = identity();
    Mat A1(n_, n_), A2(n_, n_), Om(n_, n_), E(n_, n_), P(n_, n_);
    for (const Segment& s : grid) {
      const double h = s.b - s.a;
      point(s.reversed, s.a + (0.5 - g) * h, A1);
      point(s.reversed, s.a + (0.5 + g) * h, A2);
      Om = (0.5 * h) * (A1 + A2);
      P.noalias() = A2 * A1;
      P.noalias() -= A1 * A2;
      Om += (std::sqrt(3.0) / 12.0 * h * h) * P;
      E = Om.exp();  // scaling and squaring with a Pade approximant (Eigen MatrixFunctions)
      P.noalias() = E * Phi;
      Phi = P;
    }
    return Phi;
  }

 private:
  void copy(const HarmonicSet& set, std::vector<Mat>& out) const {
    out.clear();
    for (const Eigen::MatrixXd& m : set.A) out.emplace_back(m);
  }

  // E = sum_{j=0}^{J} X^j / j!  (eq 3.27).  J <= 4 by Paterson-Stockmeyer (at most two
  // products), beyond by Horner.
  void taylor(const Mat& X, int J, Mat& X2, Mat& T, Mat& E) const {
    E = identity();
    switch (J) {
      case 1:
        E += X;
        return;
      case 2:
        X2.noalias() = X * X;
        E += X + 0.5 * X2;
        return;
      case 3:
        X2.noalias() = X * X;
        T = (1.0 / 6.0) * X;
        T.diagonal().array() += 0.5;
        E += X;
        E.noalias() += X2 * T;
        return;
      case 4:
        X2.noalias() = X * X;
        T = (1.0 / 6.0) * X + (1.0 / 24.0) * X2;
        T.diagonal().array() += 0.5;
        E += X;
        E.noalias() += X2 * T;
        return;
      default:
        // I + X/1 (I + X/2 (... (I + X/J))).
        T = identity() + X / static_cast<double>(J);
        for (int j = J - 1; j >= 1; --j) {
          X2.noalias() = X * T;
          T = identity() + X2 / static_cast<double>(j);
        }
        E = T;
        return;
    }
  }

  const PeriodicSystem& sys_;
  int n_;
  std::vector<Mat> normal_, reversed_;
  std::vector<double> basis_;
};

// Runs `fn` with the kernel of the right dimension and returns a MatrixXd.
template <typename Fn>
Eigen::MatrixXd dispatch(const PeriodicSystem& sys, Fn&& fn) {
  switch (sys.n) {
    case 2: {
      Kernel<2> k(sys);
      return fn(k);
    }
    case 4: {
      Kernel<4> k(sys);
      return fn(k);
    }
    case 6: {
      Kernel<6> k(sys);
      return fn(k);
    }
    case 8: {
      Kernel<8> k(sys);
      return fn(k);
    }
    default: {
      Kernel<Eigen::Dynamic> k(sys);
      return fn(k);
    }
  }
}

// The Magnus grid doubled by bisecting every substep, so that the two grids are proportional
// and Richardson extrapolation removes the h^4 term exactly.
std::vector<Segment> bisect(const std::vector<Segment>& grid) {
  std::vector<Segment> out;
  out.reserve(2 * grid.size());
  for (const Segment& s : grid) {
    const double m = 0.5 * (s.a + s.b);
    out.push_back({s.a, m, s.reversed, -1});
    out.push_back({m, s.b, s.reversed, -1});
  }
  return out;
}

}  // namespace

const char* method_name(TransitionMethod m) {
  switch (m) {
    case TransitionMethod::RK4:
      return "rk4";
    case TransitionMethod::Hsu:
      return "hsu";
    case TransitionMethod::Magnus4:
      return "magnus";
  }
  return "unknown";
}

Eigen::MatrixXd transition_matrix_rk4(const PeriodicSystem& sys, int steps) {
  check_count("steps", steps);
  sys.validate();
  return dispatch(sys, [&](auto& k) { return Eigen::MatrixXd(k.rk4(steps)); });
}

Eigen::MatrixXd transition_matrix_hsu(const PeriodicSystem& sys, int intervals, int terms) {
  check_count("intervals", intervals);
  check_count("terms", terms);
  sys.validate();
  return dispatch(sys, [&](auto& k) { return Eigen::MatrixXd(k.hsu(intervals, terms)); });
}

// Accuracy: Magnus4 is fourth order and symmetric, so Phi_h - Phi = c4 h^4 + c6 h^6 + ...
// With Phi_h (steps) and Phi_{h/2} (every substep bisected), the returned
//   (16 Phi_{h/2} - Phi_h) / 15
// is sixth-order accurate, and error_estimate = ||Phi_{h/2} - Phi_h||_max / 15 estimates the
// error of Phi_{h/2}, i.e. it is a conservative (pessimistic) bound for the returned matrix
// once the steps resolve A(psi).  On a rotor-like 4x4 system (harmonics to 4/rev, entries up to
// about 10) steps = 50 gives Phi to about 1e-10 relative.
TransitionResult transition_matrix_magnus4(const PeriodicSystem& sys, int steps) {
  check_count("steps", steps);
  sys.validate();
  const std::vector<Segment> coarse = make_grid(sys, steps);
  const std::vector<Segment> fine = bisect(coarse);
  const Eigen::MatrixXd ph =
      dispatch(sys, [&](auto& k) { return Eigen::MatrixXd(k.magnus(coarse)); });
  const Eigen::MatrixXd ph2 =
      dispatch(sys, [&](auto& k) { return Eigen::MatrixXd(k.magnus(fine)); });
  TransitionResult out;
  out.phi = (16.0 * ph2 - ph) / 15.0;
  out.error_estimate = (ph2 - ph).cwiseAbs().maxCoeff() / 15.0;
  return out;
}

TransitionResult transition_matrix(const PeriodicSystem& sys, const TransitionOptions& opt) {
  switch (opt.method) {
    case TransitionMethod::RK4:
      return {transition_matrix_rk4(sys, opt.steps), 0.0};
    case TransitionMethod::Hsu:
      return {transition_matrix_hsu(sys, opt.steps, opt.terms), 0.0};
    case TransitionMethod::Magnus4:
      return transition_matrix_magnus4(sys, opt.steps);
  }
  throw InvalidInput("method", std::to_string(static_cast<int>(opt.method)), "unknown method");
}

}  // namespace flaplag
