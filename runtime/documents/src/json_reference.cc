// flaplag documents — the reference of the result structs in the JSON documents (docs/json.md),
// written from the field tables (core/fields.h) that the JSON writer (json_fields.h) and the
// Python module walk.
#include "flaplag/documents/json_reference.h"

#include <complex>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "flaplag/campbell.h"
#include "flaplag/documents/json_fields.h"
#include "flaplag/model_fields.h"
#include "flaplag/rotor/parameter_table.h"
#include "flaplag/study.h"
#include "flaplag/trim.h"

namespace flaplag::documents {

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

}  // namespace

std::string section_link(const char* name) {
  return "[" + std::string(name) + "](#" + anchor(name) + ")";
}

namespace {

template <class V>
std::string type_text(unsigned flags) {
  using json_detail::is_optional;
  using json_detail::is_vector;
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

}  // namespace

std::string table_row(const std::string& key, const std::string& type, const std::string& units,
                      const std::string& doc) {
  auto cell = [](std::string s) {
    std::string out;
    for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
  };
  return "| `" + key + "` | " + cell(type) + " | " + cell(units) + " | " + cell(doc) + " |\n";
}

namespace {

template <class T>
std::string struct_section(const std::string& intro) {
  std::string out = "### " + std::string(struct_name<T>()) + "\n\n" + intro + "\n\n" + kTableHead;
  for_each_row<T>([&](const auto& row) {
    using V = typename std::decay_t<decltype(row)>::value_type;
    out += table_row(row.name, type_text<V>(row.flags), row.units, row.doc);
  });
  return out + "\n";
}

}  // namespace

std::string results_reference() {
  std::string out;
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

}  // namespace flaplag::documents
