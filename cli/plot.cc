// flaplag CLI — gnuplot scripts and rendering.
#include "plot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/numerics/continuation.h"
#include "options.h"
#include "output.h"

extern char** environ;

namespace flaplag::cli {
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

std::string line_plot_script(const std::string& title, const std::vector<Panel>& panels,
                             int columns) {
  std::string s;
  int block = 0;
  std::vector<std::vector<std::string>> names(panels.size());
  for (std::size_t p = 0; p < panels.size(); ++p) {
    for (const Curve& c : panels[p].curves) {
      const std::string name = "$d" + std::to_string(block++);
      names[p].push_back(name);
      s += name + " << EOD\n";
      for (std::size_t i = 0; i < c.x.size() && i < c.y.size(); ++i)
        s += value(c.x[i]) + " " + value(c.y[i]) + "\n";
      s += "EOD\n";
    }
  }
  s += "set grid\nset key outside right top\n";
  const std::size_t cols = static_cast<std::size_t>(std::max(columns, 1));
  s += "set multiplot layout " + std::to_string((panels.size() + cols - 1) / cols) + "," +
       std::to_string(cols) + " title " + quoted(title) + "\n";
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const Panel& pn = panels[p];
    s += "set title " + quoted(pn.title) + "\nset xlabel " + quoted(pn.xlabel) + "\nset ylabel " +
         quoted(pn.ylabel) + "\n";
    s += "plot ";
    for (std::size_t c = 0; c < pn.curves.size(); ++c) {
      const Curve& cv = pn.curves[c];
      if (c > 0) s += ", ";
      s += names[p][c] + " using 1:2 " +
           (cv.points   ? "with points pt " + std::to_string(cv.point_type) + " ps 0.8"
            : cv.smooth ? std::string("smooth csplines with lines lw 1.5")
                        : std::string("with lines lw 1.5")) +
           " title " + quoted(cv.title);
    }
    if (pn.zero_line)
      s += std::string(pn.curves.empty() ? "" : ", ") + "0 with lines lc rgb 'black' dt 2 notitle";
    for (std::size_t k = 0; k < pn.levels.size(); ++k) {
      s += std::string(pn.curves.empty() && !pn.zero_line && k == 0 ? "" : ", ") +
           value(pn.levels[k].first) + " with lines lc rgb 'red' dt 3 lw 1.5 title " +
           quoted(pn.levels[k].second);
    }
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
  s += "set title " + quoted(title) + "\nset xlabel " + quoted(xlabel) + "\nset ylabel " +
       quoted(ylabel) + "\n";
  s += "set cblabel " + quoted("max zeta [1/rev]") +
       "\nset palette defined (-1 '#2166ac', 0 '#f7f7f7', 1 "
       "'#b2182b')\n";
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
       "$boundary using 1:2 with lines lc rgb 'black' lw 2 title 'zeta = 0'\n";
  return s;
}

void SweepPicture::add_criterion(std::optional<double> c) {
  if (c && std::isfinite(*c) && std::find(criteria.begin(), criteria.end(), *c) == criteria.end())
    criteria.push_back(*c);
}

namespace {

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
  if (max_zeta || picture.quantity == SweepQuantity::Zeta)
    return Panel{max_zeta ? "largest damping exponent zeta over the modes"
                          : "damping exponent zeta (real part of the characteristic exponent)",
                 "mu",
                 "zeta [1/rev]",
                 {},
                 true,
                 {}};
  Panel p{"damping ratio -zeta/|lambda| (omega continued from hover)",
          "mu",
          "damping ratio -zeta/|lambda| [% of critical]",
          {},
          true,
          {}};
  for (double c : picture.criteria)
    p.levels.emplace_back(100.0 * c, "criterion " + num(100.0 * c) + " %");
  return p;
}

}  // namespace

std::string sweep_plot_script(const std::string& model, const std::vector<double>& mu,
                              const std::vector<ModeCurve>& modes, const SweepPicture& picture) {
  Panel pz = sweep_panel(picture, false);
  Panel pw{"frequency omega", "mu", "omega [per rev]", {}, false, {}};
  for (const ModeCurve& m : modes) {
    pz.curves.push_back({m.label, mu, sweep_quantity(m, picture.quantity), false, 7});
    pw.curves.push_back({m.label, mu, m.omega, false, 7});
  }
  return line_plot_script("flaplag sweep: " + model, {pz, pw});
}

std::string sweep_overlay_script(const std::vector<SweepOverlay>& sweeps, bool max_zeta,
                                 const SweepPicture& picture) {
  Panel pz = sweep_panel(picture, max_zeta);
  Panel pw{"frequency omega", "mu", "omega [per rev]", {}, false, {}};
  for (const SweepOverlay& s : sweeps) {
    if (max_zeta) {
      // NaN (a gap) where no mode has a zeta.
      std::vector<double> z(s.mu.size(), NAN);
      for (const ModeCurve& m : s.modes)
        for (std::size_t i = 0; i < z.size() && i < m.zeta.size(); ++i)
          if (std::isfinite(m.zeta[i]) && !(z[i] >= m.zeta[i])) z[i] = m.zeta[i];
      pz.curves.push_back({s.label, s.mu, z, false, 7});
      continue;
    }
    for (const ModeCurve& m : s.modes) {
      pz.curves.push_back(
          {s.label + ": " + m.label, s.mu, sweep_quantity(m, picture.quantity), false, 7});
      pw.curves.push_back({s.label + ": " + m.label, s.mu, m.omega, false, 7});
    }
  }
  if (max_zeta) return line_plot_script("flaplag sweeps: largest zeta", {pz});
  return line_plot_script("flaplag sweeps", {pz, pw});
}

std::string study_plot_script(const std::string& parameter, const std::vector<StudyMark>& rows,
                              std::optional<double> damping_criterion) {
  Curve flutter{"mu_c, flutter", {}, {}, true, 7},
      periodic{"mu_c, periodic (omega = 0, 1/2, 1)", {}, {}, true, 5};
  Curve intervals{"unstable intervals", {}, {}, false, 7};
  for (const StudyMark& row : rows) {
    if (row.mu_c) {
      Curve& c = row.periodic ? periodic : flutter;
      c.x.push_back(row.value);
      c.y.push_back(*row.mu_c);
    }
    for (const auto& [on, off] : row.intervals) {
      intervals.x.insert(intervals.x.end(), {row.value, row.value, NAN});
      intervals.y.insert(intervals.y.end(), {on, off, NAN});
    }
  }
  Panel p{"critical advance ratio", parameter, "mu", {intervals, flutter, periodic}, false, {}};
  // Per mode, where its damping ratio first falls below the criterion.
  std::vector<Curve> below;
  for (const StudyMark& row : rows) {
    for (const auto& [mode, mu] : row.crossings) {
      auto it = std::find_if(below.begin(), below.end(),
                             [&, m = mode](const Curve& c) { return c.title == m; });
      if (it == below.end()) {
        below.push_back({mode, {}, {}, true, 4 + 2 * static_cast<int>(below.size())});
        it = below.end() - 1;
      }
      it->x.push_back(row.value);
      it->y.push_back(mu);
    }
  }
  if (damping_criterion) {
    for (Curve& c : below) {
      c.title = c.title + ": damping ratio < " + num(100.0 * *damping_criterion) + " %";
      p.curves.push_back(c);
    }
  }
  return line_plot_script("flaplag study: " + parameter, {p});
}

std::string max_zeta_plot_script(const std::string& xname, const std::vector<double>& x,
                                 const std::string& yname, const std::vector<double>& y,
                                 const std::vector<std::vector<double>>& z) {
  return map_plot_script("flaplag map: max zeta", xname, x, yname, y, z);
}

std::string response_plot_script(double mu, const std::vector<double>& psi_deg,
                                 const std::vector<double>& flap, const std::vector<double>& lag) {
  Panel pf{"flap tip deflection w/l",           "psi [deg]", "w/l",
           {{"flap", psi_deg, flap, false, 7}}, false,       {}};
  Panel pl{"lag tip deflection v/l (positive lag)", "psi [deg]", "v/l",
           {{"lag", psi_deg, lag, false, 7}},       false,       {}};
  return line_plot_script("flaplag response at mu = " + num(mu), {pf, pl});
}

std::string simulate_plot_script(double mu, const std::vector<double>& revolutions,
                                 const std::vector<double>& flap, const std::vector<double>& lag) {
  Panel pf{"flap tip perturbation",
           "revolutions",
           "dw/l",
           {{"flap", revolutions, flap, false, 7}},
           false,
           {}};
  Panel pl{"lag tip perturbation",
           "revolutions",
           "dv/l",
           {{"lag", revolutions, lag, false, 7}},
           false,
           {}};
  return line_plot_script("flaplag simulate at mu = " + num(mu), {pf, pl});
}

std::string mode_shapes_plot_script(double omega_flap, double omega_lag,
                                    const std::vector<double>& x0,
                                    const std::vector<ShapeCurves>& flap,
                                    const std::vector<ShapeCurves>& lag) {
  const std::string x = "x0 = r/l, from the root of the elastic blade";
  Panel flap_shapes{"flap mode shapes eta_k(x0)", x, "shape [tip value 1]", {}, true, {}};
  Panel lag_shapes{"lag mode shapes gamma_k(x0)", x, "shape [tip value 1]", {}, true, {}};
  Panel flap_slopes{"flap slopes eta_k'(x0)", x, "slope [1/l]", {}, true, {}};
  Panel lag_slopes{"lag slopes gamma_k'(x0)", x, "slope [1/l]", {}, true, {}};
  for (std::size_t k = 0; k < flap.size(); ++k) {
    const std::string name = "eta" + std::to_string(k + 1);
    flap_shapes.curves.push_back({name, x0, flap[k].value, false, 7, true});
    flap_slopes.curves.push_back({name, x0, flap[k].slope, false, 7, true});
  }
  for (std::size_t k = 0; k < lag.size(); ++k) {
    const std::string name = "gamma" + std::to_string(k + 1);
    lag_shapes.curves.push_back({name, x0, lag[k].value, false, 7, true});
    lag_slopes.curves.push_back({name, x0, lag[k].slope, false, 7, true});
  }
  return line_plot_script("flaplag modes: exact rotating modes, omega_{F1} = " + num(omega_flap) +
                              ", omega_{L1} = " + num(omega_lag) + " per rev",
                          {flap_shapes, lag_shapes, flap_slopes, lag_slopes}, 2);
}

std::string campbell_plot_script(const CampbellPicture& c) {
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
  s += "set grid\nset key outside right top\nset title " +
       quoted("flaplag campbell: mode frequencies against the rotor speed, mu = " + num(c.mu)) +
       "\nset xlabel " + quoted("rotor speed Omega/Omega_0") + "\nset ylabel " +
       quoted("frequency omega/Omega_0 [per rev at Omega_0]") + "\n";
  const double xmax = right > 0.0 ? right : 1.0, ymax = top > 0.0 ? 1.15 * top : 1.0;
  s += "set xrange [0:" + value(xmax) + "]\nset yrange [0:" + value(ymax) + "]\n";
  s += "set arrow from 1, graph 0 to 1, graph 1 nohead lc rgb 'gray40' dt 3\n";
  s += "set label " + quoted("Omega_0") + " at 1, graph 0.03 left offset 0.5, 0\n";
  // Each per-rev line named where it leaves the frame.
  for (int n = 1; n <= c.harmonics; ++n) {
    const double x = std::min(xmax, ymax / n);
    s += "set label " + quoted(std::to_string(n) + "/rev") + " at " + value(x) + ", " +
         value(n * x) + " right offset -0.3, -0.8 tc rgb 'gray40'\n";
  }
  s += "plot ";
  for (std::size_t m = 0; m < c.modes.size(); ++m)
    s += "$m" + std::to_string(m) + " using 1:2 with lines lw 2 title " + quoted(c.modes[m].label) +
         ", ";
  for (int n = 1; n <= c.harmonics; ++n)
    s += std::to_string(n) + " * x with lines lc rgb 'gray60' dt 2 " +
         (n == 1 ? "title " + quoted("per-rev lines n Omega") : std::string("notitle")) + ", ";
  // (gnuplot warns about a data block without points: the crossings only when there are any.)
  if (c.crossings.empty()) {
    s.resize(s.size() - 2);
    s += "\n";
  } else {
    s += "$crossings using 1:2 with points pt 6 ps 1.2 lc rgb 'black' title " +
         quoted("crossings") + "\n";
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

}  // namespace flaplag::cli
