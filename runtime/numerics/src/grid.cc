// flaplag — the grid helper of the integrators (grid.h).
#include "grid.h"

#include <algorithm>

namespace flaplag::detail {

namespace {

// A segment [a, b] in the piece that contains its midpoint (in (0, 2 pi): no reduction needed).
Segment segment(const PeriodicSystem& sys, double a, double b, int node, bool after_break) {
  const double mid = 0.5 * (a + b);
  const int last = static_cast<int>(sys.pieces.size()) - 1;
  int i = 0;
  while (i < last && !(mid < sys.pieces[static_cast<std::size_t>(i)].end)) ++i;
  return {a, b, i, sys.pieces[static_cast<std::size_t>(i)].set, node, after_break};
}

}  // namespace

std::vector<Segment> equal_grid(const PeriodicSystem& sys, int steps) {
  const std::vector<double> edges = sys.breakpoints();
  const int n_edges = static_cast<int>(edges.size());
  const double d = kTwoPi / steps;
  std::vector<Segment> out;
  out.reserve(static_cast<std::size_t>(steps) + edges.size());
  for (int i = 0; i < steps; ++i) {
    const double a = i * d;
    const double b = (i + 1 == steps) ? kTwoPi : (i + 1) * d;
    bool at_break = false;
    for (double e : edges) at_break |= e >= a - kEdgeSlack && e <= a + kEdgeSlack;
    const int count = split_step(a, b, edges.data(), n_edges, [&](double lo, double hi) {
      out.push_back(segment(sys, lo, hi, -1, at_break));
      at_break = true;
    });
    if (count == 1) out.back().node = i;
  }
  return out;
}

std::vector<Segment> bisect(const std::vector<Segment>& grid) {
  std::vector<Segment> out;
  out.reserve(2 * grid.size());
  for (const Segment& s : grid) {
    const double m = 0.5 * (s.a + s.b);
    out.push_back({s.a, m, s.piece, s.set, -1, s.after_break});
    out.push_back({m, s.b, s.piece, s.set, -1, false});
  }
  return out;
}

void sampled_grid(const PeriodicSystem& sys, double a, double b, int count,
                  std::vector<Segment>& out) {
  std::vector<double> pts;
  for (int i = 0; i <= count; ++i) pts.push_back(a + (b - a) * i / count);
  for (double e : sys.breakpoints())
    if (e > a && e < b) pts.push_back(e);
  std::sort(pts.begin(), pts.end());
  for (std::size_t i = 1; i < pts.size(); ++i) {
    if (pts[i] - pts[i - 1] <= 1e-14) continue;
    out.push_back(segment(sys, pts[i - 1], pts[i], -1, false));
  }
}

}  // namespace flaplag::detail
