// flaplag — mode shapes imported from a table: the mode file, the quintic spline through the
// station values, and the mass-orthogonality check.
#include "flaplag/blade/imported_modes.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <system_error>
#include <utility>

#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"

namespace flaplag {
namespace {

constexpr int kDegree = 5;

// ---- the spline ------------------------------------------------------------------------------

// The values of the degree-p B-splines B_{mu-p}, ..., B_{mu} on the knots t at x, for the knot
// interval t[mu] <= x <= t[mu+1] (Cox-de Boor recurrence raised one degree at a time; every
// step is a convex combination, so the values are accurate to rounding).
void basis_values(const std::vector<double>& t, int p, int mu, double x, double* out) {
  double left[kDegree + 1], right[kDegree + 1];
  out[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = x - t[mu + 1 - j];
    right[j] = t[mu + j] - x;
    double carry = 0.0;
    for (int r = 0; r < j; ++r) {
      const double share = out[r] / (right[r + 1] + left[j - r]);
      out[r] = carry + right[r + 1] * share;
      carry = left[j - r] * share;
    }
    out[j] = carry;
  }
}

// The knot interval mu (p <= mu < nb) of t that holds x, the last one for x at its right end.
int knot_interval(const std::vector<double>& t, int p, int nb, double x) {
  if (x >= t[nb]) return nb - 1;
  const auto it = std::upper_bound(t.begin() + p + 1, t.begin() + nb, x);
  return static_cast<int>(it - t.begin()) - 1;
}

// Solves A c = y for the banded matrix A given by rows: row i holds `row[i]` at columns
// first[i] .. first[i] + p.  Gauss elimination without pivoting: a B-spline collocation
// matrix whose stations interlace the knots (Schoenberg-Whitney) is totally positive, and for
// totally positive matrices elimination without pivoting is backward stable (de Boor and
// Pinkus, 1977).  Elimination fills nothing outside the band.
std::vector<double> solve_collocation(const std::vector<std::array<double, kDegree + 1>>& row,
                                      const std::vector<int>& first, std::vector<double> y) {
  const int n = static_cast<int>(y.size());
  int kl = 0, ku = 0;
  for (int i = 0; i < n; ++i) {
    kl = std::max(kl, i - first[i]);
    ku = std::max(ku, first[i] + kDegree - i);
  }
  const int width = kl + ku + 1;
  std::vector<double> band(static_cast<std::size_t>(n) * width, 0.0);
  auto at = [&](int i, int j) -> double& {
    return band[static_cast<std::size_t>(i) * width + (j - i + kl)];
  };
  for (int i = 0; i < n; ++i)
    for (int r = 0; r <= kDegree; ++r) at(i, first[i] + r) = row[i][r];
  for (int k = 0; k < n; ++k) {
    const double pivot = at(k, k);
    if (!(std::abs(pivot) > 0.0) || !std::isfinite(pivot)) {
      throw InvalidInput("stations", std::to_string(n),
                         "the spline through them cannot be formed (stations too close)");
    }
    const int last_row = std::min(n - 1, k + kl), last_col = std::min(n - 1, k + ku);
    for (int i = k + 1; i <= last_row; ++i) {
      const double f = at(i, k) / pivot;
      if (f == 0.0) continue;
      for (int j = k; j <= last_col; ++j) at(i, j) -= f * at(k, j);
      y[i] -= f * y[k];
    }
  }
  for (int k = n - 1; k >= 0; --k) {
    double s = y[k];
    const int last_col = std::min(n - 1, k + ku);
    for (int j = k + 1; j <= last_col; ++j) s -= at(k, j) * y[j];
    y[k] = s / at(k, k);
  }
  return y;
}

void check_stations(const std::vector<double>& x0, std::size_t values) {
  const std::size_t n = x0.size();
  if (n < static_cast<std::size_t>(kMinModeStations) ||
      n > static_cast<std::size_t>(kMaxModeStations)) {
    throw InvalidInput("stations", std::to_string(n),
                       "a tabulated mode shape needs " + std::to_string(kMinModeStations) + ".." +
                           std::to_string(kMaxModeStations) + " stations");
  }
  if (values != n) {
    throw InvalidInput("stations", std::to_string(values) + " values",
                       "needs one value per station (" + std::to_string(n) + ")");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(x0[i]) || (i > 0 && !(x0[i] > x0[i - 1]))) {
      throw InvalidInput("x0 at station " + std::to_string(i + 1), round_trip_text(x0[i]),
                         "stations must be finite and strictly increasing");
    }
  }
}

}  // namespace

TabulatedModeShape::TabulatedModeShape(std::vector<double> x0, std::vector<double> values) {
  check_stations(x0, values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw InvalidInput("value at station " + std::to_string(i + 1), round_trip_text(values[i]),
                         "must be finite");
    }
  }
  const int n = static_cast<int>(x0.size()), p = kDegree;
  // Not-a-knot knots: x0[0] and x0[n-1] with multiplicity p + 1, interior knots x0[3] ..
  // x0[n-4] (x0[1], x0[2], x0[n-3], x0[n-2] dropped); n B-splines.
  std::vector<double> t;
  t.reserve(static_cast<std::size_t>(n + p + 1));
  t.insert(t.end(), p + 1, x0.front());
  for (int i = (p + 1) / 2; i <= n - 1 - (p + 1) / 2; ++i) t.push_back(x0[i]);
  t.insert(t.end(), p + 1, x0.back());
  const int nb = n;
  std::vector<std::array<double, kDegree + 1>> rows(static_cast<std::size_t>(n));
  std::vector<int> first(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const int mu = knot_interval(t, p, nb, x0[i]);
    basis_values(t, p, mu, x0[i], rows[i].data());
    first[i] = mu - p;
  }
  // B-spline coefficients of the spline and of its derivatives (de Boor's difference formula:
  // the k-th derivative is sum_i d_i B_{i, p-k} with d^(k)_i = (p-k+1) (d^(k-1)_i - d^(k-1)_{i-1})
  // / (t_{i+p-k+1} - t_i)).
  std::array<std::vector<double>, kDegree + 1> coef;
  coef[0] = solve_collocation(rows, first, std::move(values));
  for (int k = 1; k <= p; ++k) {
    coef[k].assign(static_cast<std::size_t>(nb), 0.0);
    for (int i = k; i < nb; ++i) {
      const double span = t[i + p - k + 1] - t[i];
      if (span > 0.0) coef[k][i] = (p - k + 1) * (coef[k - 1][i] - coef[k - 1][i - 1]) / span;
    }
  }
  // One Taylor polynomial per nonempty knot interval, from the derivatives at its left end.
  const double factorial[kDegree + 1] = {1, 1, 2, 6, 24, 120};
  for (int mu = p; mu < nb; ++mu) {
    if (!(t[mu + 1] > t[mu])) continue;
    std::array<double, kDegree + 1> c{};
    for (int k = 0; k <= p; ++k) {
      double b[kDegree + 1];
      basis_values(t, p - k, mu, t[mu], b);
      double s = 0.0;
      for (int r = 0; r <= p - k; ++r) s += coef[k][mu - (p - k) + r] * b[r];
      c[k] = s / factorial[k];
    }
    left_.push_back(t[mu]);
    taylor_.push_back(c);
  }
}

double TabulatedModeShape::value(int d, double x0) const {
  if (d < 0 || d > 3) throw InvalidInput("derivative order", std::to_string(d), "must be 0..3");
  const auto it = std::upper_bound(left_.begin(), left_.end(), x0);
  const std::size_t piece =
      it == left_.begin() ? 0 : static_cast<std::size_t>(it - left_.begin()) - 1;
  const std::array<double, kDegree + 1>& c = taylor_[piece];
  const double u = x0 - left_[piece];
  // sum_{k >= d} c_k k! / (k - d)! u^(k - d), by Horner.
  double s = 0.0;
  for (int k = kDegree; k >= d; --k) {
    double falling = 1.0;
    for (int j = 0; j < d; ++j) falling *= k - j;
    s = s * u + c[k] * falling;
  }
  return s;
}

// ---- the mode file ---------------------------------------------------------------------------

namespace {

// The tolerance within which the first and last stations are taken as 0 and 1.
constexpr double kEndTolerance = 1e-9;
// A tip value at most this fraction of the largest |value| is a zero tip.
constexpr double kZeroTip = 1e-6;
// Root conditions after tip normalisation.
constexpr double kRootValue = 1e-6;
constexpr double kRootSlope = 1e-2;  // of the largest |slope| at the stations

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

std::string shown_cell(std::string_view cell) {
  if (cell.empty()) return "\"\"";
  std::string s(cell.substr(0, 40));
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return cell.size() > 40 ? s + "..." : s;
}

struct Reader {
  std::string_view source;
  [[noreturn]] void fail(std::size_t line, std::string_view column, const std::string& value,
                         const std::string& reason) const {
    throw InvalidInput(
        std::string(source) + ":" + std::to_string(line) + ": " + std::string(column), value,
        reason);
  }
};

// A decimal number filling the whole cell.
double number(const Reader& r, std::size_t line, std::string_view column, std::string_view cell) {
  if (cell.empty()) r.fail(line, column, "\"\"", "empty cell: a number is needed");
  std::string_view text = cell;
  if (text.size() > 1 && text.front() == '+' && text[1] != '-' && text[1] != '+')
    text.remove_prefix(1);
  double v = 0.0;
  const auto res = std::from_chars(text.data(), text.data() + text.size(), v);
  if (res.ec == std::errc::result_out_of_range) {
    r.fail(line, column, shown_cell(cell), "not a finite number (beyond the range of a double)");
  }
  if (res.ec != std::errc() || res.ptr != text.data() + text.size()) {
    r.fail(line, column, shown_cell(cell), "not a number");
  }
  if (!std::isfinite(v)) r.fail(line, column, shown_cell(cell), "not a finite number");
  return v;
}

// "flapK" / "lagK" with K a positive integer without leading zeros; false otherwise.
bool mode_name(std::string_view name, BendingDirection* dir, int* number) {
  std::string_view digits;
  if (name.rfind("flap", 0) == 0) {
    *dir = BendingDirection::Flap;
    digits = name.substr(4);
  } else if (name.rfind("lag", 0) == 0) {
    *dir = BendingDirection::Lag;
    digits = name.substr(3);
  } else {
    return false;
  }
  if (digits.empty() || digits.size() > 4 || digits.front() == '0') return false;
  int k = 0;
  for (char c : digits) {
    if (c < '0' || c > '9') return false;
    k = 10 * k + (c - '0');
  }
  *number = k;
  return true;
}

// The cells of one line (',' separated, each trimmed), at most limit + 1 of them (enough to
// see that a row has too many).
std::vector<std::string_view> cells(std::string_view line, std::size_t limit) {
  std::vector<std::string_view> out;
  while (out.size() <= limit) {
    const std::size_t comma = line.find(',');
    out.push_back(trim(line.substr(0, comma)));
    if (comma == std::string_view::npos) break;
    line.remove_prefix(comma + 1);
  }
  return out;
}

// The mode file read line by line: the header, then the omega row and the stations in any
// order; finish() checks the whole and scales every shape to tip value 1.
class ModeTableReader {
 public:
  ModeTableReader(const Reader& r, std::string source) : r_(r) { out_.source = std::move(source); }

  // One line (untrimmed) that is neither blank nor a comment.
  void read(std::string_view line, std::size_t line_no) {
    if (names_.empty()) {
      header(line, line_no);
      return;
    }
    const std::vector<std::string_view> c = cells(line, names_.size());
    if (c.size() < names_.size()) {
      r_.fail(line_no, names_[c.size()], "(missing)",
              "the row has " + std::to_string(c.size()) + " cells, the header " +
                  std::to_string(names_.size()));
    }
    if (c.size() > names_.size()) {
      r_.fail(line_no, "column " + std::to_string(names_.size() + 1), shown_cell(c[names_.size()]),
              "an extra cell: the header has " + std::to_string(names_.size()) + " columns");
    }
    if (c.front() == "omega") {
      omega_row(c, line_no);
    } else {
      station_row(c, line_no);
    }
  }

  // After the last line (line_no, the number of lines).
  ImportedModes finish(std::size_t line_no) {
    if (names_.empty()) {
      r_.fail(line_no, "column 1", "(missing)",
              "no header row (x0,flap1,...,lag1,...): the text has no table");
    }
    check_stations();
    if (omega_line_ == 0) {
      r_.fail(line_no, "x0", "(missing)",
              "no omega row: a row whose first cell is `omega` gives each column's rotating "
              "frequency by Omega");
    }
    out_.x0 = columns_[0];
    for (std::size_t j = 1; j < names_.size(); ++j) finish_mode(j);
    return std::move(out_);
  }

 private:
  // x0, then flapK and lagK columns (at least one of each).
  void header(std::string_view line, std::size_t line_no) {
    header_line_ = line_no;
    const std::vector<std::string_view> c = cells(line, kMaxModeColumns + 1);
    if (c.front() != "x0") {
      r_.fail(line_no, "column 1", shown_cell(c.front()),
              "the header row must start with x0 (then the columns flap1, ..., lag1, ...)");
    }
    names_.emplace_back("x0");
    bool flap = false, lag = false;
    for (std::size_t j = 1; j < c.size(); ++j) {
      const std::string where = "column " + std::to_string(j + 1);
      if (j > static_cast<std::size_t>(kMaxModeColumns)) {
        r_.fail(line_no, where, shown_cell(c[j]),
                "more than " + std::to_string(kMaxModeColumns) + " mode columns");
      }
      BendingDirection dir{};
      int k = 0;
      if (!mode_name(c[j], &dir, &k)) {
        r_.fail(line_no, where, shown_cell(c[j]),
                "a mode column is named flapK or lagK (K = 1, 2, ...)");
      }
      const std::string name(c[j]);
      if (std::find(names_.begin(), names_.end(), name) != names_.end())
        r_.fail(line_no, where, name, "column given twice");
      (dir == BendingDirection::Flap ? flap : lag) = true;
      names_.push_back(name);
      ImportedMode m;
      m.name = name;
      m.direction = dir;
      out_.modes.push_back(std::move(m));
    }
    if (!flap || !lag) {
      r_.fail(line_no, "column " + std::to_string(c.size() + 1), "(missing)",
              std::string("the header names no ") + (flap ? "lag" : "flap") +
                  " mode: at least one flapK and one lagK column are needed");
    }
    columns_.resize(names_.size());
  }

  // `omega,w1,w2,...`: each column's rotating frequency by Omega.
  void omega_row(const std::vector<std::string_view>& c, std::size_t line_no) {
    if (omega_line_ != 0) {
      r_.fail(line_no, "x0", "omega",
              "a second omega row (the first is line " + std::to_string(omega_line_) + ")");
    }
    omega_line_ = line_no;
    for (std::size_t j = 1; j < c.size(); ++j) {
      const double w = number(r_, line_no, names_[j], c[j]);
      if (!(w > 0.0)) {
        r_.fail(line_no, names_[j], shown_cell(c[j]), "a rotating frequency by Omega must be > 0");
      }
      omega_.push_back(w);
    }
  }

  // A station x0 in [0, 1], after the previous one, and the shapes' values there.
  void station_row(const std::vector<std::string_view>& c, std::size_t line_no) {
    if (lines_.size() >= static_cast<std::size_t>(kMaxModeStations)) {
      r_.fail(line_no, "x0", shown_cell(c.front()),
              "more than " + std::to_string(kMaxModeStations) + " stations");
    }
    std::vector<double>& x0 = columns_[0];
    const double x = number(r_, line_no, "x0", c.front());
    if (!x0.empty() && !(x > x0.back())) {
      r_.fail(line_no, "x0", shown_cell(c.front()),
              "stations must be strictly increasing (the previous is " +
                  round_trip_text(x0.back()) + ", line " + std::to_string(lines_.back()) + ")");
    }
    if (x0.empty() && std::abs(x) > kEndTolerance) {
      r_.fail(line_no, "x0", shown_cell(c.front()),
              "the first station must be 0 (the root of the elastic blade)");
    }
    if (x > 1.0 + kEndTolerance) {
      r_.fail(line_no, "x0", shown_cell(c.front()),
              "stations run from 0 to 1 (the tip of the elastic blade)");
    }
    x0.push_back(x0.empty() ? 0.0 : x);
    for (std::size_t j = 1; j < c.size(); ++j)
      columns_[j].push_back(number(r_, line_no, names_[j], c[j]));
    lines_.push_back(line_no);
  }

  // Enough stations, the last at the tip (set to 1 exactly).
  void check_stations() {
    std::vector<double>& x0 = columns_[0];
    const std::size_t n = lines_.size();
    if (n < static_cast<std::size_t>(kMinModeStations)) {
      r_.fail(n > 0 ? lines_.back() : header_line_, "x0", std::to_string(n) + " stations",
              "a mode table needs at least " + std::to_string(kMinModeStations) + " stations");
    }
    if (std::abs(x0.back() - 1.0) > kEndTolerance) {
      r_.fail(lines_.back(), "x0", round_trip_text(x0.back()),
              "the last station must be 1 (the tip of the elastic blade)");
    }
    if (!(x0[n - 2] < 1.0)) {
      r_.fail(lines_.back(), "x0", round_trip_text(x0.back()),
              "stations must be strictly increasing to the tip, 1 (the previous is " +
                  round_trip_text(x0[n - 2]) + ")");
    }
    x0.back() = 1.0;
  }

  // Column j as mode j - 1: scaled to tip value 1, a cantilever's zero value and slope at the
  // root checked.
  void finish_mode(std::size_t j) {
    ImportedMode& m = out_.modes[j - 1];
    m.omega = omega_[j - 1];
    std::vector<double>& v = columns_[j];
    double largest = 0.0;
    for (double x : v) largest = std::max(largest, std::abs(x));
    const double tip = v.back();
    if (!(std::abs(tip) > kZeroTip * largest)) {
      r_.fail(lines_.back(), m.name, round_trip_text(tip),
              "the tip value is 0 (at most 1e-6 of the shape's largest value, " +
                  round_trip_text(largest) + "): the shape cannot be scaled to tip value 1");
    }
    for (double& x : v) x /= tip;
    v.back() = 1.0;
    if (std::abs(tip - 1.0) > 1e-9) {
      out_.notes.push_back(m.name + " scaled by 1/" + short_text(tip) + " to tip value 1");
    }
    if (std::abs(v.front()) > kRootValue) {
      r_.fail(lines_.front(), m.name, round_trip_text(v.front() * tip),
              "a cantilevered blade's shape is 0 at the root (here " + short_text(v.front()) +
                  " of the tip value, more than 1e-6)");
    }
    const TabulatedModeShape shape(out_.x0, v);
    double steepest = 0.0;
    for (double x : out_.x0) steepest = std::max(steepest, std::abs(shape.value(1, x)));
    const double root_slope = shape.value(1, 0.0);
    if (std::abs(root_slope) > kRootSlope * steepest) {
      r_.fail(lines_.front(), m.name, "slope " + short_text(root_slope),
              "a cantilevered blade's shape has zero slope at the root: the spline through the "
              "stations (scaled to tip value 1) has slope " +
                  short_text(root_slope) + " there, more than 1e-2 of its largest slope, " +
                  short_text(steepest));
    }
    m.values = std::move(v);
  }

  const Reader& r_;
  ImportedModes out_;
  std::vector<std::size_t> lines_;  // the file line of each station
  std::vector<double> omega_;
  std::size_t omega_line_ = 0, header_line_ = 0;
  std::vector<std::string> names_;  // the header, x0 included
  std::vector<std::vector<double>> columns_;
};

}  // namespace

ImportedModes parse_mode_table(std::string_view text, std::string source) {
  const Reader r{source};
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.remove_prefix(3);  // a UTF-8 byte order mark
  ModeTableReader reader(r, source);
  std::size_t line_no = 0;
  while (!text.empty() || line_no == 0) {
    ++line_no;
    const std::size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
    const std::string_view content = trim(line);
    if (content.empty() || content.front() == '#') continue;
    reader.read(line, line_no);
  }
  return reader.finish(line_no);
}

ModeSet imported_mode_set(const ImportedModes& modes, int flap_modes, int lag_modes) {
  ModeSet s;
  s.kind = "imported";
  const int counts[model::kDirectionCount] = {flap_modes, lag_modes};
  for (const model::Direction dir : model::kDirections) {
    const int count = counts[model::index(dir)];
    // The table's columns are named by the direction and the mode: flap1, lag2, ...
    const std::string base = model::kDirectionNames[model::index(dir)];
    if (count < 1) {
      throw InvalidInput(base + " modes", std::to_string(count), "must be >= 1");
    }
    for (int k = 1; k <= count; ++k) {
      const std::string name = base + std::to_string(k);
      const auto it = std::find_if(modes.modes.begin(), modes.modes.end(),
                                   [&](const ImportedMode& m) { return m.name == name; });
      if (it == modes.modes.end()) {
        throw InvalidInput(modes.source, name + " missing",
                           "the model has " + std::to_string(count) + " " + base +
                               " modes and the mode table no column " + name);
      }
      s[dir].shapes.push_back(std::make_shared<TabulatedModeShape>(modes.x0, it->values));
      s[dir].omega.push_back(it->omega);
    }
  }
  return s;
}

namespace {

// The header of a mode table: what it holds and, when known, the stiffnesses.
std::string mode_table_header(const ModeSet& modes) {
  const DirectionModes& flap = modes[model::Direction::Flap];
  const DirectionModes& lag = modes[model::Direction::Lag];
  std::string out;
  out += "# flaplag mode shapes: " + std::to_string(flap.count()) + " flap and " +
         std::to_string(lag.count()) + " lag " + (modes.kind.empty() ? "" : modes.kind + " ") +
         "modes of the blade, tip value 1\n";
  out += "# x0: elastic span station by l (0 root, 1 tip); flapK, lagK: the shapes there;\n";
  out += "# the row omega: each mode's rotating frequency by Omega\n";
  if (flap.stiffness > 0.0 || lag.stiffness > 0.0) {
    // With a blade table the stiffnesses are the scales of its columns (rotating_modes.h).
    out += std::string(modes.blade ? "# stiffness scale s of the blade table's EI columns "
                                     "(EI/(Omega^2 l I_b) = s x column)"
                                   : "# stiffness EI/(Omega^2 l I_b)") +
           ":";
    for (const model::Direction dir : model::kDirections) {
      out += std::string(dir == model::kDirections[0] ? " " : ", ") +
             model::kDirectionNames[model::index(dir)] + " " +
             round_trip_text(modes[dir].stiffness);
    }
    out += "\n";
  }
  return out;
}

}  // namespace

std::string mode_table_text(const ModeSet& modes, int stations) {
  if (stations < kMinModeStations || stations > kMaxModeStations) {
    throw InvalidInput(
        "stations", std::to_string(stations),
        "must be " + std::to_string(kMinModeStations) + ".." + std::to_string(kMaxModeStations));
  }
  bool complete = true;
  for (const DirectionModes& d : modes.directions)
    complete = complete && d.count() > 0 && d.omega.size() == d.shapes.size();
  if (!complete) {
    throw InvalidInput("modes",
                       std::to_string(modes[model::Direction::Flap].count()) + " x " +
                           std::to_string(modes[model::Direction::Lag].count()),
                       "a mode table needs at least one flap and one lag mode, each with its "
                       "frequency");
  }
  std::string out = mode_table_header(modes);
  out += "x0";
  for (const model::Direction dir : model::kDirections)
    for (int k = 0; k < modes[dir].count(); ++k)
      out += std::string(",") + model::kDirectionNames[model::index(dir)] + std::to_string(k + 1);
  out += "\n";
  for (int i = 0; i < stations; ++i) {
    const double x = static_cast<double>(i) / (stations - 1);
    out += round_trip_text(x);
    for (const DirectionModes& d : modes.directions)
      for (const auto& s : d.shapes) out += "," + round_trip_text(s->value(0, x));
    out += "\n";
  }
  out += "omega";
  for (const DirectionModes& d : modes.directions)
    for (double w : d.omega) out += "," + round_trip_text(w);
  out += "\n";
  return out;
}

double mass_orthogonality_defect(const ModeSet& modes) {
  // Gauss panels on [0, 1], ending at the corners of the blade's mass distribution when it has
  // a few (the mass is linear between its stations).
  std::vector<double> ends = {0.0};
  if (modes.blade && modes.blade->x0.size() <= 66) {
    for (double c : modes.blade->corners()) ends.push_back(c);
  }
  ends.push_back(1.0);
  std::vector<double> x, w;
  for (std::size_t i = 0; i + 1 < ends.size(); ++i) {
    const SpanRule rule = span_rule(ends[i], ends[i + 1]);
    x.insert(x.end(), rule.x0.begin(), rule.x0.end());
    w.insert(w.end(), rule.weight.begin(), rule.weight.end());
  }
  std::vector<double> mass(x.size(), 3.0);
  double tip_mass = 0.0;
  if (modes.blade) {
    for (std::size_t q = 0; q < x.size(); ++q) mass[q] = modes.blade->mass_at(x[q]);
    tip_mass = modes.blade->tip_mass;
  }
  double defect = 0.0;
  for (const DirectionModes& d : modes.directions) {
    const std::vector<std::shared_ptr<const ModeShape>>* shapes = &d.shapes;
    const std::size_t n = shapes->size();
    std::vector<std::vector<double>> v(n, std::vector<double>(x.size()));
    std::vector<double> tip(n);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t q = 0; q < x.size(); ++q) v[i][q] = (*shapes)[i]->value(0, x[q]);
      tip[i] = (*shapes)[i]->value(0, 1.0);
    }
    auto inner = [&](std::size_t i, std::size_t j) {
      double s = tip_mass * tip[i] * tip[j];
      for (std::size_t q = 0; q < x.size(); ++q) s += w[q] * mass[q] * v[i][q] * v[j][q];
      return s;
    };
    std::vector<double> diagonal(n);
    for (std::size_t i = 0; i < n; ++i) diagonal[i] = inner(i, i);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        defect = std::max(defect, std::abs(inner(i, j)) / std::sqrt(diagonal[i] * diagonal[j]));
  }
  return defect;
}

}  // namespace flaplag
