// flaplag — the linear periodic system  y' = A(psi) y + f(psi),  period T = 2*pi.
//
// The period [0, 2 pi) is a list of pieces, sorted and without gaps.  A piece is an azimuth
// interval on which A and f are smooth: either harmonic coefficient matrices (one of the
// system's harmonic sets; harmonic index h: 0 -> 1, 2k-1 -> cos(k psi), 2k -> sin(k psi)) or an
// evaluator callback (the exact circular reversed-flow region, where the aerodynamic integrals
// are split at a station that moves with psi), smooth between its declared inner breaks.  A
// jumps only at piece edges and breaks (breakpoints()); every integrator splits its steps there
// and takes each substep's coefficients from the piece that contains its midpoint.  The rotor's
// systems: one normal piece; normal, reversed-flow sector (Appendix D), normal; or normal,
// exact region, normal.
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

// One piece [begin, end) of the period: the harmonic set `set` of its system, or (set = -1) the
// evaluator, called only for psi in [begin, end] (at the ends: the one-sided limit from inside).
struct SystemPiece {
  using Evaluator = std::function<void(double psi, Eigen::MatrixXd& A, Eigen::VectorXd& f)>;
  double begin = 0.0;  // radians, 0 <= begin < end <= 2*pi
  double end = 0.0;
  int set = 0;                 // index into PeriodicSystem::sets, -1: the evaluator
  Evaluator evaluator;         // set == -1: sets A (n x n) and f (n) at psi
  std::vector<double> breaks;  // set == -1: where A is not smooth, inside (begin, end), sorted
};

struct PeriodicSystem {
  using Evaluator = SystemPiece::Evaluator;
  int n = 0;                        // state dimension
  std::vector<HarmonicSet> sets;    // sets[0]: the base set, which the constructor spreads over
                                    // the whole period (the normal-flow region)
  std::vector<SystemPiece> pieces;  // sorted, covering [0, 2 pi) without gaps

  PeriodicSystem() = default;
  // One piece: `base` over the whole period; n from its constant harmonic (0 without one).
  explicit PeriodicSystem(HarmonicSet base);
  // [begin, end) cut out of the base piece that contains it and given the harmonic set `set`
  // (added to sets) or the evaluator with its inner breaks.  Throws InvalidInput unless
  // 0 <= begin < end <= 2 pi lies inside one piece of the base set.
  void add_harmonic_piece(double begin, double end, HarmonicSet set);
  void add_evaluator_piece(double begin, double end, Evaluator evaluator,
                           std::vector<double> breaks = {});
  // For a system rebuilt in place (its storage kept): reset_pieces() makes sets[0] the one
  // piece again, add_set_piece() gives [begin, end) to sets[set] (1 <= set < sets.size(), else
  // InvalidInput; the range as add_harmonic_piece).
  void reset_pieces();
  void add_set_piece(double begin, double end, int set);

  // Throws InvalidInput unless n >= 1, there is a base set, every harmonic is n x n (f: n or
  // absent) and finite, every set has at least the constant harmonic, the pieces are sorted and
  // cover [0, 2 pi) without gaps, each names a set or has an evaluator, and evaluator breaks are
  // sorted inside their piece.
  void validate() const;

  // The piece that contains psi (reduced to [0, 2 pi) first), as an index into pieces.
  int piece_at(double psi) const;
  // Whether some piece has an evaluator instead of harmonics.
  bool has_evaluator() const;

  // A(psi), f(psi) with psi reduced to [0, 2 pi) first (any finite psi).
  Eigen::MatrixXd A(double psi) const;
  Eigen::VectorXd f(double psi) const;
  // Mean of A over [a, b] inside one smooth piece (a < b, both in [0, 2 pi]); callers split
  // intervals with breakpoints().  Exact for harmonic pieces; on an evaluator piece an 8-point
  // Gauss-Legendre mean (error O((b - a)^16) for the analytic pieces it is made for).
  Eigen::MatrixXd A_mean(double a, double b) const;
  // The piece edges and evaluator breaks inside (0, 2 pi), sorted.
  std::vector<double> breakpoints() const;
  // int_0^{2 pi} trace A(psi) dpsi: the base set's exact integral over the period, corrected
  // on each piece of another set (exactly) or with an evaluator (composite Gauss-Legendre on
  // each smooth part, converged to rounding for analytic pieces).
  double trace_integral() const;
};

}  // namespace flaplag
