// The periodic systems of periodic_fixtures.h, compiled once for the tests and the benches that
// use them.  The dense inverse and the operator norm are written here with Eigen's core
// operations and the library's eigen-solve: Eigen's decompositions (LU, the self-adjoint
// eigen-solver) cost more compile time than the rest of the fixtures together.
#include "periodic_fixtures.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "flaplag/core/constants.h"
#include "flaplag/numerics/dense.h"

namespace flaplag::fixtures {

Eigen::MatrixXd rotor_hover_matrix() {
  Eigen::MatrixXd A(4, 4);
  A << -0.3, -1.3914, -0.1, -0.3,  //
      1.0, 0.0, 0.0, 0.0,          //
      0.05, 0.2, -0.04, -1.6388,   //
      0.0, 0.0, 1.0, 0.0;
  return A;
}

PeriodicSystem rotor_like() {
  auto fill = [](HarmonicSet& set, double sign) {
    set.A.assign(9, Eigen::MatrixXd::Zero(4, 4));
    set.A[0] = rotor_hover_matrix();
    for (int h = 1; h < 9; ++h) {
      const double w = 1.0 / ((h + 1) / 2);
      set.A[h](0, 0) = sign * 0.4 * w * std::cos(h);
      set.A[h](0, 1) = 1.2 * w * std::sin(1.3 * h);
      set.A[h](0, 3) = 0.5 * w * std::cos(0.7 * h);
      set.A[h](2, 0) = 0.2 * w * std::sin(2.1 * h);
      set.A[h](2, 1) = sign * 0.8 * w * std::cos(1.9 * h);
      set.A[h](2, 2) = 0.1 * w * std::sin(0.4 * h);
      set.A[h](2, 3) = 0.5 * w * std::cos(2.9 * h);
    }
    set.A[1](0, 1) = 3.0;
  };
  HarmonicSet normal, reversed;
  fill(normal, 1.0);
  fill(reversed, -1.0);
  return with_sector(std::move(normal), std::move(reversed), 1.25 * kPi, 1.75 * kPi);
}

PeriodicSystem with_sector(HarmonicSet normal, HarmonicSet reversed, double begin, double end) {
  PeriodicSystem s(std::move(normal));
  s.add_harmonic_piece(begin, end, std::move(reversed));
  return s;
}

const HarmonicSet& set_at(const PeriodicSystem& s, double psi) {
  return s.sets.at(
      static_cast<std::size_t>(s.pieces.at(static_cast<std::size_t>(s.piece_at(psi))).set));
}

std::vector<Eigen::MatrixXd> harmonics_of(const MatrixFn& F, int n, int degree) {
  const int M = 4 * (degree + 1);
  std::vector<Eigen::MatrixXd> c(2 * static_cast<std::size_t>(degree) + 1,
                                 Eigen::MatrixXd::Zero(n, n));
  for (int j = 0; j < M; ++j) {
    const double psi = kTwoPi * j / M;
    const Eigen::MatrixXd f = F(psi);
    c[0] += f / M;
    for (int k = 1; k <= degree; ++k) {
      c[2 * k - 1] += (2.0 / M) * std::cos(k * psi) * f;
      c[2 * k] += (2.0 / M) * std::sin(k * psi) * f;
    }
  }
  return c;
}

PeriodicSystem reducible_system(const Eigen::MatrixXd& B, const Frame& normal, int degree,
                                const Frame* reversed, double sector_begin, double sector_end) {
  auto a_of = [&B](const Frame& fr) {
    return [&B, &fr](double psi) -> Eigen::MatrixXd {
      const Eigen::MatrixXd P = fr.P(psi);
      const Eigen::MatrixXd Pinv = inverse(P);
      return fr.dP(psi) * Pinv + P * B * Pinv;
    };
  };
  const int n = static_cast<int>(B.rows());
  PeriodicSystem s(HarmonicSet{harmonics_of(a_of(normal), n, degree), {}});
  if (reversed)
    s.add_harmonic_piece(sector_begin, sector_end,
                         HarmonicSet{harmonics_of(a_of(*reversed), n, degree), {}});
  return s;
}

Eigen::MatrixXd reducible_phi(const Eigen::MatrixXd& B, const Frame& normal) {
  const Eigen::MatrixXd P0 = normal.P(0.0);
  return P0 * matrix_exponential(kTwoPi * B) * inverse(P0);
}

Eigen::MatrixXd A_rate(const PeriodicSystem& s, double psi) {
  const HarmonicSet& set = set_at(s, psi);
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(s.n, s.n);
  for (std::size_t h = 1; h < set.A.size(); ++h) {
    const double k = static_cast<double>((h + 1) / 2);
    d += (h % 2 == 1 ? -k * std::sin(k * psi) : k * std::cos(k * psi)) * set.A[h];
  }
  return d;
}

SystemScale scale_of(const PeriodicSystem& s) {
  SystemScale out;
  for (int j = 0; j < 2000; ++j) {
    const double psi = kTwoPi * (j + 0.5) / 2000;
    const Eigen::MatrixXd A = s.A(psi), D = A_rate(s, psi);
    out.L = std::max(out.L, operator_norm(A));
    out.C = std::max(out.C, operator_norm(A * D - D * A));
  }
  return out;
}

double rk4_error_model(const SystemScale& s, int steps) {
  const double h = kTwoPi / steps;
  return kTwoPi * std::pow(h * s.L, 4) * s.L / 120.0;
}

double hsu_error_model(const SystemScale& s, int intervals, int terms) {
  const double d = kTwoPi / intervals;
  return kTwoPi * d * d * s.C / 12.0 +
         kTwoPi * std::pow(d * s.L, terms) * s.L / std::tgamma(terms + 2.0);
}

Eigen::Matrix2d rotation(double t) {
  Eigen::Matrix2d R;
  R << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
  return R;
}

Eigen::Matrix2d rotation_rate(double t) {
  Eigen::Matrix2d R;
  R << -std::sin(t), -std::cos(t), std::cos(t), -std::sin(t);
  return R;
}

Frame frame2(double c, double s0) {
  auto u = [=](double p) {
    return 0.5 * std::sin(p) + 0.3 * std::cos(2 * p) + c * std::sin(p - s0);
  };
  auto du = [=](double p) {
    return 0.5 * std::cos(p) - 0.6 * std::sin(2 * p) + c * std::cos(p - s0);
  };
  Frame f;
  f.P = [=](double p) -> Eigen::MatrixXd {
    Eigen::Matrix2d U;
    U << 1.0, u(p), 0.0, 1.0;
    return rotation(p) * U;
  };
  f.dP = [=](double p) -> Eigen::MatrixXd {
    Eigen::Matrix2d U, dU;
    U << 1.0, u(p), 0.0, 1.0;
    dU << 0.0, du(p), 0.0, 0.0;
    return rotation_rate(p) * U + rotation(p) * dU;
  };
  return f;
}

Frame frame4(double c, double s0) {
  auto N = [=](double p) {
    Eigen::Matrix4d n = Eigen::Matrix4d::Zero();
    n(0, 1) = 0.4 * std::cos(p);
    n(0, 2) = 0.3 * std::sin(p) - 0.2;
    n(1, 3) = 0.5 * std::cos(p) + 0.2 * std::sin(p);
    n(2, 3) = -0.3 * std::sin(p);
    n(0, 3) = 0.2 + c * std::sin(p - s0);
    return n;
  };
  auto dN = [=](double p) {
    Eigen::Matrix4d n = Eigen::Matrix4d::Zero();
    n(0, 1) = -0.4 * std::sin(p);
    n(0, 2) = 0.3 * std::cos(p);
    n(1, 3) = -0.5 * std::sin(p) + 0.2 * std::cos(p);
    n(2, 3) = -0.3 * std::cos(p);
    n(0, 3) = c * std::cos(p - s0);
    return n;
  };
  auto Rb = [](double p) {
    Eigen::Matrix4d r = Eigen::Matrix4d::Zero();
    r.topLeftCorner<2, 2>() = rotation(p);
    r.bottomRightCorner<2, 2>() = rotation(2 * p);
    return r;
  };
  auto dRb = [](double p) {
    Eigen::Matrix4d r = Eigen::Matrix4d::Zero();
    r.topLeftCorner<2, 2>() = rotation_rate(p);
    r.bottomRightCorner<2, 2>() = 2.0 * rotation_rate(2 * p);
    return r;
  };
  Frame f;
  f.P = [=](double p) -> Eigen::MatrixXd { return Rb(p) * (Eigen::Matrix4d::Identity() + N(p)); };
  f.dP = [=](double p) -> Eigen::MatrixXd {
    return dRb(p) * (Eigen::Matrix4d::Identity() + N(p)) + Rb(p) * dN(p);
  };
  return f;
}

Eigen::MatrixXd with_eigenvalues(const std::vector<std::pair<double, double>>& pairs) {
  const int n = 2 * static_cast<int>(pairs.size());
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n / 2; ++k) {
    D(2 * k, 2 * k) = D(2 * k + 1, 2 * k + 1) = pairs[k].first;
    D(2 * k, 2 * k + 1) = -pairs[k].second;
    D(2 * k + 1, 2 * k) = pairs[k].second;
  }
  Eigen::MatrixXd S(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) S(i, j) = (i == j ? 2.0 : 0.0) + 0.3 * std::sin(1.0 + i + 2.0 * j);
  return S * D * inverse(S);
}

PeriodicSystem markus_yamabe() {
  HarmonicSet set;
  set.A.assign(5, Eigen::MatrixXd::Zero(2, 2));
  set.A[0] << -0.25, 1.0, -1.0, -0.25;
  set.A[3] << 0.75, 0.0, 0.0, -0.75;   // cos 2 psi
  set.A[4] << 0.0, -0.75, -0.75, 0.0;  // sin 2 psi
  return PeriodicSystem(std::move(set));
}

Frame markus_yamabe_frame() {
  Frame f;
  f.P = [](double p) -> Eigen::MatrixXd {
    Eigen::Matrix2d m;
    m << -std::cos(p), std::sin(p), std::sin(p), std::cos(p);
    return m;
  };
  f.dP = [](double p) -> Eigen::MatrixXd {
    Eigen::Matrix2d m;
    m << std::sin(p), std::cos(p), std::cos(p), -std::sin(p);
    return m;
  };
  return f;
}

std::vector<ExactCase> exact_cases() {
  std::vector<ExactCase> out;
  Eigen::MatrixXd B2(2, 2);
  B2 << -0.1, 1.3, -0.9, -0.2;
  const Eigen::MatrixXd B4 = with_eigenvalues({{-0.15, 1.17}, {-0.02, 1.28}});
  const Frame f2 = frame2(), f4 = frame4();
  const Frame f2s = frame2(0.7, 0.8 * kPi), f4s = frame4(0.6, 0.9 * kPi);
  out.push_back({"2 states", reducible_system(B2, f2, 6), B2, f2, f2, reducible_phi(B2, f2)});
  out.push_back({"2 states, sector [0.8 pi, 1.8 pi)",
                 reducible_system(B2, f2, 6, &f2s, 0.8 * kPi, 1.8 * kPi), B2, f2, f2s,
                 reducible_phi(B2, f2)});
  out.push_back({"4 states", reducible_system(B4, f4, 8), B4, f4, f4, reducible_phi(B4, f4)});
  out.push_back({"4 states, sector [0.9 pi, 1.9 pi)",
                 reducible_system(B4, f4, 8, &f4s, 0.9 * kPi, 1.9 * kPi), B4, f4, f4s,
                 reducible_phi(B4, f4)});
  Eigen::MatrixXd Bmy = Eigen::MatrixXd::Zero(2, 2);
  Bmy.diagonal() << 0.5, -1.0;
  const Frame fmy = markus_yamabe_frame();
  out.push_back({"Markus-Yamabe", markus_yamabe(), Bmy, fmy, fmy, reducible_phi(Bmy, fmy)});
  return out;
}

PeriodicSystem sector_as_varying(const PeriodicSystem& sector) {
  PeriodicSystem v(sector.sets.at(0));
  v.n = sector.n;
  const SystemPiece& piece = sector.pieces.at(1);  // normal, sector, normal
  const HarmonicSet rev = sector.sets.at(1);
  const int n = sector.n;
  v.add_evaluator_piece(piece.begin, piece.end,
                        [rev, n](double psi, Eigen::MatrixXd& A, Eigen::VectorXd& f) {
                          A.setZero(n, n);
                          f.setZero(n);
                          for (std::size_t h = 0; h < rev.A.size(); ++h)
                            A += harmonic_basis(static_cast<int>(h), psi) * rev.A[h];
                          for (std::size_t h = 0; h < rev.f.size(); ++h)
                            f += harmonic_basis(static_cast<int>(h), psi) * rev.f[h];
                        });
  return v;
}

PeriodicSystem clipped_scalar(double c) {
  PeriodicSystem s(HarmonicSet{
      {Eigen::MatrixXd::Constant(1, 1, -0.05), Eigen::MatrixXd::Constant(1, 1, 0.7)}, {}});
  const double a = std::asin(c);
  s.add_evaluator_piece(kPi, kTwoPi,
                        [c](double psi, Eigen::MatrixXd& A, Eigen::VectorXd& f) {
                          A = Eigen::MatrixXd::Constant(
                              1, 1, 0.3 + 0.9 * std::clamp(-std::sin(psi), 0.0, c));
                          f = Eigen::VectorXd::Zero(1);
                        },
                        {kPi + a, kTwoPi - a});
  return s;
}

double clipped_log_phi(double c) {
  const double a = std::asin(c);
  return -0.05 * kPi + 0.3 * kPi + 0.9 * (2.0 * (1.0 - std::cos(a)) + c * (kPi - 2.0 * a));
}

namespace {

// Gauss-Jordan elimination with partial pivoting (the pivot of largest modulus in each column):
// [m | I] -> [I | m^-1].  m square and nonsingular.
template <typename Mat>
Mat gauss_jordan_inverse(Mat m) {
  const Eigen::Index n = m.rows();
  Mat inv = Mat::Identity(n, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    Eigen::Index p = k;
    for (Eigen::Index i = k + 1; i < n; ++i)
      if (std::abs(m(i, k)) > std::abs(m(p, k))) p = i;
    m.row(k).swap(m.row(p));
    inv.row(k).swap(inv.row(p));
    const typename Mat::Scalar d = m(k, k);
    m.row(k) /= d;
    inv.row(k) /= d;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (i == k) continue;
      const typename Mat::Scalar f = m(i, k);
      m.row(i) -= f * m.row(k);
      inv.row(i) -= f * inv.row(k);
    }
  }
  return inv;
}

}  // namespace

double operator_norm(const Eigen::MatrixXd& m) {
  const Eigen::MatrixXd gram = m.transpose() * m;
  return std::sqrt(spectral_radius(gram, EigenStorage::Dynamic));
}
Eigen::MatrixXd inverse(const Eigen::MatrixXd& m) { return gauss_jordan_inverse(m); }
Eigen::MatrixXcd inverse(const Eigen::MatrixXcd& m) { return gauss_jordan_inverse(m); }

}  // namespace flaplag::fixtures
