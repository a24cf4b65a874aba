// flaplag documents — gnuplot scripts and rendering.
#include "flaplag/documents/plot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/documents/output.h"
#include "flaplag/model_api.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/rotor/parameter_table.h"

extern char** environ;

namespace flaplag::documents {
namespace {

bool ends_with(const std::string& s, const char* suffix) {
  const std::string t(suffix);
  return s.size() >= t.size() && s.compare(s.size() - t.size(), t.size(), t) == 0;
}

// Every text of a script (titles, labels, names read from a result file or typed) reaches
// gnuplot through this function and nowhere else: a single-quoted gnuplot string, ' doubled.
// gnuplot 5.4 expands neither backquotes (`cmd`: a shell command) nor @macros inside single
// quotes, and a ';' or '"' there is text.  A line break would end the command and start a new
// one, so every control character (newline, CR, tab, NUL, ...) becomes a blank.
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\'')
      q += "''";
    else if (u < 0x20 || u == 0x7f)
      q += ' ';
    else
      q += c;
  }
  return q + "'";
}

// Data values in gnuplot's inline blocks: "NaN" marks a gap (gnuplot skips it).
std::string value(double v) { return std::isfinite(v) ? round_trip_text(v) : "NaN"; }

}  // namespace

bool is_plot_path(const std::string& path) {
  return ends_with(path, ".svg") || ends_with(path, ".png");
}

std::string literal_text(const std::string& s) {
  std::string t;
  for (char c : s) {
    if (std::string_view("^_@&~{}\\").find(c) != std::string_view::npos) t += '\\';
    t += c;
  }
  return t;
}

namespace {

// The series colours (Okabe-Ito, told apart also by colour-blind readers), by Curve::color.
const char* const kPalette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                "#E69F00", "#56B4E9", "#7F7F7F", "#000000"};
constexpr int kPaletteSize = static_cast<int>(sizeof kPalette / sizeof kPalette[0]);

std::string color(int index) {
  return std::string(" lc rgb '") + (index < 0 ? "#000000" : kPalette[index % kPaletteSize]) + "'";
}

// "[a:b]" with "*" for an open end.
std::string range(double lo, double hi) {
  return "[" + (std::isfinite(lo) ? value(lo) : std::string("*")) + ":" +
         (std::isfinite(hi) ? value(hi) : std::string("*")) + "]";
}

// The key of every picture: below its panel, entries side by side, marker before the text.
const char* const kKey = "set key below center horizontal reverse Left samplen 2 spacing 1.1\n";

}  // namespace

std::string line_plot_script(const std::string& title, const std::vector<Panel>& panels,
                             int columns) {
  std::string s;
  int block = 0;
  std::vector<std::vector<std::string>> names(panels.size());
  for (std::size_t p = 0; p < panels.size(); ++p) {
    for (const Curve& c : panels[p].curves) {
      if (c.key_only) {
        names[p].push_back("NaN");  // nothing drawn: the key's entry only
        continue;
      }
      const std::string name = "$d" + std::to_string(block++);
      names[p].push_back(name + " using 1:2");
      s += name + " << EOD\n";
      for (std::size_t i = 0; i < c.x.size() && i < c.y.size(); ++i)
        s += value(c.x[i]) + " " + value(c.y[i]) + "\n";
      s += "EOD\n";
    }
  }
  s += "set grid\n";
  s += kKey;
  const std::size_t cols = static_cast<std::size_t>(std::max(columns, 1));
  s += "set multiplot layout " + std::to_string((panels.size() + cols - 1) / cols) + "," +
       std::to_string(cols) + " title " + quoted(title) + " font ',13'\n";
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const Panel& pn = panels[p];
    s += "set title " + quoted(pn.title) + "\nset xlabel " + quoted(pn.xlabel) + "\nset ylabel " +
         quoted(pn.ylabel) + "\n";
    s += "set xrange " + range(pn.xmin, pn.xmax) + "\nset yrange " + range(pn.ymin, pn.ymax) + "\n";
    s += "set autoscale xfix\nset offsets graph " + value(pn.x_margin) + ", graph " +
         value(pn.x_margin) + ", graph 0.04, graph 0.04\n";
    std::vector<std::string> items;
    for (std::size_t c = 0; c < pn.curves.size(); ++c) {
      const Curve& cv = pn.curves[c];
      std::string item = names[p][c] + " " +
                         (cv.points ? "with points pt " + std::to_string(cv.point_type) + " ps " +
                                          value(cv.point_size)
                          : cv.smooth ? std::string("smooth csplines with lines lw 1.5")
                                      : std::string("with lines lw 1.5")) +
                         color(cv.color);
      item += cv.title.empty() ? std::string(" notitle")
                               : " title " + quoted(cv.title) + (cv.literal ? " noenhanced" : "");
      items.push_back(item);
    }
    if (pn.zero_line) items.push_back("0 with lines lc rgb 'black' dt 2 notitle");
    for (const auto& [y, text] : pn.levels)
      items.push_back(value(y) + " with lines lc rgb '#C00000' dt 3 lw 1.5 title " + quoted(text));
    // (A panel without anything to draw still needs one item: an empty key entry.)
    if (items.empty()) items.push_back("NaN notitle");
    s += "plot ";
    for (std::size_t i = 0; i < items.size(); ++i) s += (i > 0 ? ", " : "") + items[i];
    s += "\n";
  }
  s += "unset multiplot\n";
  return s;
}

std::string map_plot_script(const std::string& title, const std::string& xlabel,
                            const std::vector<double>& x, const std::string& ylabel,
                            const std::vector<double>& y,
                            const std::vector<std::vector<double>>& z) {
  // Nonuniform matrix format: first row "n x1 .. xn", then "y z1 .. zn" per row.
  std::string s = "$map << EOD\n" + std::to_string(x.size());
  for (double v : x) s += " " + value(v);
  s += "\n";
  for (std::size_t i = 0; i < y.size() && i < z.size(); ++i) {
    s += value(y[i]);
    for (std::size_t j = 0; j < x.size(); ++j) s += " " + value(j < z[i].size() ? z[i][j] : NAN);
    s += "\n";
  }
  s += "EOD\n";
  s += "set title " + quoted(title) + " font ',13'\nset xlabel " + quoted(xlabel) +
       "\nset ylabel " + quoted(ylabel) + "\n";
  s += "set cblabel " + quoted("largest damping exponent max ζ [1/rev]  (> 0: unstable)") +
       "\nset palette defined (-1 '#2166ac', 0 '#f7f7f7', 1 "
       "'#b2182b')\n";
  s += kKey;
  // Symmetric colour range so that white is zeta = 0.
  double zmax = 0.0;
  for (const auto& row : z)
    for (double v : row)
      if (std::isfinite(v)) zmax = std::max(zmax, std::abs(v));
  if (zmax > 0.0) s += "set cbrange [" + value(-zmax) + ":" + value(zmax) + "]\n";
  s += "set autoscale xfix\nset autoscale yfix\nset view map\nset contour base\nset cntrparam "
       "levels discrete 0\nunset surface\n"
       "set table $boundary\nsplot $map nonuniform matrix using 1:2:3 notitle\nunset table\n"
       "unset contour\nset surface\n";
  s += "plot $map nonuniform matrix using 1:2:3 with image notitle, "
       "$boundary using 1:2 with lines lc rgb 'black' lw 2 title " +
       quoted("ζ = 0: the stability boundary") + "\n";
  return s;
}

// ---- axis labels from the parameter table ----------------------------------------------------

std::string symbol_text(const std::string& ascii) {
  static const std::pair<const char*, const char*> kGreek[] = {
      {"omega", "ω̄"},  {"gamma", "γ"}, {"sigma", "σ"}, {"theta", "θ"},
      {"beta", "β"},   {"eta", "η"},   {"mu", "μ"},    {"zeta", "ζ"},
      {"lambda", "λ"}, {"alpha", "α"}, {"psi", "ψ"},   {"delta", "δ"}};
  const std::size_t bar = ascii.find('_');
  std::string base = ascii.substr(0, bar);
  for (const auto& [word, greek] : kGreek)
    if (base == word) base = greek;
  if (bar == std::string::npos) return literal_text(base);
  return literal_text(base) + "_{" + literal_text(ascii.substr(bar + 1)) + "}";
}

std::optional<std::string> parameter_axis_label(const std::string& word) {
  if (word == "mu") return std::string("advance ratio μ");
  std::string field = word;
  for (char& c : field)
    if (c == '-') c = '_';
  const ParameterSpec* spec = find_parameter(field);
  if (spec == nullptr || spec->type != ParameterType::Real) return std::nullopt;
  // What it is measured by is in its units: the description to its first comma or " by ".
  std::string what = spec->description;
  what = what.substr(0, std::min(what.find(','), what.find(" by ")));
  std::string label = what;
  if (spec->symbol[0] != '\0') label += " " + symbol_text(spec->symbol);
  if (std::string(spec->units) != "-") label += " [" + std::string(spec->units) + "]";
  return label;
}

void SweepPicture::add_criterion(std::optional<double> c) {
  if (c && std::isfinite(*c) && std::find(criteria.begin(), criteria.end(), *c) == criteria.end())
    criteria.push_back(*c);
}

std::optional<double> locked_frequency(double omega) {
  if (!std::isfinite(omega) || classify_crossing(omega) != InstabilityKind::Periodic)
    return std::nullopt;
  // k halves: 0 stays 0, an odd k is 1/2 and an even k > 0 is 1 per rev (the deviation kept).
  const double a = std::abs(omega);
  const long k = std::lround(2.0 * a);
  if (k == 0) return a;
  return k % 2 == 1 ? a - static_cast<double>(k - 1) / 2.0 : a - static_cast<double>(k / 2 - 1);
}

namespace {

const char* const kMu = "advance ratio μ";
const char* const kWarningTitle = "warning at this μ (see the row message in the result)";
const char* const kFailedTitle = "failed at this μ (no exponents; drawn at 0)";
const char* const kLockedTitle = "locked to 0, 1/2 or 1 per rev (drawn as ω mod 1)";

// The y quantity of a mode in the picture: zeta itself, or -zeta/|lambda| in % (NaN: a gap).
std::vector<double> sweep_quantity(const ModeCurve& m, SweepQuantity q) {
  if (q == SweepQuantity::Zeta) return m.zeta;
  std::vector<double> y;
  for (std::size_t i = 0; i < m.zeta.size(); ++i) {
    const std::optional<double> r = damping_ratio(m.zeta[i], i < m.omega.size() ? m.omega[i] : NAN);
    y.push_back(r ? 100.0 * *r : NAN);
  }
  return y;
}

// The first panel of a sweep picture: zeta, or the damping ratio with its criterion lines.
Panel sweep_panel(const SweepPicture& picture, bool max_zeta) {
  Panel p;
  p.xlabel = kMu;
  p.zero_line = true;
  if (max_zeta || picture.quantity == SweepQuantity::Zeta) {
    p.title = max_zeta ? "largest damping exponent over the modes (> 0: unstable)"
                       : "damping exponent ζ, the real part of the exponent λ = ζ + iω "
                         "(> 0: unstable)";
    p.ylabel = max_zeta ? "max ζ [1/rev]" : "ζ [1/rev]";
    return p;
  }
  p.title = "damping ratio −ζ/|λ| of each mode (ω continued from hover; < 0: unstable)";
  p.ylabel = "damping ratio −ζ/|λ| [% of critical]";
  for (double c : picture.criteria)
    p.levels.emplace_back(100.0 * c, "criterion " + num(100.0 * c) + " % of critical");
  return p;
}

Panel frequency_panel() {
  Panel p;
  p.title = "frequency ω, the imaginary part of the exponent";
  p.xlabel = kMu;
  p.ylabel = "ω [per rev]";
  return p;
}

// The markers of the rows that are not ok, on the curves of `y` (or at 0 where a curve has no
// value there), with one key entry each kind.
void mark_rows(const std::vector<double>& mu, const std::vector<RowStatus>& status,
               const std::vector<std::vector<double>>& y, Curve* warning, Curve* failed) {
  for (std::size_t i = 0; i < mu.size() && i < status.size(); ++i) {
    if (status[i] == RowStatus::Ok) continue;
    Curve* c = status[i] == RowStatus::Warning ? warning : failed;
    bool any = false;
    for (const std::vector<double>& v : y) {
      if (i < v.size() && std::isfinite(v[i])) {
        c->x.push_back(mu[i]);
        c->y.push_back(v[i]);
        any = true;
      }
    }
    if (!any) {
      c->x.push_back(mu[i]);
      c->y.push_back(0.0);
    }
  }
}

// The modes in the order of their labels: flap before lag, then by number (model_api.h),
// whatever the order of the result (an M x N model's hover order is by frequency).
std::vector<const ModeCurve*> in_order(const std::vector<ModeCurve>& modes) {
  auto key = [](const std::string& label) {
    std::string direction;
    int k = 0;
    model::parse_mode_label(label, &direction, &k);  // labels were checked on reading
    return std::make_pair(direction == "lag", k);
  };
  std::vector<const ModeCurve*> order;
  for (const ModeCurve& m : modes) order.push_back(&m);
  std::stable_sort(order.begin(), order.end(), [&](const ModeCurve* a, const ModeCurve* b) {
    return key(a->label) < key(b->label);
  });
  return order;
}

// The curves of one sweep: the first-panel quantity and the frequency of each mode (the locked
// stretches as open markers, ω mod 1), its rows not ok marked; `prefix` before each mode's
// label (an overlay); colours from *next.
void add_sweep(const SweepOverlay& s, const std::string& prefix, const SweepPicture& picture,
               int* next, Panel* pz, Panel* pw, Curve* warning, Curve* failed, bool* locked) {
  std::vector<std::vector<double>> shown;
  for (const ModeCurve* mode : in_order(s.modes)) {
    const ModeCurve& m = *mode;
    const int colour = (*next)++;
    const std::vector<double> y = sweep_quantity(m, picture.quantity);
    pz->curves.push_back({prefix + m.label, s.mu, y, false, 7, false, colour, 0.8, true});
    shown.push_back(y);
    // (The modes' key is the first panel's, the colours the same.)
    Curve free{"", s.mu, {}, false, 7, false, colour};
    Curve lock{"", {}, {}, true, 6, false, colour, 0.9};
    for (std::size_t i = 0; i < s.mu.size(); ++i) {
      const double w = i < m.omega.size() ? m.omega[i] : NAN;
      const std::optional<double> folded = locked_frequency(w);
      free.y.push_back(folded ? NAN : w);
      if (folded) {
        lock.x.push_back(s.mu[i]);
        lock.y.push_back(*folded);
      }
    }
    pw->curves.push_back(free);
    if (!lock.x.empty()) {
      pw->curves.push_back(lock);
      *locked = true;
    }
  }
  mark_rows(s.mu, s.status, shown, warning, failed);
}

// A damping-ratio panel zoomed to the lightly damped modes when a heavily damped one would
// flatten them (a flap mode at 57 % over a lag mode at 1 %): the y axis ends at four times the
// least damped mode's largest ratio (at least the criterion and 2 %), and the title names the
// curves that leave the panel and how high they reach.  Nothing changes when the curves share a
// scale.
void focus_on_light_modes(Panel* p, const std::vector<double>& criteria) {
  double light = INFINITY, top = -INFINITY, bottom = INFINITY;
  for (const Curve& c : p->curves) {
    if (c.points) continue;
    double m = -INFINITY;
    for (double y : c.y)
      if (std::isfinite(y)) {
        m = std::max(m, y);
        bottom = std::min(bottom, y);
      }
    if (!std::isfinite(m)) continue;
    light = std::min(light, m);
    top = std::max(top, m);
  }
  if (!std::isfinite(light)) return;
  double floor = 2.0;
  for (double c : criteria) floor = std::max(floor, 100.0 * c);
  const double focus = 4.0 * std::max(light, floor);
  if (!(top > 2.0 * focus)) return;
  p->ymax = focus;
  if (bottom > -focus) p->ymin = std::min(0.0, bottom) - 0.05 * focus;
  std::string above;
  for (const Curve& c : p->curves) {
    if (c.points) continue;
    double m = -INFINITY;
    for (double y : c.y)
      if (std::isfinite(y)) m = std::max(m, y);
    if (m > focus) above += (above.empty() ? "" : ", ") + c.title + " up to " + num(m) + " %";
  }
  p->title += "; zoomed to the lightly damped modes (" + above + ")";
}

std::string sweeps_script(const std::string& title, const std::vector<SweepOverlay>& sweeps,
                          bool overlay, const SweepPicture& picture) {
  Panel pz = sweep_panel(picture, false), pw = frequency_panel();
  Curve warning{kWarningTitle, {}, {}, true, 2, false, -1, 1.4};
  Curve failed{kFailedTitle, {}, {}, true, 11, false, 1, 1.4};
  bool locked = false;
  int next = 0;
  for (const SweepOverlay& s : sweeps)
    add_sweep(s, overlay ? s.label + ": " : "", picture, &next, &pz, &pw, &warning, &failed,
              &locked);
  if (picture.quantity == SweepQuantity::DampingRatio) focus_on_light_modes(&pz, picture.criteria);
  for (Curve* c : {&warning, &failed})
    if (!c->x.empty()) pz.curves.push_back(*c);
  if (locked) pw.curves.push_back({kLockedTitle, {}, {}, true, 6, false, -1, 0.8, false, true});
  return line_plot_script(title, {pz, pw});
}

}  // namespace

std::string sweep_plot_script(const std::string& title, const SweepOverlay& sweep,
                              const SweepPicture& picture) {
  return sweeps_script(title, {sweep}, false, picture);
}

std::string sweep_overlay_script(const std::string& title, const std::vector<SweepOverlay>& sweeps,
                                 bool max_zeta, const SweepPicture& picture) {
  if (!max_zeta) return sweeps_script(title, sweeps, true, picture);
  Panel pz = sweep_panel(picture, true);
  Curve warning{kWarningTitle, {}, {}, true, 2, false, -1, 1.4};
  Curve failed{kFailedTitle, {}, {}, true, 11, false, 1, 1.4};
  int next = 0;
  for (const SweepOverlay& s : sweeps) {
    // NaN (a gap) where no mode has a zeta.
    std::vector<double> z(s.mu.size(), NAN);
    for (const ModeCurve& m : s.modes)
      for (std::size_t i = 0; i < z.size() && i < m.zeta.size(); ++i)
        if (std::isfinite(m.zeta[i]) && !(z[i] >= m.zeta[i])) z[i] = m.zeta[i];
    pz.curves.push_back({s.label, s.mu, z, false, 7, false, next++, 0.8, true});
    mark_rows(s.mu, s.status, {z}, &warning, &failed);
  }
  for (Curve* c : {&warning, &failed})
    if (!c->x.empty()) pz.curves.push_back(*c);
  return line_plot_script(title, {pz});
}

std::string study_plot_script(const std::string& title, const std::string& axis_label,
                              double mu_max, const std::vector<StudyMark>& rows,
                              std::optional<double> damping_criterion) {
  Curve intervals{"unstable intervals (an open end drawn to μ_{max})", {}, {}, false, 7, false, 6};
  // Periodic rows by their locked frequency, as the paper writes 0, 1/2 or 1 into Fig 15's marks.
  Curve flutter{"μ_c, flutter", {}, {}, true, 7, false, 0, 1.0},
      periodic{"μ_c, periodic (ω locked to 0, 1/2 or 1 per rev)", {}, {}, true, 5, false, 1, 1.0},
      one{"μ_c, periodic, ω = 1 per rev", {}, {}, true, 5, false, 1, 1.0},
      half{"μ_c, periodic, ω = 1/2 per rev", {}, {}, true, 13, false, 3, 1.3},
      zero{"μ_c, periodic, ω = 0 (a real exponent)", {}, {}, true, 15, false, 4, 1.2};
  Curve stable{"stable up to μ_{max} = " + num(mu_max), {}, {}, true, 8, false, 2, 1.3};
  Curve hover{"unstable in hover (drawn at 0)", {}, {}, true, 11, false, 1, 1.3};
  Curve failed{"failed: μ_c unknown (drawn at 0)", {}, {}, true, 2, false, -1, 1.4};
  Curve warning{"warning (see the row message in the result)", {}, {}, true, 6, false, -1, 2.0};
  for (const StudyMark& row : rows) {
    double at = NAN;  // where the row's marker is
    if (row.mu_c) {
      const std::optional<double> locked = locked_frequency(row.omega);
      const long halves = locked ? std::lround(2.0 * *locked) : -1;
      Curve& c = !row.periodic ? flutter
                 : halves == 2 ? one
                 : halves == 1 ? half
                 : halves == 0 ? zero
                               : periodic;
      at = *row.mu_c;
      c.x.push_back(row.value);
      c.y.push_back(at);
    } else if (row.hover_unstable || row.status == RowStatus::Failed) {
      at = 0.0;
      Curve& c = row.hover_unstable ? hover : failed;
      c.x.push_back(row.value);
      c.y.push_back(at);
    } else if (row.intervals.empty()) {
      at = mu_max;
      stable.x.push_back(row.value);
      stable.y.push_back(at);
    }
    if (row.status == RowStatus::Warning && std::isfinite(at)) {
      warning.x.push_back(row.value);
      warning.y.push_back(at);
    }
    for (const auto& [on, off] : row.intervals) {
      intervals.x.insert(intervals.x.end(), {row.value, row.value, NAN});
      intervals.y.insert(intervals.y.end(), {on, off, NAN});
    }
  }
  Panel p;
  p.title =
      "critical advance ratio μ_c, the first μ with ζ > 0 (scanned up to μ_{max} = " + num(mu_max) +
      ")";
  p.xlabel = axis_label;
  p.ylabel = "μ_c";
  p.ymin = 0.0;
  p.ymax = 1.05 * mu_max;
  p.x_margin = 0.03;
  for (Curve* c :
       {&intervals, &flutter, &one, &half, &zero, &periodic, &stable, &hover, &failed, &warning})
    if (!c->x.empty()) p.curves.push_back(*c);
  // Per mode, where its damping ratio first falls below the criterion.
  if (damping_criterion) {
    std::vector<Curve> below;
    for (const StudyMark& row : rows) {
      for (const auto& [mode, mu] : row.crossings) {
        auto it = std::find_if(below.begin(), below.end(),
                               [&, m = mode](const Curve& c) { return c.title == m; });
        if (it == below.end()) {
          const int n = static_cast<int>(below.size());
          below.push_back({mode, {}, {}, true, 4 + 2 * n, false, 3 + n, 1.0, true});
          it = below.end() - 1;
        }
        it->x.push_back(row.value);
        it->y.push_back(mu);
      }
    }
    for (Curve& c : below) {
      c.title += ": damping ratio < " + num(100.0 * *damping_criterion) + " %";
      p.curves.push_back(c);
    }
  }
  return line_plot_script(title, {p});
}

std::string max_zeta_plot_script(const std::string& title, const std::string& xlabel,
                                 const std::vector<double>& x, const std::string& ylabel,
                                 const std::vector<double>& y,
                                 const std::vector<std::vector<double>>& z) {
  return map_plot_script(title, xlabel, x, ylabel, y, z);
}

namespace {

std::string tip_script(const std::string& title, const std::string& xlabel,
                       const std::string& flap_title, const std::string& flap_label,
                       const std::string& lag_title, const std::string& lag_label,
                       const std::vector<double>& x, const std::vector<double>& flap,
                       const std::vector<double>& lag) {
  Panel pf, pl;
  pf.title = flap_title;
  pl.title = lag_title;
  pf.xlabel = pl.xlabel = xlabel;
  pf.ylabel = flap_label;
  pl.ylabel = lag_label;
  pf.curves.push_back({"", x, flap, false, 7, false, 0});
  pl.curves.push_back({"", x, lag, false, 7, false, 1});
  pf.xmin = pl.xmin = x.empty() ? NAN : x.front();
  pf.xmax = pl.xmax = x.empty() ? NAN : x.back();
  return line_plot_script(title, {pf, pl});
}

}  // namespace

std::string response_plot_script(const std::string& title, const std::vector<double>& psi_deg,
                                 const std::vector<double>& flap, const std::vector<double>& lag) {
  return tip_script(title, "azimuth ψ [deg]",
                    "flap tip deflection w/l over one revolution (hover equilibrium included)",
                    "w/l", "lag tip deflection v/l (positive lag)", "v/l", psi_deg, flap, lag);
}

std::string simulate_plot_script(const std::string& title, const std::vector<double>& revolutions,
                                 const std::vector<double>& flap, const std::vector<double>& lag) {
  return tip_script(title, "time [revolutions]", "flap tip perturbation Δw/l", "Δw/l",
                    "lag tip perturbation Δv/l (positive lag)", "Δv/l", revolutions, flap, lag);
}

std::string mode_shapes_plot_script(const std::string& title, const std::vector<double>& x0,
                                    const std::vector<ShapeCurves>& flap,
                                    const std::vector<ShapeCurves>& lag) {
  const std::string x = "x_0 = r/l, from the root of the elastic blade";
  auto panel = [&](const char* t, const char* y) {
    Panel p;
    p.title = t;
    p.xlabel = x;
    p.ylabel = y;
    p.zero_line = true;
    p.xmin = 0.0;
    p.xmax = 1.0;
    return p;
  };
  Panel flap_shapes = panel("flap mode shapes η_k(x_0)", "η_k [tip value 1]");
  Panel lag_shapes = panel("lag mode shapes γ_k(x_0)", "γ_k [tip value 1]");
  Panel flap_slopes = panel("flap slopes η_k'(x_0)", "η_k' [1/l]");
  Panel lag_slopes = panel("lag slopes γ_k'(x_0)", "γ_k' [1/l]");
  for (std::size_t k = 0; k < flap.size(); ++k) {
    const std::string name = "η_" + std::to_string(k + 1);
    const int c = static_cast<int>(k);
    flap_shapes.curves.push_back({name, x0, flap[k].value, false, 7, true, c});
    flap_slopes.curves.push_back({name, x0, flap[k].slope, false, 7, true, c});
  }
  for (std::size_t k = 0; k < lag.size(); ++k) {
    const std::string name = "γ_" + std::to_string(k + 1);
    const int c = static_cast<int>(k);
    lag_shapes.curves.push_back({name, x0, lag[k].value, false, 7, true, c});
    lag_slopes.curves.push_back({name, x0, lag[k].slope, false, 7, true, c});
  }
  return line_plot_script(title, {flap_shapes, lag_shapes, flap_slopes, lag_slopes}, 2);
}

std::string campbell_plot_script(const std::string& title, const CampbellPicture& c) {
  std::string s;
  double top = 0.0, right = 0.0;
  for (double v : c.speed)
    if (std::isfinite(v)) right = std::max(right, v);
  for (std::size_t m = 0; m < c.modes.size(); ++m) {
    s += "$m" + std::to_string(m) + " << EOD\n";
    for (std::size_t i = 0; i < c.speed.size() && i < c.modes[m].omega.size(); ++i) {
      s += value(c.speed[i]) + " " + value(c.modes[m].omega[i]) + "\n";
      if (std::isfinite(c.modes[m].omega[i])) top = std::max(top, c.modes[m].omega[i]);
    }
    s += "EOD\n";
  }
  s += "$crossings << EOD\n";
  for (const auto& [x, y] : c.crossings) s += value(x) + " " + value(y) + "\n";
  s += "EOD\n";
  // The per-rev lines are clipped above the modes: they are references, not data.
  s += "set grid\n";
  s += kKey;
  s += "set title " + quoted(title) + " font ',13'\nset xlabel " + quoted("rotor speed Ω/Ω_0") +
       "\nset ylabel " + quoted("frequency ω/Ω_0 [per rev at Ω_0]") + "\n";
  const double xmax = right > 0.0 ? right : 1.0, ymax = top > 0.0 ? 1.15 * top : 1.0;
  s += "set xrange [0:" + value(xmax) + "]\nset yrange [0:" + value(ymax) + "]\n";
  s += "set arrow from 1, graph 0 to 1, graph 1 nohead lc rgb 'gray40' dt 3\n";
  s += "set label " + quoted("Ω_0") + " at 1, graph 0.03 left offset 0.5, 0\n";
  // Each per-rev line named where it leaves the frame.
  for (int n = 1; n <= c.harmonics; ++n) {
    const double x = std::min(xmax, ymax / n);
    s += "set label " + quoted(std::to_string(n) + "/rev") + " at " + value(x) + ", " +
         value(n * x) + " right offset -0.3, -0.8 tc rgb 'gray40'\n";
  }
  s += "plot ";
  for (std::size_t m = 0; m < c.modes.size(); ++m)
    s += "$m" + std::to_string(m) + " using 1:2 with lines lw 2" + color(static_cast<int>(m)) +
         " title " + quoted(c.modes[m].label) + " noenhanced, ";
  for (int n = 1; n <= c.harmonics; ++n)
    s += std::to_string(n) + " * x with lines lc rgb 'gray60' dt 2 " +
         (n == 1 ? "title " + quoted("per-rev lines nΩ") : std::string("notitle")) + ", ";
  // (gnuplot warns about a data block without points: the crossings only when there are any.)
  if (c.crossings.empty()) {
    s.resize(s.size() - 2);
    s += "\n";
  } else {
    s += "$crossings using 1:2 with points pt 6 ps 1.2 lc rgb 'black' title " +
         quoted("crossings with the per-rev lines") + "\n";
  }
  return s;
}

namespace {

// An unlinked temporary file holding `text`, positioned at its start (-1 on failure): gnuplot
// reads its script from it as standard input, so that no pipe can fill up while we read the
// image, and no file name is left for anyone to replace meanwhile.
int script_file(const std::string& text) {
  const char* dir = std::getenv("TMPDIR");
  std::string pattern = (dir != nullptr && dir[0] == '/' ? std::string(dir) : std::string("/tmp")) +
                        "/flaplag-plot-XXXXXX";
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) return -1;
  ::unlink(name.data());
  ::fcntl(fd, F_SETFD, FD_CLOEXEC);
  if (!write_all(fd, text) || ::lseek(fd, 0, SEEK_SET) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

enum class Gnuplot { Ok, Missing, Failed };

// Runs gnuplot (found on PATH, executed directly: no shell) with `script` on its standard input,
// its standard output (the image) captured into *image and its messages discarded.
Gnuplot run_gnuplot(const std::string& script, std::string* image) {
  const int in = script_file(script);
  if (in < 0) return Gnuplot::Failed;
  int out[2];
  if (::pipe(out) != 0) {
    ::close(in);
    return Gnuplot::Failed;
  }
  ::fcntl(out[0], F_SETFD, FD_CLOEXEC);
  ::fcntl(out[1], F_SETFD, FD_CLOEXEC);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in, 0);
  posix_spawn_file_actions_adddup2(&actions, out[1], 1);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  char program[] = "gnuplot";
  char* argv[] = {program, nullptr};
  pid_t pid = -1;
  const int spawned = ::posix_spawnp(&pid, program, &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(in);
  ::close(out[1]);
  if (spawned != 0) {
    ::close(out[0]);
    return spawned == ENOENT ? Gnuplot::Missing : Gnuplot::Failed;
  }
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(out[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    image->append(buf, static_cast<std::size_t>(n));
  }
  ::close(out[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return Gnuplot::Failed;
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127) return Gnuplot::Missing;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || image->empty()) return Gnuplot::Failed;
  return Gnuplot::Ok;
}

// The DeferredPictures of the running command, if any.
DeferredPictures* deferred = nullptr;

}  // namespace

DeferredPictures::DeferredPictures() : previous_(deferred) { deferred = this; }

DeferredPictures::~DeferredPictures() { deferred = previous_; }

void DeferredPictures::commit() {
  for (const auto& [target, image] : pictures_) target.write(image);
  pictures_.clear();
}

namespace {

const char* const kSvgTerminal = "set terminal svg size 900,700 dynamic enhanced font 'Sans,12'\n";
const char* const kPngTerminal = "set terminal pngcairo size 1200,900 enhanced font 'Sans,11'\n";

}  // namespace

std::string render_plot(const std::string& script, const std::string& path) {
  if (!is_plot_path(path)) throw InvalidInput("plot", shown(path), "must end in .svg or .png");
  OutputTarget target(path, "plot");  // checked before anything runs
  const bool svg = ends_with(path, ".svg");
  const std::string full = std::string(svg ? kSvgTerminal : kPngTerminal) + "set output\n" + script;
  std::string image;
  switch (run_gnuplot(full, &image)) {
    case Gnuplot::Missing:
      return "gnuplot is not installed (Debian: gnuplot-nox): plot " + path + " not written";
    case Gnuplot::Failed:
      return "gnuplot failed: plot " + path + " not written";
    case Gnuplot::Ok:
      break;
  }
  if (deferred != nullptr)
    deferred->pictures_.emplace_back(std::move(target), std::move(image));
  else
    target.write(image);
  return "";
}

std::string render_svg(const std::string& script) {
  std::string image;
  switch (run_gnuplot(std::string(kSvgTerminal) + "set output\n" + script, &image)) {
    case Gnuplot::Missing:
      throw RendererUnavailable("gnuplot is not installed (Debian: gnuplot-nox)");
    case Gnuplot::Failed:
      throw RendererUnavailable("gnuplot failed to draw a picture");
    case Gnuplot::Ok:
      break;
  }
  return image;
}

}  // namespace flaplag::documents
