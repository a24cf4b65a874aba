// Blade unit: assumed mode (eq 4.1), nonrotating cantilever functions, spanwise integrals
// (Appendices B, D), elastic coupling (Appendix E), error formatting.
//
// Reference values of the assumed-mode integrals are exact rationals (polynomial integrands,
// integrated symbolically by hand / with exact rational arithmetic); they are not outputs of the
// code under test.
#include "flaplag/blade/blade.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "flaplag/blade/rotating_modes.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "model_fixtures.h"
#include "test_util.h"

namespace flaplag::blade_test {
namespace {

using flaplag::model::Direction;
using model::AeroIntegral;
using model::Factor;
using model::FactorRef;
using model::Inner;
using model::StructuralIntegral;
using testing::AbsClose;
using testing::RelClose;
using namespace testing::fixtures;

StructuralIntegral structural(const char* name, int outer_mass, std::vector<FactorRef> outer,
                              Inner inner, int inner_mass, std::vector<FactorRef> inner_f) {
  StructuralIntegral s{name,
                       name,
                       outer_mass,
                       static_cast<int>(outer.size()),
                       {kNone, kNone, kNone, kNone},
                       inner,
                       inner_mass,
                       static_cast<int>(inner_f.size()),
                       {kNone, kNone, kNone, kNone},
                       ""};
  for (std::size_t i = 0; i < outer.size(); ++i) s.outer[i] = outer[i];
  for (std::size_t i = 0; i < inner_f.size(); ++i) s.inner_factors[i] = inner_f[i];
  return s;
}

// ---------------------------------------------------------------- assumed mode, eq 4.1

TEST(AssumedMode, BoundaryConditionsAndTipValue) {
  auto eta = assumed_mode_shape();
  EXPECT_EQ(0.0, eta->value(0, 0.0));
  EXPECT_EQ(0.0, eta->value(1, 0.0));
  EXPECT_EQ(0.0, eta->value(2, 1.0));
  EXPECT_EQ(0.0, eta->value(3, 1.0));
  EXPECT_TRUE(RelClose(1.0, eta->value(0, 1.0), 1e-15));
}

TEST(AssumedMode, MatchesEquation41AndDerivativesAreConsistent) {
  auto eta = assumed_mode_shape();
  for (double x : {0.0, 0.13, 0.5, 0.77, 1.0}) {
    const double eq41 = -(1.0 / 3.0) * (1.0 - 4.0 * x - std::pow(1.0 - x, 4));
    EXPECT_TRUE(AbsClose(eq41, eta->value(0, x), 1e-15)) << x;
  }
  const double h = 1e-5;
  for (double x : {0.2, 0.5, 0.8}) {
    for (int d = 0; d < 3; ++d) {
      const double fd = (eta->value(d, x + h) - eta->value(d, x - h)) / (2 * h);
      EXPECT_TRUE(AbsClose(fd, eta->value(d + 1, x), 1e-8)) << "d=" << d << " x=" << x;
    }
  }
  EXPECT_THROW(eta->value(4, 0.5), InvalidInput);
}

TEST(AssumedMode, ModeSet) {
  const ModeSet m = assumed_modes(1.175, 1.28303);
  EXPECT_EQ("assumed", m.kind);
  ASSERT_EQ(1u, m.shapes(Direction::Flap).size());
  ASSERT_EQ(1u, m.shapes(Direction::Lag).size());
  EXPECT_EQ(1.175, m[Direction::Flap].omega[0]);
  EXPECT_EQ(1.28303, m[Direction::Lag].omega[0]);
  EXPECT_EQ(0.0, m[Direction::Flap].stiffness);
  EXPECT_EQ(0.0, m[Direction::Lag].stiffness);
  EXPECT_THROW(assumed_modes(-1.0, 1.0), InvalidInput);
  EXPECT_THROW(assumed_modes(1.0, std::nan("")), InvalidInput);
}

// ---------------------------------------------------------------- cantilever functions

TEST(Cantilever, Roots) {
  const double known[] = {1.875104068711961, 4.694091132974175, 7.854757438237613,
                          10.99554073487547, 14.13716839104647};
  for (int j = 1; j <= 5; ++j) {
    EXPECT_TRUE(RelClose(known[j - 1], cantilever_root(j), 1e-14)) << "j=" << j;
  }
  for (int j = 1; j <= 20; ++j) {
    const double b = cantilever_root(j);
    // Frequency equation in the overflow-free form cos b + 1/cosh b = 0, to rounding of b.
    EXPECT_LT(std::abs(std::cos(b) + 1.0 / std::cosh(b)), 4e-16 * b) << "j=" << j;
    if (j >= 2) {
      EXPECT_LT(std::abs(b - (j - 0.5) * 3.141592653589793), 0.02) << "j=" << j;
    }
  }
  EXPECT_THROW(cantilever_root(0), InvalidInput);
}

TEST(Cantilever, BoundaryConditionsAndTipSign) {
  for (int j = 1; j <= 10; ++j) {
    auto phi = cantilever_mode(j);
    const double b = cantilever_root(j);
    EXPECT_TRUE(AbsClose(0.0, phi->value(0, 0.0), 1e-14)) << j;
    EXPECT_TRUE(AbsClose(0.0, phi->value(1, 0.0), 1e-14 * b)) << j;
    EXPECT_TRUE(AbsClose(0.0, phi->value(2, 1.0), 1e-13 * b * b)) << j;
    EXPECT_TRUE(AbsClose(0.0, phi->value(3, 1.0), 1e-13 * b * b * b)) << j;
    // Classical normalisation: tip value 2 (-1)^(j+1).
    EXPECT_TRUE(RelClose(j % 2 == 1 ? 2.0 : -2.0, phi->value(0, 1.0), 1e-13)) << j;
  }
}

TEST(Cantilever, MatchesDirectFormulaInLongDouble) {
  // The textbook formula in long double, with the root refined in long double: it loses about
  // log10(e^b) digits to cancellation, so it is a valid reference only for b <= ~17 (j <= 6).
  for (int j = 1; j <= 6; ++j) {
    long double b = cantilever_root(j);
    for (int it = 0; it < 3; ++it) {
      b -= (1.0L + std::cos(b) * std::cosh(b)) /
           (std::cos(b) * std::sinh(b) - std::sin(b) * std::cosh(b));
    }
    const long double sigma = (std::cosh(b) + std::cos(b)) / (std::sinh(b) + std::sin(b));
    auto phi = cantilever_mode(j);
    for (double x : {0.1, 0.37, 0.5, 0.81, 0.99}) {
      const long double bx = b * x;
      const long double d[4] = {
          std::cosh(bx) - std::cos(bx) - sigma * (std::sinh(bx) - std::sin(bx)),
          b * (std::sinh(bx) + std::sin(bx) - sigma * (std::cosh(bx) - std::cos(bx))),
          b * b * (std::cosh(bx) + std::cos(bx) - sigma * (std::sinh(bx) + std::sin(bx))),
          b * b * b * (std::sinh(bx) - std::sin(bx) - sigma * (std::cosh(bx) + std::cos(bx)))};
      for (int k = 0; k < 4; ++k) {
        const double scale = std::pow(static_cast<double>(b), k);
        EXPECT_TRUE(AbsClose(static_cast<double>(d[k]), phi->value(k, x), 1e-12 * scale))
            << "j=" << j << " d=" << k << " x=" << x;
      }
    }
  }
}

TEST(Cantilever, OrthonormalityAndCurvatureIntegrals) {
  const int n = 12;
  const SpanRule rule = span_rule(0.0, 1.0);
  std::vector<std::shared_ptr<const ModeShape>> phi;
  for (int j = 1; j <= n; ++j) phi.push_back(cantilever_mode(j));
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j <= i; ++j) {
      double m = 0.0;
      double k = 0.0;
      for (std::size_t q = 0; q < rule.x0.size(); ++q) {
        m += rule.weight[q] * phi[i]->value(0, rule.x0[q]) * phi[j]->value(0, rule.x0[q]);
        k += rule.weight[q] * phi[i]->value(2, rule.x0[q]) * phi[j]->value(2, rule.x0[q]);
      }
      const double b4 = std::pow(cantilever_root(i + 1), 4);
      const double tol = i < 8 ? 1e-13 : 1e-12;
      EXPECT_TRUE(AbsClose(i == j ? 1.0 : 0.0, m, tol)) << i << "," << j;
      EXPECT_TRUE(AbsClose(i == j ? b4 : 0.0, k, tol * b4)) << i << "," << j;
    }
  }
}

TEST(Cantilever, DerivativesConsistent) {
  const double h = 1e-6;
  for (int j : {1, 3, 8}) {
    auto phi = cantilever_mode(j);
    const double b = cantilever_root(j);
    for (double x : {0.25, 0.6, 0.95}) {
      for (int d = 0; d < 3; ++d) {
        const double fd = (phi->value(d, x + h) - phi->value(d, x - h)) / (2 * h);
        EXPECT_TRUE(AbsClose(fd, phi->value(d + 1, x), 1e-6 * std::pow(b, d + 2)))
            << "j=" << j << " d=" << d << " x=" << x;
      }
    }
  }
}

// ---------------------------------------------------------------- aerodynamic integrals

TEST(AeroIntegral, AssumedModeExactValues) {
  const ModeSet m = assumed_modes(1.175, 1.28303);
  const SpanGeometry unit;
  // F1 = int x^2 eta = 71/315;  F6 = int x eta eta' = 301/810  (l/R = 1, e1 = 0).
  EXPECT_TRUE(
      RelClose(71.0 / 315.0, aero_integral(aero("x^2 eta", 2, {kEta}), m, unit, 0, 1), 1e-14));
  EXPECT_TRUE(RelClose(301.0 / 810.0,
                       aero_integral(aero("x eta eta'", 1, {kEta, kEtaP}), m, unit, 0, 1), 1e-14));
  // Offset hinge, l/R < 1, tip loss: x = 1/20 + (19/20) x0 on [1/10, 97/100].
  SpanGeometry g;
  g.e1 = 0.05;
  g.lr = 0.95;
  g.tip_loss_a = 0.1;
  g.tip_loss_b = 0.97;
  EXPECT_TRUE(RelClose(0.2032798983095815392857,
                       aero_integral(aero("x^2 eta", 2, {kEta}), m, g, 0.1, 0.97), 1e-14));
  EXPECT_TRUE(
      RelClose(0.2142655818384214954790,
               aero_integral(aero("x^3 eta eta' gamma' gamma", 3, {kEta, kEtaP, kGammaP, kGamma}),
                             m, g, 0.1, 0.97),
               1e-14));
}

TEST(AeroIntegral, BadModeIndexNamesTheIntegral) {
  const ModeSet m = assumed_modes(1.175, 1.28303);
  const AeroIntegral a = aero("x eta2", 1, {FactorRef{Factor::Eta, 1}});
  try {
    aero_integral(a, m, SpanGeometry{}, 0.0, 1.0);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("x eta2"), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------- structural integrals

TEST(StructuralIntegral, AssumedModeExactValues) {
  const ModeSet m = assumed_modes(1.175, 1.28303);
  // M_F = 3 int eta^2 = 104/135
  EXPECT_TRUE(RelClose(
      104.0 / 135.0,
      structural_integral(structural("M_F1", 1, {kEta, kEta}, Inner::None, 0, {}), m, 0.0), 1e-14));
  // B3 = int eta' [int_x^1 3 gamma] ... with eta' squared: int eta' eta' [int_x^1 3 gamma] = 22/27
  const auto tail = structural("tail", 0, {kEtaP, kEtaP}, Inner::Tail, 1, {kGamma});
  EXPECT_TRUE(RelClose(22.0 / 27.0, structural_integral(tail, m, 0.0), 1e-14));
  // P_111 = int eta' eta' [int_x^1 3 gamma x1] = 1634/2457
  const auto p =
      structural("P_111", 0, {kEtaP, kEtaP}, Inner::Tail, 1, {kGamma, FactorRef{Factor::X0, 0}});
  EXPECT_TRUE(RelClose(1634.0 / 2457.0, structural_integral(p, m, 0.0), 1e-14));
  // B1 with e1/l = 1/10: int eta' [int_x^1 3 (x1 + 1/10)] = 74/75
  const auto b1 = structural("B1_1", 0, {kEtaP}, Inner::Tail, 1, {kArm});
  EXPECT_TRUE(RelClose(74.0 / 75.0, structural_integral(b1, m, 0.1), 1e-14));
  // Four outer factors times a two-factor tail: int 3 arm eta eta' [int_x^1 3 gamma'^2 x1]
  const auto q = structural("q", 1, {kArm, kEta, kEtaP}, Inner::Tail, 1,
                            {kGammaP, kGammaP, FactorRef{Factor::X0, 0}});
  EXPECT_TRUE(RelClose(53688233.0 / 45945900.0, structural_integral(q, m, 0.1), 1e-14));
}

TEST(StructuralIntegral, SwapOfIntegrationOrder) {
  // int_0^1 eta'eta' [int_x^1 3 gamma dx1] dx = int_0^1 3 gamma [int_0^x eta'eta' dx1] dx:
  // the tail and head nestings are evaluated on different point sets, so this checks both.
  const auto tail = structural("tail", 0, {kEtaP, kEtaP}, Inner::Tail, 1, {kGamma});
  const auto head = structural("head", 1, {kGamma}, Inner::Head, 0, {kEtaP, kEtaP});
  const ModeSet assumed = assumed_modes(1.175, 1.28303);
  EXPECT_TRUE(RelClose(22.0 / 27.0, structural_integral(head, assumed, 0.0), 1e-14));

  ExactModeOptions o;
  o.flap_modes = 3;
  o.lag_modes = 2;
  const ModeSet exact = exact_modes(1.175, 1.28303, o);
  const FactorRef e2p{Factor::EtaPrime, 2};
  const FactorRef g1{Factor::Gamma, 1};
  const auto tail2 = structural("tail2", 0, {kEtaP, e2p}, Inner::Tail, 1, {g1, kArm});
  const auto head2 = structural("head2", 1, {g1, kArm}, Inner::Head, 0, {kEtaP, e2p});
  const double a = structural_integral(tail2, exact, 0.05);
  const double b = structural_integral(head2, exact, 0.05);
  EXPECT_TRUE(RelClose(a, b, 1e-12, 1.0)) << a << " vs " << b;

  const std::vector<StructuralIntegral> list = {tail, head, tail2, head2};
  const auto all = structural_integrals(descriptor({}, list), exact, 0.05);
  EXPECT_EQ(a, all[2]);
  EXPECT_EQ(b, all[3]);
  EXPECT_TRUE(RelClose(all[0], all[1], 1e-13));
}

TEST(StructuralIntegral, InvalidInputs) {
  const ModeSet m = assumed_modes(1.175, 1.28303);
  const auto s = structural("M_F1", 1, {kEta, kEta}, Inner::None, 0, {});
  EXPECT_THROW(structural_integral(s, m, -0.1), InvalidInput);
  EXPECT_THROW(structural_integral(s, m, 0.0, 0.0), InvalidInput);
  const auto bad = structural("bad", 1, {FactorRef{Factor::GammaPrime, 3}}, Inner::None, 0, {});
  EXPECT_THROW(structural_integral(bad, m, 0.0), InvalidInput);
}

// ---------------------------------------------------------------- elastic coupling

TEST(ElasticCoupling, ZeroForAssumedModesAndAtZeroPitch) {
  const ModeSet assumed = assumed_modes(1.175, 1.28303);
  const ElasticCoupling a = elastic_coupling(assumed, 0.15);
  EXPECT_EQ(0.0, a.block(Direction::Flap, Direction::Flap).norm() +
                     a.block(Direction::Lag, Direction::Lag).norm() +
                     a.block(Direction::Flap, Direction::Lag).norm() +
                     a.block(Direction::Lag, Direction::Flap).norm());
  ExactModeOptions o;
  o.flap_modes = 2;
  o.lag_modes = 3;
  const ModeSet exact = exact_modes(1.175, 1.28303, o);
  const ElasticCoupling z = elastic_coupling(exact, 0.0);
  EXPECT_EQ(0.0, z.block(Direction::Flap, Direction::Flap).norm() +
                     z.block(Direction::Lag, Direction::Lag).norm() +
                     z.block(Direction::Flap, Direction::Lag).norm() +
                     z.block(Direction::Lag, Direction::Flap).norm());
  const ElasticCoupling n = no_elastic_coupling(exact);
  EXPECT_EQ(2, n.block(Direction::Flap, Direction::Flap).rows());
  EXPECT_EQ(3, n.block(Direction::Lag, Direction::Lag).rows());
  EXPECT_EQ(2, n.block(Direction::Flap, Direction::Lag).rows());
  EXPECT_EQ(3, n.block(Direction::Flap, Direction::Lag).cols());
  EXPECT_EQ(3, n.block(Direction::Lag, Direction::Flap).rows());
  EXPECT_EQ(2, n.block(Direction::Lag, Direction::Flap).cols());
}

TEST(ElasticCoupling, SymmetryValuesAndSign) {
  ExactModeOptions o;
  o.flap_modes = 2;
  o.lag_modes = 3;
  const ExactModes r = exact_rotating_modes(1.175, 1.28303, o);
  const double theta = 0.15;
  const ElasticCoupling e = elastic_coupling(r.modes, theta);
  ASSERT_EQ(2, e.block(Direction::Flap, Direction::Flap).rows());
  ASSERT_EQ(3, e.block(Direction::Lag, Direction::Lag).cols());
  EXPECT_LT((e.block(Direction::Flap, Direction::Flap) -
             e.block(Direction::Flap, Direction::Flap).transpose())
                .norm(),
            1e-12 * e.block(Direction::Flap, Direction::Flap).norm());
  EXPECT_LT((e.block(Direction::Lag, Direction::Lag) -
             e.block(Direction::Lag, Direction::Lag).transpose())
                .norm(),
            1e-12 * e.block(Direction::Lag, Direction::Lag).norm());
  EXPECT_EQ(0.0, (e.block(Direction::Lag, Direction::Flap) -
                  e.block(Direction::Flap, Direction::Lag).transpose())
                     .norm());

  // Independent value: int eta_i'' gamma_m'' = sum_j c_j d_j beta_j^4 (orthogonality of phi'').
  const double dk = r.modes[Direction::Lag].stiffness - r.modes[Direction::Flap].stiffness;
  ASSERT_GT(dk, 0.0);  // lag stiffer than flap for this blade
  for (int i = 0; i < 2; ++i) {
    for (int m = 0; m < 3; ++m) {
      double cc = 0.0;
      for (int j = 0; j < 5; ++j) {
        cc += r[Direction::Flap].coefficients(j, i) * r[Direction::Lag].coefficients(j, m) *
              std::pow(cantilever_root(j + 1), 4);
      }
      EXPECT_TRUE(RelClose(dk * std::sin(theta) * std::cos(theta) * cc,
                           e.block(Direction::Flap, Direction::Lag)(i, m), 1e-12, 1e-3))
          << i << "," << m;
    }
  }
  // (EI)_z > (EI)_y: E^s > 0 on the diagonal; E^cs has the sign of theta.
  EXPECT_GT(e.block(Direction::Flap, Direction::Flap)(0, 0), 0.0);
  EXPECT_GT(e.block(Direction::Lag, Direction::Lag)(0, 0), 0.0);
  EXPECT_GT(e.block(Direction::Flap, Direction::Lag)(0, 0), 0.0);
  const ElasticCoupling neg = elastic_coupling(r.modes, -theta);
  EXPECT_TRUE(RelClose(-e.block(Direction::Flap, Direction::Lag)(0, 0),
                       neg.block(Direction::Flap, Direction::Lag)(0, 0), 1e-15));
  EXPECT_TRUE(RelClose(e.block(Direction::Flap, Direction::Flap)(0, 0),
                       neg.block(Direction::Flap, Direction::Flap)(0, 0), 1e-15));
  EXPECT_THROW(elastic_coupling(r.modes, std::nan("")), InvalidInput);
}

// ---------------------------------------------------------------- errors

TEST(FormatValue, RoundTripAndNonFinite) {
  EXPECT_EQ("nan", round_trip_text(std::nan("")));
  EXPECT_EQ("inf", round_trip_text(HUGE_VAL));
  EXPECT_EQ("-inf", round_trip_text(-HUGE_VAL));
  EXPECT_EQ("0.5", round_trip_text(0.5));
  EXPECT_EQ("0.1", round_trip_text(0.1));  // shortest form, not %.17g
  EXPECT_EQ(1.175, std::stod(round_trip_text(1.175)));
}

}  // namespace
}  // namespace flaplag::blade_test
