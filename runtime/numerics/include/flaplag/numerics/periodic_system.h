// flaplag — the linear periodic system  y' = A(psi) y + f(psi),  period T = 2*pi.
//
// A(psi) is stored as harmonic coefficient matrices for two flow regions: the normal region and
// the reversed-flow sector (Appendix D).  Harmonic index h: 0 -> 1, 2k-1 -> cos(k psi),
// 2k -> sin(k psi).  Inside [sector_begin, sector_end) the reversed harmonics apply; A jumps at
// the sector edges, so every integrator splits its steps there.
#pragma once

#include <Eigen/Dense>
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

  // Throws InvalidInput unless n >= 1, every harmonic is n x n (f: n or absent) and finite, the
  // normal (and, with a sector, the reversed) set has at least the constant harmonic, and
  // 0 <= sector_begin < sector_end <= 2 pi.
  void validate() const;

  // Region at psi (psi reduced to [0, 2 pi)).
  bool in_sector(double psi) const;
  const HarmonicSet& region(double psi) const;

  // A(psi), f(psi) with psi reduced to [0, 2 pi) first (any finite psi).
  Eigen::MatrixXd A(double psi) const;
  Eigen::VectorXd f(double psi) const;
  // Exact mean of A over [a, b] inside one region (a < b, both in [0, 2 pi]); callers split
  // intervals at the sector edges with breakpoints().
  Eigen::MatrixXd A_mean(double a, double b) const;
  // Sector edges inside (0, 2 pi), sorted; empty without a sector.
  std::vector<double> breakpoints() const;
  // int_0^{2 pi} trace A(psi) dpsi, exact.
  double trace_integral() const;
};

}  // namespace flaplag
