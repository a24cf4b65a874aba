// The paper's exact-mode results (Figs 10-14, Section 4.3): exact rotating modes, elastic
// coupling on unless noted, theta = 0.15, gamma = 10 unless noted, Hsu K = 50, J = 4 (the
// paper's method).
//
// Two things are checked for every case, and they are deliberately different in kind:
//  (a) With the correct rotating modes (the default) flaplag does NOT reproduce the paper (see
//      docs/validation.md).  Those numbers are regression pins: computed once by flaplag, stated
//      here with the paper's value alongside, tolerance 2e-3 on mu_c and omega.  They are not
//      tuned to anything.
//  (b) With the 1974 shapes (RotorParameters::paper_1974_shapes, docs/validation.md) flaplag is
//  compared
//      with the paper's printed numbers: +-0.01 on mu_c, +-0.005 on omega.  Three numbers miss
//      those tolerances; each case says by how much and why, the test asserts the documented
//      size of the miss, and docs/validation.md discusses them.  No tolerance was widened to
//      make a case pass silently.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/blade/blade.h"
#include "flaplag/blade/rotating_modes.h"
#include "test_util.h"

namespace exact_modes_paper_test {

using flaplag::Analysis;
using flaplag::CriticalOptions;
using flaplag::CriticalResult;
using flaplag::ModeKind;
using flaplag::RotorParameters;
using flaplag::TransitionMethod;
using flaplag::TransitionOptions;
using flaplag::model::Direction;
using flaplag::testing::AbsClose;

namespace {

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();  // "stable up to mu = 2"
constexpr double kPinTol = 2e-3;      // regression pins (mu_c and omega)
constexpr double kPaperMuTol = 0.01;  // paper's figures are read to ~3 digits
constexpr double kPaperOmegaTol = 0.005;

TransitionOptions hsu() {
  return TransitionOptions::Paper();  // K = 50, J = 4 (paper 4.2)
}

// The reference: Magnus with automatically chosen, error-controlled steps.
TransitionOptions magnus() {
  TransitionOptions o;
  o.method = TransitionMethod::Magnus4;
  return o;
}

RotorParameters exact_case(double theta, double lock, bool coupling, bool shapes_1974) {
  RotorParameters p;
  p.modes = ModeKind::Exact;
  p.theta = theta;
  p.gamma = lock;
  p.elastic_coupling = coupling;
  p.paper_1974_shapes = shapes_1974;
  p.basis = flaplag::kPaperBasis;  // the paper's five cantilever functions (4.1(b))
  return p;
}

CriticalResult critical(const RotorParameters& p, const TransitionOptions& o = hsu()) {
  CriticalOptions c;  // mu_max = 2, scan step 0.01
  return Analysis(p, o).critical(c);
}

// Largest real part among the lag exponents ("lag", and "lag2", ... with several modes).
double lag_zeta(const Analysis& an, double mu) {
  const auto pt = an.point(mu);
  double z = -std::numeric_limits<double>::infinity();
  for (const auto& e : pt.exponents) {
    if (e.label.rfind("lag", 0) == 0) z = std::max(z, e.zeta);
  }
  return z;
}

void expect_pin(const CriticalResult& r, double mu_c, double omega, const std::string& what) {
  SCOPED_TRACE(what);
  if (std::isnan(mu_c)) {
    EXPECT_FALSE(r.mu_c.has_value())
        << "pinned as stable up to mu = 2, found mu_c = " << r.mu_c.value_or(-1.0);
    return;
  }
  ASSERT_TRUE(r.mu_c.has_value()) << r.message;
  EXPECT_EQ(flaplag::InstabilityKind::Flutter, r.kind);
  EXPECT_EQ(0u, r.mode.rfind("lag", 0)) << r.mode;
  EXPECT_TRUE(AbsClose(mu_c, r.mu_c.value_or(-1.0), kPinTol));
  EXPECT_TRUE(AbsClose(omega, r.omega, kPinTol));
}

// ------------------------------------------------------------------ the paper's cases

struct PaperCase {
  const char* name;
  double theta, lock;
  bool coupling;
  double paper_mu, paper_omega;  // NaN omega: the paper gives none
  double pin_mu, pin_omega;      // flaplag, correct modes (NaN: stable up to mu = 2)
  double pin74_mu, pin74_omega;  // flaplag, 1974 shapes
  // Documented misses of the 1974-shape result against the paper (0: within the tolerances).
  double known_mu_miss, known_omega_miss;
};

std::string case_name(const ::testing::TestParamInfo<PaperCase>& info) { return info.param.name; }

// Readable ctest names instead of gtest's byte dump.
void PrintTo(const PaperCase& c, std::ostream* os) { *os << c.name; }

class PaperExactModes : public ::testing::TestWithParam<PaperCase> {};

// (a) Correct modes: regression pins.  The paper's value is in the case table for reference.
TEST_P(PaperExactModes, CorrectModesPinnedFlaplagValue) {
  const PaperCase& c = GetParam();
  expect_pin(
      critical(exact_case(c.theta, c.lock, c.coupling, false)), c.pin_mu, c.pin_omega,
      std::string(c.name) + ", correct modes (paper mu_c " + std::to_string(c.paper_mu) + ")");
}

// (b) 1974 shapes: the paper's numbers, plus a pin of what flaplag computes with them.
TEST_P(PaperExactModes, Paper1974ShapesReproduceThePaper) {
  const PaperCase& c = GetParam();
  const auto r = critical(exact_case(c.theta, c.lock, c.coupling, true));
  expect_pin(r, c.pin74_mu, c.pin74_omega, std::string(c.name) + ", 1974 shapes (pin)");
  ASSERT_TRUE(r.mu_c.has_value());
  if (c.known_mu_miss == 0.0) {
    EXPECT_TRUE(AbsClose(c.paper_mu, r.mu_c.value_or(-1.0), kPaperMuTol)) << "paper mu_c";
  } else {
    // A known, documented miss: assert its size so that it cannot grow (or vanish) unnoticed.
    EXPECT_TRUE(AbsClose(c.known_mu_miss, r.mu_c.value_or(-1.0) - c.paper_mu, kPinTol))
        << "known mu_c miss";
  }
  if (!std::isnan(c.paper_omega)) {
    if (c.known_omega_miss == 0.0) {
      EXPECT_TRUE(AbsClose(c.paper_omega, r.omega, kPaperOmegaTol)) << "paper omega";
    } else {
      EXPECT_TRUE(AbsClose(c.known_omega_miss, r.omega - c.paper_omega, kPinTol))
          << "known omega miss";
    }
  }
}

// The paper's mu_c lies where flaplag's (1974-shape) lag exponent is within 1e-3 per rev of
// zero.  This is the meaningful comparison where the exponent crosses zero at a shallow angle
// (theta = 0.05, gamma = 5: dzeta/dmu ~ 0.006-0.015, so 1e-3 in zeta is 0.07-0.17 in mu).  It
// discriminates: with the 1974 shapes |zeta| <= 0.0008 at every paper mu_c, with the correct
// modes zeta is -0.0024 ... -0.0123 there.
TEST_P(PaperExactModes, Paper1974ShapesLagExponentNearZeroAtThePapersMuC) {
  const PaperCase& c = GetParam();
  const Analysis an(exact_case(c.theta, c.lock, c.coupling, true), hsu());
  EXPECT_LT(std::abs(lag_zeta(an, c.paper_mu)), 1e-3);
}

// Paper values from Section 4.3 (Figs 10, 13, 14); the pins are flaplag's own numbers.
const PaperCase kPaperCases[] = {
    // Fig 10, exact modes without elastic coupling: paper 0.653 (no omega given).
    {"Fig10_NoCoupling_Paper0653", 0.15, 10.0, false, 0.653, kNone,  //
     0.788898, 1.285983, 0.660746, 1.285949, 0.0, 0.0},
    // Fig 10 / Fig 14 gamma = 10: with elastic coupling, paper 0.583, omega 1.295.
    {"Fig10_Coupling_Paper0583", 0.15, 10.0, true, 0.583, 1.295,  //
     0.803304, 1.296057, 0.585498, 1.294711, 0.0, 0.0},
    // Fig 13, theta = 0.05: paper 1.435, omega 1.279.  1974 shapes: 1.4631 (+0.028): the lag
    // exponent stays within 0.0015 of zero from mu = 1.0 to 1.5 (slope ~0.006 per unit mu at
    // the crossing), so 2e-4 in zeta moves mu_c by 0.03.  Correct modes: stable to mu = 2.
    {"Fig13_Theta005_Paper1435", 0.05, 10.0, true, 1.435, 1.279,  //
     kNone, kNone, 1.463139, 1.278901, 0.028139, 0.0},
    // Fig 13, theta = 0.30: paper 0.535, omega 1.332.  1974 shapes: mu_c 0.5356 agrees; omega
    // 1.3244 is 0.0076 low.  omega rises ~0.1 per unit mu here, and flaplag reaches 1.332 at
    // mu ~ 0.6: the paper's (mu_c, omega) pair is not a point of one flaplag curve.
    {"Fig13_Theta030_Paper0535", 0.30, 10.0, true, 0.535, 1.332,  //
     0.687404, 1.332463, 0.535644, 1.324428, 0.0, -0.007572},
    // Fig 14, gamma = 5: paper 1.425, omega 1.283.  1974 shapes: 1.3701 (-0.055), omega agrees;
    // shallow crossing again (dzeta/dmu ~ 0.012).  Correct modes: stable to mu = 2.
    {"Fig14_Gamma5_Paper1425", 0.15, 5.0, true, 1.425, 1.283,  //
     kNone, kNone, 1.370068, 1.282979, -0.054932, 0.0},
    // Fig 14, gamma = 15: paper 0.568, omega 1.294.
    {"Fig14_Gamma15_Paper0568", 0.15, 15.0, true, 0.568, 1.294,  //
     0.729627, 1.301918, 0.573014, 1.296127, 0.0, 0.0},
};

INSTANTIATE_TEST_SUITE_P(Section43, PaperExactModes, ::testing::ValuesIn(kPaperCases), case_name);

// The paper's method (Hsu K = 50, J = 4) against the 4th-order Magnus reference, once, for
// the typical case with both shape sets: the discretisation error is far below the paper's
// reading accuracy here (at mu ~ 1.46 it grows to ~5e-3; docs/validation.md).
TEST(PaperExactModesMethod, HsuAgreesWithMagnusForTheTypicalCase) {
  for (bool shapes_1974 : {false, true}) {
    SCOPED_TRACE(shapes_1974 ? "1974 shapes" : "correct modes");
    const RotorParameters p = exact_case(0.15, 10.0, true, shapes_1974);
    const auto h = critical(p, hsu());
    const auto m = critical(p, magnus());
    ASSERT_TRUE(h.mu_c.has_value() && m.mu_c.has_value());
    EXPECT_TRUE(AbsClose(m.mu_c.value_or(-1.0), h.mu_c.value_or(-1.0), 1e-3));
    EXPECT_TRUE(AbsClose(m.omega, h.omega, 1e-3));
  }
}

// ------------------------------------------------------------------ Fig 11: reversed flow
//
// The paper: "for this particular case the effects of reversed flow are negligible for
// mu < 0.6 and start being important for mu > 0.8"; with reversed flow the instability occurs
// at a higher mu; "the difference in mu_c ... for mu = 1.0 is approximately 7 %".  The case of
// Fig 11 is not stated; the text around it is the typical case.  Testable content:
//  - |zeta_rf - zeta_norf| negligible (< 2e-4, 3 % of the hover lag damping) at mu <= 0.6,
//  - without reversed flow the lag mode is less stable at mu = 0.8 and 1.0 (conservative),
//  - mu_c with and without reversed flow (pinned; the ~7 % is discussed in docs/validation.md:
//    flaplag's correct modes give -6.2 %, the 1974 shapes +0.5 % for the typical case).
struct ReversedFlowCase {
  const char* name;
  bool shapes_1974;
  double mu_c_rf, mu_c_norf;
};

// Readable ctest names instead of gtest's byte dump.
void PrintTo(const ReversedFlowCase& c, std::ostream* os) { *os << c.name; }

class FigureEleven : public ::testing::TestWithParam<ReversedFlowCase> {};

TEST_P(FigureEleven, ReversedFlowNegligibleBelow06AndStabilizingAbove08) {
  const ReversedFlowCase& c = GetParam();
  RotorParameters p = exact_case(0.15, 10.0, true, c.shapes_1974);
  const Analysis with(p, hsu());
  p.reversed_flow = false;
  const Analysis without(p, hsu());
  for (double mu : {0.2, 0.4, 0.6}) {
    EXPECT_LT(std::abs(lag_zeta(with, mu) - lag_zeta(without, mu)), 2e-4) << "mu = " << mu;
  }
  for (double mu : {0.8, 1.0}) {
    EXPECT_GT(lag_zeta(without, mu), lag_zeta(with, mu) + 1e-3) << "mu = " << mu;
  }
  const auto rf = with.critical({});
  const auto norf = without.critical({});
  expect_pin(rf, c.mu_c_rf, rf.omega, "with reversed flow");
  expect_pin(norf, c.mu_c_norf, norf.omega, "without reversed flow");
}

const ReversedFlowCase kReversedFlowCases[] = {
    // correct modes: 0.8033 -> 0.7535 without reversed flow (-6.2 %)
    {"CorrectModes", false, 0.803304, 0.753484},
    // 1974 shapes: 0.5855 -> 0.5887 (+0.5 %: mu_c < 0.6, where reversed flow is negligible)
    {"Paper1974Shapes", true, 0.585498, 0.588700},
};

INSTANTIATE_TEST_SUITE_P(Typical, FigureEleven, ::testing::ValuesIn(kReversedFlowCases),
                         [](const ::testing::TestParamInfo<ReversedFlowCase>& i) {
                           return std::string(i.param.name);
                         });

// ------------------------------------------------------------------ elastic coupling

// Appendix E: every coupling term carries sin(theta), so at theta = 0 the coupled and the
// uncoupled exact-mode systems are the same system, bit for bit.
TEST(ElasticCouplingInTheAnalysis, VanishesAtZeroPitch) {
  for (bool shapes_1974 : {false, true}) {
    SCOPED_TRACE(shapes_1974 ? "1974 shapes" : "correct modes");
    const Analysis on(exact_case(0.0, 10.0, true, shapes_1974), hsu());
    const Analysis off(exact_case(0.0, 10.0, false, shapes_1974), hsu());
    EXPECT_EQ(on.hover().q0, off.hover().q0);
    EXPECT_EQ(on.hover().A0, off.hover().A0);
    for (double mu : {0.3, 1.2}) {
      const auto a = on.system(mu);
      const auto b = off.system(mu);
      ASSERT_EQ(2u, a.sets.size());  // normal and the reversed-flow sector
      ASSERT_EQ(a.sets.size(), b.sets.size());
      for (std::size_t k = 0; k < a.sets.size(); ++k) {
        ASSERT_EQ(a.sets[k].A.size(), b.sets[k].A.size());
        for (std::size_t h = 0; h < a.sets[k].A.size(); ++h)
          EXPECT_EQ(a.sets[k].A[h], b.sets[k].A[h])
              << "mu = " << mu << ", set " << k << ", harmonic " << h;
      }
    }
    const auto rc = on.critical({});
    const auto ru = off.critical({});
    EXPECT_EQ(rc.mu_c.has_value(), ru.mu_c.has_value());
    EXPECT_EQ(rc.mu_c.value_or(-1.0), ru.mu_c.value_or(-1.0));
  }
}

// ... and at theta = 0.15 it is not negligible: it moves mu_c (Fig 10: 0.653 -> 0.583 in the
// paper; flaplag 0.789 -> 0.803 with correct modes, 0.661 -> 0.585 with the 1974 shapes).
TEST(ElasticCouplingInTheAnalysis, ChangesTheSystemAtTheTypicalPitch) {
  const Analysis on(exact_case(0.15, 10.0, true, false), hsu());
  const Analysis off(exact_case(0.15, 10.0, false, false), hsu());
  EXPECT_GT((on.hover().A0 - off.hover().A0).norm(), 1e-3);
}

// The 1974 sign slip flips the even-numbered cantilever functions in the shapes.  Because the
// functions are orthonormal (int phi_i phi_j = delta_ij) and their curvatures orthogonal
// (int phi_i'' phi_j'' = beta_j^4 delta_ij), scale-free ratios of the generalized mass and the
// curvature integrals behind E^s, E^cs are unchanged by it: the slip cannot be seen in the
// masses or in the elastic coupling, only in the aerodynamic and tension integrals (x-weighted,
// slopes, products of three shapes).  docs/validation.md lists those.
TEST(Paper1974Shapes, MassAndCouplingRatiosUnchangedAerodynamicIntegralsChanged) {
  const auto correct = Analysis(exact_case(0.15, 10.0, true, false), hsu());
  const auto slip = Analysis(exact_case(0.15, 10.0, true, true), hsu());
  const auto& mc = correct.modes();
  const auto& ms = slip.modes();
  auto integral = [](const flaplag::ModeShape& a, int da, const flaplag::ModeShape& b, int db) {
    const auto rule = flaplag::span_rule(0.0, 1.0);
    double s = 0.0;
    for (std::size_t q = 0; q < rule.x0.size(); ++q) {
      s += rule.weight[q] * a.value(da, rule.x0[q]) * b.value(db, rule.x0[q]);
    }
    return s;
  };
  const auto& fc = *mc.shapes(Direction::Flap)[0];
  const auto& lc = *mc.shapes(Direction::Lag)[0];
  const auto& fs = *ms.shapes(Direction::Flap)[0];
  const auto& ls = *ms.shapes(Direction::Lag)[0];
  // int eta''^2 / int eta^2, int gamma''^2 / int gamma^2, (int eta'' gamma'')^2 / (...)
  EXPECT_TRUE(flaplag::testing::RelClose(integral(fc, 2, fc, 2) / integral(fc, 0, fc, 0),
                                         integral(fs, 2, fs, 2) / integral(fs, 0, fs, 0), 1e-10));
  EXPECT_TRUE(flaplag::testing::RelClose(integral(lc, 2, lc, 2) / integral(lc, 0, lc, 0),
                                         integral(ls, 2, ls, 2) / integral(ls, 0, ls, 0), 1e-10));
  const double xc = integral(fc, 2, lc, 2);
  const double xs = integral(fs, 2, ls, 2);
  EXPECT_TRUE(flaplag::testing::RelClose(
      xc * xc / (integral(fc, 0, fc, 0) * integral(lc, 0, lc, 0)),
      xs * xs / (integral(fs, 0, fs, 0) * integral(ls, 0, ls, 0)), 1e-10));
  // An aerodynamic integral, tip-normalised: F8 = int x eta^2 / int eta^2 changes (0.7911
  // correct, 0.8216 with the slip: the flipped shape has more of its mass outboard).
  auto x_weighted = [](const flaplag::ModeShape& a) {
    const auto rule = flaplag::span_rule(0.0, 1.0);
    double s = 0.0, m = 0.0;
    for (std::size_t q = 0; q < rule.x0.size(); ++q) {
      const double v = a.value(0, rule.x0[q]);
      s += rule.weight[q] * rule.x0[q] * v * v;
      m += rule.weight[q] * v * v;
    }
    return s / m;
  };
  EXPECT_GT(std::abs(x_weighted(fs) - x_weighted(fc)), 0.02);
}

// ------------------------------------------------------------------ convergence in modes

// mu_c of the typical case (theta = 0.15, gamma = 10, correct modes, elastic coupling) with
// M flap x N lag modes; pinned (docs/validation.md has the whole table).  A second flap mode
// moves mu_c from 0.80 to 1.40 (0.79 -> 0.96 without coupling, so the elastic coupling of
// flap 2 with the lag mode takes part) -- the paper's remark that stability boundaries are
// sensitive to the number of degrees of freedom.
struct ModesCase {
  const char* name;
  int flap, lag;
  bool coupling, shapes_1974;
  double mu_c, omega;
};

// Readable ctest names instead of gtest's byte dump.
void PrintTo(const ModesCase& c, std::ostream* os) { *os << c.name; }

class ModeConvergence : public ::testing::TestWithParam<ModesCase> {};

TEST_P(ModeConvergence, PinnedCriticalAdvanceRatio) {
  const ModesCase& c = GetParam();
  RotorParameters p = exact_case(0.15, 10.0, c.coupling, c.shapes_1974);
  p.model = flaplag::find_model("paper", c.flap, c.lag).name;
  const Analysis an(p, hsu());
  ASSERT_EQ(c.flap, an.model().flap_modes);
  ASSERT_EQ(c.lag, an.model().lag_modes);
  expect_pin(an.critical({}), c.mu_c, c.omega, c.name);
}

const ModesCase kModesCases[] = {
    {"Paper2x1_Coupling", 2, 1, true, false, 1.396544, 1.286947},
    {"Paper1x2_Coupling", 1, 2, true, false, 0.805401, 1.296129},
    {"Paper2x2_Coupling", 2, 2, true, false, 1.470681, 1.290811},
    {"Paper2x2_NoCoupling", 2, 2, false, false, 0.960180, 1.281226},
    {"Paper2x2_1974Shapes", 2, 2, true, true, 0.733163, 1.298087},
};

INSTANTIATE_TEST_SUITE_P(Typical, ModeConvergence, ::testing::ValuesIn(kModesCases),
                         [](const ::testing::TestParamInfo<ModesCase>& i) {
                           return std::string(i.param.name);
                         });

}  // namespace

// Fig 12 (correct modes + coupling): lag structural damping raises mu_c steeply up to
// eta_SL ~ 0.02, then the gain levels off.  Checked as monotonic growth and as an average slope
// over [0, 0.02] at least twice that over [0.02, 0.05] (flaplag: 0.803, 1.318, 1.478, 1.592,
// 1.777; slopes 34 and 10 per unit eta_SL).
TEST(FigureTwelve, LagDampingRaisesMuCriticalSteeplyThenLevelsOff) {
  std::vector<double> mu;
  for (double eta : {0.0, 0.01, 0.02, 0.03, 0.05}) {
    RotorParameters p = exact_case(0.15, 10.0, true, false);
    p.damping_lag = eta;
    const auto c = critical(p);
    ASSERT_TRUE(c.mu_c.has_value()) << "eta_SL = " << eta;
    EXPECT_EQ(c.mode, "lag");
    mu.push_back(c.mu_c.value_or(-1.0));
  }
  for (size_t j = 1; j < mu.size(); ++j) EXPECT_GT(mu[j], mu[j - 1]);
  const double early = (mu[2] - mu[0]) / 0.02, late = (mu[4] - mu[2]) / 0.03;
  EXPECT_GT(early, 2.0 * late) << "slopes " << early << " and " << late;
}

// Fig 16 (typical case, correct modes + coupling): mu_c is relatively insensitive to precone,
// negative droop is stabilizing and positive droop destabilizing.
TEST(FigureSixteen, PreconeMildNegativeDroopStabilizingPositiveDroopDestabilizing) {
  auto mu_c = [](double precone, double droop) {
    RotorParameters p = exact_case(0.15, 10.0, true, false);
    p.precone = precone;
    p.droop = droop;
    const auto c = critical(p);
    EXPECT_TRUE(c.mu_c.has_value());
    return c.mu_c.value_or(-1.0);
  };
  const double base = mu_c(0.0, 0.0);
  const double droop_up = mu_c(0.0, 0.02), droop_down = mu_c(0.0, -0.02);
  const double precone_up = mu_c(0.02, 0.0), precone_down = mu_c(-0.02, 0.0);
  EXPECT_LT(droop_up, base - 0.05);
  EXPECT_GT(droop_down, base + 0.05);
  const double droop_effect = std::min(base - droop_up, droop_down - base);
  EXPECT_LT(std::abs(precone_up - base), 0.25 * droop_effect);
  EXPECT_LT(std::abs(precone_down - base), 0.25 * droop_effect);
}

}  // namespace exact_modes_paper_test
