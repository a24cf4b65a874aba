// flaplag CLI — pictures of results, rendered by gnuplot (Debian gnuplot-nox: svg and
// pngcairo terminals).  flaplag writes a gnuplot script with the data inline and writes
// gnuplot's image output to the requested file under the rules of -o (output.h).  Without
// gnuplot the data is still written and the plot is skipped with one warning line.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace flaplag::cli {

// The extensions --plot accepts (".svg", ".png"); false otherwise.
bool is_plot_path(const std::string& path);

// One curve of a line plot.
struct Curve {
  std::string title;
  std::vector<double> x, y;  // NaN: a gap
  bool points = false;       // markers instead of a line
  int point_type = 7;        // gnuplot point type for markers
};

struct Panel {
  std::string title, xlabel, ylabel;
  std::vector<Curve> curves;
  bool zero_line = false;  // draw y = 0 (the stability boundary of zeta)
};

// Panels stacked vertically in one picture.
std::string line_plot_script(const std::string& title, const std::vector<Panel>& panels);

// A heat map of z over (x, y) (z[i][j] at y[i], x[j]; NaN where unknown) with the z = 0
// contour drawn: the stability boundary of a max-zeta map.
std::string map_plot_script(const std::string& title, const std::string& xlabel,
                            const std::vector<double>& x, const std::string& ylabel,
                            const std::vector<double>& y,
                            const std::vector<std::vector<double>>& z);

// Renders `script` (without terminal/output lines) into `path` (.svg or .png).  Returns "" on
// success, or a one-line warning when gnuplot is not installed or fails (nothing is written
// then).  Throws InvalidInput("plot", path, reason) for an output path that cannot be written.
std::string render_plot(const std::string& script, const std::string& path);

}  // namespace flaplag::cli
