// Mode shapes imported from a table (blade/imported_modes.h): the mode file and its errors, the
// quintic spline through the stations, the mass-orthogonality check, and the round trip that
// matters: the exact modes of the typical case exported, imported through
// RotorParameters::mode_shapes, give the same critical advance ratio.
//
// Expected values come from elsewhere than the code under test: polynomials the spline must
// reproduce, the exact modes (rotating_modes.h) the spline must converge to at its order,
// integrals by a composite Simpson rule written here, and the critical advance ratio of the
// computed modes.
#include "flaplag/blade/imported_modes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/core/errors.h"

namespace flaplag::imported_modes_test {
namespace {

using flaplag::model::Direction;

std::string text_of(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// Eq 4.1, the assumed mode: 0 with zero slope at the root, 1 at the tip.
double assumed(double x) { return -(1.0 - 4.0 * x - std::pow(1.0 - x, 4)) / 3.0; }
// A second shape with the cantilever root conditions and tip value -2.
double second(double x) { return x * x * (3.0 - 5.0 * x); }

// The lines of a good table: a comment, the header, 11 stations (lines 3..13), a blank line and
// the omega row (line 15).  lag1 is twice the assumed mode (tip value 2).
std::vector<std::string> good_lines(const std::function<double(double)>& flap2 = second) {
  std::vector<std::string> l = {"# a test table", "x0,flap1,lag1,flap2"};
  for (int i = 0; i <= 10; ++i) {
    const double x = i / 10.0;
    l.push_back(text_of(x) + "," + text_of(assumed(x)) + "," + text_of(2.0 * assumed(x)) + "," +
                text_of(flap2(x)));
  }
  l.push_back("");
  l.push_back("omega,1.175,1.28303,3.4");
  return l;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

// Replaces cell `column` (0-based) of a comma-separated line.
std::string with_cell(const std::string& line, int column, const std::string& value) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(line.substr(start, comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  cells.at(static_cast<std::size_t>(column)) = value;
  std::string out;
  for (std::size_t i = 0; i < cells.size(); ++i) out += (i ? "," : "") + cells[i];
  return out;
}

// The table refused with an InvalidInput named "t.csv:<line>: <column>" whose message is one
// line and whose reason contains `reason`.
void expect_refused(const std::vector<std::string>& lines, int line, const std::string& column,
                    const std::string& reason) {
  try {
    parse_mode_table(joined(lines), "t.csv");
    ADD_FAILURE() << "accepted; expected an error at line " << line << ", " << column;
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_EQ(e.name(), "t.csv:" + std::to_string(line) + ": " + column) << what;
    EXPECT_NE(e.reason().find(reason), std::string::npos) << what;
  }
}

// ---- the mode file -----------------------------------------------------------------------------

TEST(ModeTable, ReadsAGoodTable) {
  std::vector<std::string> l = good_lines();
  // Blanks around cells, a '+' sign, a Windows line end, a comment between rows.
  l[4] = " " + with_cell(l[4], 1, " +" + text_of(assumed(0.2)) + "\t") + " \r";
  l.insert(l.begin() + 8, "   # a comment inside the table");
  // A spreadsheet's byte order mark.
  const ImportedModes m = parse_mode_table("\xEF\xBB\xBF" + joined(l), "t.csv");
  EXPECT_EQ(m.source, "t.csv");
  ASSERT_EQ(m.x0.size(), 11u);
  EXPECT_EQ(m.x0.front(), 0.0);
  EXPECT_EQ(m.x0.back(), 1.0);
  ASSERT_EQ(m.modes.size(), 3u);
  EXPECT_EQ(m.modes[0].name, "flap1");
  EXPECT_EQ(m.modes[1].name, "lag1");
  EXPECT_EQ(m.modes[2].name, "flap2");
  EXPECT_EQ(m.modes[0].direction, BendingDirection::Flap);
  EXPECT_EQ(m.modes[1].direction, BendingDirection::Lag);
  EXPECT_EQ(m.modes[1].omega, 1.28303);
  EXPECT_EQ(m.modes[2].omega, 3.4);
  // Tip-normalised: lag1 is the assumed mode again, flap2 divided by its tip value -2.
  for (std::size_t i = 0; i < m.x0.size(); ++i) {
    const double x = static_cast<double>(i) / 10.0;
    EXPECT_NEAR(m.modes[0].values[i], assumed(x), 1e-15);
    EXPECT_NEAR(m.modes[1].values[i], assumed(x), 1e-15);
    EXPECT_NEAR(m.modes[2].values[i], second(x) / -2.0, 1e-15);
  }
  EXPECT_EQ(m.modes[2].values.back(), 1.0);
  // Notes for the scaled shapes only.
  ASSERT_EQ(m.notes.size(), 2u);
  EXPECT_NE(m.notes[0].find("lag1 scaled by 1/2"), std::string::npos) << m.notes[0];
  EXPECT_NE(m.notes[1].find("flap2 scaled by 1/-2"), std::string::npos) << m.notes[1];
}

TEST(ModeTable, EachErrorIsOneLineNamingRowAndColumn) {
  const std::vector<std::string> good = good_lines();
  auto changed = [&](int line, int column, const std::string& value) {
    std::vector<std::string> l = good;
    l[line - 1] = with_cell(l[line - 1], column, value);
    return l;
  };
  expect_refused(changed(7, 1, "0.1x"), 7, "flap1", "not a number");
  expect_refused(changed(7, 1, "abc"), 7, "flap1", "not a number");
  expect_refused(changed(7, 1, "0x1p3"), 7, "flap1", "not a number");
  expect_refused(changed(7, 2, ""), 7, "lag1", "empty cell");
  for (const char* bad : {"inf", "-inf", "nan", "1e999"})
    expect_refused(changed(9, 3, bad), 9, "flap2", "finite");
  expect_refused(changed(4, 0, "zero"), 4, "x0", "not a number");
  {  // a missing cell: the first column without one
    std::vector<std::string> l = good;
    l[4] = l[4].substr(0, l[4].rfind(','));
    expect_refused(l, 5, "flap2", "cells");
  }
  {  // an extra cell
    std::vector<std::string> l = good;
    l[5] += ",0";
    expect_refused(l, 6, "column 5", "extra cell");
  }
  // Stations: strictly increasing, from 0 to 1.
  expect_refused(changed(8, 0, "0.4"), 8, "x0", "strictly increasing");
  expect_refused(changed(8, 0, "0.3"), 8, "x0", "strictly increasing");
  expect_refused(changed(3, 0, "0.001"), 3, "x0", "first station must be 0");
  expect_refused(changed(13, 0, "0.95"), 13, "x0", "last station must be 1");
  expect_refused(changed(13, 0, "1.5"), 13, "x0", "from 0 to 1");
  {  // the tip within 1e-9 of 1 is 1: then the station before it must be below 1
    std::vector<std::string> l = changed(13, 0, "1.0000000005");
    EXPECT_EQ(parse_mode_table(joined(l), "t.csv").x0.back(), 1.0);
    l[11] = with_cell(l[11], 0, "1");
    expect_refused(l, 13, "x0", "strictly increasing to the tip");
  }
  // The omega row.
  expect_refused(changed(15, 2, "0"), 15, "lag1", "> 0");
  expect_refused(changed(15, 3, "-3.4"), 15, "flap2", "> 0");
  expect_refused(changed(15, 1, "fast"), 15, "flap1", "not a number");
  {
    std::vector<std::string> l = good;
    l.pop_back();  // the file ends at line 14
    expect_refused(l, 14, "x0", "no omega row");
    l.push_back("omega,1,2,3");
    l.push_back("omega,1,2,3");
    expect_refused(l, 16, "x0", "second omega row");
  }
  // The header.
  expect_refused(changed(2, 3, "flap1"), 2, "column 4", "twice");
  for (const char* name : {"torsion1", "flap0", "flap01", "Flap1", "lag", "flap1a"})
    expect_refused(changed(2, 3, name), 2, "column 4", "flapK or lagK");
  expect_refused(changed(2, 0, "r"), 2, "column 1", "start with x0");
  expect_refused(changed(2, 2, "flap3"), 2, "column 5", "no lag mode");
  {  // more than 50 mode columns
    std::string header = "x0";
    for (int k = 1; k <= 26; ++k) header += ",flap" + std::to_string(k);
    for (int k = 1; k <= 25; ++k) header += ",lag" + std::to_string(k);
    std::vector<std::string> l = good;
    l[1] = header;
    expect_refused(l, 2, "column 52", "more than 50 mode columns");
  }
  {  // no table at all
    expect_refused({"# nothing", ""}, 2, "column 1", "no header row");
  }
  // Shapes: a zero tip, a nonzero root value, a nonzero root slope (a hinged shape).
  expect_refused(good_lines([](double x) { return x * x * (1.0 - x); }), 13, "flap2",
                 "tip value is 0");
  expect_refused(good_lines([](double x) { return second(x) + 0.01; }), 3, "flap2",
                 "0 at the root");
  expect_refused(good_lines([](double x) { return x; }), 3, "flap2", "zero slope at the root");
}

TEST(ModeTable, StationCountsAreBounded) {
  // Seven stations (lines 2..8): too few.
  std::vector<std::string> l = {"x0,flap1,lag1"};
  for (int i = 0; i <= 6; ++i) {
    const double x = i / 6.0;
    l.push_back(text_of(x) + "," + text_of(assumed(x)) + "," + text_of(assumed(x)));
  }
  l.push_back("omega,1.1,1.2");
  expect_refused(l, 8, "x0", "at least 8 stations");
  // Eight are enough.
  std::vector<std::string> eight = {"x0,flap1,lag1"};
  for (int i = 0; i <= 7; ++i) {
    const double x = i / 7.0;
    eight.push_back(text_of(x) + "," + text_of(assumed(x)) + "," + text_of(assumed(x)));
  }
  eight.push_back("omega,1.1,1.2");
  EXPECT_EQ(parse_mode_table(joined(eight), "t.csv").x0.size(), 8u);
  // 100001 stations: refused at the first one too many (line 100002), before reading on.
  std::vector<std::string> big = {"x0,flap1,lag1"};
  const int n = kMaxModeStations + 1;
  for (int i = 0; i < n; ++i) {
    const double x = static_cast<double>(i) / (n - 1);
    const std::string v = text_of(assumed(x));
    big.push_back(text_of(x) + "," + v + "," + v);
  }
  big.push_back("omega,1.1,1.2");
  expect_refused(big, n + 1, "x0", "more than 100000 stations");
}

TEST(ModeTable, ModeSetTakesTheColumnsByNumber) {
  // Columns in the order lag1, flap2, flap1.
  std::vector<std::string> l = {"x0,lag1,flap2,flap1"};
  for (int i = 0; i <= 10; ++i) {
    const double x = i / 10.0;
    l.push_back(text_of(x) + "," + text_of(assumed(x)) + "," + text_of(second(x)) + "," +
                text_of(assumed(x)));
  }
  l.push_back("omega,1.3,3.5,1.1");
  const ImportedModes table = parse_mode_table(joined(l), "fe.csv");
  const ModeSet s = imported_mode_set(table, 2, 1);
  EXPECT_EQ(s.kind, "imported");
  ASSERT_EQ(s.shapes(Direction::Flap).size(), 2u);
  ASSERT_EQ(s.shapes(Direction::Lag).size(), 1u);
  EXPECT_EQ(s[Direction::Flap].omega, (std::vector<double>{1.1, 3.5}));
  EXPECT_EQ(s[Direction::Lag].omega, (std::vector<double>{1.3}));
  EXPECT_EQ(s[Direction::Flap].stiffness, 0.0);
  EXPECT_EQ(s[Direction::Lag].stiffness, 0.0);
  EXPECT_EQ(s.blade, nullptr);
  // The shapes are the splines of flap1 = eq 4.1 (a quartic: reproduced) and flap2.
  for (double x : {0.0, 0.13, 0.5, 0.77, 1.0}) {
    EXPECT_NEAR(s.shapes(Direction::Flap)[0]->value(0, x), assumed(x), 1e-14);
    EXPECT_NEAR(s.shapes(Direction::Flap)[0]->value(2, x), 4.0 * (1 - x) * (1 - x), 1e-12);
    EXPECT_NEAR(s.shapes(Direction::Flap)[1]->value(1, x), x * (6.0 - 15.0 * x) / -2.0, 1e-12);
  }
  try {
    imported_mode_set(table, 3, 1);
    ADD_FAILURE() << "a third flap mode from two columns";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), "fe.csv");
    EXPECT_NE(e.reason().find("no column flap3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(imported_mode_set(table, 1, 2), InvalidInput);
  EXPECT_THROW(imported_mode_set(table, 0, 1), InvalidInput);
}

TEST(ModeTable, WrittenTablesReadBack) {
  ExactModeOptions opt;
  opt.flap_modes = 2;
  opt.lag_modes = 3;
  const ModeSet ex = exact_modes(1.175, 1.28303, opt);
  const std::string text = mode_table_text(ex, 101);
  EXPECT_EQ(text.rfind("# ", 0), 0u);  // a comment header saying what it is
  const ImportedModes m = parse_mode_table(text, "exported.csv");
  ASSERT_EQ(m.x0.size(), 101u);
  ASSERT_EQ(m.modes.size(), 5u);
  EXPECT_EQ(m.modes[2].name, "lag1");
  EXPECT_TRUE(m.notes.empty());  // the exact modes have tip value 1 already
  for (int k = 0; k < 2; ++k) EXPECT_EQ(m.modes[k].omega, ex[Direction::Flap].omega[k]);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(m.modes[2 + k].omega, ex[Direction::Lag].omega[k]);
  for (std::size_t i = 0; i + 1 < m.x0.size(); ++i) {
    EXPECT_EQ(m.x0[i], static_cast<double>(i) / 100.0);
    EXPECT_NEAR(m.modes[1].values[i], ex.shapes(Direction::Flap)[1]->value(0, m.x0[i]), 1e-15);
  }
  EXPECT_THROW(mode_table_text(ex, kMinModeStations - 1), InvalidInput);
  EXPECT_THROW(mode_table_text(ex, kMaxModeStations + 1), InvalidInput);
}

// ---- the spline --------------------------------------------------------------------------------

// A spline of degree 5 holds every quintic: the interpolant of one is the quintic itself, on
// any stations.
TEST(TabulatedModeShape, ReproducesQuinticsOnUnevenStations) {
  auto f = [](int d, double x) {
    // 1 - 2x + 3x^2 + 0.5x^3 - 4x^4 + 2.5x^5 and its derivatives
    const double c[6] = {1, -2, 3, 0.5, -4, 2.5};
    double s = 0.0;
    for (int k = d; k <= 5; ++k) {
      double falling = 1.0;
      for (int j = 0; j < d; ++j) falling *= k - j;
      s += c[k] * falling * std::pow(x, k - d);
    }
    return s;
  };
  std::vector<double> x, v;
  for (int i = 0; i <= 12; ++i) {
    const double t = i / 12.0;
    x.push_back(t * t * (3.0 - 2.0 * t));  // clustered at both ends
    v.push_back(f(0, x.back()));
  }
  const TabulatedModeShape s(x, v);
  // Rounding, amplified by 1/h^d on the smallest intervals (h = 0.02).
  const double tolerance[4] = {1e-14, 1e-13, 1e-11, 1e-9};
  for (int q = 0; q <= 100; ++q) {
    const double t = q / 100.0;
    for (int d = 0; d <= 3; ++d)
      EXPECT_NEAR(s.value(d, t), f(d, t), tolerance[d] * std::max(1.0, std::abs(f(d, t))))
          << "d" << d << " at " << t;
  }
}

// The d-th derivative converges as h^(6 - d) to the exact rotating modes (the first three flap
// and lag modes of the typical blade, 12 cantilever functions): a cubic spline would give
// h^(4 - d).  Measured maximum errors at 401 stations: d0 3e-12, d1 1e-8, d2 2e-5, d3 2e-2.
TEST(TabulatedModeShape, ConvergesAtItsOrderToTheExactModes) {
  ExactModeOptions opt;
  opt.n_basis = kMaxBasisFunctions;
  opt.flap_modes = 3;
  opt.lag_modes = 3;
  const ModeSet ex = exact_modes(1.175, 1.28303, opt);
  auto errors = [&](const ModeShape& exact, int n) {
    std::vector<double> x(n), v(n);
    for (int i = 0; i < n; ++i) {
      x[i] = static_cast<double>(i) / (n - 1);
      v[i] = exact.value(0, x[i]);
    }
    const TabulatedModeShape s(x, v);
    std::vector<double> e(4, 0.0);
    for (int q = 0; q <= 3000; ++q) {
      const double t = q / 3000.0;
      for (int d = 0; d <= 3; ++d)
        e[d] = std::max(e[d], std::abs(s.value(d, t) - exact.value(d, t)));
    }
    return e;
  };
  const double bound_401[4] = {1e-11, 3e-8, 5e-5, 5e-2};
  for (const auto* shapes : {&ex.shapes(Direction::Flap), &ex.shapes(Direction::Lag)}) {
    for (std::size_t m = 0; m < shapes->size(); ++m) {
      const std::vector<double> coarse = errors(*(*shapes)[m], 401);
      const std::vector<double> fine = errors(*(*shapes)[m], 801);
      for (int d = 0; d <= 3; ++d) {
        const double order = std::log2(coarse[d] / fine[d]);
        EXPECT_GT(order, 6 - d - 0.4) << "mode " << m + 1 << " d" << d;
        EXPECT_LT(order, 6 - d + 0.6) << "mode " << m + 1 << " d" << d;
        EXPECT_LT(coarse[d], bound_401[d]) << "mode " << m + 1 << " d" << d;
      }
    }
  }
}

TEST(TabulatedModeShape, RefusesBadStations) {
  const std::vector<double> x = {0, 0.1, 0.2, 0.3, 0.5, 0.7, 0.9, 1.0};
  const std::vector<double> v(8, 1.0);
  EXPECT_NO_THROW(TabulatedModeShape(x, v));
  EXPECT_THROW(TabulatedModeShape({0, 0.2, 0.4, 0.6, 0.8, 0.9, 1.0}, std::vector<double>(7, 1.0)),
               InvalidInput);
  EXPECT_THROW(TabulatedModeShape(x, std::vector<double>(7, 1.0)), InvalidInput);
  EXPECT_THROW(TabulatedModeShape({0, 0.1, 0.2, 0.2, 0.5, 0.7, 0.9, 1.0}, v), InvalidInput);
  std::vector<double> nan = v;
  nan[3] = std::nan("");
  EXPECT_THROW(TabulatedModeShape(x, nan), InvalidInput);
  const TabulatedModeShape s(x, v);
  EXPECT_THROW(s.value(4, 0.5), InvalidInput);
  EXPECT_THROW(s.value(-1, 0.5), InvalidInput);
  EXPECT_NEAR(s.value(0, 0.4), 1.0, 1e-14);
  EXPECT_NEAR(s.value(3, 0.4), 0.0, 1e-9);
}

// ---- mass orthogonality ------------------------------------------------------------------------

// int_0^1 f by composite Simpson on 20000 intervals (independent of the code's Gauss rule).
double simpson(const std::function<double(double)>& f) {
  const int n = 20000;
  double s = f(0.0) + f(1.0);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * f(static_cast<double>(i) / n);
  return s / (3.0 * n);
}

// phi_1 of the clamped-free beam, classical form (beta_1 is small: no cancellation).
double cantilever1(double x) {
  const double b = 1.8751040687119611;
  const double sigma = (std::cosh(b) + std::cos(b)) / (std::sinh(b) + std::sin(b));
  return std::cosh(b * x) - std::cos(b * x) - sigma * (std::sinh(b * x) - std::sin(b * x));
}

TEST(MassOrthogonality, ExactModesAreOrthogonal) {
  ExactModeOptions opt;
  opt.flap_modes = 4;
  opt.lag_modes = 3;
  const ModeSet ex = exact_modes(1.175, 1.28303, opt);
  EXPECT_LT(mass_orthogonality_defect(ex), 1e-12);
  // and so are their splines at 401 stations
  const ModeSet imported =
      imported_mode_set(parse_mode_table(mode_table_text(ex, 401), "x.csv"), 4, 3);
  EXPECT_LT(mass_orthogonality_defect(imported), 1e-10);
  // one mode per direction: nothing to compare
  EXPECT_EQ(mass_orthogonality_defect(assumed_modes(1.1, 1.2)), 0.0);
}

TEST(MassOrthogonality, TwoSimilarShapesAreFarFromOrthogonal) {
  ModeSet s = assumed_modes(1.1, 1.2);
  s[Direction::Lag].shapes.push_back(cantilever_mode(1));  // lag: eq 4.1 and phi_1 (tip value 2)
  s[Direction::Lag].omega.push_back(3.0);
  const double ab = simpson([](double x) { return 3.0 * assumed(x) * cantilever1(x); });
  const double aa = simpson([](double x) { return 3.0 * assumed(x) * assumed(x); });
  const double bb = simpson([](double x) { return 3.0 * cantilever1(x) * cantilever1(x); });
  const double expected = std::abs(ab) / std::sqrt(aa * bb);
  EXPECT_GT(expected, 0.9);
  EXPECT_NEAR(mass_orthogonality_defect(s), expected, 1e-10);
}

// The blade's mass and tip mass weight the integrals: the uniform blade's exact modes on a blade
// with a tip mass are not orthogonal.
TEST(MassOrthogonality, UsesTheBladeMassAndTipMass) {
  ExactModeOptions opt;
  opt.flap_modes = 2;
  const ModeSet ex = exact_modes(1.175, 1.28303, opt);
  ModeSet weighted = ex;
  BladeProperties b = uniform_blade();
  b.mass = {2.4, 2.4};  // int 2.4 x0^2 = 0.8, plus the tip mass 0.2
  b.tip_mass = 0.2;
  weighted.blade = std::make_shared<const BladeProperties>(b);
  const ModeShape& f1 = *ex.shapes(Direction::Flap)[0];
  const ModeShape& f2 = *ex.shapes(Direction::Flap)[1];
  auto mass = [&](const ModeShape& a, const ModeShape& c) {
    return simpson([&](double x) { return 2.4 * a.value(0, x) * c.value(0, x); }) +
           0.2 * a.value(0, 1.0) * c.value(0, 1.0);
  };
  const double expected = std::abs(mass(f1, f2)) / std::sqrt(mass(f1, f1) * mass(f2, f2));
  EXPECT_GT(expected, 1e-2);
  EXPECT_NEAR(mass_orthogonality_defect(weighted), expected, 1e-10);
  b.tip_mass = 0.0;
  b.mass = {3.0, 3.0};
  weighted.blade = std::make_shared<const BladeProperties>(b);
  EXPECT_LT(mass_orthogonality_defect(weighted), 1e-12);
}

// ---- through the rotor -------------------------------------------------------------------------

// The stations the round trip needs: mu_c of the imported shapes against the computed ones,
// measured (typical case 1 x 1 / 2 x 2): 51 stations 1.5e-6 / 6.5e-6, 101: 2.4e-7 / 1.1e-6,
// 201: 1.1e-8 / 4.8e-8, 401: 4.7e-10 / 2.1e-9, 1001: 1e-11 / 1e-11.
constexpr int kRoundTripStations = 401;

std::shared_ptr<const ImportedModes> exported(const ModeSet& modes, int stations) {
  return std::make_shared<const ImportedModes>(
      parse_mode_table(mode_table_text(modes, stations), "exported.csv"));
}

class RoundTrip : public ::testing::TestWithParam<const char*> {};

TEST_P(RoundTrip, ImportedExactModesGiveTheSameCriticalAdvanceRatio) {
  RotorParameters p;
  p.modes = ModeKind::Exact;
  p.model = GetParam();
  const Analysis computed(p, {});
  const CriticalResult c = computed.critical({});
  ASSERT_NE(c.status, Status::Failed) << c.message;
  ASSERT_TRUE(c.mu_c.has_value());

  RotorParameters q = p;
  q.mode_shapes = exported(computed.modes(), kRoundTripStations);
  const Analysis imported(q, {});
  const ModeSet& a = computed.modes();
  const ModeSet& b = imported.modes();
  EXPECT_EQ(b.kind, "imported");
  ASSERT_EQ(a[Direction::Flap].omega.size(), b[Direction::Flap].omega.size());
  ASSERT_EQ(a[Direction::Lag].omega.size(), b[Direction::Lag].omega.size());
  for (std::size_t k = 0; k < a[Direction::Flap].omega.size(); ++k)
    EXPECT_NEAR(b[Direction::Flap].omega[k], a[Direction::Flap].omega[k], 1e-12);
  for (std::size_t k = 0; k < a[Direction::Lag].omega.size(); ++k)
    EXPECT_NEAR(b[Direction::Lag].omega[k], a[Direction::Lag].omega[k], 1e-12);
  // The elastic coupling's stiffnesses, as the exact modes have them.
  EXPECT_NEAR(b[Direction::Flap].stiffness, a[Direction::Flap].stiffness,
              1e-12 * a[Direction::Flap].stiffness);
  EXPECT_NEAR(b[Direction::Lag].stiffness, a[Direction::Lag].stiffness,
              1e-12 * a[Direction::Lag].stiffness);

  const CriticalResult r = imported.critical({});
  ASSERT_TRUE(r.mu_c.has_value()) << r.message;
  EXPECT_NEAR(*r.mu_c, *c.mu_c, 1e-8);
  // No Galerkin basis behind imported shapes, hence no basis error; orthogonal: no note.
  EXPECT_TRUE(c.basis.has_value());
  EXPECT_FALSE(r.basis.has_value());
  EXPECT_FALSE(r.basis_error.has_value());
  EXPECT_TRUE(r.notes.empty()) << r.notes.front();

  // The comparison resolves the shapes: 51 stations are visibly worse.
  q.mode_shapes = exported(computed.modes(), 51);
  const CriticalResult coarse = Analysis(q, {}).critical({});
  ASSERT_TRUE(coarse.mu_c.has_value());
  EXPECT_GT(std::abs(*coarse.mu_c - *c.mu_c), 1e-7);
}

INSTANTIATE_TEST_SUITE_P(TypicalCase, RoundTrip, ::testing::Values("paper", "paper-2x2"),
                         [](const ::testing::TestParamInfo<const char*>& model) {
                           return std::string(model.param) == "paper" ? "OneByOne" : "TwoByTwo";
                         });

TEST(ImportedModes, NeedExactModesAndEnoughColumns) {
  RotorParameters p;
  p.modes = ModeKind::Exact;
  const Analysis computed(p, {});
  RotorParameters q = p;
  q.mode_shapes = exported(computed.modes(), 101);
  q.modes = ModeKind::Assumed;
  try {
    const Analysis bad(q, {});
    ADD_FAILURE() << "imported shapes with assumed modes";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), "mode_shapes");
    EXPECT_EQ(e.value(), "exported.csv");
    EXPECT_NE(e.reason().find("`modes` = exact"), std::string::npos) << e.what();
  }
  q.modes = ModeKind::Exact;
  q.model = "paper-2x1";
  try {
    const Analysis bad(q, {});
    ADD_FAILURE() << "two flap modes from a table of one";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), "mode_shapes");
    EXPECT_NE(e.reason().find("flap2"), std::string::npos) << e.what();
  }
}

// Shapes that are not mass-orthogonal: every result says so in a note.
TEST(ImportedModes, NotOrthogonalShapesAreNoted) {
  ExactModeOptions opt;
  opt.flap_modes = 2;
  ModeSet s = exact_modes(1.175, 1.28303, opt);
  // flap2 replaced by a shape close to flap1 (eq 4.1): far from orthogonal to it.
  s[Direction::Flap].shapes[1] = assumed_mode_shape();
  RotorParameters p;
  p.modes = ModeKind::Exact;
  p.model = "paper-2x1";
  p.mode_shapes = exported(s, 201);
  const Analysis an(p, {});
  const double defect = mass_orthogonality_defect(an.modes());
  EXPECT_GT(defect, 0.5);
  const PointResult r = an.point(0.1);
  ASSERT_EQ(r.notes.size(), 1u) << r.message;
  EXPECT_NE(r.notes[0].find("not mass-orthogonal"), std::string::npos) << r.notes[0];
  EXPECT_NE(r.notes[0].find("exported.csv"), std::string::npos) << r.notes[0];
}

}  // namespace
}  // namespace flaplag::imported_modes_test
