// flaplag documents — pictures of results, rendered by gnuplot (Debian gnuplot-nox: svg and
// pngcairo terminals).  flaplag writes a gnuplot script with the data inline and writes
// gnuplot's image output to the requested file under the rules of an output (output.h).  Every text
// in a script (a title, a label, a name read from a result file) is a single-quoted gnuplot string,
// never code, and gnuplot is executed directly, without a shell.  Without gnuplot the data is
// still written and the plot is skipped with one warning line.
#pragma once

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "flaplag/documents/names.h"
#include "flaplag/documents/output.h"

namespace flaplag::documents {

// The extensions --plot accepts (".svg", ".png"); false otherwise.
bool is_plot_path(const std::string& path);

// Texts: every title and label is gnuplot enhanced text (μ, ω̄_{L1}: a subscript in braces),
// always inside a single-quoted string (never code).  A text taken from a result file or typed
// (a model name, a mode label, a --label) is either escaped (literal_text) or drawn with
// `noenhanced` (Curve::literal), so that its markup characters are drawn as they are.

// `s` with each enhanced-text markup character (^ _ @ & ~ { } \) escaped: drawn literally.
std::string literal_text(const std::string& s);

// One curve of a line plot.
struct Curve {
  std::string title;         // "" : not in the key
  std::vector<double> x, y;  // NaN: a gap
  bool points = false;       // markers instead of a line
  int point_type = 7;        // gnuplot point type for markers
  bool smooth = false;       // a cubic spline through the points (smooth data at few stations)
  int color = -1;            // index into the palette (series colours); -1: black
  double point_size = 0.8;
  bool literal = false;   // the title is a name from a result or typed: drawn as is (noenhanced)
  bool key_only = false;  // no data: an entry of the key that explains a marker
};

struct Panel {
  std::string title, xlabel, ylabel;
  std::vector<Curve> curves;
  bool zero_line = false;  // draw y = 0 (the stability boundary of zeta)
  // Horizontal lines y = value, each with its title (a damping criterion).
  std::vector<std::pair<double, std::string>> levels;
  // Fixed ends of the axes (NaN: autoscaled; an autoscaled y axis gets a margin of 4 %).
  double xmin = NAN, xmax = NAN, ymin = NAN, ymax = NAN;
  double x_margin = 0.0;  // of an autoscaled x axis, a fraction of the width (markers at the ends)
};

// Panels in one picture, row by row in `columns` columns (1: stacked vertically), under one
// title (the case), each panel's key below it.
std::string line_plot_script(const std::string& title, const std::vector<Panel>& panels,
                             int columns = 1);

// A heat map of z over (x, y) (z[i][j] at y[i], x[j]; NaN where unknown) with the z = 0
// contour drawn: the stability boundary of a max-zeta map.
std::string map_plot_script(const std::string& title, const std::string& xlabel,
                            const std::vector<double>& x, const std::string& ylabel,
                            const std::vector<double>& y,
                            const std::vector<std::vector<double>>& z);

// The axis label of a rotor parameter from the parameter table (parameter_table.h): its
// description (to its first comma or " by ") and symbol in enhanced text with its units, e.g.
// "first rotating lag frequency ω̄_{L1} [per rev]"; "advance ratio μ" for "mu".  `word`: the
// field or its option spelling ("omega-lag"); nullopt for a word that names no real parameter.
std::optional<std::string> parameter_axis_label(const std::string& word);
// The table's ASCII symbol ("omega_L1", "theta_1c", "C_Do") as enhanced text ("ω̄_{L1}",
// "θ_{1c}", "C_{Do}").
std::string symbol_text(const std::string& ascii);

// ---- the pictures of the commands ------------------------------------------------------------
// Each is drawn from the numbers of the command's JSON output (plot_data.cc builds them from
// the result, for --plot and `flaplag plot DATA.json` alike).  `title`: the case (model,
// linearization, operating values) in enhanced text, one line.

// The status of a row of a result: drawn with a marker when not ok.
enum class RowStatus { Ok, Warning, Failed };

// sweep: the damping ratio -zeta/|lambda| in % of critical (or zeta, as the paper's Figs 3-8)
// and omega(mu) of each mode's dominant exponent; a frequency locked to 0, 1/2 or 1 per rev is
// drawn modulo 1 (in [0, 1]) with open markers; rows not ok are marked.
struct ModeCurve {
  std::string label;
  std::vector<double> zeta, omega;  // at the sweep's mu values
};
enum class SweepQuantity { DampingRatio, Zeta };
struct SweepPicture {
  SweepQuantity quantity = SweepQuantity::DampingRatio;
  // Damping ratio: the criterion lines (fractions of critical; drawn in %), each once.
  std::vector<double> criteria;
  void add_criterion(std::optional<double> c);
};
struct SweepOverlay {
  std::string label;  // the sweep's name in an overlay (curves "LABEL: MODE")
  std::vector<double> mu;
  std::vector<ModeCurve> modes;
  std::vector<RowStatus> status;  // per row (missing: ok)
};
std::string sweep_plot_script(const std::string& title, const SweepOverlay& sweep,
                              const SweepPicture& picture = {});

// Several sweeps in one picture (`flaplag plot A.json B.json ...`): each curve titled
// "LABEL: MODE" (max_zeta: one curve per sweep, the largest zeta over its modes at each mu,
// titled LABEL, in one zeta panel).
std::string sweep_overlay_script(const std::string& title, const std::vector<SweepOverlay>& sweeps,
                                 bool max_zeta, const SweepPicture& picture = {});

// A frequency locked to 0, 1/2 or 1 per rev (within the tolerance of the instability kinds,
// numerics/continuation.h) folded into [0, 1] as the paper draws it (-1 -> 1, 3/2 -> 1/2);
// nullopt when omega is not locked.
std::optional<double> locked_frequency(double omega);

// study: mu_c per value, flutter and periodic marked differently (Fig 15), the unstable
// intervals (an open end drawn to mu-max), rows stable up to mu_max marked there, rows unstable
// in hover or failed marked at mu = 0, rows with a warning ringed.
struct StudyMark {
  double value = 0.0;
  std::optional<double> mu_c;
  bool periodic = false;
  double omega = NAN;  // at mu_c: a periodic row is drawn by its locked value (0, 1/2 or 1)
  std::vector<std::pair<double, double>> intervals;
  // The first mu below the damping criterion, per mode that crosses it.
  std::vector<std::pair<std::string, double>> crossings;
  RowStatus status = RowStatus::Ok;
  bool hover_unstable = false;
};
std::string study_plot_script(const std::string& title, const std::string& axis_label,
                              double mu_max, const std::vector<StudyMark>& rows,
                              std::optional<double> damping_criterion = std::nullopt);

// map: the max-zeta heat map with its zeta = 0 boundary (axis labels in enhanced text).
std::string max_zeta_plot_script(const std::string& title, const std::string& xlabel,
                                 const std::vector<double>& x, const std::string& ylabel,
                                 const std::vector<double>& y,
                                 const std::vector<std::vector<double>>& z);

// response (psi in degrees) and simulate (time in revolutions): tip flap and lag.
std::string response_plot_script(const std::string& title, const std::vector<double>& psi_deg,
                                 const std::vector<double>& flap, const std::vector<double>& lag);
std::string simulate_plot_script(const std::string& title, const std::vector<double>& revolutions,
                                 const std::vector<double>& flap, const std::vector<double>& lag);

// modes: the shapes (tip value 1) and slopes of the flap and lag modes at the stations x0;
// a flap mode is named η_k, a lag mode γ_k (k from 1, in order).
struct ShapeCurves {
  std::vector<double> value, slope;  // at x0
};
std::string mode_shapes_plot_script(const std::string& title, const std::vector<double>& x0,
                                    const std::vector<ShapeCurves>& flap,
                                    const std::vector<ShapeCurves>& lag);

// campbell: each mode's frequency by the nominal speed against Omega/Omega_0 (NaN: a gap), the
// per-rev lines n Omega (n = 1..harmonics), the crossings marked, the nominal speed marked.
struct CampbellPicture {
  double mu = 0.0;
  int harmonics = 0;
  std::vector<double> speed;
  std::vector<ModeCurve> modes;                      // the frequencies in ModeCurve::omega
  std::vector<std::pair<double, double>> crossings;  // (speed, frequency)
};
std::string campbell_plot_script(const std::string& title, const CampbellPicture& picture);

// The picture of a result file (a sweep, study, map, response, modes, simulate or campbell result
// as a front end writes it as JSON).  Throws InvalidInput("argument", data as typed, reason) for
// a file that cannot be read, is not JSON or not such a result; RendererUnavailable when gnuplot
// is missing or fails.  Returns "" (nothing for stdout).  A file is read up to
// json_read_limit(memory_limit) bytes (read_file.h); `option` spells the fields named in
// refusals.  A sweep is drawn with `quantity` on its first panel and the damping criterion its
// file holds (damping_criterion; none in a file written before it).
std::string plot_data_file(const std::string& data, const std::string& plot,
                           std::uint64_t memory_limit, const Spelling& option,
                           SweepQuantity quantity = SweepQuantity::DampingRatio);
// The picture of a parsed result as plot_data_file draws it: its gnuplot script, or nullopt for a
// result without a picture (point, critical, trim, ...).  `file` names the result in refusals,
// which are plot_data_file's.
std::optional<std::string> result_plot_script(const nlohmann::json& result, const std::string& file,
                                              SweepQuantity quantity = SweepQuantity::DampingRatio);

// Result files drawn in one picture: plain data from the front end (the fields label, max_zeta
// and mode are named in refusals as `option` spells them).
struct PlotFiles {
  std::vector<std::string> data;    // the result files, as typed
  std::vector<std::string> labels;  // empty (each from its file's case) or one per file
  bool max_zeta = false;            // the least stable mode of each file
  std::string mode;                 // "" or the one mode to draw from each file
  std::string plot;                 // the picture's path (.svg or .png)
  std::uint64_t memory_limit = 0;   // bytes (limits.h)
  SweepQuantity quantity = SweepQuantity::DampingRatio;
};

// One file without labels, max_zeta or mode is plot_data_file (the same bytes); otherwise every
// file must be a sweep result (InvalidInput("argument", the first other file as typed, reason)
// if not).  labels: each from its file's case (model, trim, periodic linearization) unless given.
// mode: a label as the files write it, where a mode without a number and the same mode with
// number 1 are one mode ("lag" of a 1 x 1 model is "lag1" of an M x N model, and either name
// selects it in either file); each file must have it.
std::string plot_data_files(const PlotFiles& files, const Spelling& option);

// gnuplot is not installed or failed (the message is one line).
struct RendererUnavailable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Renders `script` (without terminal/output lines) into `path` (.svg or .png) by gnuplot,
// executed directly (found on PATH, no shell) with the script on its standard input.  Returns ""
// on success, or a one-line warning when gnuplot is not installed or fails (nothing is written
// then).  Throws InvalidInput("plot", path, reason) for an output path that cannot be written
// (OutputTarget).  While a DeferredPictures exists, the image is kept there instead of written.
std::string render_plot(const std::string& script, const std::string& path);

// Renders `script` (as render_plot) into SVG text in memory, for a page that inlines it.  Throws
// RendererUnavailable (one line) when gnuplot is missing or fails.
std::string render_svg(const std::string& script);

// The pictures of one command, written after its output (flaplag's main): a command whose
// output cannot be written, or that fails after drawing, leaves no picture behind.  While one
// exists, render_plot() renders into it; commit() writes what it holds (throwing as
// OutputTarget::write, InvalidInput("plot", ...)); what is not committed is dropped.
class DeferredPictures {
 public:
  DeferredPictures();
  ~DeferredPictures();
  DeferredPictures(const DeferredPictures&) = delete;
  DeferredPictures& operator=(const DeferredPictures&) = delete;
  void commit();

 private:
  friend std::string render_plot(const std::string& script, const std::string& path);
  DeferredPictures* previous_;
  std::vector<std::pair<OutputTarget, std::string>> pictures_;
};

}  // namespace flaplag::documents
