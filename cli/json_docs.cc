// flaplag CLI — docs/json.md, the reference of the JSON documents: which command writes which
// document and its header (this command line's part), then the result structs from their field
// tables (documents/json_reference.h).
#include "json_docs.h"

#include <string>

#include "flaplag/documents/json_reference.h"
#include "flaplag/documents/names.h"
#include "flaplag/rotor/parameter_table.h"

namespace flaplag::cli {

namespace {

using documents::kTableHead;
using documents::section_link;
using documents::table_row;

std::string header_section() {
  std::string out =
      "## The header\n\n"
      "Every document of an analysis command starts with these keys (`flaplag trim` without "
      "`method`), and every document is completed with `version`, `commit` and `case` (the "
      "command line or case file behind it).\n\n";
  out += kTableHead;
  out += table_row("command", "string", "", "the command that wrote the document");
  out += table_row("model", section_link("Model"), "", "the compiled model");
  out += table_row("mode_shapes", "string", "", "assumed, exact or imported");
  out += table_row("elastic_coupling", "boolean", "", "the elastic coupling is on");
  out += table_row("method", "object", "",
                   "the Floquet method: name, steps (or \"automatic\"), terms (hsu), "
                   "zeta-tolerance");
  out += table_row("parameters", "object", "", "the rotor parameters, by the keys below");
  out += table_row("blade_table", "object", "",
                   "only with --blade-table: source, stations, root_offset, length_ratio, "
                   "tip_mass (M_tip l^2/I_b), twist_min, twist_max [rad]; for a dimensional "
                   "table also radius [m], rotor_speed [rad/s], air_density [kg/m^3], blades, "
                   "reference_chord [m], inertia I_b [kg m^2], gamma, sigma, omega_flap_hz, "
                   "omega_lag_hz");
  out += table_row("inflow", "object", "",
                   "only with --inflow momentum: kind, thrust_coefficient, shaft_angle [rad] of "
                   "eq 2.25; `point` adds lambda (at its mu), `critical` lambda_at_mu_c (null "
                   "without mu_c)");
  out += table_row("linearization", "string", "",
                   "only with --periodic-linearization: \"periodic\", the operating condition's "
                   "linearization about the periodic equilibrium q°(psi) (results written before "
                   "it was part of the condition have parameters.periodic-linearization instead)");
  out += "\n### parameters\n\n" + std::string(kTableHead);
  for (const ParameterSpec& s : parameter_table()) {
    const char* type = s.type == ParameterType::Real ? "number"
                       : s.type == ParameterType::Integer
                           ? (s.names != nullptr ? "integer or string" : "integer")
                       : s.type == ParameterType::Flag ? "boolean"
                                                       : "string";
    out += table_row(json_key(s), type, s.units, s.description);
  }
  return out + "\n";
}

std::string documents_section() {
  return "## Documents\n\n"
         "- `flaplag point --json`: the header, the keys of " +
         section_link("PointResult") + ", `hover` (a " + section_link("HoverResult") +
         ") and, with `--trim`, `trim` (a " + section_link("TrimResult") +
         "); with `--periodic-linearization` and no trim, `equilibrium` (a " +
         section_link("TrimEquilibrium") +
         ": the q° at mu the exponents rest on, null where there is none; with a trim it is the "
         "trim's).\n"
         "- `flaplag sweep --json`: the header, `mu` (start, stop, step), `labels` (the modes), "
         "`rows`, `max_liouville_residual`, with `--damping-criterion` `damping_criterion` and "
         "`damping_crossings` (as in " +
         section_link("SweepResult") + "), with `--trim` `trim` (a " + section_link("TrimResult") +
         " per row), `status` and "
         "`message` (of the sweep, as " +
         section_link("SweepResult") +
         ").  A row is the point's `mu`, then under each label the dominant exponent of that "
         "mode (`{zeta, omega, damping_ratio}`, the largest zeta; `damping_ratio` as in " +
         section_link("Exponent") +
         "; null when the point has none), then the "
         "other keys of " +
         section_link("PointResult") +
         " and, with `--periodic-linearization` and no trim, `equilibrium` (a " +
         section_link("TrimEquilibrium") +
         ": the q° at the row's mu the point rests on; null where there is none, beyond the fold "
         "of "
         "the branch from hover).\n"
         "- `flaplag critical --json`: the header, the keys of " +
         section_link("CriticalResult") + " and, with `--trim`, `trim` (the " +
         section_link("TrimResult") +
         " at mu_c, or null); with `--periodic-linearization` and no trim, `equilibrium` (a " +
         section_link("TrimEquilibrium") +
         ": the q° at mu_c; absent without mu_c).\n"
         "- `flaplag study --json`: the header, `vary` (the parameter), `mu_max`, `scan_step`, "
         "with `--damping-criterion` `damping_criterion`, `rows` (one per value: " +
         section_link("StudyRow") +
         "), `status` and `message`.\n"
         "- `flaplag map --json`: the header, `x` and `y` (`name`, `values`), without a mu axis "
         "`mu`, the grids `max_zeta`, `mode` and `kind` (rows y, columns x; the keys of " +
         section_link("MapCell") +
         ", null where unknown), `status` and `message`.\n"
         "- `flaplag trim --json`: the header (without `method`) and the keys of " +
         section_link("TrimResult") +
         ".\n"
         "- `flaplag campbell --json`: the header and the keys of " +
         section_link("CampbellResult") +
         ".\n"
         "- `flaplag modes --json` (no header): `command`, `basis`, `parameters` (the blade's "
         "frequencies and geometry), with --blade-table `blade_table` (as in the header), "
         "`e1_over_l`, `fig9` (rows of `nonrotating`, `flap_rotating`, `lag_rotating`), `x0`, "
         "`flap` and `lag` (each `rotating_first`, `nonrotating_first`, `stiffness` = "
         "EI/(Omega^2 l I_b) or, with a blade table, `stiffness_scale` s instead (EI/(Omega^2 l "
         "I_b) = s times the table's EI column), `rotating_all`, and `modes`: `name`, `omega`, "
         "`rayleigh_omega`, the shape `value` and its derivatives `d1`, `d2`, `d3` at `x0`), "
         "`status`, `message`.\n"
         "- `flaplag` (the typical case) `--json`: the header, `hover`, `critical` (a " +
         section_link("CriticalResult") +
         ", with `equilibrium` as `flaplag critical`'s) and `table` (labels, rows as in a sweep, "
         "max_liouville_residual, status, message).\n\n"
         "A number that is not finite is written as null (the library marks the result that "
         "holds one with a non-ok status); the one exception is a zeta of -inf, written as the "
         "string \"-inf\".\n\n";
}

}  // namespace

std::string json_reference() {
  std::string out =
      "# JSON reference\n\n"
      "<!-- Generated by `cmake --build build --target refresh-docs` from the field tables "
      "(`describe(Tag<T>)` next to each result struct); do not edit. -->\n\n"
      "The keys of the documents that `flaplag ... --json` writes.  The objects below are the "
      "library's result structs, written from one table each; the Python module's results have "
      "the same keys as attributes.  Units: zeta and omega per rev (1/rev), advance ratios and "
      "angles nondimensional or in radians; \"-\" is dimensionless.\n\n";
  out += documents_section();
  out += header_section();
  return out + documents::results_reference();
}

}  // namespace flaplag::cli
