// flaplag — mode shapes and rotating frequencies imported from a table (e.g. exported from a
// finite-element model of the blade), and the spline that turns station values into shapes.
//
// The mode file (CSV, ASCII or UTF-8 with or without a byte order mark):
//
//   # comment lines start with '#'; blank lines are skipped too
//   x0,flap1,flap2,lag1
//   0,0,0,0
//   0.05,0.0037,-0.0151,0.0036
//   ...                                (one row per station, at least 8, at most 100000)
//   1,1,1,1
//   omega,1.175,3.41,1.28303
//
//   - the header row: `x0`, then the mode columns, named `flapK` (flap bending, K = 1, 2, ...)
//     or `lagK` (lag bending), in any order, each once, at least one of each direction and at
//     most 50 in all;
//   - one row per station: x0 = x0bar, the elastic span station by l (0 at the root of the
//     elastic blade, 1 at its tip), strictly increasing from 0 to 1 (within 1e-9, then taken
//     as exactly 0 and 1), then each column's shape value there (any scale and sign);
//   - one row whose first cell is `omega`: each column's rotating natural frequency by Omega
//     (finite, > 0), anywhere in the file.
//   Cells are separated by ',' and may be padded with blanks; numbers are decimal
//   ("1.5", "-2e-3", "+0.25"); a line may end in "\r\n".
//
// On import each shape is scaled to tip value +1, eta(1) = gamma(1) = 1, as every mode of
// blade.h (a note in ImportedModes::notes says by how much when the factor is not 1).  The
// shapes must be those of a cantilevered (hingeless) blade: after the scaling |eta(0)| <= 1e-6
// and the spline's root slope |eta'(0)| <= 1e-2 max |eta'| (the slopes at the stations).
//
// Every problem throws flaplag::InvalidInput (core/errors.h) with a one-line message whose name
// says where: "<source>:<line>: <column>" (the line counted from 1 in the text, comments and
// blank lines included; the column by its header name, or "x0"), the value the cell holds, and
// the reason: a cell that is not a number or not finite, a missing or extra cell, a duplicate
// or unknown column name, stations not strictly increasing or not from 0 to 1, fewer than 8 or
// more than 100000 stations, more than 50 mode columns, no `omega` row (or two), omega <= 0, a
// shape with a tip value of 0 (|eta(1)| <= 1e-6 of its largest value), a shape that violates
// the root conditions above.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "flaplag/blade/blade.h"
#include "flaplag/blade/rotating_modes.h"

namespace flaplag {

inline constexpr int kMinModeStations = 8;
inline constexpr int kMaxModeStations = 100000;
inline constexpr int kMaxModeColumns = 50;  // mode columns (x0 not counted)

// A mode shape given by its values at stations 0 = x_0 < x_1 < ... < x_{n-1} = 1 (n >= 8):
// the quintic spline (degree 5, C^4) that interpolates them, with the not-a-knot end
// conditions (the knots x_1, x_2, x_{n-3}, x_{n-2} are dropped, so that the first and last
// three intervals are one polynomial each: no derivative is imposed at the ends, which an
// exported shape does not give, and a blade with a tip mass does not have free-end conditions
// eta'' = eta''' = 0).
//
// Why quintic: for a smooth shape f and station spacing h, the d-th derivative of the spline is
// within C h^(6 - d) max|f^(6)| of f^(d) (d = 0..3: values O(h^6), slopes O(h^5), curvature
// O(h^4), the third derivative O(h^3)), against O(h^(4 - d)) for a cubic spline.  The spanwise
// integrals use eta and eta' (aerodynamic and structural) and eta'' (elastic coupling), so a
// quintic spline reaches a given accuracy with far fewer stations.  Measured on the uniform
// blade's exact modes of the typical case (tests/imported_modes_test.cpp), the critical advance
// ratio of the imported shapes differs from the computed one by 5e-4 / 2e-3 (1 x 1 / 2 x 2
// modes) at 21 stations, 1.5e-6 / 6.5e-6 at 51, 1e-8 / 5e-8 at 201, 5e-10 / 2e-9 at 401.
//
// The spline is built as a B-spline (collocation matrix: banded and totally positive, solved by
// Gauss elimination without pivoting, which is stable for such matrices) and kept as one
// Taylor polynomial per knot interval.  x0 outside [0, 1] extends the end polynomials.
class TabulatedModeShape final : public ModeShape {
 public:
  // Throws InvalidInput ("stations", ...) for fewer than kMinModeStations or more than
  // kMaxModeStations stations, x0 and values of different sizes, stations not finite and
  // strictly increasing, a non-finite value.
  TabulatedModeShape(std::vector<double> x0, std::vector<double> values);
  // d in 0..3 (else InvalidInput "derivative order").
  double value(int d, double x0) const override;

 private:
  std::vector<double> left_;                   // left end of each polynomial piece
  std::vector<std::array<double, 6>> taylor_;  // its coefficients in (x - left)^k, k = 0..5
};

// One column of a mode file.
struct ImportedMode {
  std::string name;  // "flap1", "lag2", ... as in the header
  BendingDirection direction = BendingDirection::Flap;
  double omega = 0.0;          // rotating frequency by Omega (the `omega` row)
  std::vector<double> values;  // at ImportedModes::x0, tip-normalised (last value exactly 1)
};

struct ImportedModes {
  std::vector<double> x0;           // the stations, first exactly 0, last exactly 1
  std::vector<ImportedMode> modes;  // in the file's column order
  std::string source;               // where the table came from ("blade-modes.csv"), for messages
  // Remarks about the import that do not refuse it (a shape scaled to tip value 1).
  std::vector<std::string> notes;
};

// The mode file `text` (format above); `source` names it in messages and in the result.
ImportedModes parse_mode_table(std::string_view text, std::string source);

// The ModeSet of the first flap_modes (>= 1) flap and lag_modes (>= 1) lag columns by their
// number (flap1, flap2, ..., lag1, ...): TabulatedModeShape shapes, kind "imported", the
// frequencies of the `omega` row, stiffness_flap = stiffness_lag = 0 (the caller fills them when
// it knows the blade) and no blade table.  Throws InvalidInput naming the source when a column
// flapK / lagK with K up to the count is missing, or for a count < 1.
ModeSet imported_mode_set(const ImportedModes& modes, int flap_modes, int lag_modes);

// A mode file (format above, with a '#' comment header saying what it is) of the shapes of
// `modes` at `stations` equally spaced stations (kMinModeStations..kMaxModeStations, else
// InvalidInput "stations"), every number written so that it reads back as the same double:
// parse_mode_table reads it back.  The columns are flap1..flapM, lag1..lagN.
std::string mode_table_text(const ModeSet& modes, int stations);

// How far the shapes of each direction are from mass-orthogonal: the largest, over pairs
// i != j of the same direction, of
//   |int_0^1 mbar phi_i phi_j dx0 + M_tip phi_i(1) phi_j(1)|  /  sqrt(M_ii M_jj)
// (M_ii the same with j = i), with mbar = 3 and M_tip = 0 when modes.blade is null, else
// modes.blade->mass_at(x0) and modes.blade->tip_mass.  0 with one mode per direction; ~1e-14
// for the exact modes of the uniform blade.  True modes of one blade are orthogonal in its mass;
// shapes from another model, or of another blade, are not: a defect above ~1e-3 deserves a
// warning (Analysis adds a note to its results when imported shapes exceed it).
double mass_orthogonality_defect(const ModeSet& modes);

// The defect above which Analysis notes that imported shapes are not mass-orthogonal.
inline constexpr double kMassOrthogonalityWarning = 1e-3;

}  // namespace flaplag
