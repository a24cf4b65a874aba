// The inflow models (rotor/inflow.h): the values of lambda, their validation, and that the
// system builder evaluates the hover equilibrium at lambda(0) and the system at mu at lambda(mu).
#include "flaplag/rotor/inflow.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "flaplag/analysis.h"
#include "flaplag/core/errors.h"
#include "flaplag/rotor/system_builder.h"
#include "test_util.h"

namespace flaplag::inflow_test {
namespace {

using detail::SystemBuilder;
using testing::RelClose;

// Eq 2.25 with the numbers put in by hand: lambda - mu tan(alpha) - C_T / (2 |(mu, lambda)|).
double momentum_residual(double lam, double ct, double mu, double alpha) {
  return lam - mu * std::tan(alpha) - ct / (2.0 * std::sqrt(mu * mu + lam * lam));
}

TEST(InflowModel, EachKindGivesItsLambda) {
  const RotorParameters p;  // the typical case
  for (double mu : {0.0, 0.3, 1.2}) {
    EXPECT_EQ(InflowModel::Uniform().lambda(p, mu), hover_inflow(p)) << mu;  // eq 2.24, held
    EXPECT_EQ(InflowModel::Given(0.0375).lambda(p, mu), 0.0375) << mu;
  }
  const double ct = 0.005, alpha = 0.04;
  const InflowModel m = InflowModel::Momentum(ct, alpha);
  EXPECT_EQ(m.lambda(p, 0.0), std::sqrt(0.5 * ct));  // hover: lambda = C_T / (2 lambda)
  for (double mu : {0.05, 0.3, 1.2}) {
    const double lam = m.lambda(p, mu);
    EXPECT_LT(std::abs(momentum_residual(lam, ct, mu, alpha)), 1e-15) << mu << ": " << lam;
    EXPECT_EQ(lam, momentum_inflow(ct, mu, alpha)) << mu;
  }
  // The induced part falls with mu (lambda - mu tan(alpha) ~ C_T / (2 mu) at high speed).
  EXPECT_GT(m.lambda(p, 0.1) - 0.1 * std::tan(alpha), m.lambda(p, 0.4) - 0.4 * std::tan(alpha));
  EXPECT_TRUE(RelClose(ct / 2.4, m.lambda(p, 1.2) - 1.2 * std::tan(alpha), 1e-3));
}

TEST(InflowModel, BadModelsNameTheField) {
  auto name_of = [](const InflowModel& m) {
    const std::optional<InvalidInput> e = m.Validate();
    return e ? e->name() : std::string("(valid)");
  };
  EXPECT_EQ(name_of(InflowModel::Uniform()), "(valid)");
  EXPECT_EQ(name_of(InflowModel::Momentum(0.0, 0.0)), "thrust_coefficient");
  EXPECT_EQ(name_of(InflowModel::Momentum(0.2, 0.0)), "thrust_coefficient");
  EXPECT_EQ(name_of(InflowModel::Momentum(0.005, 1.6)), "shaft_angle");
  EXPECT_EQ(name_of(InflowModel::Given(std::numeric_limits<double>::quiet_NaN())), "inflow");
  EXPECT_THROW(InflowModel::Momentum(0.005, 0.0).lambda(RotorParameters{}, -0.1), InvalidInput);
  EXPECT_THROW(InflowModel::Given(INFINITY).lambda(RotorParameters{}, 0.1), InvalidInput);
}

// A model that records the inflow each coefficient evaluation is given, by mu, and otherwise is
// the paper's model.
std::map<double, double>& seen() {
  static std::map<double, double> s;
  return s;
}
const model::ModelDescriptor& paper() { return find_model("paper"); }
void recording_coefficients(const model::CoefficientInputs& in,
                            const model::CoefficientOutputs& out) {
  seen()[in.mu] = in.inflow;
  paper().coefficients(in, out);
}
void recording_equilibrium(const model::CoefficientInputs& in,
                           const model::EquilibriumOutputs& out) {
  seen()[-1.0 - in.mu] = in.inflow;  // the hover equilibrium, kept apart from the systems
  paper().equilibrium(in, out);
}

TEST(InflowModel, TheBuilderUsesLambdaOfMuAndTheHoverEquilibriumLambdaOfZero) {
  model::ModelDescriptor m = paper();
  m.coefficients = recording_coefficients;
  m.equilibrium = recording_equilibrium;
  const RotorParameters p;
  const double ct = 0.006, alpha = 0.0;
  seen().clear();
  const SystemBuilder b(p, m, InflowModel::Momentum(ct, alpha));
  EXPECT_EQ(seen().at(-1.0), std::sqrt(0.5 * ct));  // the equilibrium, at mu = 0
  EXPECT_EQ(b.hover().inflow, std::sqrt(0.5 * ct));
  for (double mu : {0.2, 0.7}) {
    b.system(mu);
    EXPECT_EQ(seen().at(mu), momentum_inflow(ct, mu, alpha)) << mu;
    EXPECT_EQ(b.inflow(mu), momentum_inflow(ct, mu, alpha)) << mu;
  }
  // In hover the momentum model is the given lambda sqrt(C_T / 2), bit for bit.
  const SystemBuilder given(p, paper(), InflowModel::Given(std::sqrt(0.5 * ct)));
  const SystemBuilder momentum(p, paper(), InflowModel::Momentum(ct, alpha));
  EXPECT_EQ(given.system(0.0).A(1.0), momentum.system(0.0).A(1.0));
  EXPECT_EQ(given.system(0.0).f(1.0), momentum.system(0.0).f(1.0));
  EXPECT_NE(given.system(0.3).f(1.0), momentum.system(0.3).f(1.0));  // lambda(0.3) < lambda(0)
}

// An Analysis at fixed controls takes the inflow model of its operating condition; with a trim,
// any model but eq 2.24 is refused (each trim has its own eq 2.25 inflow).
TEST(InflowModel, AnAnalysisTakesItFromItsCondition) {
  OperatingCondition c;
  c.inflow = InflowModel::Momentum(0.005, 0.0);
  const Analysis an(RotorParameters{}, {}, c);
  EXPECT_EQ(an.hover().inflow, std::sqrt(0.5 * 0.005));
  c.inflow = InflowModel::Momentum(-1.0, 0.0);
  try {
    Analysis(RotorParameters{}, {}, c);
    ADD_FAILURE() << "a negative C_T accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), "thrust_coefficient") << e.what();
  }
}

}  // namespace
}  // namespace flaplag::inflow_test
