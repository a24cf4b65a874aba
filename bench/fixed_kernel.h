// The comparison kernel of the point benchmarks (issue 10): one stability point's arithmetic
// written plainly on fixed-size Eigen types, compiled with the same flags in the same program,
// so that the ratio to the library's path is taken in one run on one machine.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <vector>

#include "flaplag/core/constants.h"
#include "flaplag/numerics/periodic_system.h"

namespace flaplag::bench {

// The comparison kernel: the same arithmetic written plainly on fixed-size Eigen types, for
// the ratio of issue 10 (taken in one run, same flags).  Per interval of Hsu's grid (K = 50 equal
// steps, split at the sector edges as transition.cc does): the exact interval mean of A as the
// sum of the harmonic matrices weighted by their interval means (eqs 4.2-4.5), exp(delta C) by
// the J = 4 Taylor polynomial in Paterson-Stockmeyer form (two products) and the accumulated
// product (one); then the 4x4 eigenvalues of Phi (no eigenvectors, no identification, no
// checks).  The grid, the harmonics in Matrix4d form and the weights (the cos/sin/sinc values,
// i.e. all transcendental functions) are prepared outside the timed loop, so the kernel is the
// arithmetic floor of one point.
struct FixedKernel {
  struct Interval {
    double delta;
    int region;
    std::vector<double> weight;  // delta * interval mean of each harmonic basis function
  };
  std::array<std::vector<Eigen::Matrix4d>, 2> A;  // harmonics of the two regions
  std::vector<Interval> grid;

  explicit FixedKernel(const flaplag::PeriodicSystem& s, int K) {
    for (int r = 0; r < 2; ++r) {
      const flaplag::HarmonicSet& set = r == 0 ? s.normal : s.reversed;
      for (const Eigen::MatrixXd& m : set.A) A[r].push_back(m);
    }
    auto add = [&](double a, double b) {
      Interval iv{b - a, s.in_sector(0.5 * (a + b)) ? 1 : 0, {}};
      for (std::size_t h = 0; h < A[iv.region].size(); ++h)
        iv.weight.push_back((b - a) * flaplag::harmonic_mean(static_cast<int>(h), a, b));
      grid.push_back(iv);
    };
    const double d = flaplag::kTwoPi / K;
    for (int i = 0; i < K; ++i) {
      double a = i * d;
      const double b = (i + 1) * d;
      for (double e : s.breakpoints())
        if (e > a && e < b) {
          add(a, e);
          a = e;
        }
      add(a, b);
    }
  }

  Eigen::Matrix4d phi() const {
    Eigen::Matrix4d Phi = Eigen::Matrix4d::Identity();
    for (const Interval& iv : grid) {
      const std::vector<Eigen::Matrix4d>& H = A[iv.region];
      Eigen::Matrix4d X = iv.weight[0] * H[0];  // X = delta C_k
      for (std::size_t h = 1; h < H.size(); ++h) X += iv.weight[h] * H[h];
      const Eigen::Matrix4d X2 = X * X;
      Eigen::Matrix4d T = (1.0 / 6.0) * X + (1.0 / 24.0) * X2;
      T.diagonal().array() += 0.5;
      Eigen::Matrix4d E = Eigen::Matrix4d::Identity() + X;
      E.noalias() += X2 * T;
      Phi = (E * Phi).eval();
    }
    return Phi;
  }
};

}  // namespace flaplag::bench
