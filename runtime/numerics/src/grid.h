// flaplag — the one grid helper of the integrators, and the one RK4 step.
//
// Every integrator walks [a, b] in steps that never straddle a place where A(psi) jumps or
// kinks (the system's breakpoints: piece edges and declared breaks); a step that contains one
// strictly inside is split there, and each substep takes the coefficients of the piece that
// contains its midpoint.  Two step rules exist, each bit for bit what its integrators always
// used:
// - equal_grid: the transition matrices (steps psi_i = i d, d = 2 pi / steps, the last ending at
//   2 pi; an edge within 1e-12 * 2 pi of a grid point is no split);
// - sampled_grid: the response and simulation (points a + (b - a) i / count and the edges
//   strictly inside, sorted; gaps of at most 1e-14 are skipped).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <vector>

#include "flaplag/core/constants.h"
#include "flaplag/numerics/periodic_system.h"

namespace flaplag::detail {

// An edge this close to a grid point is not split off (the midpoint rule picks the piece of
// each neighbouring step correctly).
inline constexpr double kEdgeSlack = 1e-12 * kTwoPi;

// One substep.  `piece` is the system's piece that contains the midpoint (an index into
// PeriodicSystem::pieces) and `set` that piece's harmonic set (-1: A from its evaluator); `node` >=
// 0 marks an unsplit equal step number `node` (its ends are grid points node and node + 1), split
// substeps have node = -1; `after_break`: a lies on (within kEdgeSlack of) a breakpoint, so A at a
// need not equal A at the previous substep's end.
struct Segment {
  double a, b;
  int piece;
  int set;
  int node;
  bool after_break;
};

// Whether one of the sorted `edges` lies strictly inside (a, b) beyond the slack.
[[gnu::always_inline]] inline bool edge_inside(double a, double b, const double* edges,
                                               int n_edges) {
  bool split = false;
  for (int k = 0; k < n_edges; ++k) split |= edges[k] > a + kEdgeSlack && edges[k] < b - kEdgeSlack;
  return split;
}

// The segment splitter: calls fn(lo, hi) for the substeps of [a, b] cut at the edges strictly
// inside (beyond the slack), in order; returns their count.
template <typename Fn>
[[gnu::always_inline]] inline int split_step(double a, double b, const double* edges, int n_edges,
                                             Fn&& fn) {
  double lo = a;
  int count = 1;
  for (int k = 0; k < n_edges; ++k) {
    if (edges[k] > a + kEdgeSlack && edges[k] < b - kEdgeSlack) {
      fn(lo, edges[k]);
      lo = edges[k];
      ++count;
    }
  }
  fn(lo, b);
  return count;
}

// The harmonic set `set` (>= 0) of sys.
inline const HarmonicSet& harmonic_set(const PeriodicSystem& sys, int set) {
  return sys.sets[static_cast<std::size_t>(set)];
}
// The evaluator of segment s (s.set == -1).
inline const PeriodicSystem::Evaluator& evaluator(const PeriodicSystem& sys, const Segment& s) {
  return sys.pieces[static_cast<std::size_t>(s.piece)].evaluator;
}

// `steps` equal steps over [0, 2 pi], split at the breakpoints.
std::vector<Segment> equal_grid(const PeriodicSystem& sys, int steps);

// Every segment bisected (node -1): proportional grids for Richardson extrapolation.
std::vector<Segment> bisect(const std::vector<Segment>& grid);

// The points a + (b - a) i / count, i = 0 .. count, and the breakpoints strictly inside (a, b),
// sorted; the segments between consecutive points (gaps <= 1e-14 skipped) appended to out.
// 0 <= a < b <= 2 pi.
void sampled_grid(const PeriodicSystem& sys, double a, double b, int count,
                  std::vector<Segment>& out);

// The four stages of one classical RK4 step over h from y: rhs(stage, y, k) sets k = F(y) at
// stage 0 (the start), 1 and 2 (the middle) or 3 (the end).  y2 .. y4 are the states the stages
// 2 .. 4 are taken at.  Works on vectors and on matrices (all columns at once).
template <typename State>
struct Rk4 {
  State k1, k2, k3, k4, y2, y3, y4;

  template <typename Rhs>
  [[gnu::always_inline]] inline void stages(double h, const State& y, Rhs&& rhs) {
    rhs(0, y, k1);
    y2 = y + (0.5 * h) * k1;
    rhs(1, y2, k2);
    y3 = y + (0.5 * h) * k2;
    rhs(2, y3, k3);
    y4 = y + h * k3;
    rhs(3, y4, k4);
  }
  // y += h/6 (k1 + 2 k2 + 2 k3 + k4), from the stages just taken.
  [[gnu::always_inline]] inline void advance(double h, State& y) const {
    y += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  template <typename Rhs>
  [[gnu::always_inline]] inline void step(double h, State& y, Rhs&& rhs) {
    stages(h, y, rhs);
    advance(h, y);
  }
};

}  // namespace flaplag::detail
