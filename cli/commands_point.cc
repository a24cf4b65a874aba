// flaplag CLI — the stability of one rotor: the typical case, point, sweep and critical, and the
// hover equilibrium they rest on.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "commands_internal.h"
#include "flaplag/core/format.h"
#include "flaplag/documents/output.h"
#include "flaplag/trim.h"

namespace flaplag::cli::cmd {

namespace {

// The short zeta(mu) table of the typical case: mu = 0, 0.1, ..., 1.0, continued from hover in
// steps of kTableScan (every kTableEvery-th point of the continuation is shown).
constexpr double kTableStop = 1.0;
constexpr double kTableScan = 0.01;
constexpr int kTableEvery = 10;

// ---- exponents in tables: damping ratio and locked frequencies (issue 9 item 6) ----------------

// What the exponent columns mean, above every table that has them.
const char* const kExponentLegend =
    "  zeta: real part of the characteristic exponent lambda = zeta + i omega, 1/rev (> 0: "
    "unstable)\n"
    "  damping ratio: -zeta/|lambda| in % of critical (omega continued from hover, not modulo "
    "1/rev); for omega = 0 (a real exponent) +100 if decaying, -100 if growing\n"
    "  locked: omega locked to 0, 1/2 or 1 per rev (mod 1; a real multiplier: the periodic kind)\n";
// The same, short, above the zeta(mu) tables.
const char* const kSweepLegend =
    "  zeta in 1/rev (real part of the exponent lambda = zeta + i omega); ratio: damping ratio\n"
    "  -zeta/|lambda| in % of critical; p after omega: locked to 0, 1/2 or 1 per rev (mod 1: the\n"
    "  periodic kind)\n";

// Mode labels in the order hover reports them, each once.
std::vector<std::string> mode_labels(const Analysis& an) {
  std::vector<std::string> labels;
  for (const std::string& l : an.hover().labels) {
    if (std::find(labels.begin(), labels.end(), l) == labels.end()) labels.push_back(l);
  }
  return labels;
}

// The exponent that decides a mode's stability: largest zeta; of a conjugate pair the one with
// omega >= 0 (numerics/continuation.h).
const LabelledExponent* dominant(const PointResult& r, const std::string& label) {
  return dominant_exponent(r, label);
}
Json point_json(const Request& r, const PointResult& p) { return to_json(p, in_vocabulary(r)); }

// The exponent table of point and hover: the label, zeta and omega (the exponent's rows), the
// damping ratio in % and the locked frequency; a point's multipliers.
template <class Exponent>
std::string exponent_table(const std::vector<Exponent>& exponents) {
  constexpr bool multipliers = std::is_same_v<Exponent, LabelledExponent>;
  std::vector<std::string> head{"mode", described_heading<Exponent>("zeta"),
                                described_heading<Exponent>("omega"), "damping ratio [%]",
                                "locked"};
  if (multipliers) head.push_back("multiplier");
  TextTable t(head);
  for (const Exponent& e : exponents) {
    std::vector<std::string> row =
        described_cells(e, {"label", "zeta", "omega"}, CellStyle::Text, {});
    const std::string locked = locked_text(e.omega);
    row.push_back(ratio_cell(e.zeta, e.omega));
    row.push_back(locked.empty() ? "-" : locked);
    if constexpr (multipliers) row.push_back(complex_text(e.multiplier));
    t.add_row(row);
  }
  return t.render();
}

std::string point_text(const Request& r, const PointResult& p) {
  std::string out = "Characteristic exponents at mu = " + cell(p.mu) + " (per rev)\n";
  out += kExponentLegend;
  out += exponent_table(p.exponents);
  KeyValues kv;
  kv.add("stable", stable_text(p.stable));
  kv.add("Liouville residual",
         optional_text(p.liouville_residual) + "  (|det Phi - exp int tr A|, relative)");
  kv.add("error estimate",
         optional_text(p.error) + "  (largest zeta error, per rev: Richardson from K and K/2)");
  // The point's other rows (its table), each under its key and units; a row without a value
  // (an optional not set) is left out of the text.
  const std::vector<const char*> others = documents::other_cell_keys<PointResult>(
      {"mu", "stable", "liouville_residual", "error_estimate", "status", "message"});
  const std::vector<std::string> cells = described_cells(p, others, CellStyle::Text, {});
  for (std::size_t i = 0; i < others.size(); ++i)
    if (cells[i] != "-") kv.add(documents::described_heading<PointResult>(others[i]), cells[i]);
  out += kv.render();
  return out + status_text(p.status, vocab(r, p.message));
}

Json critical_json(const Request& r, const CriticalResult& c) {
  return to_json(c, in_vocabulary(r));
}

std::string critical_text(const Request& r, const CriticalResult& c) {
  std::string out =
      "Critical advance ratio (first mu in 0.." + cell(c.mu_max) + " with zeta > 0)\n";
  KeyValues kv;
  if (c.mu_c) {
    kv.add("mu_c", num(*c.mu_c) + (c.mu_c_error && finite(*c.mu_c_error)
                                       ? "  (estimated error " + num(*c.mu_c_error) + ")"
                                       : ""));
    kv.add("mode", c.mode);
    kv.add("omega", cell(c.omega) + " per rev");
    kv.add("kind", c.kind == InstabilityKind::Flutter
                       ? "flutter (omega not locked to 0, 1/2 or 1 per rev)"
                       : "periodic (omega locked to 0, 1/2 or 1 per rev)");
  } else if (c.hover_unstable) {
    kv.add("mu_c", "none: the blade is unstable already in hover");
  } else if (c.status == Status::Failed) {
    kv.add("mu_c", "unknown: the search failed");
  } else {
    kv.add("mu_c", "none: stable up to mu = " + cell(c.mu_max));
  }
  out += kv.render();
  return out + status_text(c.status, vocab(r, c.message)) + notes_text(r, c.notes);
}

// Largest Liouville residual over the points that have one; nullopt when none has.
std::optional<double> max_liouville(const SweepResult& s) {
  std::optional<double> m;
  for (const PointResult& p : s.points) {
    if (p.liouville_residual && finite(*p.liouville_residual)) {
      m = std::max(m.value_or(0.0), *p.liouville_residual);
    }
  }
  return m;
}

// The rows of a mode's dominant exponent (LabelledExponent's table) in the rows of a sweep.
const std::vector<const char*> kModeRows = {"zeta", "omega", "damping_ratio"};

// A row: the point's mu, the dominant exponent of each mode (kModeRows, or null), then the rest
// of the point (its table) and, about the periodic equilibrium at fixed controls, the q° the
// point rests on (`equilibria`: one per point, or empty; a trim carries its own).
Json sweep_rows_json(const Request& r, const SweepResult& s, const std::vector<std::string>& labels,
                     const std::vector<PeriodicEquilibrium>& equilibria) {
  Json rows = Json::array();
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    const PointResult& p = s.points[k];
    Json row;
    row["mu"] = jnum(p.mu);
    for (const std::string& l : labels) {
      const LabelledExponent* e = dominant(p, l);
      row[l] = e ? rows_json(*e, kModeRows, in_vocabulary(r)) : Json(nullptr);
    }
    const Json point = point_json(r, p);
    for (const auto& item : point.items()) {
      if (item.key() != "mu") row[item.key()] = item.value();
    }
    if (k < equilibria.size()) row["equilibrium"] = equilibrium_json(r, equilibria[k]);
    rows.push_back(row);
  }
  return rows;
}

std::string sweep_table_text(const Request& r, const SweepResult& s,
                             const std::vector<std::string>& labels) {
  std::vector<std::string> header{"mu"};
  for (const std::string& l : labels) {
    header.push_back(l + " zeta");
    header.push_back(l + " omega");
    header.push_back(l + " ratio [%]");
  }
  header.push_back("stable");
  header.push_back("Liouville");
  TextTable t(header);
  std::string notes;
  for (const PointResult& p : s.points) {
    std::vector<std::string> row{cell(p.mu)};
    for (const std::string& l : labels) {
      const LabelledExponent* e = dominant(p, l);
      row.push_back(e ? zeta_cell(e->zeta) : "-");
      // " p": locked (periodic kind), as the paper marks Fig 15's periodic points.
      row.push_back(e ? cell(e->omega) + (locked_text(e->omega).empty() ? "  " : " p") : "-");
      row.push_back(e ? ratio_cell(e->zeta, e->omega) : "-");
    }
    row.push_back(stable_text(p.stable));
    row.push_back(optional_text(p.liouville_residual));
    t.add_row(row);
    if (p.status != Status::Ok || !p.message.empty()) {
      notes +=
          "  mu = " + cell(p.mu) + ": " + status_name(p.status) + ": " + vocab(r, p.message) + "\n";
    }
  }
  return kSweepLegend + t.render() + notes + status_text(s.status, vocab(r, s.message));
}

// Empty fields for what is not known (no exponent of a label, no residual, unknown stability).
// Per mode "<label>_<row>" of kModeRows, then the damping ratios, then the point's other rows
// (its table): a column added later never moves the columns before it.
std::string sweep_csv(const Request& r, const SweepResult& s,
                      const std::vector<std::string>& labels) {
  const std::vector<const char*> exponent_keys(kModeRows.begin(), kModeRows.end() - 1);
  const std::vector<const char*> ratio_keys(kModeRows.end() - 1, kModeRows.end());
  // The point's own columns, by its table (core/fields.h).
  const std::vector<const char*> point_keys = {"liouville_residual", "error_estimate", "stable",
                                               "status", "message"};
  auto mode_cells = [&](const PointResult& p, const std::vector<const char*>& keys) {
    std::vector<std::string> cells;
    for (const std::string& l : labels) {
      const LabelledExponent* e = dominant(p, l);
      const std::vector<std::string> c =
          e ? described_cells(*e, keys, CellStyle::Csv, {}) : std::vector<std::string>(keys.size());
      cells.insert(cells.end(), c.begin(), c.end());
    }
    return cells;
  };
  std::vector<std::string> head{"mu"};
  for (const std::string& l : labels)
    for (const char* k : exponent_keys) head.push_back(l + "_" + k);
  head.insert(head.end(), point_keys.begin(), point_keys.end());
  for (const std::string& l : labels)
    for (const char* k : ratio_keys) head.push_back(l + "_" + k);
  std::vector<const char*> placed = point_keys;
  placed.push_back("mu");
  const std::vector<const char*> other_keys = documents::other_cell_keys<PointResult>(placed);
  head.insert(head.end(), other_keys.begin(), other_keys.end());
  std::string out = csv_fields(head) + "\n";
  for (const PointResult& p : s.points) {
    std::vector<std::string> line{finite(p.mu) ? exact_num(p.mu) : std::string()};
    for (const auto& cells : {mode_cells(p, exponent_keys),
                              described_cells(p, point_keys, CellStyle::Csv, in_vocabulary(r)),
                              mode_cells(p, ratio_keys),
                              described_cells(p, other_keys, CellStyle::Csv, in_vocabulary(r))})
      line.insert(line.end(), cells.begin(), cells.end());
    out += csv_fields(line) + "\n";
  }
  return out;
}

// The crossings of --damping-criterion: one line per mode.
std::string crossings_text(const SweepResult& s) {
  if (!s.damping_criterion) return "";
  std::string out = "\nDamping criterion " + num(100.0 * *s.damping_criterion) +
                    " % of critical: the first mu where each mode's damping ratio falls below "
                    "it\n  (interpolated linearly between the sweep points around it)\n";
  TextTable t({"mode", "mu", "status", "between mu"});
  for (const DampingCrossing& c : s.damping_crossings) {
    std::string between = "-";
    if (c.mu_above && c.mu_below) between = cell(*c.mu_above) + " and " + cell(*c.mu_below);
    t.add_row({c.mode, c.mu ? cell(*c.mu) : "-", enum_name(c.status), between});
  }
  return out + t.render();
}

// The crossings as JSON, from their table (numerics/continuation.h).
Json crossings_json(const Request& r, const SweepResult& s) {
  Json a = Json::array();
  for (const DampingCrossing& c : s.damping_crossings) a.push_back(to_json(c, in_vocabulary(r)));
  return a;
}

}  // namespace

Json hover_json(const Request& r, const Analysis& an) {
  return rows_json(
      an.hover(),
      std::vector<const char*>(std::begin(kHoverDocumentRows), std::end(kHoverDocumentRows)),
      in_vocabulary(r));
}

std::string hover_text(const Request& r, const Analysis& an) {
  const HoverResult& h = an.hover();
  std::string out = "Hover equilibrium (eqs 2.24, 2.29-2.32)\n";
  KeyValues kv;
  kv.add("inflow lambda", cell(h.inflow));
  for (const auto& [name, q] : h.equilibrium) kv.add(name, cell(q));
  out += kv.render();
  out += "\nHover exponents (eigenvalues of A at mu = 0, per rev)\n";
  out += kExponentLegend;
  out += exponent_table(hover_exponents(h));
  const std::optional<bool> stable = hover_stable(h);
  out += std::string("  hover is ") +
         (!stable   ? "of unknown stability"
          : *stable ? "stable"
                    : "UNSTABLE") +
         "\n";
  return out + status_text(h.status, vocab(r, h.message));
}

Output typical(const Request& r, const Analysis& an) {
  const RotorCritical crit = an.critical(CriticalOptions{});
  // One continuation from hover in steps of kTableScan, shown every kTableEvery-th point: the
  // exponents of each row are continued exactly as `flaplag point` continues them, at a tenth of
  // the cost of continuing every row from hover again.
  const RotorSweep all = an.sweep(0.0, kTableStop, kTableScan);
  RotorSweep table;
  table.status = all.status;
  table.message = all.message;
  for (std::size_t i = 0; i < all.points.size(); ++i) {
    // A sweep that stopped early ends with the failed point: show it too.
    if (i % kTableEvery != 0 && i + 1 != all.points.size()) continue;
    table.points.push_back(all.points[i]);
    if (i < all.equilibria.size()) table.equilibria.push_back(all.equilibria[i]);
  }
  const std::vector<std::string> labels = mode_labels(an);
  const std::optional<double> max_res = max_liouville(table);
  const auto json = [&] {
    Json j = header_json("typical", an);
    j["hover"] = hover_json(r, an);
    j["critical"] = critical_json(r, crit);
    if (crit.equilibrium) j["critical"]["equilibrium"] = equilibrium_json(r, *crit.equilibrium);
    Json t;
    t["labels"] = labels;
    t["rows"] = sweep_rows_json(r, table, labels, table.equilibria);
    t["max_liouville_residual"] = optional_json(max_res);
    j["table"] = status_json(t, table.status, vocab(r, table.message));
    return j;
  };
  std::optional<Json> j = result_document(r, json, nullptr);
  if (r.json) return std::move(*j);
  std::string out =
      "flaplag: coupled flap-lag stability of a hingeless blade in forward flight "
      "(NASA CR-132431)\n";
  out += header_text(an) + "\n";
  out += warnings_text(an);
  out += hover_text(r, an) + "\n";
  out += critical_text(r, crit) + "\n";
  out += "Exponents zeta(mu), omega(mu) per rev (dominant exponent of each mode)\n";
  out += sweep_table_text(r, table, labels);
  out += "  Liouville residual |det Phi - exp int tr A| (relative), max over the table: " +
         optional_text(max_res) + "\n";
  return text_output(r, std::move(out), std::move(j));
}

Output point(const Request& r, const Analysis& an) {
  // Trimmed: p.trim, the trim the point rests on (its problems are in the point's status).
  const RotorPoint p = an.point(r.mu, r.scan_step);
  const std::optional<TrimResult>& t = p.trim;
  const auto json = [&] {
    Json j = header_json("point", an);
    // With the momentum inflow: lambda at this mu (the hover's is hover.inflow).
    if (const std::optional<double> lam = inflow_at(an, r.mu)) j["inflow"]["lambda"] = jnum(*lam);
    j.update(point_json(r, p));
    j["hover"] = hover_json(r, an);
    if (t) j["trim"] = trim_json(r, *t);
    if (p.equilibrium) j["equilibrium"] = equilibrium_json(r, *p.equilibrium);
    return j;
  };
  std::optional<Json> j = result_document(r, json, nullptr);
  if (r.json) return std::move(*j);
  const std::optional<double> lam = inflow_at(an, r.mu);
  return text_output(
      r,
      header_text(an) + "\n" + warnings_text(an) + (t ? trim_text(r, *t) + "\n" : "") +
          point_text(r, p) +
          (lam ? "  inflow lambda at mu = " + cell(r.mu) + ": " + cell(*lam) + " (eq 2.25)\n" : ""),
      std::move(j));
}

Output sweep(const Request& r, const Analysis& an, std::string& warning) {
  // Trimmed: s.trims, the trimmed controls at each point of the sweep (their problems are in
  // the points' status).
  RotorSweep s = an.sweep(r.sweep_start, r.sweep_stop, r.sweep_step, r.threads);
  const std::vector<TrimResult>& trims = s.trims;
  const std::vector<std::string> labels = mode_labels(an);
  if (r.damping_criterion) apply_damping_criterion(s, labels, *r.damping_criterion);
  const auto json = [&] {
    Json j = header_json("sweep", an);
    j["mu"] = Json{{"start", r.sweep_start}, {"stop", r.sweep_stop}, {"step", r.sweep_step}};
    j["labels"] = labels;
    j["rows"] = sweep_rows_json(r, s, labels, s.equilibria);
    j["max_liouville_residual"] = optional_json(max_liouville(s));
    if (s.damping_criterion) {
      j["damping_criterion"] = jnum(*s.damping_criterion);
      j["damping_crossings"] = crossings_json(r, s);
    }
    if (trimmed(r)) {
      Json tj = Json::array();
      for (const TrimResult& t : trims) tj.push_back(trim_json(r, t));
      j["trim"] = tj;
    }
    return status_json(j, s.status, vocab(r, s.message));
  };
  std::optional<Json> j = result_document(r, json, &warning);
  if (r.json) return std::move(*j);
  if (r.csv) return text_output(r, sweep_csv(r, s, labels), std::move(j));
  std::string trim_table;
  if (trimmed(r)) {
    trim_table = std::string("\nTrim (") + trim_kind_name(r.trim.kind) +
                 ") at each mu, C_T = " + cell(r.trim.thrust_coefficient) + "\n";
    trim_table += described_table(trims,
                                  {{"mu", "mu"},
                                   {"theta0", "theta0"},
                                   {"theta1c", "theta1c"},
                                   {"theta1s", "theta1s"},
                                   {"inflow", "lambda"},
                                   {"thrust_coefficient", "C_T"},
                                   {"status", "status"}},
                                  in_vocabulary(r))
                      .render();
  }
  return text_output(r,
                     header_text(an) + "\n" + warnings_text(an) +
                         "Exponents per rev (dominant exponent of each mode)\n" +
                         sweep_table_text(r, s, labels) + crossings_text(s) + trim_table,
                     std::move(j));
}

Output critical(const Request& r, const Analysis& an) {
  const RotorCritical c = an.critical(r.critical, r.threads);
  const std::optional<TrimResult>& t = c.trim;  // trimmed: the trim at mu_c the result rests on
  const auto json = [&] {
    Json j = header_json("critical", an);
    // With the momentum inflow: lambda at mu_c (null without one).
    if (j.contains("inflow"))
      j["inflow"]["lambda_at_mu_c"] = c.mu_c ? jnum(*inflow_at(an, *c.mu_c)) : Json(nullptr);
    j.update(critical_json(r, c));
    if (trimmed(r)) j["trim"] = t ? trim_json(r, *t) : Json(nullptr);
    if (c.equilibrium) j["equilibrium"] = equilibrium_json(r, *c.equilibrium);
    return j;
  };
  std::optional<Json> j = result_document(r, json, nullptr);
  if (r.json) return std::move(*j);
  const std::optional<double> lam = c.mu_c ? inflow_at(an, *c.mu_c) : std::nullopt;
  return text_output(r,
                     header_text(an) + "\n" + warnings_text(an) + critical_text(r, c) +
                         (lam ? "  inflow lambda at mu_c: " + cell(*lam) + " (eq 2.25)\n" : "") +
                         (t ? "\n" + trim_text(r, *t) : ""),
                     std::move(j));
}

}  // namespace flaplag::cli::cmd
