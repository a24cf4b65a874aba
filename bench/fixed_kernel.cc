// The comparison kernel of bench/fixed_kernel.h.
#include "fixed_kernel.h"

#include <limits>

#include "flaplag/core/constants.h"
#include "flaplag/numerics/dense.h"

namespace flaplag::bench {

FixedKernel::FixedKernel(const flaplag::PeriodicSystem& s, int K) {
  for (std::size_t r = 0; r < s.sets.size() && r < 2; ++r)  // normal and the sector
    for (const Eigen::MatrixXd& m : s.sets[r].A) A[r].push_back(m);
  auto add = [&](double a, double b) {
    Interval iv{b - a, s.pieces[static_cast<std::size_t>(s.piece_at(0.5 * (a + b)))].set, {}};
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

Eigen::Matrix4d FixedKernel::phi() const {
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

Eigen::Vector4cd FixedKernel::eigenvalues() const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector4cd values = Eigen::Vector4cd::Constant({nan, nan});  // if QR does not converge
  flaplag::fixed_eigenvalues(phi(), &values);
  return values;
}

}  // namespace flaplag::bench
