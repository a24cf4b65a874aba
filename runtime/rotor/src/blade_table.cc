// flaplag — a blade property table: parsing, and the nondimensional blade it describes.
#include "flaplag/rotor/blade_table.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <memory>
#include <system_error>
#include <tuple>

#include "flaplag/blade/blade_elements.h"
#include "flaplag/blade/rotating_modes.h"
#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"

namespace flaplag {
namespace {

constexpr std::size_t kMaxStations = 100000;

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) {
    s.remove_prefix(1);
  }
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

// A cell as the user wrote it, short and printable.
std::string shown_cell(std::string_view cell) {
  std::string out;
  for (char c : cell.substr(0, 40)) out += (c >= 32 && c < 127) ? c : '?';
  if (cell.size() > 40) out += "...";
  return out.empty() ? "\"\"" : out;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(trim(line.substr(
        start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
    if (cells.size() > 16) break;  // more cells than any table has: reported as extra
  }
  return cells;
}

struct Where {
  const std::string& source;
  std::size_t line;
  std::string at(std::string_view column) const {
    return source + ":" + std::to_string(line) + ": " + std::string(column);
  }
};

double number(const Where& w, std::string_view column, std::string_view cell) {
  double v = 0.0;
  const char* end = cell.data() + cell.size();
  const auto [ptr, ec] = std::from_chars(cell.data(), end, v);
  if (cell.empty() || ec != std::errc() || ptr != end) {
    throw InvalidInput(w.at(column), shown_cell(cell), "not a number");
  }
  if (!std::isfinite(v)) throw InvalidInput(w.at(column), shown_cell(cell), "must be finite");
  return v;
}

enum class Column { Station, Mass, EIFlap, EILag, Chord, Twist };

bool column_of(std::string_view name, Column* c, bool* dimensional) {
  static const std::map<std::string_view, Column> names = {
      {"x", Column::Station},      {"r", Column::Station},    {"m", Column::Mass},
      {"EI_flap", Column::EIFlap}, {"EI_lag", Column::EILag}, {"chord", Column::Chord},
      {"twist_deg", Column::Twist}};
  const auto it = names.find(name);
  if (it == names.end()) return false;
  *c = it->second;
  if (it->second == Column::Station) *dimensional = name == "r";
  return true;
}

// A name in the first cell: a keyword line (`tip_mass,0.1`), not a row of numbers.
bool is_keyword(std::string_view first) {
  return !first.empty() &&
         (std::isalpha(static_cast<unsigned char>(first.front())) || first.front() == '_') &&
         first != "inf" && first != "nan";
}

// The table read line by line: the header, then keyword lines and rows in any order.
class BladeTableReader {
 public:
  explicit BladeTableReader(std::string source) { t_.source = std::move(source); }

  // One line that is neither blank nor a comment.
  void read(std::string_view line, std::size_t line_no) {
    const Where w{t_.source, line_no};
    const std::vector<std::string_view> cells = split(line);
    if (!have_header_) {
      header(w, line, cells);
      have_header_ = true;
    } else if (is_keyword(cells.front())) {
      keyword(w, line, cells);
    } else {
      row(w, line, cells);
      t_.line.push_back(static_cast<int>(line_no));
    }
  }

  // The table, after the last line: what the whole of it must have.
  BladeTable finish() {
    if (!have_header_)
      throw InvalidInput(t_.source, "(empty)",
                         "has no header line (x or r, m, EI_flap, EI_lag, ...)");
    if (t_.station.size() < 2) {
      throw InvalidInput(t_.source, std::to_string(t_.station.size()) + " stations",
                         "a blade table needs at least 2 stations (root and tip)");
    }
    if (t_.dimensional) {
      for (const auto& [seen, name] :
           {std::pair{seen_speed_, "rotor_speed_rpm"}, std::pair{seen_density_, "air_density"},
            std::pair{seen_blades_, "blades"}}) {
        if (!seen)
          throw InvalidInput(
              t_.source, "(missing)",
              std::string("a dimensional table needs the line `") + name + ",VALUE`");
      }
    }
    return std::move(t_);
  }

 private:
  void header(const Where& w, std::string_view line, const std::vector<std::string_view>& cells) {
    bool has[6] = {};
    for (std::string_view name : cells) {
      Column c;
      bool dim = false;
      if (!column_of(name, &c, &dim)) {
        throw InvalidInput(w.at("header"), shown_cell(name),
                           "unknown column (x or r, m, EI_flap, EI_lag, chord, twist_deg)");
      }
      if (has[static_cast<int>(c)])
        throw InvalidInput(w.at("header"), shown_cell(name), "given twice");
      has[static_cast<int>(c)] = true;
      if (c == Column::Station) t_.dimensional = dim;
      columns_.push_back(c);
      column_names_.emplace_back(name);
    }
    for (const auto& [c, name] :
         {std::pair{Column::Station, "x (or r)"}, std::pair{Column::Mass, "m"},
          std::pair{Column::EIFlap, "EI_flap"}, std::pair{Column::EILag, "EI_lag"}}) {
      if (!has[static_cast<int>(c)])
        throw InvalidInput(w.at("header"), shown_cell(line), std::string("has no column ") + name);
    }
    if (t_.dimensional && !has[static_cast<int>(Column::Chord)]) {
      throw InvalidInput(w.at("header"), shown_cell(line),
                         "a dimensional table (column r) needs the chord column");
    }
  }

  // `name,value`: the tip mass; a dimensional table's rotor speed, air density and blades.
  void keyword(const Where& w, std::string_view line, const std::vector<std::string_view>& cells) {
    const std::string_view first = cells.front();
    if (cells.size() != 2)
      throw InvalidInput(w.at(first), shown_cell(line), "a keyword line is `name,value`");
    const double v = number(w, first, cells[1]);
    bool* seen = nullptr;
    if (first == "tip_mass") {
      if (!(v >= 0.0)) throw InvalidInput(w.at(first), shown_cell(cells[1]), "must be >= 0");
      t_.tip_mass = v;
      seen = &seen_tip_;
    } else if (first == "rotor_speed_rpm" || first == "air_density" || first == "blades") {
      if (!t_.dimensional) {
        throw InvalidInput(w.at(first), shown_cell(cells[1]),
                           "only in a dimensional table (column r, SI units)");
      }
      if (!(v > 0.0)) throw InvalidInput(w.at(first), shown_cell(cells[1]), "must be positive");
      if (first == "rotor_speed_rpm") {
        t_.rotor_speed_rpm = v;
        seen = &seen_speed_;
      } else if (first == "air_density") {
        t_.air_density = v;
        seen = &seen_density_;
      } else {
        if (v != std::floor(v) || v > 64) {
          throw InvalidInput(w.at(first), shown_cell(cells[1]), "must be a whole number 1..64");
        }
        t_.blades = static_cast<int>(v);
        seen = &seen_blades_;
      }
    } else {
      throw InvalidInput(w.at("keyword"), shown_cell(first),
                         "unknown (tip_mass; rotor_speed_rpm, air_density, blades)");
    }
    if (*seen) throw InvalidInput(w.at(first), shown_cell(cells[1]), "given twice");
    *seen = true;
  }

  // A station: one number per column of the header.
  void row(const Where& w, std::string_view line, const std::vector<std::string_view>& cells) {
    if (cells.size() != columns_.size()) {
      throw InvalidInput(w.at("row"), shown_cell(line),
                         std::to_string(cells.size()) + " cells for " +
                             std::to_string(columns_.size()) + " columns");
    }
    if (t_.station.size() >= kMaxStations) {
      throw InvalidInput(w.at("row"), shown_cell(line),
                         "more than " + std::to_string(kMaxStations) + " stations");
    }
    for (std::size_t i = 0; i < cells.size(); ++i) cell(w, i, cells[i]);
  }

  void cell(const Where& w, std::size_t i, std::string_view cell) {
    const std::string& column = column_names_[i];
    const double v = number(w, column, cell);
    const Column c = columns_[i];
    const bool positive =
        c == Column::Mass || c == Column::EIFlap || c == Column::EILag || c == Column::Chord;
    if (positive && !(v > 0.0))
      throw InvalidInput(w.at(column), shown_cell(cell), "must be positive");
    switch (c) {
      case Column::Station:
        if (v < 0.0) throw InvalidInput(w.at(column), shown_cell(cell), "must be >= 0");
        if (!t_.station.empty() && !(v > t_.station.back())) {
          throw InvalidInput(w.at(column), shown_cell(cell),
                             "stations must increase (the previous is " +
                                 round_trip_text(t_.station.back()) + ")");
        }
        t_.station.push_back(v);
        break;
      case Column::Mass:
        t_.mass.push_back(v);
        break;
      case Column::EIFlap:
        t_.ei_flap.push_back(v);
        break;
      case Column::EILag:
        t_.ei_lag.push_back(v);
        break;
      case Column::Chord:
        t_.chord.push_back(v);
        break;
      case Column::Twist:
        if (!(std::abs(v) < 90.0))
          throw InvalidInput(w.at(column), shown_cell(cell), "must be within (-90, 90) degrees");
        t_.twist_deg.push_back(v);
        break;
    }
  }

  BladeTable t_;
  std::vector<Column> columns_;
  std::vector<std::string> column_names_;
  bool have_header_ = false, seen_tip_ = false, seen_speed_ = false, seen_density_ = false,
       seen_blades_ = false;
};

}  // namespace

BladeTable parse_blade_table(std::string_view text, std::string source) {
  BladeTableReader reader(std::move(source));
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // a UTF-8 byte order mark
  std::size_t line_no = 0, start = 0;
  while (start <= text.size()) {
    const std::size_t nl = text.find('\n', start);
    const std::string_view line = trim(
        text.substr(start, nl == std::string_view::npos ? std::string_view::npos : nl - start));
    start = nl == std::string_view::npos ? text.size() + 1 : nl + 1;
    ++line_no;
    if (line.empty() || line.front() == '#') continue;
    reader.read(line, line_no);
  }
  return reader.finish();
}

std::vector<std::string> blade_table_fields(bool dimensional) {
  std::vector<std::string> f = {"root_offset", "length_ratio", "modes"};
  if (dimensional) {
    for (const char* n : {"gamma", "sigma", "omega_flap", "omega_lag"}) f.emplace_back(n);
  }
  return f;
}

namespace {

// int_a^b f for f linear between the stations times a polynomial weight of degree <= 2:
// Simpson on every interval is exact for the cubic.
template <typename F>
double simpson(const std::vector<double>& s, F f) {
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < s.size(); ++i) {
    const double a = s[i], b = s[i + 1];
    sum += (b - a) / 6.0 * (f(i, a, 0.0) + 4.0 * f(i, 0.5 * (a + b), 0.5) + f(i, b, 1.0));
  }
  return sum;
}

double lerp(const std::vector<double>& v, std::size_t i, double t) {
  return v[i] + t * (v[i + 1] - v[i]);
}

// Column value at station position s (linear interpolation).
double at(const std::vector<double>& st, const std::vector<double>& v, double s) {
  if (s <= st.front()) return v.front();
  if (s >= st.back()) return v.back();
  const std::size_t i =
      static_cast<std::size_t>(std::upper_bound(st.begin(), st.end(), s) - st.begin()) - 1;
  return lerp(v, i, (s - st[i]) / (st[i + 1] - st[i]));
}

}  // namespace

BladeOrigin apply_blade_table(const BladeTable& t, RotorParameters& p) {
  const std::vector<double>& s = t.station;
  const double tip = s.back(), root = s.front();
  auto blade = std::make_shared<BladeProperties>();
  BladeProperties& b = *blade;
  b.source = t.source;
  BladeOrigin& o = b.origin;
  o.dimensional = t.dimensional;
  if (!t.dimensional && std::abs(tip - 1.0) > 1e-9) {
    throw InvalidInput(t.source + ":" + std::to_string(t.line.back()) + ": x", round_trip_text(tip),
                       "the last station is the tip, x = 1");
  }
  const double radius = t.dimensional ? tip : 1.0;
  o.root_offset = root / radius;
  o.length_ratio = (tip - root) / radius;
  if (!(o.root_offset < 1.0 - 1e-6)) {
    throw InvalidInput(t.source, round_trip_text(root),
                       "the root station must lie inside the blade");
  }
  const double l = tip - root;  // in the table's length unit
  for (double x : s) b.x0.push_back(std::min((x - root) / l, 1.0));
  b.x0.front() = 0.0;
  b.x0.back() = 1.0;
  // The reference chord: the chord at x = 0.75 (r = 0.75 R).
  if (!t.chord.empty()) {
    const double x_ref = 0.75 * radius;
    if (x_ref < root) {
      throw InvalidInput(t.source, round_trip_text(root),
                         "the reference chord is taken at 0.75 R, inboard of the root station");
    }
    o.reference_chord = at(s, t.chord, x_ref);
    for (double c : t.chord) b.chord.push_back(c / o.reference_chord);
  } else {
    b.chord.assign(s.size(), 1.0);
  }
  if (!t.twist_deg.empty()) {
    for (double d : t.twist_deg) b.twist.push_back(d * kPi / 180.0);
  } else {
    b.twist.assign(s.size(), 0.0);
  }
  // I_b = int_0^l m r0^2 dr0 + M_tip l^2, in the table's units (r0 from the root).
  const double blade_mass =
      simpson(s, [&](std::size_t i, double, double u) { return lerp(t.mass, i, u); });
  const double moment = simpson(s, [&](std::size_t i, double r, double u) {
    return lerp(t.mass, i, u) * (r - root) * (r - root);
  });
  // A nondimensional table's tip mass is a fraction of the blade's mass.
  const double tip_mass = t.dimensional ? t.tip_mass : t.tip_mass * blade_mass;
  const double inertia = moment + tip_mass * l * l;
  for (double m : t.mass) b.mass.push_back(m * l * l * l / inertia);
  b.tip_mass = tip_mass * l * l / inertia;
  o.tip_mass = b.tip_mass;
  p.blade = nullptr;
  p.modes = ModeKind::Exact;
  p.root_offset = o.root_offset;
  p.length_ratio = o.length_ratio;
  if (t.dimensional) {
    o.radius = radius;
    o.rotor_speed = t.rotor_speed_rpm * kTwoPi / 60.0;
    o.air_density = t.air_density;
    o.blades = t.blades;
    o.inertia = inertia;
    const double omega2 = o.rotor_speed * o.rotor_speed;
    for (double ei : t.ei_flap) b.stiffness_flap.push_back(ei / (omega2 * l * inertia));
    for (double ei : t.ei_lag) b.stiffness_lag.push_back(ei / (omega2 * l * inertia));
    o.gamma = o.air_density * p.lift_slope * o.reference_chord * std::pow(radius, 4) / inertia;
    o.sigma = o.blades * o.reference_chord / (kPi * radius);
    p.gamma = o.gamma;
    p.sigma = o.sigma;
  } else {
    // Shapes: scaled to the first rotating frequencies by the analysis.
    const double f0 = t.ei_flap.front(), l0 = t.ei_lag.front();
    for (double ei : t.ei_flap) b.stiffness_flap.push_back(ei / f0);
    for (double ei : t.ei_lag) b.stiffness_lag.push_back(ei / l0);
  }
  try {
    // The mass normalised to rounding (the integral above is exact).
    const BladeProperties normal = normalised_mass(b);
    b.mass = normal.mass;
    b.tip_mass = normal.tip_mass;
    validate(b);
  } catch (const InvalidInput& e) {
    throw InvalidInput(t.source + ": " + e.name(), e.value(), e.reason());
  }
  if (t.dimensional) {
    // The rotating frequencies of the given stiffness; the analysis then scales the columns to
    // these frequencies, i.e. by 1 (to rounding).
    std::tie(o.omega_flap, o.omega_lag) = stiffness_frequencies(p, blade);
    p.omega_flap = o.omega_flap;
    p.omega_lag = o.omega_lag;
  }
  p.blade = blade;
  return o;
}

std::pair<double, double> stiffness_frequencies(const RotorParameters& p,
                                                std::shared_ptr<const BladeProperties> blade) {
  ExactModeOptions opt;
  opt.n_basis = p.basis == kElementBasis ? kMaxBasisFunctions : galerkin_basis(p);
  opt.e1_over_l = p.root_offset / p.length_ratio;
  opt.blade = std::move(blade);
  const ExactModes modes =
      p.basis == kElementBasis ? element_stiffness_modes(opt) : blade_stiffness_modes(opt);
  return {modes.modes[model::Direction::Flap].omega[0],
          modes.modes[model::Direction::Lag].omega[0]};
}

}  // namespace flaplag
