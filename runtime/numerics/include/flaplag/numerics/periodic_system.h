// flaplag — the linear periodic system  y' = A(psi) y + f(psi),  period T = 2*pi.
//
// A(psi) is stored as harmonic coefficient matrices for two flow regions: the normal region and
// the reversed-flow sector (Appendix D).  Harmonic index h: 0 -> 1, 2k-1 -> cos(k psi),
// 2k -> sin(k psi).  Inside [sector_begin, sector_end) the reversed harmonics apply; A jumps at
// the sector edges, so every integrator splits its steps there.
//
// Optionally (instead of a sector) a *varying region* [varying_begin, varying_end) in which A
// and f are not finite Fourier series but are evaluated at each psi by a callback (the exact
// circular reversed-flow region: the aerodynamic integrals are split at a station that moves
// with psi).  The callback is piecewise smooth: smooth between consecutive points of
// breakpoints(), which include the region's edges and varying_breaks.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

namespace flaplag {

struct HarmonicSet {
  std::vector<Eigen::MatrixXd> A;  // [H] each n x n
  std::vector<Eigen::VectorXd> f;  // [H] each n
};

// Basis function phi_h(psi).
double harmonic_basis(int h, double psi);
// Its name: "const", "cos psi", "sin psi", "cos 2psi", "sin 2psi", ... (h >= 0).
std::string harmonic_name(int h);
// psi reduced to [0, 2 pi) (NaN and inf stay NaN).
double reduce_azimuth(double psi);
// Exact mean of phi_h over [a, b] (eqs 4.2-4.5 generalised), b > a.
double harmonic_mean(int h, double a, double b);

struct PeriodicSystem {
  int n = 0;             // state dimension
  HarmonicSet normal;    // normal-flow region
  HarmonicSet reversed;  // reversed-flow sector (ignored when !has_sector)
  bool has_sector = false;
  double sector_begin = 0.0;  // radians, 0 <= begin < end <= 2*pi
  double sector_end = 0.0;

  // The varying region (ignored when !has_varying; never together with a sector).  varying(psi,
  // A, f) sets A (n x n) and f (n) at psi in [varying_begin, varying_end]; it is called only
  // there (at the edges: the one-sided limit from inside), with psi in [0, 2 pi].
  using Evaluator = std::function<void(double psi, Eigen::MatrixXd& A, Eigen::VectorXd& f)>;
  bool has_varying = false;
  double varying_begin = 0.0;  // radians, 0 <= begin < end <= 2*pi
  double varying_end = 0.0;
  std::vector<double> varying_breaks;  // where A is not smooth, inside (begin, end), sorted
  Evaluator varying;

  // Throws InvalidInput unless n >= 1, every harmonic is n x n (f: n or absent) and finite, the
  // normal (and, with a sector, the reversed) set has at least the constant harmonic,
  // 0 <= sector_begin < sector_end <= 2 pi, and a varying region (no sector, an evaluator,
  // 0 <= varying_begin < varying_end <= 2 pi, breaks sorted inside it).
  void validate() const;

  // Region at psi (psi reduced to [0, 2 pi)).  region() is the harmonic set that applies
  // outside the varying region (callers test in_varying() first).
  bool in_sector(double psi) const;
  bool in_varying(double psi) const;
  const HarmonicSet& region(double psi) const;

  // A(psi), f(psi) with psi reduced to [0, 2 pi) first (any finite psi).
  Eigen::MatrixXd A(double psi) const;
  Eigen::VectorXd f(double psi) const;
  // Mean of A over [a, b] inside one smooth piece (a < b, both in [0, 2 pi]); callers split
  // intervals with breakpoints().  Exact for the harmonic regions; in the varying region an
  // 8-point Gauss-Legendre mean (error O((b - a)^16) for the analytic pieces it is made for).
  Eigen::MatrixXd A_mean(double a, double b) const;
  // Sector edges, or the varying region's edges and breaks, inside (0, 2 pi), sorted; empty
  // without either.
  std::vector<double> breakpoints() const;
  // int_0^{2 pi} trace A(psi) dpsi: exact for harmonic regions; over the varying region by
  // composite Gauss-Legendre on each smooth piece (converged to rounding for analytic pieces).
  double trace_integral() const;
};

}  // namespace flaplag
