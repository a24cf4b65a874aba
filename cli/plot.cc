// flaplag CLI — gnuplot scripts and rendering.
#include "plot.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "options.h"
#include "output.h"

namespace flaplag::cli {
namespace {

bool ends_with(const std::string& s, const char* suffix) {
  const std::string t(suffix);
  return s.size() >= t.size() && s.compare(s.size() - t.size(), t.size(), t) == 0;
}

// A gnuplot string literal.
std::string quoted(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') q += '\\';
    q += c == '\n' ? ' ' : c;
  }
  return q + "\"";
}

// Data values in gnuplot's inline blocks: "NaN" marks a gap (gnuplot skips it).
std::string value(double v) { return std::isfinite(v) ? round_trip_text(v) : "NaN"; }

}  // namespace

bool is_plot_path(const std::string& path) {
  return ends_with(path, ".svg") || ends_with(path, ".png");
}

std::string line_plot_script(const std::string& title, const std::vector<Panel>& panels) {
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
  s += "set multiplot layout " + std::to_string(panels.size()) + ",1 title " + quoted(title) + "\n";
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const Panel& pn = panels[p];
    s += "set title " + quoted(pn.title) + "\nset xlabel " + quoted(pn.xlabel) + "\nset ylabel " +
         quoted(pn.ylabel) + "\n";
    s += "plot ";
    for (std::size_t c = 0; c < pn.curves.size(); ++c) {
      const Curve& cv = pn.curves[c];
      if (c > 0) s += ", ";
      s += names[p][c] + " using 1:2 " +
           (cv.points ? "with points pt " + std::to_string(cv.point_type) + " ps 0.8"
                      : std::string("with lines lw 1.5")) +
           " title " + quoted(cv.title);
    }
    if (pn.zero_line)
      s += std::string(pn.curves.empty() ? "" : ", ") + "0 with lines lc rgb 'black' dt 2 notitle";
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
  s += "set cblabel \"max zeta [1/rev]\"\nset palette defined (-1 '#2166ac', 0 '#f7f7f7', 1 "
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

std::string sweep_plot_script(const std::string& model, const std::vector<double>& mu,
                              const std::vector<ModeCurve>& modes) {
  Panel pz{"damping exponent zeta (real part of the characteristic exponent)",
           "mu",
           "zeta [1/rev]",
           {},
           true};
  Panel pw{"frequency omega", "mu", "omega [per rev]", {}, false};
  for (const ModeCurve& m : modes) {
    pz.curves.push_back({m.label, mu, m.zeta, false, 7});
    pw.curves.push_back({m.label, mu, m.omega, false, 7});
  }
  return line_plot_script("flaplag sweep: " + model, {pz, pw});
}

std::string sweep_overlay_script(const std::vector<SweepOverlay>& sweeps, bool max_zeta) {
  Panel pz{max_zeta ? "largest damping exponent zeta over the modes"
                    : "damping exponent zeta (real part of the characteristic exponent)",
           "mu",
           "zeta [1/rev]",
           {},
           true};
  Panel pw{"frequency omega", "mu", "omega [per rev]", {}, false};
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
      pz.curves.push_back({s.label + ": " + m.label, s.mu, m.zeta, false, 7});
      pw.curves.push_back({s.label + ": " + m.label, s.mu, m.omega, false, 7});
    }
  }
  if (max_zeta) return line_plot_script("flaplag sweeps: largest zeta", {pz});
  return line_plot_script("flaplag sweeps", {pz, pw});
}

std::string study_plot_script(const std::string& parameter, const std::vector<StudyMark>& rows) {
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
  Panel p{"critical advance ratio", parameter, "mu", {intervals, flutter, periodic}, false};
  return line_plot_script("flaplag study: " + parameter, {p});
}

std::string max_zeta_plot_script(const std::string& xname, const std::vector<double>& x,
                                 const std::string& yname, const std::vector<double>& y,
                                 const std::vector<std::vector<double>>& z) {
  return map_plot_script("flaplag map: max zeta", xname, x, yname, y, z);
}

std::string response_plot_script(double mu, const std::vector<double>& psi_deg,
                                 const std::vector<double>& flap, const std::vector<double>& lag) {
  Panel pf{
      "flap tip deflection w/l", "psi [deg]", "w/l", {{"flap", psi_deg, flap, false, 7}}, false};
  Panel pl{"lag tip deflection v/l (positive lag)",
           "psi [deg]",
           "v/l",
           {{"lag", psi_deg, lag, false, 7}},
           false};
  return line_plot_script("flaplag response at mu = " + num(mu), {pf, pl});
}

std::string simulate_plot_script(double mu, const std::vector<double>& revolutions,
                                 const std::vector<double>& flap, const std::vector<double>& lag) {
  Panel pf{"flap tip perturbation",
           "revolutions",
           "dw/l",
           {{"flap", revolutions, flap, false, 7}},
           false};
  Panel pl{
      "lag tip perturbation", "revolutions", "dv/l", {{"lag", revolutions, lag, false, 7}}, false};
  return line_plot_script("flaplag simulate at mu = " + num(mu), {pf, pl});
}

std::string render_plot(const std::string& script, const std::string& path) {
  if (!is_plot_path(path)) throw InvalidInput("plot", shown(path), "must end in .svg or .png");
  const OutputTarget target(path);  // checked before anything runs
  const bool svg = ends_with(path, ".svg");
  const std::string full =
      std::string(svg ? "set terminal svg size 900,700 dynamic enhanced font 'Sans,12'\n"
                      : "set terminal pngcairo size 1200,900 enhanced font 'Sans,11'\n") +
      "set output\n" + script;
  char name[] = "/tmp/flaplag-plot-XXXXXX";
  const int fd = mkstemp(name);
  if (fd < 0) return "plot " + path + " not written: no temporary file for the gnuplot script";
  {
    std::ofstream f(name, std::ios::binary);
    f << full;
  }
  close(fd);
  // gnuplot writes the image to its standard output; its messages go to stderr, discarded.
  const std::string command = "gnuplot " + std::string(name) + " 2>/dev/null";
  std::FILE* pipe = popen(command.c_str(), "r");
  std::string image;
  int status = -1;
  if (pipe != nullptr) {
    char buf[65536];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) image.append(buf, n);
    status = pclose(pipe);
  }
  std::remove(name);
  const int code = status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code == 127)
    return "gnuplot is not installed (Debian: gnuplot-nox): plot " + path + " not written";
  if (code != 0 || image.empty()) return "gnuplot failed: plot " + path + " not written";
  target.write(image);
  return "";
}

}  // namespace flaplag::cli
