// The rotor's periodic system (runtime/rotor/system_builder.h): the exact circular
// reversed-flow region against the Appendix D sector and against loads assembled from
// aerodynamic integrals done by Gauss quadrature at the split station of each psi.
#include "flaplag/rotor/system_builder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "test_util.h"

namespace flaplag::system_builder_test {
namespace {

using detail::exact_reversed_region;
using detail::SystemBuilder;

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

// A blade with every geometric parameter away from its default, so that a mix-up of e1, l/R,
// A and B in the split station shows.
RotorParameters offset_blade(bool exact_modes, bool exact_region) {
  RotorParameters p;
  p.root_offset = 0.03;
  p.length_ratio = 0.97;
  p.tip_loss_a = 0.08;
  p.tip_loss_b = 0.96;
  p.modes = exact_modes ? ModeKind::Exact : ModeKind::Assumed;
  p.exact_reversed_flow = exact_region;
  return p;
}

// The region is where the circle of diameter mu covers part of the aerodynamic span: its edges
// are the psi with -mu sin psi = e1 + (l/R) A, its breaks those with -mu sin psi = e1 + (l/R) B.
TEST(ExactReversedRegion, EdgesWhereTheCircleMeetsTheSpanLimits) {
  const RotorParameters p = offset_blade(false, true);
  const double x_a = 0.03 + 0.97 * 0.08, x_b = 0.03 + 0.97 * 0.96;
  EXPECT_FALSE(exact_reversed_region(0.0, p).exists);
  EXPECT_FALSE(exact_reversed_region(0.99 * x_a, p).exists);
  for (double mu : {0.5, 0.99, 1.3, 3.0}) {
    const auto r = exact_reversed_region(mu, p);
    ASSERT_TRUE(r.exists) << mu;
    EXPECT_NEAR(x_a, -mu * std::sin(r.begin), 1e-14) << mu;
    EXPECT_NEAR(x_a, -mu * std::sin(r.end), 1e-14) << mu;
    EXPECT_GT(r.begin, kPi);
    EXPECT_LT(r.end, kTwoPi);
    EXPECT_LT(r.begin, 1.5 * kPi);
    if (mu <= x_b) {
      EXPECT_TRUE(r.breaks.empty()) << mu;
      continue;
    }
    ASSERT_EQ(2u, r.breaks.size()) << mu;
    for (double b : r.breaks) EXPECT_NEAR(x_b, -mu * std::sin(b), 1e-14) << mu;
    EXPECT_LT(r.begin, r.breaks[0]);
    EXPECT_LT(r.breaks[0], r.breaks[1]);
    EXPECT_LT(r.breaks[1], r.end);
  }
  // the default blade (e1 = A = 0): the whole retreating side at every mu > 0
  const auto r = exact_reversed_region(0.2, RotorParameters{});
  EXPECT_EQ(kPi, r.begin);
  EXPECT_EQ(kTwoPi, r.end);
}

// Where the circle does not reach the aerodynamic span (mu <= e1 + (l/R) A), and at mu = 0,
// the exact and sector options give the same A and f: the sector's integrals split at
// x0 = (mu - e1)/(l/R) <= A are the normal ones too.
TEST(ExactReversedRegion, SameAsTheSectorWithoutReversedSpan) {
  RotorParameters p = offset_blade(false, false);
  p.tip_loss_a = 0.3;  // x_A = 0.321
  RotorParameters q = p;
  q.exact_reversed_flow = true;
  const SystemBuilder sector(p, find_model(p.model)), exact(q, find_model(q.model));
  for (double mu : {0.0, 0.2, 0.32}) {
    const PeriodicSystem a = sector.system(mu), b = exact.system(mu);
    EXPECT_EQ(1u, b.pieces.size()) << mu;  // neither an exact region nor a sector
    for (int k = 0; k < 24; ++k) {
      const double psi = (k + 0.3) * kTwoPi / 24;
      const Eigen::MatrixXd Aa = a.A(psi), Ab = b.A(psi);
      EXPECT_LE(max_abs(Aa - Ab), 1e-15 * max_abs(Aa)) << "mu = " << mu << ", psi = " << psi;
      EXPECT_LE((a.f(psi) - b.f(psi)).cwiseAbs().maxCoeff(), 1e-15 * max_abs(Aa))
          << "mu = " << mu << ", psi = " << psi;
    }
  }
  const PeriodicSystem a0 = sector.system(0.0), b0 = exact.system(0.0);
  ASSERT_EQ(a0.sets.at(0).A.size(), b0.sets.at(0).A.size());
  for (std::size_t h = 0; h < a0.sets[0].A.size(); ++h) EXPECT_EQ(a0.sets[0].A[h], b0.sets[0].A[h]);
}

// Independent check of the exact region: at each psi, the aerodynamic integrals by Gauss
// quadrature (blade.h aero_integral), split at x0(psi) = (-mu sin psi - e1)/(l/R) clipped to
// [A, B] and negated on the reversed part (-int_A^{x0} + int_{x0}^B), assembled by the builder,
// summed at psi; against the system's A(psi) and f(psi) (a Chebyshev series in x0).
struct GaussCase {
  const char* name;
  const char* model;
  bool exact_modes;
  double mu;
};

void PrintTo(const GaussCase& c, std::ostream* os) { *os << c.name; }

class ExactRegionGauss : public ::testing::TestWithParam<GaussCase> {};

TEST_P(ExactRegionGauss, AMatchesGaussQuadratureOfTheSplitIntegrals) {
  RotorParameters p = offset_blade(GetParam().exact_modes, true);
  p.model = GetParam().model;
  const SystemBuilder b(p, find_model(p.model));
  const double mu = GetParam().mu;
  const PeriodicSystem sys = b.system(mu);
  ASSERT_TRUE(sys.has_evaluator());
  SpanGeometry g;
  g.e1 = p.root_offset;
  g.lr = p.length_ratio;
  g.tip_loss_a = p.tip_loss_a;
  g.tip_loss_b = p.tip_loss_b;
  const model::ModelDescriptor& m = b.model();
  // normal side, both region edges' neighbourhoods, the middle, and (mu > x_B) the fully
  // reversed part between the breaks
  for (double psi : {1.0, 3.3, 3.8, 4.4, 1.5 * kPi, 5.1, 5.9, 6.2}) {
    const double x0 = std::clamp((-mu * std::sin(psi) - g.e1) / g.lr, g.tip_loss_a, g.tip_loss_b);
    std::vector<double> aero;
    for (int j = 0; j < m.n_aero; ++j)
      aero.push_back(-aero_integral(m.aero[j], b.modes(), g, g.tip_loss_a, x0) +
                     aero_integral(m.aero[j], b.modes(), g, x0, g.tip_loss_b));
    const HarmonicSet set = b.harmonics(mu, aero);
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(sys.n, sys.n);
    Eigen::VectorXd f = Eigen::VectorXd::Zero(sys.n);
    for (std::size_t h = 0; h < set.A.size(); ++h) {
      A += harmonic_basis(static_cast<int>(h), psi) * set.A[h];
      f += harmonic_basis(static_cast<int>(h), psi) * set.f[h];
    }
    const double scale = max_abs(A);
    EXPECT_LE(max_abs(sys.A(psi) - A), 1e-12 * scale) << "psi = " << psi << ", x0 = " << x0;
    EXPECT_LE((sys.f(psi) - f).cwiseAbs().maxCoeff(), 1e-12 * scale) << "psi = " << psi;
  }
}

INSTANTIATE_TEST_SUITE_P(Models, ExactRegionGauss,
                         ::testing::Values(GaussCase{"assumed_mu06", "paper", false, 0.6},
                                           GaussCase{"assumed_mu13", "paper", false, 1.3},
                                           GaussCase{"no_radial_flow_mu13", "no-radial-flow", false,
                                                     1.3},
                                           GaussCase{"lag_order_2_mu08", "lag-order-2", false, 0.8},
                                           GaussCase{"exact_mu06", "paper", true, 0.6},
                                           GaussCase{"exact2x1_mu08", "paper-2x1", true, 0.8},
                                           GaussCase{"exact1x2_mu08", "paper-1x2", true, 0.8},
                                           GaussCase{"exact2x2_mu13", "paper-2x2", true, 1.3}),
                         [](const auto& tp) { return std::string(tp.param.name); });

// mu >= 1 on the default blade: between the breaks the whole span is reversed, so the
// integrals there are the negated normal ones, as in the sector of eqs D.5-D.6.
TEST(ExactReversedRegion, FullyReversedBetweenTheBreaks) {
  RotorParameters p;
  p.exact_reversed_flow = true;
  const SystemBuilder b(p, find_model(p.model));
  const std::vector<double> r = b.exact_integrals(1.5, 1.5 * kPi);
  const std::vector<double>& n = b.normal_integrals();
  ASSERT_EQ(n.size(), r.size());
  for (std::size_t j = 0; j < n.size(); ++j) EXPECT_DOUBLE_EQ(-n[j], r[j]);
  const std::vector<double> side = b.exact_integrals(1.5, 1.0);  // advancing side
  for (std::size_t j = 0; j < n.size(); ++j) EXPECT_DOUBLE_EQ(n[j], side[j]);
}

// system(mu, &out) reuses out's storage and gives the system of system(mu), every field and bit,
// whatever out held before: a sector system after one without (mu = 0) and back, an exact
// region after a sector (and back), and exact modes with their larger state.
TEST(SystemBuilder, ReusedSystemIsTheSystemOfItsMu) {
  auto same = [](const PeriodicSystem& a, const PeriodicSystem& b, const std::string& where) {
    EXPECT_EQ(a.n, b.n) << where;
    ASSERT_EQ(a.pieces.size(), b.pieces.size()) << where;
    for (std::size_t i = 0; i < a.pieces.size(); ++i) {
      EXPECT_EQ(a.pieces[i].begin, b.pieces[i].begin) << where;
      EXPECT_EQ(a.pieces[i].end, b.pieces[i].end) << where;
      EXPECT_EQ(a.pieces[i].set, b.pieces[i].set) << where;
      EXPECT_EQ(a.pieces[i].breaks, b.pieces[i].breaks) << where;
      EXPECT_EQ(static_cast<bool>(a.pieces[i].evaluator), static_cast<bool>(b.pieces[i].evaluator))
          << where;
    }
    ASSERT_EQ(a.sets.size(), b.sets.size()) << where;
    for (std::size_t k = 0; k < a.sets.size(); ++k) {
      const HarmonicSet* x = &a.sets[k];
      const HarmonicSet* y = &b.sets[k];
      ASSERT_EQ(x->A.size(), y->A.size()) << where;
      ASSERT_EQ(x->f.size(), y->f.size()) << where;
      for (std::size_t h = 0; h < x->A.size(); ++h) EXPECT_TRUE(x->A[h] == y->A[h]) << where;
      for (std::size_t h = 0; h < x->f.size(); ++h) EXPECT_TRUE(x->f[h] == y->f[h]) << where;
    }
    for (double psi : {0.3, 4.2, 4.9})  // the varying region's evaluator too
      EXPECT_TRUE(a.A(psi) == b.A(psi)) << where << ", psi = " << psi;
  };
  for (bool exact_modes : {false, true}) {
    RotorParameters p = offset_blade(exact_modes, false), q = offset_blade(exact_modes, true);
    const SystemBuilder sector(p, find_model(p.model)), exact(q, find_model(q.model));
    PeriodicSystem reused;
    for (double mu : {0.0, 0.6, 0.0, 1.3, 0.4}) {
      const std::string where = std::string(exact_modes ? "exact modes" : "assumed modes") +
                                ", mu = " + std::to_string(mu);
      sector.system(mu, &reused);
      same(sector.system(mu), reused, where + " (sector)");
      exact.system(mu, &reused);
      same(exact.system(mu), reused, where + " (exact region)");
    }
  }
  const RotorParameters typical;
  const SystemBuilder b(typical, find_model(typical.model));
  EXPECT_THROW(b.system(0.1, nullptr), InvalidInput);
}

// The contract behind building a system from the first n_linear_aero integrals only (the
// reversed-flow sector's): mass, coefficients and equilibrium of every compiled family, at
// several mode counts, give the same bits, all finite, when every later integral is NaN.
TEST(SystemBuilder, TheLinearFunctionsReadOnlyTheirIntegrals) {
  for (const model::ModelFamily* f : model::compiled_families()) {
    for (const auto& [M, N] : {std::pair{1, 1}, std::pair{2, 1}, std::pair{3, 2}}) {
      const model::ModelDescriptor& d = model::instantiate(*f, M, N);
      SCOPED_TRACE(d.name);
      ASSERT_GT(d.n_linear_aero, 0);
      ASSERT_LE(d.n_linear_aero, d.n_aero);
      const int n = M + N, H = d.n_harmonics;
      const int modes[2] = {M, N};
      std::vector<double> q0[2], omega[2], damping[2], elastic[2][2];
      model::CoefficientInputs in{};
      in.lock = 8.0;
      in.lr = 0.95;
      in.theta = 0.1;
      in.inflow = 0.03;
      in.precone = 0.02;
      in.droop = 0.01;
      in.cdo_a = 0.002;
      in.mu = 0.7;
      in.theta1c = 0.03;
      in.theta1s = -0.02;
      for (int r = 0; r < 2; ++r) {
        in.modes[r] = modes[r];
        for (int k = 0; k < modes[r]; ++k) {
          q0[r].push_back(0.01 * (k + 1 + r));
          omega[r].push_back(1.1 + 2.0 * k + 0.3 * r);
          damping[r].push_back(0.002 * (k + 1));
        }
        in.q0[r] = q0[r].data();
        in.omega[r] = omega[r].data();
        in.damping[r] = damping[r].data();
        for (int c = 0; c < 2; ++c) {
          for (int k = 0; k < modes[r] * modes[c]; ++k)
            elastic[r][c].push_back(0.01 * std::sin(k + r + c));
          in.elastic[r][c] = elastic[r][c].data();
        }
      }
      std::vector<double> aero(static_cast<std::size_t>(d.n_aero));
      std::vector<double> structural(static_cast<std::size_t>(d.n_structural));
      for (std::size_t j = 0; j < aero.size(); ++j)
        aero[j] = 0.1 + 0.05 * std::sin(1.0 + static_cast<double>(j));
      for (std::size_t j = 0; j < structural.size(); ++j)
        structural[j] = 0.2 + 0.1 * std::cos(2.0 + static_cast<double>(j));
      in.structural = structural.data();
      auto run = [&](const std::vector<double>& a) {
        in.aero = a.data();
        std::vector<double> out(
            static_cast<std::size_t>(n * n + H * n * 2 * n + H * n + n * n + n));
        double* mass = out.data();
        double* force = mass + n * n;
        double* forcing = force + H * n * 2 * n;
        double* S = forcing + H * n;
        d.mass(in, mass);
        d.coefficients(in, {force, forcing});
        d.equilibrium(in, {S, S + n * n});
        return out;
      };
      const std::vector<double> full = run(aero);
      std::vector<double> prefix = aero;
      for (std::size_t j = static_cast<std::size_t>(d.n_linear_aero); j < prefix.size(); ++j)
        prefix[j] = std::numeric_limits<double>::quiet_NaN();
      const std::vector<double> cut = run(prefix);
      for (std::size_t k = 0; k < full.size(); ++k) {
        ASSERT_TRUE(std::isfinite(cut[k]))
            << "output " << k << " reads an integral from " << d.n_linear_aero << " on";
        ASSERT_EQ(full[k], cut[k]) << k;
      }
    }
  }
}

}  // namespace
}  // namespace flaplag::system_builder_test
