// Rotating modes by cubic finite elements (blade/blade_elements.h).
//
// Expected values come from elsewhere than the code under test: polynomials the Hermite cubics
// must reproduce, the clamped-free boundary conditions, the uniform blade's Galerkin modes
// (another discretization of the same equations, converged to ~1e-8 in its first frequencies),
// and the orthogonality of modes in the mass.  The comparison with an independent extrapolated
// finite-element model of a tapered blade with a tip mass is in blade_properties_test.cpp.
#include "flaplag/blade/blade_elements.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "flaplag/blade/blade.h"
#include "flaplag/core/errors.h"
#include "test_util.h"

namespace flaplag::blade_elements_test {
namespace {

using flaplag::model::Direction;
using testing::AbsClose;
using testing::RelClose;

constexpr double kOmegaF = 1.175;  // the paper's typical blade
constexpr double kOmegaL = 1.28303;

// A Hermite-cubic shape through nodal values and slopes of a cubic is that cubic, with every
// derivative, on every element.
TEST(ElementModeShape, ReproducesACubicAndItsDerivatives) {
  auto f = [](int d, double x) {
    switch (d) {
      case 0:
        return 0.3 - 1.2 * x + 2.5 * x * x - 0.7 * x * x * x;
      case 1:
        return -1.2 + 5.0 * x - 2.1 * x * x;
      case 2:
        return 5.0 - 4.2 * x;
      default:
        return -4.2;
    }
  };
  const std::vector<double> nodes = {0.0, 0.1, 0.35, 0.4, 0.8, 1.0};
  std::vector<double> w, dw;
  for (double x : nodes) {
    w.push_back(f(0, x));
    dw.push_back(f(1, x));
  }
  const ElementModeShape shape(nodes, w, dw);
  for (int d = 0; d <= 3; ++d) {
    for (double x = 0.0; x <= 1.0; x += 1.0 / 64.0) {
      // The d-th derivative scales as 1/h^d: its rounding too.
      EXPECT_TRUE(AbsClose(f(d, x), shape.value(d, x), 1e-12 * std::pow(20.0, d)))
          << "d = " << d << ", x = " << x;
    }
  }
  EXPECT_THROW(shape.value(4, 0.5), InvalidInput);
}

TEST(ElementNodes, HoldTheStationsAndNoLongerElements) {
  BladeProperties b = uniform_blade();
  b.x0 = {0.0, 0.013, 0.5, 1.0};
  const std::vector<double> nodes = element_nodes(&b);
  for (double s : b.x0) {
    bool found = false;
    for (double x : nodes) found = found || x == s;
    EXPECT_TRUE(found) << s;
  }
  for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
    EXPECT_GT(nodes[i + 1], nodes[i]);
    EXPECT_LE(nodes[i + 1] - nodes[i], 1.0 / kElementsPerSpan + 1e-15);
  }
  EXPECT_EQ(static_cast<std::size_t>(kElementsPerSpan) + 1, element_nodes(nullptr).size());
}

ExactModeOptions three_and_three(double e1_over_l) {
  ExactModeOptions o;
  o.flap_modes = 3;
  o.lag_modes = 3;
  o.e1_over_l = e1_over_l;
  return o;
}

class UniformBladeElements : public ::testing::TestWithParam<double> {};

// The same blade by two discretizations.  They agree to the error of the coarser, the Galerkin
// basis: with 12 functions its first flap frequency at a given stiffness is 2.1e-6 per rev high
// (1.1e-5 with e1/l = 0.1; docs/validation.md, "Nonuniform blades"), so the stiffness that gives
// omega_F1 is 2e-5 (1.8e-4) relative low, and the higher frequencies and the shapes are off by a
// few 1e-6 (4e-5).  The tolerances are about three times those differences.
TEST_P(UniformBladeElements, AgreeWithTheGalerkinModesToTheirError) {
  ExactModeOptions o = three_and_three(GetParam());
  const double scale = GetParam() > 0.0 ? 6.0 : 1.0;
  const ExactModes el = element_rotating_modes(kOmegaF, kOmegaL, o);
  o.n_basis = kMaxBasisFunctions;
  const ExactModes g = exact_rotating_modes(kOmegaF, kOmegaL, o);
  std::printf("e1/l = %g: k_y %.3e, k_z %.3e, flap 2 %.3e, flap 3 %.3e, lag 2 %.3e relative\n",
              GetParam(),
              el.modes[Direction::Flap].stiffness / g.modes[Direction::Flap].stiffness - 1.0,
              el.modes[Direction::Lag].stiffness / g.modes[Direction::Lag].stiffness - 1.0,
              el[Direction::Flap].omega_all[1] / g[Direction::Flap].omega_all[1] - 1.0,
              el[Direction::Flap].omega_all[2] / g[Direction::Flap].omega_all[2] - 1.0,
              el[Direction::Lag].omega_all[1] / g[Direction::Lag].omega_all[1] - 1.0);
  EXPECT_TRUE(RelClose(g.modes[Direction::Flap].stiffness, el.modes[Direction::Flap].stiffness,
                       1e-4 * scale));
  EXPECT_TRUE(RelClose(g.modes[Direction::Lag].stiffness, el.modes[Direction::Lag].stiffness,
                       1e-6 * scale));
  // The requested first frequencies, to rounding.
  EXPECT_TRUE(RelClose(kOmegaF, el.modes[Direction::Flap].omega[0], 1e-14));
  EXPECT_TRUE(RelClose(kOmegaL, el.modes[Direction::Lag].omega[0], 1e-14));
  for (int i = 1; i < 3; ++i) {
    EXPECT_TRUE(
        RelClose(g[Direction::Flap].omega_all[i], el[Direction::Flap].omega_all[i], 2e-5 * scale))
        << "flap " << i + 1;
    EXPECT_TRUE(
        RelClose(g[Direction::Lag].omega_all[i], el[Direction::Lag].omega_all[i], 3e-7 * scale))
        << "lag " << i + 1;
  }
  // The shapes: the same tip-normalised modes.
  for (int i = 0; i < 3; ++i) {
    for (double x = 0.05; x < 1.0; x += 0.1) {
      EXPECT_TRUE(AbsClose(g.modes.shapes(Direction::Flap)[i]->value(0, x),
                           el.modes.shapes(Direction::Flap)[i]->value(0, x), 2e-4 * scale))
          << "flap " << i + 1 << " at " << x;
      EXPECT_TRUE(AbsClose(g.modes.shapes(Direction::Lag)[i]->value(0, x),
                           el.modes.shapes(Direction::Lag)[i]->value(0, x), 2e-4 * scale))
          << "lag " << i + 1 << " at " << x;
    }
  }
}

// Without rotation the uniform cantilever's frequencies are known in closed form,
// sqrt(k / mbar) beta_1^2: the elements' nonrotating first frequency at their own stiffness is it
// to their h^4 error, (beta_1 h)^4 / 720 ~ 2e-10.
TEST_P(UniformBladeElements, NonrotatingFrequencyIsTheClosedForm) {
  const ExactModes el = element_rotating_modes(kOmegaF, kOmegaL, three_and_three(GetParam()));
  const double b1 = cantilever_root(1);
  EXPECT_TRUE(RelClose(std::sqrt(el.modes[Direction::Flap].stiffness / 3.0) * b1 * b1,
                       el[Direction::Flap].omega_nonrotating, 1e-9));
  EXPECT_TRUE(RelClose(std::sqrt(el.modes[Direction::Lag].stiffness / 3.0) * b1 * b1,
                       el[Direction::Lag].omega_nonrotating, 1e-9));
}

INSTANTIATE_TEST_SUITE_P(RootOffsets, UniformBladeElements, ::testing::Values(0.0, 0.1));

// Clamped at the root, tip value 1, orthogonal in the mass (mbar = 3), on the mesh given.
TEST(UniformBladeElements, ModesAreClampedTipNormalisedAndOrthogonal) {
  const ExactModes el = element_rotating_modes(kOmegaF, kOmegaL, three_and_three(0.0));
  EXPECT_EQ(static_cast<std::size_t>(kElementsPerSpan) - 1, el.modes.mesh.size());
  EXPECT_EQ("exact", el.modes.kind);
  for (const auto* shapes : {&el.modes.shapes(Direction::Flap), &el.modes.shapes(Direction::Lag)}) {
    for (std::size_t i = 0; i < shapes->size(); ++i) {
      const ModeShape& s = *(*shapes)[i];
      EXPECT_EQ(0.0, s.value(0, 0.0));
      EXPECT_EQ(0.0, s.value(1, 0.0));
      EXPECT_TRUE(AbsClose(1.0, s.value(0, 1.0), 1e-14));
      for (std::size_t j = 0; j < i; ++j) {
        const ModeShape& o = *(*shapes)[j];
        const SpanRule rule = span_rule(0.0, 1.0, el.modes.mesh);
        double mij = 0.0, mii = 0.0;
        for (std::size_t q = 0; q < rule.x0.size(); ++q) {
          mij += rule.weight[q] * s.value(0, rule.x0[q]) * o.value(0, rule.x0[q]);
          mii += rule.weight[q] * s.value(0, rule.x0[q]) * s.value(0, rule.x0[q]);
        }
        EXPECT_LT(std::abs(mij), 1e-11 * mii) << i << " " << j;
      }
    }
  }
}

TEST(UniformBladeElements, RefusesWhatTheyCannotGive) {
  ExactModeOptions o = three_and_three(0.0);
  EXPECT_THROW(element_rotating_modes(1.0, kOmegaL, o), InvalidInput);  // below the k -> 0 limit
  EXPECT_THROW(element_rotating_modes(kOmegaF, -1.0, o), InvalidInput);
  EXPECT_THROW(element_stiffness_modes(o), InvalidInput);  // no table
  o.paper_1974_shapes = true;
  EXPECT_THROW(element_rotating_modes(kOmegaF, kOmegaL, o), InvalidInput);
  o.paper_1974_shapes = false;
  o.flap_modes = 13;
  EXPECT_THROW(element_rotating_modes(kOmegaF, kOmegaL, o), InvalidInput);
}

}  // namespace
}  // namespace flaplag::blade_elements_test
