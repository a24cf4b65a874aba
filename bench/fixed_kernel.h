// The comparison kernel of the point benchmarks: one stability point's arithmetic written plainly
// on fixed-size Eigen types (fixed_kernel.cc, compiled once with the benches' flags and linked
// into each of them), so that the ratio to the library's path is taken in one run on one
// machine.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

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

  FixedKernel(const flaplag::PeriodicSystem& s, int K);

  // Phi(2 pi, 0) of the system.
  Eigen::Matrix4d phi() const;
  // The eigenvalues of phi() (Eigen::EigenSolver<Eigen::Matrix4d>, no eigenvectors: the
  // library's fixed_eigenvalues, the instantiation its 4 x 4 points use, with the same flags).
  // NaN when the QR iteration does not converge.
  Eigen::Vector4cd eigenvalues() const;
};

}  // namespace flaplag::bench
