// flaplag CLI — docs/json.md, the reference of the JSON documents, written from the field tables
// (core/fields.h) that the JSON writer (json_fields.h) and the Python module walk.
#include "json_docs.h"

#include <complex>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "commands_internal.h"
#include "flaplag/campbell.h"
#include "flaplag/model_fields.h"
#include "flaplag/rotor/parameter_table.h"
#include "flaplag/study.h"
#include "flaplag/trim.h"
#include "options.h"

namespace flaplag::cli {

namespace {

// The described structs of the reference, by the name of their section.
template <class T>
const char* struct_name();
template <>
const char* struct_name<LabelledExponent>() {
  return "Exponent";
}
template <>
const char* struct_name<PointResult>() {
  return "PointResult";
}
template <>
const char* struct_name<SweepResult>() {
  return "SweepResult";
}
template <>
const char* struct_name<InstabilityInterval>() {
  return "Interval";
}
template <>
const char* struct_name<DampingCrossing>() {
  return "DampingCrossing";
}
template <>
const char* struct_name<CriticalResult>() {
  return "CriticalResult";
}
template <>
const char* struct_name<TrimResult>() {
  return "TrimResult";
}
template <>
const char* struct_name<TrimEquilibrium>() {
  return "TrimEquilibrium";
}
template <>
const char* struct_name<CampbellResult>() {
  return "CampbellResult";
}
template <>
const char* struct_name<CampbellPoint>() {
  return "CampbellPoint";
}
template <>
const char* struct_name<CampbellFrequency>() {
  return "CampbellFrequency";
}
template <>
const char* struct_name<CampbellCrossing>() {
  return "CampbellCrossing";
}

template <>
const char* struct_name<StudyRow>() {
  return "StudyRow";
}
template <>
const char* struct_name<MapCell>() {
  return "MapCell";
}

template <>
const char* struct_name<HoverResult>() {
  return "HoverResult";
}
template <>
const char* struct_name<HoverExponent>() {
  return "HoverExponent";
}
template <>
const char* struct_name<SystemSnapshot>() {
  return "SystemSnapshot";
}
template <>
const char* struct_name<AeroIntegral>() {
  return "AeroIntegral";
}
template <>
const char* struct_name<StructuralIntegral>() {
  return "StructuralIntegral";
}
template <>
const char* struct_name<ThrustResult>() {
  return "ThrustResult";
}
template <>
const char* struct_name<FloquetSample>() {
  return "FloquetSample";
}
template <>
const char* struct_name<model::ModelDescriptor>() {
  return "Model";
}
template <>
const char* struct_name<PeriodicEquilibrium>() {
  return "PeriodicEquilibrium";
}

std::string anchor(const std::string& name) {
  std::string a;
  for (char c : name) a += static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return a;
}

std::string section_link(const char* name) {
  return "[" + std::string(name) + "](#" + anchor(name) + ")";
}

template <class V>
std::string type_text(unsigned flags) {
  using documents::json_detail::is_optional;
  using documents::json_detail::is_vector;
  if constexpr (std::is_same_v<V, double>) {
    return (flags & kFieldNegativeInfinity) ? "number or \"-inf\"" : "number";
  } else if constexpr (std::is_same_v<V, int>) {
    return "integer";
  } else if constexpr (std::is_same_v<V, bool>) {
    return "boolean";
  } else if constexpr (std::is_same_v<V, std::string>) {
    return "string";
  } else if constexpr (std::is_same_v<V, std::complex<double>>) {
    return "{re, im}";
  } else if constexpr (is_described_enum_v<V>) {
    std::string names;
    const auto table = describe(Tag<V>{});
    for (std::size_t i = 0; i < table.size(); ++i) {
      names += (i == 0                  ? ""
                : i + 1 == table.size() ? " or "
                                        : ", ") +
               ("\"" + std::string(table[i].name) + "\"");
    }
    return names;
  } else if constexpr (is_named_values_field<V>::value) {
    return "object of numbers";
  } else if constexpr (std::is_same_v<V, Eigen::MatrixXd>) {
    return "array of rows (arrays of numbers)";
  } else if constexpr (std::is_same_v<V, Eigen::VectorXd>) {
    return "array of numbers";
  } else if constexpr (is_optional<V>::value) {
    using Inner = typename V::value_type;  // an optional optional: absent, null or a value
    return type_text<Inner>(flags) + (is_optional<Inner>::value ? "" : " or null");
  } else if constexpr (is_vector<V>::value) {
    return "array of " + type_text<typename V::value_type>(flags);
  } else {
    return section_link(struct_name<V>());
  }
}

// One row of a markdown table; '|' in the text would end a cell.
std::string table_row(const std::string& key, const std::string& type, const std::string& units,
                      const std::string& doc) {
  auto cell = [](std::string s) {
    std::string out;
    for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
  };
  return "| `" + key + "` | " + cell(type) + " | " + cell(units) + " | " + cell(doc) + " |\n";
}

const char* const kTableHead = "| key | type | units | description |\n|---|---|---|---|\n";

template <class T>
std::string struct_section(const std::string& intro) {
  std::string out = "### " + std::string(struct_name<T>()) + "\n\n" + intro + "\n\n" + kTableHead;
  for_each_row<T>([&](const auto& row) {
    using V = typename std::decay_t<decltype(row)>::value_type;
    out += table_row(row.name, type_text<V>(row.flags), row.units, row.doc);
  });
  return out + "\n";
}

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
         ": the q° at mu the exponents rest on; with a trim it is the trim's).\n"
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
         ".\n"
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
         ") and `table` (labels, rows as in a sweep, max_liouville_residual, status, message).\n\n"
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
  out += "## Results\n\n";
  out += struct_section<model::ModelDescriptor>(
      "The compiled ordering model a result was computed with (the header's `model`; "
      "`flaplag models --json` lists them; Python: `Analysis.model`, `flaplag.models()`).");
  out += struct_section<PointResult>("The labelled exponents at one advance ratio mu.");
  out += struct_section<LabelledExponent>(
      "One characteristic exponent lambda = zeta + i omega with its mode label.");
  out += struct_section<HoverResult>(
      "The hover equilibrium (eqs 2.24, 2.29-2.32) and the hover exponents: a document's "
      "`hover` (`point`, `system`, the typical case) has `inflow`, `equilibrium`, `exponents`, "
      "`stable`, `status` and `message`; Python's `HoverResult` (`Analysis.hover`) has every "
      "row but `exponents` (a property made from `eigenvalues` and `labels`).");
  out += struct_section<HoverExponent>("An eigenvalue of A0 with its mode label.");
  out += struct_section<SweepResult>(
      "Exponents along advance ratios, continued from hover (the Python module's "
      "`SweepResult`; the command line writes its points as `rows`, see above).");
  out += struct_section<DampingCrossing>(
      "Where one mode's damping ratio -zeta/|lambda| (a fraction of critical, omega continued "
      "from hover) first falls below the damping criterion along a sweep.");
  out += struct_section<CriticalResult>(
      "The critical advance ratio mu_c: the first mu in (0, mu_max] where an exponent has "
      "zeta > zeta_threshold.");
  out += struct_section<InstabilityInterval>(
      "One interval of instability in mu: max zeta > zeta_threshold for onset < mu < end.");
  out += struct_section<TrimResult>(
      "A trim at one mu: the controls at which the model's own C_T equals the target (and, "
      "kind moment, the first flap harmonic vanishes).  The Python module's TrimResult also "
      "has `parameters` (the rotor parameters with the trimmed pitch).");
  out += struct_section<TrimEquilibrium>("The periodic equilibrium a trim about it rests on.");
  out += struct_section<StudyRow>(
      "One value of a study: a row of `flaplag study --json`, with the keys of " +
      section_link("CriticalResult") +
      " a table of mu_c shows.  Python: `StudyResult.rows` (a CriticalResult each, with `trim` "
      "and `damping_crossings`) and its columns.");
  out += struct_section<MapCell>(
      "One cell of a stability map: the least stable exponent there.  `flaplag map --json` "
      "writes `max_zeta`, `mode` and `kind` as grids; Python's `MapResult` has `max_zeta`, "
      "`omega`, `mode`, `kind` and the cells' `status` and `message` (`cell_status`, "
      "`cell_message`) as arrays of the map's shape.");
  out += struct_section<SystemSnapshot>(
      "The linear periodic system y' = A(psi) y + f(psi) at one (mu, psi) for auditing: "
      "`flaplag system --json` is the header and these keys, with `hover` (a " +
      section_link("HoverResult") +
      ") after `f`.  Python: `Analysis.system` (`SystemResult`: `states`, and the integrals "
      "as dicts by name).");
  out += struct_section<AeroIntegral>("One spanwise aerodynamic integral.");
  out += struct_section<StructuralIntegral>("One generalized mass or structural integral.");
  out += struct_section<CampbellResult>(
      "The Campbell diagram: every mode's frequency against the rotor speed Omega/Omega_0, the "
      "blade's bending stiffness fixed at its value for the nominal speed Omega_0.");
  out += struct_section<CampbellPoint>("The modes at one rotor speed.");
  out += struct_section<CampbellFrequency>("One mode at one rotor speed.");
  out += struct_section<CampbellCrossing>("Where a mode's frequency meets a per-rev line n Omega.");
  out +=
      "## Python results\n\n"
      "Results of the Python module that no command writes as JSON; its classes have these keys "
      "as attributes (lists as numpy arrays).\n\n";
  out += struct_section<ThrustResult>(
      "The model's own thrust at one mu (`Analysis.thrust`), at the given pitch and inflow.");
  out += struct_section<FloquetSample>(
      "One Floquet analysis at mu without continuation (`Analysis.floquet`): the exponents "
      "unlabelled, in the order of the eigen-solve.");
  out += struct_section<PeriodicEquilibrium>(
      "The periodic equilibrium q°(psi) of the nonlinear equations at one mu "
      "(`Analysis.periodic_equilibrium`, as `PeriodicEquilibriumResult`).  The Python class also "
      "has the Fourier coefficients of q° (`coefficients`, modes x 2K+1), the sample azimuths "
      "`psi`, the states `y` there and `tips`, one `TipMotion` per blade direction (its tip "
      "deflection at `psi`).");
  return out;
}

}  // namespace flaplag::cli
