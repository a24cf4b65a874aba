// Exact rotating modes (paper 4.1(b), Appendix A) and the Fig. 9 frequency relation.
//
// The checks use properties that hold independently of the implementation: Rayleigh-Ritz
// monotonicity in the basis size, the orthogonality relations A.1-A.4 evaluated by quadrature
// from the returned shapes (through the structural-integral machinery), Rayleigh's principle, the
// classical Southwell coefficient of the uniform cantilever (1.193), boundary conditions.
#include "flaplag/blade/rotating_modes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "flaplag/blade/blade.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "test_util.h"

namespace flaplag::rotating_modes_test {
namespace {

using flaplag::model::Direction;
using model::Factor;
using model::FactorRef;
using model::Inner;
using model::StructuralIntegral;
using testing::AbsClose;
using testing::RelClose;

constexpr double kOmegaF = 1.175;  // the paper's typical blade
constexpr double kOmegaL = 1.28303;

double integral(const ModeShape& a, int da, const ModeShape& b, int db) {
  const SpanRule rule = span_rule(0.0, 1.0);
  double s = 0.0;
  for (std::size_t q = 0; q < rule.x0.size(); ++q) {
    s += rule.weight[q] * a.value(da, rule.x0[q]) * b.value(db, rule.x0[q]);
  }
  return s;
}

// int eta_i' eta_k' [int_x^1 mbar (x1 + e1/l)] through the generalized-mass code.
double tension_integral(const ModeSet& m, bool flap, int i, int k, double e1_over_l) {
  const Factor slope = flap ? Factor::EtaPrime : Factor::GammaPrime;
  const FactorRef none{Factor::X0, 0};
  StructuralIntegral s{"T",
                       "T",
                       0,
                       2,
                       {FactorRef{slope, i}, FactorRef{slope, k}, none, none},
                       Inner::Tail,
                       1,
                       1,
                       {FactorRef{Factor::Arm, 0}, none, none, none},
                       ""};
  return structural_integral(s, m, e1_over_l, 3.0);
}

TEST(RotatingModes, TypicalBlade) {
  const ExactModes r = exact_rotating_modes(kOmegaF, kOmegaL);
  const ModeSet& m = r.modes;
  EXPECT_EQ("exact", m.kind);
  ASSERT_EQ(1u, m.shapes(Direction::Flap).size());
  ASSERT_EQ(1u, m.shapes(Direction::Lag).size());
  EXPECT_TRUE(RelClose(kOmegaF, m[Direction::Flap].omega[0], 1e-12));
  EXPECT_TRUE(RelClose(kOmegaL, m[Direction::Lag].omega[0], 1e-12));
  EXPECT_GT(m[Direction::Flap].stiffness, 0.0);
  EXPECT_GT(m[Direction::Lag].stiffness, m[Direction::Flap].stiffness);
  // Nonrotating frequency from k beta^4 = mbar wbar^2.
  const double b1 = cantilever_root(1);
  EXPECT_TRUE(RelClose(std::sqrt(m[Direction::Flap].stiffness / 3.0) * b1 * b1,
                       r[Direction::Flap].omega_nonrotating, 1e-15));
  EXPECT_TRUE(RelClose(std::sqrt(m[Direction::Lag].stiffness / 3.0) * b1 * b1,
                       r[Direction::Lag].omega_nonrotating, 1e-15));
  EXPECT_LT(r[Direction::Flap].omega_nonrotating, kOmegaF);
  std::cout << "typical blade: k_y = " << round_trip_text(m[Direction::Flap].stiffness)
            << ", k_z = " << round_trip_text(m[Direction::Lag].stiffness)
            << ", wF1N = " << round_trip_text(r[Direction::Flap].omega_nonrotating)
            << ", wL1N = " << round_trip_text(r[Direction::Lag].omega_nonrotating) << "\n";
  ::testing::Test::RecordProperty("k_y", round_trip_text(m[Direction::Flap].stiffness));
  ::testing::Test::RecordProperty("k_z", round_trip_text(m[Direction::Lag].stiffness));
}

TEST(RotatingModes, RequestedFrequencyIsTheRayleighQuotientOfTheShape) {
  // The shape's own Rayleigh quotient (quadrature, eqs A.2 and A.4) must reproduce the request.
  for (double e1 : {0.0, 0.1}) {
    ExactModeOptions o;
    o.e1_over_l = e1;
    for (double wf : {1.05, 1.175, 1.6, 3.0}) {
      for (double wl : {0.3, 0.7, 1.28303, 2.5}) {
        if (wf <= centrifugal_limit(BendingDirection::Flap, o)) continue;
        if (wl <= centrifugal_limit(BendingDirection::Lag, o)) continue;
        const ModeSet m = exact_modes(wf, wl, o);
        EXPECT_TRUE(RelClose(wf, m[Direction::Flap].omega[0], 1e-12)) << wf << " e1=" << e1;
        EXPECT_TRUE(RelClose(wl, m[Direction::Lag].omega[0], 1e-12)) << wl << " e1=" << e1;
        EXPECT_TRUE(
            RelClose(wf,
                     rayleigh_frequency(BendingDirection::Flap, *m.shapes(Direction::Flap)[0],
                                        m[Direction::Flap].stiffness, e1),
                     1e-12));
        EXPECT_TRUE(RelClose(wl,
                             rayleigh_frequency(BendingDirection::Lag, *m.shapes(Direction::Lag)[0],
                                                m[Direction::Lag].stiffness, e1),
                             1e-11));
      }
    }
  }
}

TEST(RotatingModes, ShapesBoundaryConditionsAndTipNormalisation) {
  ExactModeOptions o;
  o.flap_modes = 3;
  o.lag_modes = 3;
  const ModeSet m = exact_modes(kOmegaF, kOmegaL, o);
  for (const auto* set : {&m.shapes(Direction::Flap), &m.shapes(Direction::Lag)}) {
    for (const auto& s : *set) {
      EXPECT_TRUE(RelClose(1.0, s->value(0, 1.0), 1e-14));
      EXPECT_TRUE(AbsClose(0.0, s->value(0, 0.0), 1e-14));
      EXPECT_TRUE(AbsClose(0.0, s->value(1, 0.0), 1e-13));
      EXPECT_TRUE(AbsClose(0.0, s->value(2, 1.0), 1e-11));
      EXPECT_TRUE(AbsClose(0.0, s->value(3, 1.0), 1e-10));
    }
  }
  // The first rotating flap mode is close to the first cantilever function (tip-normalised).
  const auto phi1 = cantilever_mode(1);
  for (double x : {0.25, 0.5, 0.75}) {
    EXPECT_TRUE(AbsClose(phi1->value(0, x) / 2.0, m.shapes(Direction::Flap)[0]->value(0, x), 0.05))
        << x;
  }
}

TEST(RotatingModes, OrthogonalityRelationsA1ToA4) {
  for (double e1 : {0.0, 0.08}) {
    ExactModeOptions o;
    o.flap_modes = 4;
    o.lag_modes = 4;
    o.e1_over_l = e1;
    const ModeSet m = exact_modes(kOmegaF, kOmegaL, o);
    for (bool flap : {true, false}) {
      const auto& s = flap ? m.shapes(Direction::Flap) : m.shapes(Direction::Lag);
      const double k = flap ? m[Direction::Flap].stiffness : m[Direction::Lag].stiffness;
      const auto& w = flap ? m[Direction::Flap].omega : m[Direction::Lag].omega;
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j <= i; ++j) {
          // k int s_i'' s_j'' + int s_i' s_j' T  [- int mbar s_i s_j for lag]
          const double mass = 3.0 * integral(*s[i], 0, *s[j], 0);
          double stiff = k * integral(*s[i], 2, *s[j], 2) + tension_integral(m, flap, i, j, e1);
          if (!flap) stiff -= mass;
          if (i == j) {
            EXPECT_TRUE(RelClose(w[i] * w[i] * mass, stiff, 1e-11))
                << (flap ? "flap " : "lag ") << i << " e1=" << e1;
          } else {
            const double scale =
                std::sqrt(w[i] * w[i] * w[j] * w[j] * 3.0 * integral(*s[i], 0, *s[i], 0) * 3.0 *
                          integral(*s[j], 0, *s[j], 0));
            EXPECT_LT(std::abs(stiff), 1e-10 * scale) << i << "," << j;
            EXPECT_LT(std::abs(mass), 1e-10 * scale / (w[i] * w[j])) << i << "," << j;
          }
        }
      }
    }
  }
}

TEST(RotatingModes, FrequenciesConvergeWithBasisSize) {
  // Rayleigh-Ritz on nested subspaces: for fixed stiffness every frequency is non-increasing in
  // n_basis, and the first one settles quickly.
  const double k_y = exact_modes(kOmegaF, kOmegaL)[Direction::Flap].stiffness;
  std::vector<double> first;
  std::vector<double> prev;
  for (int n = 1; n <= 8; ++n) {
    ExactModeOptions o;
    o.n_basis = n;
    const auto w = rotating_frequencies(BendingDirection::Flap, k_y, o);
    ASSERT_EQ(static_cast<std::size_t>(n), w.size());
    for (std::size_t i = 0; i < prev.size(); ++i) {
      EXPECT_LE(w[i], prev[i] * (1 + 1e-14)) << "n=" << n << " mode " << i;
    }
    prev = w;
    first.push_back(w[0]);
  }
  for (std::size_t n = 2; n < first.size(); ++n) {
    EXPECT_LT(first[n - 1] - first[n], first[n - 2] - first[n - 1]) << "n=" << n + 1;
  }
  EXPECT_LT(first[4] - first[7], 1e-3 * first[7]);
  std::cout << "first flap frequency at k_y for n = 1..8:";
  for (double w : first) std::cout << " " << round_trip_text(w);
  std::cout << "\n";
}

TEST(RotatingModes, SouthwellCoefficient) {
  // Rayleigh quotient of phi_1 alone: wbar^2 = wbar_N^2 + K_1, K_1 = int phi_1'^2 (1-x^2)/2
  // (classical value 1.193 for the uniform cantilever, e1 = 0).
  const auto phi1 = cantilever_mode(1);
  const SpanRule rule = span_rule(0.0, 1.0);
  double k1 = 0.0;
  for (std::size_t q = 0; q < rule.x0.size(); ++q) {
    const double x = rule.x0[q];
    const double d = phi1->value(1, x);
    k1 += rule.weight[q] * d * d * 0.5 * (1 - x * x);
  }
  EXPECT_TRUE(AbsClose(1.193, k1, 5e-4));
  // Exact modes: wbar^2 - wbar_N^2 <= K_1 (Rayleigh's principle) and -> K_1 for a stiff blade.
  for (double wn : {0.3, 0.479, 1.0, 3.0}) {
    const double wr = rotating_frequency(BendingDirection::Flap, wn);
    EXPECT_LE(wr * wr - wn * wn, k1 + 1e-12) << wn;
    EXPECT_GT(wr * wr - wn * wn, 1.0) << wn;
  }
  const double stiff = rotating_frequency(BendingDirection::Flap, 30.0);
  EXPECT_TRUE(RelClose(k1, stiff * stiff - 900.0, 1e-3));
  const ExactModes r = exact_rotating_modes(kOmegaF, kOmegaL);
  std::cout << "Southwell K_1 (phi_1 Rayleigh) = " << round_trip_text(k1)
            << "; typical blade wF1^2 - wF1N^2 = "
            << round_trip_text(kOmegaF * kOmegaF - r[Direction::Flap].omega_nonrotating *
                                                       r[Direction::Flap].omega_nonrotating)
            << "\n";
  // Lag: the in-plane term lowers wbar^2 by exactly 1 at equal stiffness (eq A.4).
  const double wf = rotating_frequency(BendingDirection::Flap, 1.2);
  const double wl = rotating_frequency(BendingDirection::Lag, 1.2);
  EXPECT_TRUE(RelClose(wf * wf - 1.0, wl * wl, 1e-13));
}

TEST(RotatingModes, Fig9RoundTripAndTable) {
  for (double w : {1.05, 1.175, 1.5, 2.5}) {
    const double wn = nonrotating_frequency(BendingDirection::Flap, w);
    EXPECT_TRUE(RelClose(w, rotating_frequency(BendingDirection::Flap, wn), 1e-13));
  }
  for (double w : {0.25, 0.7, 1.28303, 2.5}) {
    const double wn = nonrotating_frequency(BendingDirection::Lag, w);
    EXPECT_TRUE(RelClose(w, rotating_frequency(BendingDirection::Lag, wn), 1e-12));
  }
  const auto t = fig9_table(BendingDirection::Lag, 0.0, 2.5, 26);
  ASSERT_EQ(26u, t.size());
  EXPECT_EQ(0.0, t.front().nonrotating);
  EXPECT_EQ(2.5, t.back().nonrotating);
  EXPECT_TRUE(RelClose(centrifugal_limit(BendingDirection::Lag), t.front().rotating, 1e-14));
  for (std::size_t i = 1; i < t.size(); ++i) {
    EXPECT_GT(t[i].rotating, t[i - 1].rotating);
    EXPECT_GT(t[i].rotating, t[i].nonrotating * 0.99);  // centrifugal stiffening
  }
  EXPECT_THROW(fig9_table(BendingDirection::Flap, 1.0, 0.5, 10), InvalidInput);
  EXPECT_THROW(fig9_table(BendingDirection::Flap, 0.0, 1.0, 1), InvalidInput);
}

TEST(RotatingModes, Paper1974ShapesOption) {
  // docs/validation.md: same frequencies and stiffnesses, even-numbered basis functions
  // sign-flipped.
  ExactModeOptions o;
  o.paper_1974_shapes = true;
  const ExactModes p = exact_rotating_modes(kOmegaF, kOmegaL, o);
  const ExactModes r = exact_rotating_modes(kOmegaF, kOmegaL);
  EXPECT_EQ(r.modes[Direction::Flap].stiffness, p.modes[Direction::Flap].stiffness);
  EXPECT_EQ(r.modes[Direction::Lag].stiffness, p.modes[Direction::Lag].stiffness);
  EXPECT_EQ(r.modes[Direction::Flap].omega, p.modes[Direction::Flap].omega);
  for (int j = 0; j < 5; ++j) {
    const double sign = (j % 2 == 0) ? 1.0 : -1.0;
    EXPECT_TRUE(RelClose(
        sign * r[Direction::Flap].coefficients(j, 0) / (r[Direction::Flap].coefficients(0, 0)),
        p[Direction::Flap].coefficients(j, 0) / p[Direction::Flap].coefficients(0, 0), 1e-14));
  }
  EXPECT_TRUE(RelClose(1.0, p.modes.shapes(Direction::Flap)[0]->value(0, 1.0), 1e-14));
  const double w74 = rayleigh_frequency(BendingDirection::Flap, *p.modes.shapes(Direction::Flap)[0],
                                        p.modes[Direction::Flap].stiffness);
  const double l74 = rayleigh_frequency(BendingDirection::Lag, *p.modes.shapes(Direction::Lag)[0],
                                        p.modes[Direction::Lag].stiffness);
  std::cout << "1974 shapes: Rayleigh flap frequency " << round_trip_text(w74)
            << " (true 1.175), lag " << round_trip_text(l74) << " (true 1.28303)\n";
  ::testing::Test::RecordProperty("rayleigh_flap_1974", round_trip_text(w74));
  // Rayleigh's principle: a shape that is not the first mode has a larger quotient.
  EXPECT_GT(w74, kOmegaF + 0.01);
  EXPECT_GT(l74, kOmegaL);
  // The design notes' independent claim (an implementation outside this code): "near 1.23".
  EXPECT_NEAR(1.23, w74, 0.01);
}

TEST(RotatingModes, UnreachableFrequenciesThrow) {
  const double flap_limit = centrifugal_limit(BendingDirection::Flap);
  const double lag_limit = centrifugal_limit(BendingDirection::Lag);
  EXPECT_GT(flap_limit, 1.0);
  EXPECT_LT(flap_limit, 1.03);
  EXPECT_TRUE(RelClose(std::sqrt(flap_limit * flap_limit - 1.0), lag_limit, 1e-12));
  try {
    exact_modes(1.0, kOmegaL);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_EQ("omega_flap", e.name());
    EXPECT_EQ("1", e.value());
    EXPECT_NE(std::string(e.what()).find(round_trip_text(flap_limit)), std::string::npos)
        << e.what();
  }
  try {
    exact_modes(kOmegaF, 0.2);  // below the 5-function lag limit 0.207...
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_EQ("omega_lag", e.name());
    EXPECT_NE(std::string(e.what()).find(round_trip_text(lag_limit)), std::string::npos)
        << e.what();
  }
  ExactModeOptions six;
  six.n_basis = 6;
  EXPECT_TRUE(RelClose(0.2, exact_modes(kOmegaF, 0.2, six)[Direction::Lag].omega[0], 1e-12));
  for (double bad : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    EXPECT_THROW(exact_modes(bad, kOmegaL), InvalidInput) << bad;
    EXPECT_THROW(exact_modes(kOmegaF, bad), InvalidInput) << bad;
  }
  try {
    exact_modes(std::nan(""), kOmegaL);
  } catch (const InvalidInput& e) {
    EXPECT_EQ("nan", e.value());
  }
  ExactModeOptions o;
  o.flap_modes = 6;
  EXPECT_THROW(exact_modes(kOmegaF, kOmegaL, o), InvalidInput);
  o = ExactModeOptions{};
  o.n_basis = 0;
  EXPECT_THROW(exact_modes(kOmegaF, kOmegaL, o), InvalidInput);
  o = ExactModeOptions{};
  o.e1_over_l = -0.1;
  EXPECT_THROW(exact_modes(kOmegaF, kOmegaL, o), InvalidInput);
}

TEST(RotatingModes, HingeOffsetRaisesTheCentrifugalLimit) {
  ExactModeOptions o;
  o.e1_over_l = 0.1;
  const double lim = centrifugal_limit(BendingDirection::Flap, o);
  EXPECT_GT(lim, centrifugal_limit(BendingDirection::Flap));
  // For fixed stiffness the offset adds centrifugal stiffening.
  const double k = 0.05;
  EXPECT_GT(rotating_frequencies(BendingDirection::Flap, k, o)[0],
            rotating_frequencies(BendingDirection::Flap, k)[0]);
}

}  // namespace
}  // namespace flaplag::rotating_modes_test
