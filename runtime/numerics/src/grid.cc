// flaplag — the grid helper of the integrators (grid.h).
#include "grid.h"

#include <algorithm>

namespace flaplag::detail {

int set_at(const PeriodicSystem& sys, double psi) {
  // psi lies in (0, 2 pi): no reduction needed (cheaper than in_sector's fmod).
  if (sys.has_varying && psi >= sys.varying_begin && psi < sys.varying_end) return -1;
  return sys.has_sector && psi >= sys.sector_begin && psi < sys.sector_end ? 1 : 0;
}

const HarmonicSet& harmonic_set(const PeriodicSystem& sys, int set) {
  return set == 1 ? sys.reversed : sys.normal;
}

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
      out.push_back({lo, hi, set_at(sys, 0.5 * (lo + hi)), -1, at_break});
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
    out.push_back({s.a, m, s.set, -1, s.after_break});
    out.push_back({m, s.b, s.set, -1, false});
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
    const double mid = 0.5 * (pts[i] + pts[i - 1]);
    out.push_back({pts[i - 1], pts[i], set_at(sys, mid), -1, false});
  }
}

}  // namespace flaplag::detail
