// PeriodicSystem: harmonic basis, exact interval means (eqs 4.2-4.5), regions, trace integral.
#include "flaplag/numerics/periodic_system.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "periodic_fixtures.h"
#include "test_util.h"

namespace flaplag::periodic_system_test {
namespace {

using testing::AbsClose;
using testing::RelClose;

// Composite Gauss-Legendre (5 points on each of `panels` panels): independent of the closed
// forms under test, and exact to rounding for the smooth integrands used here.
double quad(const std::function<double(double)>& g, double a, double b, int panels = 50) {
  static const double x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                              0.9061798459386640};
  static const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                              0.4786286704993665, 0.2369268850561891};
  const double hp = (b - a) / panels;
  double s = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double c = a + (p + 0.5) * hp;
    for (int i = 0; i < 5; ++i) s += w[i] * g(c + 0.5 * hp * x[i]);
  }
  return s * 0.5 * hp;
}

// Deterministic O(1) matrix with entries depending on a seed.
Eigen::MatrixXd pattern(int n, int seed) {
  Eigen::MatrixXd m(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) m(i, j) = std::sin(1.7 * seed + 2.3 * i + 0.9 * j + 0.1 * i * j);
  return m;
}

constexpr double kSectorBegin = 1.25 * kPi, kSectorEnd = 1.75 * kPi;

PeriodicSystem sector_system(int n, int harmonics) {
  HarmonicSet normal, reversed;
  for (int h = 0; h < harmonics; ++h) {
    normal.A.push_back(pattern(n, h) / (1.0 + h));
    reversed.A.push_back(pattern(n, 100 + h) / (1.0 + h));
    normal.f.push_back(Eigen::VectorXd::Constant(n, 0.5 + h));
    reversed.f.push_back(Eigen::VectorXd::Constant(n, -1.0 - h));
  }
  return fixtures::with_sector(normal, reversed, kSectorBegin, kSectorEnd);
}

// The set of the piece at psi.
int set_of(const PeriodicSystem& s, double psi) {
  return s.pieces[static_cast<std::size_t>(s.piece_at(psi))].set;
}

TEST(HarmonicBasis, IndexConvention) {
  const double psi = 0.731;
  EXPECT_EQ(1.0, harmonic_basis(0, psi));
  for (int k = 1; k <= 4; ++k) {
    EXPECT_TRUE(RelClose(std::cos(k * psi), harmonic_basis(2 * k - 1, psi), 1e-15));
    EXPECT_TRUE(RelClose(std::sin(k * psi), harmonic_basis(2 * k, psi), 1e-15));
  }
  EXPECT_THROW(harmonic_basis(-1, psi), InvalidInput);
}

// The names the front ends print (flaplag response, Python harmonic_names) follow the index
// convention of harmonic_basis.
TEST(HarmonicBasis, Names) {
  EXPECT_EQ("const", harmonic_name(0));
  EXPECT_EQ("cos psi", harmonic_name(1));
  EXPECT_EQ("sin psi", harmonic_name(2));
  EXPECT_EQ("cos 2psi", harmonic_name(3));
  EXPECT_EQ("sin 5psi", harmonic_name(10));
  EXPECT_EQ("cos 12psi", harmonic_name(23));
  EXPECT_THROW(harmonic_name(-1), InvalidInput);
}

TEST(HarmonicMean, MatchesQuadratureForAllHarmonics) {
  const double intervals[][2] = {
      {0.0, kTwoPi / 50}, {0.3, 1.9}, {4.0, 6.2}, {1.0, 1.0 + 0x1p-20}};  // exact length
  for (const auto& iv : intervals) {
    for (int h = 0; h <= 10; ++h) {
      const double ref =
          quad([&](double p) { return harmonic_basis(h, p); }, iv[0], iv[1]) / (iv[1] - iv[0]);
      EXPECT_TRUE(AbsClose(ref, harmonic_mean(h, iv[0], iv[1]), 1e-14))
          << "h = " << h << " on [" << iv[0] << ", " << iv[1] << "]";
    }
  }
}

TEST(HarmonicMean, PaperFormulas42To45) {
  // eqs 4.2-4.5 as printed: sin/cos(psi_avg) (2/D) sin(D/2), sin/cos(2 psi_avg) (1/D) sin D.
  const double a = 0.4, b = 0.4 + kTwoPi / 50, m = 0.5 * (a + b), D = b - a;
  EXPECT_TRUE(RelClose(std::sin(m) * 2.0 / D * std::sin(D / 2), harmonic_mean(2, a, b), 1e-14));
  EXPECT_TRUE(RelClose(std::cos(m) * 2.0 / D * std::sin(D / 2), harmonic_mean(1, a, b), 1e-14));
  EXPECT_TRUE(RelClose(std::sin(2 * m) / D * std::sin(D), harmonic_mean(4, a, b), 1e-14));
  EXPECT_TRUE(RelClose(std::cos(2 * m) / D * std::sin(D), harmonic_mean(3, a, b), 1e-14));
  // Degenerate interval: the point value.
  EXPECT_TRUE(RelClose(std::cos(3 * a), harmonic_mean(5, a, a), 1e-15));
}

TEST(PeriodicSystem, RegionsAndEdges) {
  const PeriodicSystem s = sector_system(2, 3);
  // normal [0, begin), sector [begin, end), normal [end, 2 pi)
  ASSERT_EQ(3u, s.pieces.size());
  ASSERT_EQ(2u, s.sets.size());
  EXPECT_EQ(0.0, s.pieces[0].begin);
  EXPECT_EQ(kSectorBegin, s.pieces[0].end);
  EXPECT_EQ(kSectorBegin, s.pieces[1].begin);
  EXPECT_EQ(kSectorEnd, s.pieces[1].end);
  EXPECT_EQ(kTwoPi, s.pieces[2].end);
  EXPECT_EQ(0, s.pieces[0].set);
  EXPECT_EQ(1, s.pieces[1].set);
  EXPECT_EQ(0, s.pieces[2].set);
  EXPECT_EQ(0, set_of(s, 0.0));
  EXPECT_EQ(1, set_of(s, kSectorBegin));  // [begin, end)
  EXPECT_EQ(0, set_of(s, kSectorEnd));
  EXPECT_EQ(1, set_of(s, 1.5 * kPi));
  EXPECT_EQ(1, set_of(s, 1.5 * kPi - kTwoPi));  // reduced to [0, 2 pi)
  EXPECT_EQ(1, set_of(s, 1.5 * kPi + 3 * kTwoPi));
  EXPECT_EQ(0, set_of(s, 0.5 * kPi));
  EXPECT_FALSE(s.has_evaluator());
  const std::vector<double> bp = s.breakpoints();
  ASSERT_EQ(2u, bp.size());
  EXPECT_EQ(kSectorBegin, bp[0]);
  EXPECT_EQ(kSectorEnd, bp[1]);

  // A piece from 0 or to 2 pi: the period's ends are no breakpoints.
  const PeriodicSystem t = fixtures::with_sector(s.sets[0], s.sets[1], 0.0, kTwoPi);
  EXPECT_TRUE(t.breakpoints().empty());
  ASSERT_EQ(1u, t.pieces.size());
  EXPECT_EQ(1, set_of(t, 1.5 * kPi));
  const PeriodicSystem u = fixtures::with_sector(s.sets[0], s.sets[1], 0.0, 1.0);
  ASSERT_EQ(2u, u.pieces.size());
  EXPECT_EQ(std::vector<double>{1.0}, u.breakpoints());
  EXPECT_EQ(1, set_of(u, 0.5));
  EXPECT_EQ(0, set_of(u, 1.0));
  // Only inside one piece of the base set.
  PeriodicSystem w = s;
  EXPECT_THROW(w.add_harmonic_piece(1.0, 4.5, s.sets[1]), InvalidInput);  // across an edge
  EXPECT_THROW(w.add_harmonic_piece(4.0, 4.5, s.sets[1]), InvalidInput);  // in the sector
  EXPECT_THROW(w.add_harmonic_piece(2.0, 1.0, s.sets[1]), InvalidInput);
  EXPECT_THROW(w.add_harmonic_piece(6.0, 7.0, s.sets[1]), InvalidInput);
  w.add_harmonic_piece(1.0, 2.0, s.sets[1]);  // a second sector
  EXPECT_EQ(5u, w.pieces.size());
  EXPECT_EQ((std::vector<double>{1.0, 2.0, kSectorBegin, kSectorEnd}), w.breakpoints());
  EXPECT_EQ(2, set_of(w, 1.5));
  EXPECT_NO_THROW(w.validate());
}

// A system rebuilt in place (its storage kept, as SystemBuilder does at every mu) has the pieces
// of one built afresh; a set index that is not there is refused by name.
TEST(PeriodicSystem, RebuiltInPlaceHasTheFreshPieces) {
  PeriodicSystem w = sector_system(2, 3);
  w.add_harmonic_piece(1.0, 2.0, w.sets[1]);  // three sets, five pieces
  w.sets.resize(2);
  w.reset_pieces();
  ASSERT_EQ(1u, w.pieces.size());
  EXPECT_EQ(0.0, w.pieces[0].begin);
  EXPECT_EQ(kTwoPi, w.pieces[0].end);
  EXPECT_EQ(0, w.pieces[0].set);
  for (const auto& [begin, end] : {std::pair{kSectorBegin, kSectorEnd}, std::pair{0.0, 1.0},
                                   std::pair{5.0, kTwoPi}, std::pair{0.0, kTwoPi}}) {
    PeriodicSystem fresh(w.sets[0]);
    fresh.add_harmonic_piece(begin, end, w.sets[1]);
    w.reset_pieces();
    w.add_set_piece(begin, end, 1);
    ASSERT_EQ(fresh.pieces.size(), w.pieces.size()) << begin << " " << end;
    for (std::size_t i = 0; i < w.pieces.size(); ++i) {
      EXPECT_EQ(fresh.pieces[i].begin, w.pieces[i].begin) << i;
      EXPECT_EQ(fresh.pieces[i].end, w.pieces[i].end) << i;
      EXPECT_EQ(fresh.pieces[i].set, w.pieces[i].set) << i;
    }
    EXPECT_EQ(fresh.trace_integral(), w.trace_integral());
    EXPECT_NO_THROW(w.validate());
  }
  w.reset_pieces();
  for (int bad : {0, 2, -1}) {
    try {
      w.add_set_piece(1.0, 2.0, bad);
      ADD_FAILURE() << bad;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("set"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(w.add_set_piece(2.0, 1.0, 1), InvalidInput);
}

TEST(PeriodicSystem, EvaluatesHarmonicSums) {
  const PeriodicSystem s = sector_system(3, 5);
  for (double psi : {0.2, 2.0, 1.5 * kPi}) {
    const HarmonicSet& set = fixtures::set_at(s, psi);
    Eigen::MatrixXd ref = Eigen::MatrixXd::Zero(3, 3);
    Eigen::VectorXd fref = Eigen::VectorXd::Zero(3);
    for (int h = 0; h < 5; ++h) {
      ref += harmonic_basis(h, psi) * set.A[h];
      fref += harmonic_basis(h, psi) * set.f[h];
    }
    EXPECT_LT((s.A(psi) - ref).norm(), 1e-14 * ref.norm());
    EXPECT_LT((s.f(psi) - fref).norm(), 1e-14 * fref.norm());
  }
}

TEST(PeriodicSystem, IntervalMeanMatchesQuadrature) {
  const PeriodicSystem s = sector_system(2, 7);
  const double intervals[][2] = {{0.1, 0.9}, {4.0, 5.4}, {5.6, kTwoPi}};  // normal, sector, normal
  for (const auto& iv : intervals) {
    const Eigen::MatrixXd m = s.A_mean(iv[0], iv[1]);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        const double ref =
            quad([&](double p) { return s.A(p)(i, j); }, iv[0], iv[1]) / (iv[1] - iv[0]);
        EXPECT_TRUE(AbsClose(ref, m(i, j), 1e-13));
      }
  }
}

TEST(PeriodicSystem, TraceIntegralWithSector) {
  const PeriodicSystem s = sector_system(3, 9);
  // Quadrature on the three smooth pieces.
  auto tr = [&](double p) { return s.A(p).trace(); };
  const double ref = quad(tr, 0.0, kSectorBegin) + quad(tr, kSectorBegin, kSectorEnd) +
                     quad(tr, kSectorEnd, kTwoPi);
  EXPECT_TRUE(RelClose(ref, s.trace_integral(), 1e-13, 1.0));

  const PeriodicSystem t(s.sets[0]);
  EXPECT_TRUE(RelClose(kTwoPi * s.sets[0].A[0].trace(), t.trace_integral(), 1e-15));
}

// The varying region: A and f from the evaluator inside [begin, end), harmonics outside; its
// edges and breaks are breakpoints; the trace integral by quadrature matches the closed form.
TEST(PeriodicSystem, VaryingRegion) {
  const PeriodicSystem s = fixtures::clipped_scalar(0.6);
  EXPECT_NO_THROW(s.validate());
  EXPECT_TRUE(s.has_evaluator());
  EXPECT_EQ(0, set_of(s, 0.5 * kPi));
  EXPECT_EQ(-1, set_of(s, kPi));  // [begin, end)
  EXPECT_EQ(-1, set_of(s, 1.5 * kPi - kTwoPi));
  EXPECT_EQ(0, set_of(s, kTwoPi));
  const std::vector<double>& breaks = s.pieces.at(1).breaks;
  EXPECT_DOUBLE_EQ(0.3 + 0.9 * 0.6, s.A(1.5 * kPi)(0, 0));
  EXPECT_DOUBLE_EQ(0.3 + 0.9 * 0.25, s.A(kPi + std::asin(0.25))(0, 0));
  EXPECT_DOUBLE_EQ(-0.05 + 0.7 * std::cos(1.0), s.A(1.0)(0, 0));
  EXPECT_EQ(0.0, s.f(4.0)(0));
  const std::vector<double> bp = s.breakpoints();
  ASSERT_EQ(3u, bp.size());  // pi, and the two breaks; the end 2 pi is none
  EXPECT_EQ(kPi, bp[0]);
  EXPECT_EQ(breaks.at(0), bp[1]);
  EXPECT_EQ(breaks.at(1), bp[2]);
  EXPECT_TRUE(RelClose(fixtures::clipped_log_phi(0.6), s.trace_integral(), 1e-14));
  // The mean inside one smooth piece (between breaks) against quadrature.
  const double a = kPi + 0.1, b = breaks[0];
  const double ref = quad([&](double p) { return s.A(p)(0, 0); }, a, b) / (b - a);
  EXPECT_TRUE(AbsClose(ref, s.A_mean(a, b)(0, 0), 1e-14));
}

// A varying region that reproduces a sector gives the sector's trace integral (quadrature of
// a trigonometric polynomial of degree 4 against the closed form).
TEST(PeriodicSystem, VaryingRegionTraceMatchesSector) {
  const PeriodicSystem s = sector_system(3, 9);
  const PeriodicSystem v = fixtures::sector_as_varying(s);
  EXPECT_NO_THROW(v.validate());
  EXPECT_TRUE(RelClose(s.trace_integral(), v.trace_integral(), 1e-13, 1.0));
  for (double psi : {0.3, 4.2, 5.3}) {
    EXPECT_LT((s.A(psi) - v.A(psi)).norm(), 1e-14 * s.A(psi).norm()) << psi;
    EXPECT_LT((s.f(psi) - v.f(psi)).norm(), 1e-14 * s.f(psi).norm()) << psi;
  }
}

TEST(PeriodicSystem, ValidateRejectsMalformedVaryingRegions) {
  PeriodicSystem s = fixtures::clipped_scalar(0.6);
  SystemPiece& piece = s.pieces.at(1);  // normal [0, pi), the evaluator [pi, 2 pi)
  ASSERT_EQ(-1, piece.set);
  PeriodicSystem bad = s;
  bad.pieces[1].evaluator = nullptr;
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = s;
  bad.pieces[1].end = bad.pieces[1].begin;
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = s;
  std::swap(bad.pieces[1].breaks[0], bad.pieces[1].breaks[1]);  // unsorted
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = s;
  bad.pieces[1].breaks.push_back(0.5);  // outside the piece
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = s;
  EXPECT_THROW(bad.add_evaluator_piece(4.0, 5.0, piece.evaluator), InvalidInput);  // inside it
  // An evaluator piece inside another base piece is fine (and a harmonic one as well).
  bad.add_evaluator_piece(1.0, 2.0, piece.evaluator, {1.5});
  bad.add_harmonic_piece(2.5, 3.0, bad.sets[0]);
  EXPECT_NO_THROW(bad.validate());
  EXPECT_EQ((std::vector<double>{1.0, 1.5, 2.0, 2.5, 3.0, kPi, piece.breaks[0], piece.breaks[1]}),
            bad.breakpoints());
}

TEST(PeriodicSystem, ValidateRejectsMalformedSystems) {
  PeriodicSystem s = sector_system(2, 3);
  EXPECT_NO_THROW(s.validate());
  PeriodicSystem bad = s;
  bad.n = 0;
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = s;
  bad.sets[0].A[1] = Eigen::MatrixXd::Zero(3, 3);
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = s;
  bad.sets[1].A.clear();
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = s;
  bad.pieces[1].end = bad.pieces[1].begin;
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = s;
  bad.pieces[2].end = 7.0;
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = s;
  bad.pieces[2].end = 6.0;  // a gap at the end
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = s;
  bad.pieces[1].begin = 4.0;  // a gap inside
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = s;
  bad.pieces[1].set = 2;  // no such set
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = s;
  bad.pieces[1].set = -1;  // no evaluator
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = s;
  bad.pieces.clear();
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = s;
  bad.sets.clear();
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = s;
  bad.sets[0].A[0](0, 0) = std::nan("");
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = s;
  bad.sets[0].f[0] = Eigen::VectorXd::Zero(5);
  EXPECT_THROW(bad.validate(), InvalidInput);
}

// The exactly solvable systems of periodic_fixtures.h: the harmonic expansion (trapezoidal
// coefficients of A = P' P^{-1} + P B P^{-1}, or the hand-written Markus-Yamabe harmonics)
// reproduces A off the sample points, in the right region, so the assumed degrees hold; the
// frame is continuous at the sector edges (y continuous) while A jumps there.
TEST(PeriodicSystem, ExactFixturesReproduceA) {
  for (const fixtures::ExactCase& c : fixtures::exact_cases()) {
    for (double psi : {0.0123, 0.9, 2.2, 2.6, 3.1, 4.0, 5.0, 5.7, 6.25}) {
      const fixtures::Frame& f = set_of(c.sys, psi) != 0 ? c.reversed : c.frame;
      const Eigen::MatrixXd P = f.P(psi), Pinv = fixtures::inverse(P);
      const Eigen::MatrixXd A = f.dP(psi) * Pinv + P * c.B * Pinv;
      EXPECT_LT((c.sys.A(psi) - A).cwiseAbs().maxCoeff(), 1e-13 * A.cwiseAbs().maxCoeff())
          << c.name << ", psi = " << psi;
    }
    if (c.sys.pieces.size() > 1) {
      for (double e : c.sys.breakpoints()) {
        EXPECT_LT((c.frame.P(e) - c.reversed.P(e)).cwiseAbs().maxCoeff(), 1e-15) << c.name;
        EXPECT_GT((c.frame.dP(e) - c.reversed.dP(e)).cwiseAbs().maxCoeff(), 0.1) << c.name;
      }
    }
  }
}

// det P = 1 (rotation times unipotent) or -1 (Markus-Yamabe) for all psi, so tr(P' P^{-1}) =
// (ln |det P|)' = 0 and tr A = tr B pointwise: int tr A = 2 pi tr B, with or without a sector.
TEST(PeriodicSystem, TraceIntegralOfReducibleSystems) {
  for (const fixtures::ExactCase& c : fixtures::exact_cases())
    EXPECT_TRUE(RelClose(kTwoPi * c.B.trace(), c.sys.trace_integral(), 1e-13)) << c.name;
}

// The derivative used by the error models of periodic_fixtures.h, against central differences
// (truncation h^2 |A'''| / 6 <= 1e-8 / 6 * 4^3 * 4 with h = 1e-4, harmonics to 4/rev of size
// <= 4; rounding 1e-16 / h: below 1e-6).
TEST(PeriodicSystem, FixtureDerivativeMatchesDifferences) {
  const PeriodicSystem s = fixtures::rotor_like();
  const double h = 1e-4;
  for (double psi : {0.3, 2.0, 4.5, 6.0}) {  // 4.5 lies in the sector, away from its edges
    const Eigen::MatrixXd fd = (s.A(psi + h) - s.A(psi - h)) / (2 * h);
    EXPECT_LT((fixtures::A_rate(s, psi) - fd).cwiseAbs().maxCoeff(), 1e-6) << "psi = " << psi;
  }
}

}  // namespace
}  // namespace flaplag::periodic_system_test
