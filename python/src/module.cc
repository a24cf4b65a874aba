// flaplag._flaplag — the pybind11 layer under the Python package `flaplag` (python/flaplag/).
//
// This layer only translates: parameters arrive as dicts keyed by the field names of
// RotorParameters (rotor/parameter_table.h) and TransitionOptions, already of the right Python
// type (the pure-Python layer checks types and names), and results leave as dicts, tuples and
// numpy arrays that the pure-Python layer wraps in its result classes.  Values are checked by
// the library itself (validate(), Check()); its InvalidInput becomes flaplag.InvalidInput, a
// ValueError whose message is the library's one line "<field> = <value>: <reason>".
//
// Every computation runs with the GIL released.  Studies and maps run on a thread of their own
// while the calling thread waits with the GIL released, waking every 50 ms to deliver progress
// and to look for KeyboardInterrupt (Ctrl-C cancels the run: rows already started finish).
#include <pybind11/complex.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <complex>
#include <condition_variable>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/blade/imported_modes.h"
#include "flaplag/campbell.h"
#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/field_traits.h"
#include "flaplag/core/fields.h"
#include "flaplag/core/format.h"
#include "flaplag/limits.h"
#include "flaplag/model_fields.h"
#include "flaplag/rotor/blade_table.h"
#include "flaplag/rotor/parameter_table.h"
#include "flaplag/study.h"
#include "flaplag/trim.h"
#include "flaplag/version.h"
#include "flaplag_spec/runtime_spec.h"

namespace py = pybind11;

namespace flaplag::python {
namespace {

// ---- exceptions ---------------------------------------------------------------------------------

// flaplag._flaplag.InvalidInput (a ValueError), created at import and never freed (the module
// lives as long as the interpreter).
PyObject* invalid_input_type = nullptr;

// The most characters of a value shown in a message (as the Python layer's _shown).
constexpr std::size_t kShownMax = 60;

// Text for a one-line message: every run of white space (newlines included) one space, at
// most `max` characters (cut with "...").
std::string one_line(const std::string& text, std::size_t max) {
  std::string out;
  bool space = false;
  for (const char c : text) {
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f') {
      space = !out.empty();
      continue;
    }
    if (space) out += ' ';
    space = false;
    out += c;
    if (out.size() > max) break;
  }
  if (out.size() > max) out = out.substr(0, max - 3) + "...";
  return out;
}

// The library's InvalidInput as flaplag.InvalidInput: "<field> = <value>: <reason>" on one
// line, the value bounded (a value the user gave, e.g. a model name, may be any text).
// The condition's linearization is the keyword periodic_linearization=True here.
void translate_invalid_input(const InvalidInput& e) {
  const bool linearization = e.name() == "linearization";
  const std::string name = linearization ? "periodic_linearization" : e.name();
  const std::string value = linearization ? "True" : one_line(e.value(), kShownMax);
  std::string reason = one_line(e.reason(), 1000);
  for (std::size_t at = reason.find("`linearization`"); at != std::string::npos;
       at = reason.find("`linearization`", at + 1))
    reason.replace(at, 15, "`periodic_linearization`");
  py::object type = py::reinterpret_borrow<py::object>(invalid_input_type);
  py::object exc = type(one_line(name, kShownMax) + " = " + value + ": " + reason);
  exc.attr("field") = name;
  exc.attr("value") = value;
  exc.attr("reason") = reason;
  PyErr_SetObject(invalid_input_type, exc.ptr());
}

// ---- conversions --------------------------------------------------------------------------------

py::array_t<double> to_numpy(const Eigen::MatrixXd& m) {
  py::array_t<double> a({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  auto r = a.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index k = 0; k < m.cols(); ++k) r(i, k) = m(i, k);
  return a;
}

py::array_t<double> to_numpy(const Eigen::VectorXd& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  auto r = a.mutable_unchecked<1>();
  for (Eigen::Index i = 0; i < v.size(); ++i) r(i) = v[i];
  return a;
}

py::array_t<double> to_numpy(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  auto r = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < v.size(); ++i) r(static_cast<py::ssize_t>(i)) = v[i];
  return a;
}

py::object optional(const std::optional<double>& v) {
  return v ? py::object(py::float_(*v)) : py::object(py::none());
}

// A name the user gave, quoted for a message (bounded: it may be any text).
std::string quoted(const std::string& s) {
  return s.size() <= kShownMax - 2 ? "'" + s + "'" : "'" + s.substr(0, kShownMax - 5) + "'...";
}

std::string values_text(std::size_t n) { return std::to_string(n) + " values"; }

// A Python value for a message: one line, bounded; an array by its shape (as the Python
// layer's _shown).
std::string shown(const py::handle& v) {
  if (py::isinstance<py::array>(v)) {
    const py::array a = py::reinterpret_borrow<py::array>(v);
    if (a.ndim() > 1 || a.size() > 8) {
      std::string shape;
      for (py::ssize_t i = 0; i < a.ndim(); ++i)
        shape += (i ? ", " : "") + std::to_string(a.shape(i));
      return "array of shape (" + shape + (a.ndim() == 1 ? ",)" : ")");
    }
  }
  if (py::isinstance<py::str>(v) && py::len(v) > kShownMax) return quoted(v.cast<std::string>());
  return one_line(py::repr(v).cast<std::string>(), kShownMax);
}

// RotorParameters from {field: value}; field names and Python types are the caller's check, the
// values are validate()'s (called by Analysis).
RotorParameters rotor_parameters(const py::dict& d) {
  RotorParameters p;
  for (const auto& [key, value] : d) {
    const std::string field = key.cast<std::string>();
    // The blade table and the mode file: below.
    if (field == "blade_csv" || field == "blade_source" || field == "mode_shapes_csv" ||
        field == "mode_shapes_source" || field == "linearization")
      continue;
    const ParameterSpec* s = find_parameter(field);
    if (s == nullptr) throw InvalidInput(field, shown(value), "unknown parameter");
    switch (s->type) {
      case ParameterType::Real:
        p.*s->real = value.cast<double>();
        break;
      case ParameterType::Integer:
        // basis="paper": a named value; a number must be in the range (basis=0 is refused).
        if (s->names != nullptr && py::isinstance<py::str>(value)) {
          if (!integer_from_name(*s, value.cast<std::string>(), &(p.*s->integer)))
            throw InvalidInput(field, shown(value), std::string("must be ") + s->requirement);
          break;
        }
        p.*s->integer = value.cast<int>();
        if (s->names != nullptr && !in_range(*s, p.*s->integer))
          throw InvalidInput(field, shown(value), std::string("must be ") + s->requirement);
        break;
      case ParameterType::Flag:
        p.*s->flag = value.cast<bool>();
        break;
      case ParameterType::Text:
        p.model = value.cast<std::string>();
        break;
      case ParameterType::Choice: {
        const std::string text = value.cast<std::string>();
        if (!mode_kind_from_name(text, &p.modes)) {
          std::string choices = s->choices;
          for (std::size_t i = 0; (i = choices.find('|', i)) != std::string::npos;)
            choices.replace(i, 1, ", ");
          throw InvalidInput(field, quoted(text), "must be one of " + choices);
        }
        break;
      }
    }
  }
  // blade="table.csv" (read by the Python layer): the table sets the fields it determines.
  if (d.contains("blade_csv")) {
    const std::string source =
        d.contains("blade_source") ? d["blade_source"].cast<std::string>() : "blade";
    const BladeTable table = parse_blade_table(d["blade_csv"].cast<std::string>(), source);
    for (const std::string& field : blade_table_fields(table.dimensional)) {
      if (d.contains(field.c_str()))
        throw InvalidInput(field, shown(d[field.c_str()]),
                           std::string("not with blade (the ") +
                               (table.dimensional ? "dimensional " : "") + "blade table " + source +
                               " sets it)");
    }
    apply_blade_table(table, p);
  }
  if (d.contains("mode_shapes_csv")) {
    const std::string source = d["mode_shapes_source"].cast<std::string>();
    p.mode_shapes = std::make_shared<const ImportedModes>(
        parse_mode_table(d["mode_shapes_csv"].cast<std::string>(), source));
  }
  return p;
}

py::dict parameters_dict(const RotorParameters& p) {
  py::dict d;
  for (const ParameterSpec& s : parameter_table()) {
    switch (s.type) {
      case ParameterType::Real:
        d[s.field] = p.*s.real;
        break;
      case ParameterType::Integer:
        if (const std::string name = integer_name(s, p.*s.integer); !name.empty())
          d[s.field] = name;  // "basis": "converged"
        else
          d[s.field] = p.*s.integer;
        break;
      case ParameterType::Flag:
        d[s.field] = p.*s.flag;
        break;
      case ParameterType::Text:
      case ParameterType::Choice:
        d[s.field] = parameter_text(p, s);
        break;
    }
  }
  return d;
}

// The model of M flap and N lag modes in the family of p.model (the command line's
// --flap-modes / --lag-modes; any 1..model::kMaxModes); 1 x 1 is p.model itself.
void select_mode_counts(RotorParameters& p, int flap_modes, int lag_modes) {
  for (const auto& [name, n] : {std::pair{"flap_modes", flap_modes}, {"lag_modes", lag_modes}}) {
    if (n < 1 || n > model::kMaxModes)
      throw InvalidInput(
          name, std::to_string(n),
          "must be 1.." + std::to_string(model::kMaxModes) + " (the largest exact-mode basis)");
  }
  if (flap_modes == 1 && lag_modes == 1) return;
  if (p.modes == ModeKind::Assumed) {
    const bool flap = flap_modes > 1;
    throw InvalidInput(flap ? "flap_modes" : "lag_modes",
                       std::to_string(flap ? flap_modes : lag_modes),
                       "more than one mode needs modes='exact' (the assumed mode of eq 4.1 is "
                       "one flap and one lag mode)");
  }
  p.model = find_model(p.model, flap_modes, lag_modes).name;
}

// What the Python layer's rotor dict says the rotor is linearized about ("linearization":
// "hover" or "periodic", from periodic_linearization=...; the operating condition's, not a
// rotor parameter).  The hover equilibrium when absent.
Linearization linearization_of(const py::dict& params) {
  Linearization l = Linearization::HoverEquilibrium;
  if (!params.contains("linearization")) return l;
  const py::object v = params["linearization"];
  if (!py::isinstance<py::str>(v) || !enum_from_name(v.cast<std::string>(), &l))
    throw InvalidInput("periodic_linearization", shown(v), "must be True or False");
  return l;
}

RotorParameters base_parameters(const py::dict& params, int flap_modes, int lag_modes) {
  RotorParameters p = rotor_parameters(params);
  validate(p);
  try {
    find_model(p.model);
  } catch (const InvalidInput& e) {  // "paper-13x1": the library names the mode count
    throw InvalidInput("model", p.model, e.name() == "model" ? e.reason() : e.what());
  }
  select_mode_counts(p, flap_modes, lag_modes);
  // Galerkin's method gives at most `basis` rotating modes per direction: the converged basis
  // (the default, 12) holds every mode count; with basis=N the library refuses a basis below
  // them.
  return p;
}

// ---- results: one converter for every described struct (core/fields.h) ----------------------
//
// A struct becomes a dict with one entry per row of its table, under the row's name (the key the
// command line's JSON uses): numbers and flags as they are (a zeta of -inf included), optionals
// None when empty, described enums by name, described structs as dicts, vectors as lists.  A
// struct whose Python class holds more than its table (add_extra_keys) gets that from the
// analysis it was computed with, wherever it is met: alone or as a row of another result.

// The analysis a result was computed with (nullptr: none, for a result that needs none) and the
// azimuths per revolution at which a periodic equilibrium is sampled.
struct Context {
  const Analysis* analysis = nullptr;
  int samples = 72;  // Analysis.periodic_equilibrium's default

  const Analysis& of() const {
    if (analysis == nullptr) throw std::logic_error("a result's extra keys need its analysis");
    return *analysis;
  }
};

template <class T>
py::dict to_dict(const T& object, const Context& context = {});

// What a Python class holds beyond its table: nothing, but for these.
template <class T>
void add_extra_keys(py::dict&, const T&, const Context&) {}
void add_extra_keys(py::dict& d, const PeriodicEquilibrium& e, const Context& context);
void add_extra_keys(py::dict& d, const TrimResult& t, const Context& context);
void add_extra_keys(py::dict& d, const ForcedResponse& f, const Context& context);
void add_extra_keys(py::dict& d, const TipSimulation& t, const Context& context);

template <class T>
using is_optional = is_optional_field<T>;
template <class T>
using is_vector = is_vector_field<T>;

template <class V>
py::object to_python(const V& v, const Context& context = {}) {
  if constexpr (std::is_same_v<V, double>) {
    return py::float_(v);
  } else if constexpr (std::is_same_v<V, bool>) {
    return py::bool_(v);
  } else if constexpr (std::is_same_v<V, int>) {
    return py::int_(v);
  } else if constexpr (std::is_same_v<V, std::string>) {
    return py::str(v);
  } else if constexpr (std::is_same_v<V, std::complex<double>>) {
    return py::cast(v);
  } else if constexpr (is_described_enum_v<V>) {
    return py::str(enum_name(v));
  } else if constexpr (is_named_values_field<V>::value) {
    py::dict d;
    for (const auto& [name, x] : v) d[py::str(name)] = x;
    return std::move(d);
  } else if constexpr (std::is_same_v<V, Eigen::MatrixXd> || std::is_same_v<V, Eigen::VectorXd>) {
    return to_numpy(v);
  } else if constexpr (is_optional<V>::value) {
    return v ? to_python(*v, context) : py::object(py::none());
  } else if constexpr (is_vector<V>::value) {
    py::list l;
    for (const auto& x : v) l.append(to_python(x, context));
    return std::move(l);
  } else {
    static_assert(is_described_struct_v<V>, "a field of a type Python cannot hold");
    return to_dict(v, context);
  }
}

template <class T>
py::dict to_dict(const T& object, const Context& context) {
  py::dict d;
  for_each_field(
      object, [&](const auto& row, const auto& value) { d[row.name] = to_python(value, context); });
  add_extra_keys(d, object, context);
  return d;
}

// The result structs the Python classes are built from, each with its class's name.
template <class F>
void for_each_result_struct(F&& f) {
  f(Tag<LabelledExponent>{}, "Exponent");
  f(Tag<PointResult>{}, "PointResult");
  f(Tag<SweepResult>{}, "SweepResult");
  f(Tag<InstabilityInterval>{}, "Interval");
  f(Tag<DampingCrossing>{}, "DampingCrossing");
  f(Tag<CriticalResult>{}, "CriticalResult");
  f(Tag<TrimResult>{}, "TrimResult");
  f(Tag<ThrustResult>{}, "ThrustResult");
  f(Tag<FloquetSample>{}, "FloquetSample");
  f(Tag<PeriodicEquilibrium>{}, "PeriodicEquilibriumResult");
  f(Tag<model::ModelDescriptor>{}, "ModelInfo");
  f(Tag<HoverResult>{}, "HoverResult");
  f(Tag<StudyRow>{}, "StudyRow");
  f(Tag<MapCell>{}, "MapCell");
  f(Tag<CampbellResult>{}, "CampbellResult");
  f(Tag<CampbellPoint>{}, "CampbellPoint");
  f(Tag<CampbellFrequency>{}, "CampbellFrequency");
  f(Tag<CampbellCrossing>{}, "CampbellCrossing");
  f(Tag<TipMotion>{}, "TipMotion");
  f(Tag<ForcedResponse>{}, "ResponseResult");
  f(Tag<TipSimulation>{}, "SimulationResult");
}

// The Python class of a described struct ("" for one without: a dict).
template <class T>
std::string python_class() {
  std::string name;
  for_each_result_struct([&](auto tag, const char* n) {
    if (std::is_same_v<typename decltype(tag)::type, T>) name = n;
  });
  return name;
}

// The type of a row's value in the words the Python layer turns into its annotation:
// "float", "int", "bool", "str", "complex", "dict" (numbers by name), "matrix", "vector",
// "optional <type>", "list <type>", "struct <class>" (a dict for a struct without a class).
template <class V>
std::string type_words() {
  if constexpr (std::is_same_v<V, double>) {
    return "float";
  } else if constexpr (std::is_same_v<V, bool>) {
    return "bool";
  } else if constexpr (std::is_same_v<V, int>) {
    return "int";
  } else if constexpr (std::is_same_v<V, std::string> || is_described_enum_v<V>) {
    return "str";
  } else if constexpr (std::is_same_v<V, std::complex<double>>) {
    return "complex";
  } else if constexpr (is_named_values_field<V>::value) {
    return "dict";
  } else if constexpr (std::is_same_v<V, Eigen::MatrixXd>) {
    return "matrix";
  } else if constexpr (std::is_same_v<V, Eigen::VectorXd>) {
    return "vector";
  } else if constexpr (is_optional<V>::value) {
    return "optional " + type_words<typename V::value_type>();
  } else if constexpr (is_vector<V>::value) {
    return "list " + type_words<typename V::value_type>();
  } else {
    static_assert(is_described_struct_v<V>, "a field of a type Python cannot hold");
    return "struct " + python_class<V>();
  }
}

// row(r) for each row r of the table of the struct of the Python class `name`.
template <class Row>
py::list result_rows(const std::string& name, Row&& row) {
  py::list l;
  bool found = false;
  for_each_result_struct([&](auto tag, const char* n) {
    if (name != n) return;
    found = true;
    for_each_row<typename decltype(tag)::type>([&](const auto& r) { l.append(row(r)); });
  });
  if (!found) throw InvalidInput("name", quoted(name), "not a described result");
  return l;
}

// ---- options: one converter for every described options struct (core/fields.h) -------------
//
// An options struct from {key: value} by the rows of its table: numbers and flags by their C++
// type, described enums by name, nested options structs from dicts, optionals None or a value.
// An unknown key is InvalidInput(key, value, `unknown`); a value of the wrong type is
// InvalidInput(key, value, "must be ..."); the values are the struct's Check()'s.

template <class O>
O options_from(const py::dict& d, const char* unknown);

template <class V>
V option_value(const std::string& key, const py::handle& value) {
  try {
    if constexpr (std::is_same_v<V, bool>) {
      if (!py::isinstance<py::bool_>(value) &&
          !py::isinstance(value, py::module_::import("numpy").attr("bool_")))
        throw InvalidInput(key, shown(value), "must be True or False");
      return value.cast<bool>();
    } else if constexpr (std::is_same_v<V, int>) {
      if (py::isinstance<py::bool_>(value))
        throw InvalidInput(key, shown(value), "must be a whole number");
      return value.cast<int>();
    } else if constexpr (std::is_same_v<V, double>) {
      if (py::isinstance<py::bool_>(value))
        throw InvalidInput(key, shown(value), "must be a real number");
      return value.cast<double>();
    } else if constexpr (is_described_enum_v<V>) {
      const std::string name = value.cast<std::string>();
      V v{};
      if (!enum_from_name(name, &v))
        throw InvalidInput(key, quoted(name), "must be one of " + enum_names<V>());
      return v;
    } else if constexpr (is_optional_field<V>::value) {
      if (value.is_none()) return V{};
      return V(option_value<typename V::value_type>(key, value));
    } else {
      static_assert(is_described_struct_v<V>, "an option Python cannot set");
      if (!py::isinstance<py::dict>(value))
        throw InvalidInput(key, shown(value), "must be a dict of options");
      return options_from<V>(py::reinterpret_borrow<py::dict>(value), "unknown option");
    }
  } catch (const py::cast_error&) {
    const char* what = std::is_same_v<V, int>      ? "must be a whole number"
                       : std::is_same_v<V, double> ? "must be a real number"
                                                   : "must be a string";
    throw InvalidInput(key, shown(value), what);
  }
}

// The rows named in d into o (no check: a struct with fields set by hand as well, a study's or a
// map's axes, is checked once they are set).
template <class O>
void set_options(O& o, const py::dict& d, const char* unknown) {
  for (const auto& item : d) {
    const std::string key = py::cast<std::string>(item.first);
    const py::handle value = item.second;
    const bool known = visit_row<O>(key, [&](const auto& row) {
      using V = typename std::decay_t<decltype(row)>::value_type;
      row.get(o) = option_value<V>(key, value);
    });
    if (!known) throw InvalidInput(key, shown(value), unknown);
  }
}

template <class O>
O options_from(const py::dict& d, const char* unknown) {
  O o;
  set_options(o, d, unknown);
  o.Check();
  return o;
}

TransitionOptions transition_options(const py::dict& d) {
  return options_from<TransitionOptions>(d, "unknown transition option");
}

CriticalOptions critical_options(const py::dict& d) {
  return options_from<CriticalOptions>(d, "unknown option of the critical search");
}

// Calls f(Tag<O>{}) for the options struct Python calls `name`.
template <class F>
auto with_options_struct(const std::string& name, F&& f) {
  if (name == "transition") return f(Tag<TransitionOptions>{});
  if (name == "critical") return f(Tag<CriticalOptions>{});
  if (name == "campbell") return f(Tag<CampbellOptions>{});
  if (name == "trim") return f(Tag<TrimOptions>{});
  if (name == "inflow") return f(Tag<InflowModel>{});
  if (name == "response") return f(Tag<ResponseOptions>{});
  if (name == "simulation") return f(Tag<SimulationOptions>{});
  if (name == "equilibrium") return f(Tag<PeriodicEquilibriumOptions>{});
  if (name == "study") return f(Tag<StudyOptions>{});  // its scalar options; axes by hand
  if (name == "map") return f(Tag<MapOptions>{});
  throw InvalidInput("name", quoted(name), "not a described options struct");
}

// The defaults of an options struct: the dict of a default-constructed one.
py::dict option_defaults(const std::string& name) {
  return with_options_struct(name, [](auto tag) {
    using O = typename decltype(tag)::type;
    return to_dict(O{});
  });
}

// The rows of an options struct's table: (key, units, doc, range words or None, default).
py::list option_rows(const std::string& name) {
  return with_options_struct(name, [](auto tag) {
    using O = typename decltype(tag)::type;
    const O defaults;
    py::list l;
    for_each_field(defaults, [&](const auto& row, const auto& value) {
      const Range* range = row_range(row);
      l.append(py::make_tuple(row.name, row.units, row.doc,
                              range ? py::object(py::str(range->words)) : py::object(py::none()),
                              to_python(value)));
    });
    return l;
  });
}

// The stations: an array of them, or (an integer n) n equally spaced ones over [0, 1], made
// here so that no list of n Python floats is built first.  Checked against the memory limit
// before anything is allocated; the shapes are sampled with the GIL released.
py::dict modes_dict(const ModeSet& modes, const py::object& stations, int derivative,
                    std::uint64_t memory_limit) {
  if (derivative < 0 || derivative > 3)
    throw InvalidInput("derivative", std::to_string(derivative), "must be 0, 1, 2 or 3");
  int shapes = 0;
  for (const DirectionModes& dm : modes.directions) shapes += dm.count();
  py::array_t<double> x;
  if (py::isinstance<py::int_>(stations)) {
    const long long n = stations.cast<long long>();
    if (n < 2) throw InvalidInput("x", std::to_string(n), "need at least 2 stations");
    check_memory(stations_memory(static_cast<std::size_t>(n), shapes), memory_limit, "x",
                 std::to_string(n));
    x = py::array_t<double>(static_cast<py::ssize_t>(n));
    double* p = x.mutable_data();
    {
      // numpy.linspace(0, 1, n), bit for bit: i * (1 / (n - 1)), the last exactly 1.
      py::gil_scoped_release release;
      const double step = 1.0 / static_cast<double>(n - 1);
      for (long long i = 0; i < n; ++i) p[i] = static_cast<double>(i) * step + 0.0;
      p[n - 1] = 1.0;
    }
  } else {
    x = stations.cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
    if (x.ndim() != 1) throw InvalidInput("x", "an array", "must be one-dimensional");
    check_memory(stations_memory(static_cast<std::size_t>(x.size()), shapes), memory_limit, "x",
                 values_text(static_cast<std::size_t>(x.size())));
    for (py::ssize_t i = 0; i < x.size(); ++i) {
      const double v = x.data()[i];
      if (!(v >= 0.0 && v <= 1.0))
        throw InvalidInput("x", round_trip_text(v), "stations must be in [0, 1] (x0 = r / l)");
    }
  }
  const std::size_t n = static_cast<std::size_t>(x.size());
  const double* xs = x.data();
  auto sample = [&](const std::vector<std::shared_ptr<const ModeShape>>& set) {
    py::array_t<double> a({static_cast<py::ssize_t>(set.size()), static_cast<py::ssize_t>(n)});
    double* out = a.mutable_data();
    {
      py::gil_scoped_release release;
      for (std::size_t k = 0; k < set.size(); ++k)
        for (std::size_t q = 0; q < n; ++q) out[k * n + q] = set[k]->value(derivative, xs[q]);
    }
    return a;
  };
  py::dict d;
  d["kind"] = modes.kind;
  d["x"] = x;
  d["derivative"] = derivative;
  // Per direction (model_api.h names): "flap", "lag"; "omega_flap", ...; "stiffness_flap", ...
  auto name = [](model::Direction dir) {
    return std::string(model::kDirectionNames[model::index(dir)]);
  };
  for (const model::Direction dir : model::kDirections)
    d[name(dir).c_str()] = sample(modes.shapes(dir));
  for (const model::Direction dir : model::kDirections)
    d[("omega_" + name(dir)).c_str()] = to_numpy(modes[dir].omega);
  for (const model::Direction dir : model::kDirections)
    d[("stiffness_" + name(dir)).c_str()] = modes[dir].stiffness;
  return d;
}

// ---- long runs: studies and maps ----------------------------------------------------------------

// The trim of a trimmed computation from {key: value}: kind 'thrust' or 'moment' (not 'none').
TrimOptions trim_options(const py::dict& d) {
  const std::string kind = d.contains("kind") ? d["kind"].cast<std::string>() : "none";
  if (TrimKind k; !trim_kind_from_name(kind, &k) || k == TrimKind::None)
    throw InvalidInput("kind", quoted(kind), "must be 'thrust' or 'moment'");
  return options_from<TrimOptions>(d, "unknown trim option");
}

// The same with the iteration options at their defaults (as --trim).
TrimOptions trim_options(const std::string& kind, double thrust_coefficient, double shaft_angle) {
  py::dict d;
  d["kind"] = kind;
  d["thrust_coefficient"] = thrust_coefficient;
  d["shaft_angle"] = shaft_angle;
  return trim_options(d);
}

// The trim of a study or a map: None (untrimmed: kind None) or (kind, C_T, alpha_R), as
// Python's _trim_request gives it; the trim's iteration options are the defaults (as --trim).
TrimOptions trim_of(const py::object& request) {
  if (request.is_none()) return TrimOptions{};
  const auto [kind, ct, alpha] = request.cast<std::tuple<std::string, double, double>>();
  return trim_options(kind, ct, alpha);
}

// The operating condition of a study or a map into o: None (fixed controls, eq 2.24), a trim
// (kind, C_T, alpha_R) as trim_of reads it, or an InflowModel dict (fixed controls at that
// inflow, as Python's _inflow_request gives it).
template <class O>
void set_condition(O& o, const py::object& request) {
  if (py::isinstance<py::dict>(request)) {
    o.inflow = options_from<InflowModel>(py::reinterpret_borrow<py::dict>(request),
                                         "unknown inflow option");
    return;
  }
  o.trim = trim_of(request);
}

// Runs work(cancel, progress) on a thread of its own.  The calling thread (which holds the GIL on
// entry and exit) waits with the GIL released; every 50 ms, and when the work ends, it takes the
// GIL to call progress_cb(done, total) when that changed and to check for signals.  A signal
// handler that raises (KeyboardInterrupt) or a progress callback that raises cancels the work;
// the exception is re-raised once the work has stopped.
template <typename Result, typename Work>
Result run_cancellable(Work work, const py::object& progress_cb) {
  std::atomic<bool> cancel{false};
  std::atomic<std::size_t> done{0}, total{0};
  std::mutex mutex;
  std::condition_variable cv;
  bool finished = false;
  Result result{};
  std::exception_ptr failure;
  std::optional<py::error_already_set> python_error;
  std::size_t reported = 0;

  auto poll = [&]() {  // with the GIL held
    if (python_error) return;
    if (PyErr_CheckSignals() != 0) {
      python_error.emplace();
      cancel = true;
      return;
    }
    const std::size_t d = done.load(), n = total.load();
    if (!progress_cb.is_none() && n > 0 && d != reported) {
      reported = d;
      try {
        progress_cb(d, n);
      } catch (py::error_already_set& e) {
        python_error.emplace(std::move(e));
        cancel = true;
      }
    }
  };

  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      try {
        result = work(&cancel, [&](std::size_t d, std::size_t n) {
          total = n;
          done = d;
        });
      } catch (...) {
        failure = std::current_exception();
      }
      const std::lock_guard<std::mutex> lock(mutex);
      finished = true;
      cv.notify_all();
    });
    for (;;) {
      bool end = false;
      {
        std::unique_lock<std::mutex> lock(mutex);
        end = cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return finished; });
      }
      {
        py::gil_scoped_acquire acquire;
        poll();
      }
      if (end) break;
    }
    worker.join();
  }
  if (python_error) throw std::move(*python_error);
  if (failure) std::rethrow_exception(failure);
  return result;
}

std::vector<double> values_of(const py::handle& v) { return v.cast<std::vector<double>>(); }

StudyOptions study_options(const std::string& parameter, const py::handle& values,
                           const py::dict& critical, int threads, const py::object& trim) {
  StudyOptions o;
  o.parameter = parameter;
  o.values = values_of(values);
  // The damping criterion travels with the search options (Python's study(damping_criterion=));
  // it and the threads are rows of the study's table.
  py::dict search, scalars;
  for (const auto& [key, value] : critical)
    (key.cast<std::string>() == "damping_criterion" ? scalars : search)[key] = value;
  o.critical = critical_options(search);
  set_condition(o, trim);
  scalars["threads"] = threads;
  set_options(o, scalars, "unknown study option");
  o.Check();
  return o;
}

// 2 (M + N) of the model of p.
int state_size_of(const RotorParameters& p) {
  const model::ModelDescriptor& m = find_model(p.model);
  return 2 * (m.flap_modes + m.lag_modes);
}

void check_study_memory(const RotorParameters& base, const StudyOptions& o,
                        std::uint64_t memory_limit) {
  check_memory(study_memory(o.values.size(), state_size_of(base)), memory_limit, "values",
               values_text(o.values.size()));
}

void check_map_memory(const MapOptions& o, std::uint64_t memory_limit) {
  const bool y = o.y.values.size() >= o.x.values.size();
  check_memory(map_memory(o.x.values.size(), o.y.values.size()), memory_limit, y ? "y" : "x",
               values_text((y ? o.y : o.x).values.size()));
}

py::dict study(const py::dict& params, const py::dict& transition, int flap_modes, int lag_modes,
               const std::string& parameter, const py::handle& values, const py::dict& critical,
               int threads, const py::object& progress, const py::object& trim_request,
               std::uint64_t memory_limit) {
  const RotorParameters base = base_parameters(params, flap_modes, lag_modes);
  const TransitionOptions t = transition_options(transition);
  StudyOptions o = study_options(parameter, values, critical, threads, trim_request);
  o.linearization = linearization_of(params);
  check_study_memory(base, o, memory_limit);
  const bool trimmed = o.trim.kind != TrimKind::None;
  // A trimmed row reports the trim at its mu_c (theta0, theta1c, theta1s, lambda there), as
  // `flaplag critical --trim` does: the trim the row's search made there (StudyRow::trim).
  const StudyResult r = run_cancellable<StudyResult>(
      [&](const std::atomic<bool>* cancel, ProgressFunction report) {
        return run_study(base, t, o, cancel, report);
      },
      progress);
  py::list rows;
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    py::dict row = to_dict(r.rows[i].critical);
    row["trim"] =
        trimmed && r.rows[i].trim ? py::object(to_dict(*r.rows[i].trim)) : py::object(py::none());
    if (o.damping_criterion) row["damping_crossings"] = to_python(r.rows[i].damping_crossings);
    rows.append(row);
  }
  py::dict d;
  d["values"] = to_numpy(o.values);
  d["rows"] = rows;
  d["status"] = status_name(r.status);
  d["message"] = r.message;
  return d;
}

// A map's cells into d, one entry per scalar row of MapCell's table, each of the map's shape
// (ny, nx): numbers as float arrays (nan where unknown), flags as bool arrays, text and names as
// nested lists ('' where unknown).  Unknown: a cell not computed, and for the exponent's rows
// (MapCell's own but `computed`) a cell without max_zeta.
void map_cells(const std::vector<std::vector<MapCell>>& cells, std::size_t ny, std::size_t nx,
               py::dict& d) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for_each_row<MapCell>([&](const auto& field) {
    using Row = std::decay_t<decltype(field)>;
    using V = typename Row::value_type;
    const bool exponent =
        std::is_same_v<typename Row::owner_type, MapCell> && !std::is_same_v<V, bool>;
    auto known = [&](const MapCell& c) {
      return c.computed && (!exponent || c.max_zeta.has_value());
    };
    if constexpr (std::is_same_v<V, double> || std::is_same_v<V, std::optional<double>> ||
                  std::is_same_v<V, bool>) {
      using E = std::conditional_t<std::is_same_v<V, bool>, bool, double>;
      py::array_t<E> a({static_cast<py::ssize_t>(ny), static_cast<py::ssize_t>(nx)});
      auto at = a.template mutable_unchecked<2>();
      for (std::size_t i = 0; i < ny; ++i)
        for (std::size_t j = 0; j < nx; ++j) {
          const MapCell& c = cells[i][j];
          const auto ii = static_cast<py::ssize_t>(i), jj = static_cast<py::ssize_t>(j);
          if constexpr (std::is_same_v<V, bool>) {
            at(ii, jj) = field.get(c);
          } else if constexpr (std::is_same_v<V, double>) {
            at(ii, jj) = known(c) ? field.get(c) : nan;
          } else {
            at(ii, jj) = known(c) && field.get(c) ? *field.get(c) : nan;
          }
        }
      d[field.name] = a;
    } else if constexpr (std::is_same_v<V, std::string> || is_described_enum_v<V>) {
      py::list grid;
      for (std::size_t i = 0; i < ny; ++i) {
        py::list line;
        for (std::size_t j = 0; j < nx; ++j) {
          const MapCell& c = cells[i][j];
          if constexpr (std::is_same_v<V, std::string>) {
            line.append(known(c) ? field.get(c) : std::string());
          } else {
            line.append(known(c) ? enum_name(field.get(c)) : "");
          }
        }
        grid.append(line);
      }
      d[field.name] = grid;
    }
  });
}

MapOptions map_options(const std::string& x, const py::handle& x_values, const std::string& y,
                       const py::handle& y_values, double mu, double scan_step, int threads,
                       const py::object& trim) {
  MapOptions o;
  o.x = MapAxis{x, values_of(x_values)};
  o.y = MapAxis{y, values_of(y_values)};
  set_condition(o, trim);
  py::dict scalars;  // the rows of the map's table
  scalars["mu"] = mu;
  scalars["scan_step"] = scan_step;
  scalars["threads"] = threads;
  set_options(o, scalars, "unknown map option");
  o.Check();
  return o;
}

py::dict stability_map(const py::dict& params, const py::dict& transition, int flap_modes,
                       int lag_modes, const std::string& x, const py::handle& x_values,
                       const std::string& y, const py::handle& y_values, double mu,
                       double scan_step, int threads, const py::object& progress,
                       const py::object& trim, std::uint64_t memory_limit) {
  const RotorParameters base = base_parameters(params, flap_modes, lag_modes);
  const TransitionOptions t = transition_options(transition);
  MapOptions o = map_options(x, x_values, y, y_values, mu, scan_step, threads, trim);
  o.linearization = linearization_of(params);
  check_map_memory(o, memory_limit);
  const MapResult r = run_cancellable<MapResult>(
      [&](const std::atomic<bool>* cancel, ProgressFunction report) {
        return run_map(base, t, o, cancel, report);
      },
      progress);
  py::dict d;
  d["x_values"] = to_numpy(o.x.values);
  d["y_values"] = to_numpy(o.y.values);
  map_cells(r.cells, o.y.values.size(), o.x.values.size(), d);
  d["lines_done"] = r.lines_done;
  d["cancelled"] = r.cancelled;
  d["overall_status"] = status_name(r.status);
  d["overall_message"] = r.message;
  return d;
}

// ---- response and simulation -------------------------------------------------------------------

// Rows of a 2-D array: one state vector per sample.
py::array_t<double> states_numpy(const std::vector<Eigen::VectorXd>& y, int n) {
  py::array_t<double> a({static_cast<py::ssize_t>(y.size()), static_cast<py::ssize_t>(n)});
  auto r = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < y.size(); ++i)
    for (int k = 0; k < n; ++k) r(static_cast<py::ssize_t>(i), k) = y[i](k);
  return a;
}

py::list harmonic_names(std::size_t n) {
  py::list l;
  for (std::size_t h = 0; h < n; ++h) l.append(harmonic_name(static_cast<int>(h)));
  return l;
}

// The per-direction tip motions by direction, in the model's state order (the Python classes'
// `tips`).
py::dict tip_dicts(const std::vector<TipMotion>& tips) {
  py::dict d;
  for (const TipMotion& t : tips) d[t.direction.c_str()] = to_dict(t);
  return d;
}

// The states as a samples x states array, the tips by direction and the names of the harmonics.
void add_extra_keys(py::dict& d, const ForcedResponse& f, const Context& context) {
  d["y"] = states_numpy(f.periodic.y, context.of().state_size());
  d["tips"] = tip_dicts(f.tips);
  d["harmonic_names"] = harmonic_names(f.tips.empty() ? 0 : f.tips.front().harmonics.size());
}

void add_extra_keys(py::dict& d, const TipSimulation& t, const Context& context) {
  d["y"] = states_numpy(t.simulation.y, context.of().state_size());
  d["tips"] = tip_dicts(t.tips);
}

// ---- periodic equilibrium and trim -------------------------------------------------------------

// The coefficients, and the state and the tips sampled at context.samples azimuths (none when
// the equilibrium failed).
void add_extra_keys(py::dict& d, const PeriodicEquilibrium& e, const Context& context) {
  const Analysis& a = context.of();
  std::vector<double> psi;
  std::vector<Eigen::VectorXd> y;
  std::vector<TipMotion> tips = a.tip_motions();
  if (e.status != Status::Failed) {
    for (int k = 0; k < context.samples; ++k) {
      psi.push_back(kTwoPi * k / context.samples);
      y.push_back(e.state(psi.back()));
      const std::vector<double> tip = a.tip_deflections(y.back());
      for (std::size_t i = 0; i < tips.size(); ++i) tips[i].deflection.push_back(tip[i]);
    }
  }
  d["coefficients"] = to_numpy(e.coefficients);
  d["psi"] = to_numpy(psi);
  d["y"] = states_numpy(y, a.state_size());
  d["tips"] = tip_dicts(tips);
}

// The trimmed rotor's parameters (Analysis(**parameters)).
void add_extra_keys(py::dict& d, const TrimResult& t, const Context&) {
  d["parameters"] = parameters_dict(t.parameters);
}

// ---- tables -------------------------------------------------------------------------------------

const char* type_name(ParameterType t) {
  switch (t) {
    case ParameterType::Real:
      return "real";
    case ParameterType::Integer:
      return "int";
    case ParameterType::Text:
      return "text";
    case ParameterType::Flag:
      return "flag";
    case ParameterType::Choice:
      return "choice";
  }
  return "";
}

py::list parameter_rows() {
  const RotorParameters defaults;
  const py::dict values = parameters_dict(defaults);
  py::list rows;
  for (const ParameterSpec& s : parameter_table()) {
    py::dict r;
    r["field"] = s.field;
    r["symbol"] = s.symbol;
    r["units"] = s.units;
    r["description"] = s.description;
    r["type"] = type_name(s.type);
    r["requirement"] = s.requirement;
    r["default"] = values[s.field];
    if (s.type == ParameterType::Real || s.type == ParameterType::Integer) {
      r["range"] = py::make_tuple(s.range.lo, s.range.hi, s.range.lo_open, s.range.hi_open);
    }
    if (s.type == ParameterType::Integer && s.names != nullptr) {
      py::list names;  // "converged=0|paper=5": the names
      std::string c = s.names;
      for (std::size_t start = 0; start < c.size();) {
        std::size_t bar = c.find('|', start);
        if (bar == std::string::npos) bar = c.size();
        const std::string item = c.substr(start, bar - start);
        names.append(item.substr(0, item.find('=')));
        start = bar + 1;
      }
      r["names"] = names;
    }
    if (s.type == ParameterType::Choice) {
      py::list choices;
      std::string c = s.choices;
      for (std::size_t start = 0;;) {
        const std::size_t bar = c.find('|', start);
        choices.append(c.substr(start, bar == std::string::npos ? std::string::npos : bar - start));
        if (bar == std::string::npos) break;
        start = bar + 1;
      }
      r["choices"] = choices;
    }
    rows.append(r);
  }
  return rows;
}

// The rows of an options struct's table in the form of parameter_rows (field, symbol, type,
// default, units, requirement, description; choices of an enum).
template <class O>
py::list table_rows() {
  const O defaults;
  py::list rows;
  for_each_field(defaults, [&](const auto& row, const auto& value) {
    using V = std::decay_t<decltype(value)>;
    const Range* range = row_range(row);
    py::dict r;
    r["field"] = row.name;
    r["symbol"] = "";
    r["default"] = to_python(value);
    r["units"] = *row.units != '\0' ? row.units : "-";
    r["requirement"] = range != nullptr ? range->words : "";
    r["description"] = row.doc;
    if constexpr (std::is_same_v<V, double>) {
      r["type"] = "real";
    } else if constexpr (std::is_same_v<V, int>) {
      r["type"] = "int";
    } else if constexpr (std::is_same_v<V, bool>) {
      r["type"] = "flag";
    } else if constexpr (is_described_enum_v<V>) {
      r["type"] = "choice";
      r["requirement"] = enum_names<V>();
      py::list choices;
      for (const EnumName<V>& e : describe(Tag<V>{})) choices.append(e.name);
      r["choices"] = choices;
    }
    rows.append(r);
  });
  return rows;
}

py::list model_rows() {
  py::list l;
  for (const model::ModelDescriptor* m : compiled_models()) l.append(to_dict(*m));
  return l;
}

// A sweep's dict, with the crossings of the damping criterion when one was asked for (modes in
// hover order, as the command line's --damping-criterion).
py::dict sweep_dict(const Analysis& a, RotorSweep r, const std::optional<double>& criterion) {
  if (criterion) apply_damping_criterion(r, distinct_labels(a.hover().labels), *criterion);
  return to_dict(r, Context{&a});
}

// The analysis of a's rotor trimmed at every mu with o (a's options as resolved).
Analysis trimmed(const Analysis& a, const TrimOptions& o) {
  return Analysis(a.parameters(), a.options(),
                  OperatingCondition::Trimmed(o).About(a.condition().linearization));
}

void check_criterion(const std::optional<double>& criterion) {
  if (criterion) check_damping_criterion(*criterion);
}

// flaplag.InvalidInput, and the translation of the library's InvalidInput into it.
void register_invalid_input(py::module_& m) {
  invalid_input_type = PyErr_NewExceptionWithDoc(
      "flaplag.InvalidInput",
      "An invalid parameter, option or argument: a ValueError whose message is the one line\n"
      "'<field> = <value>: <reason>'; the parts are .field, .value and .reason.",
      PyExc_ValueError, nullptr);
  if (invalid_input_type == nullptr) throw py::error_already_set();
  m.attr("InvalidInput") = py::handle(invalid_input_type);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InvalidInput& e) {
      translate_invalid_input(e);
    }
  });
}

// The tables the Python layer builds its classes and checks from: parameters, options and
// their defaults, result fields, models; the version.
void bind_tables(py::module_& m) {
  m.attr("version") = kVersion;
  m.attr("git_commit") = kGitCommit;
  m.attr("max_advance_ratio") = kMaxAdvanceRatio;
  m.def("parameter_table", &parameter_rows);
  m.def("transition_table", &table_rows<TransitionOptions>);
  m.def("inflow_table", &table_rows<InflowModel>);  // InflowModel (kind's choices: the models)
  // The defaults and the rows of an options struct, by name ("critical", "trim", ...).
  m.def("option_defaults", &option_defaults);
  m.def("option_table", &option_rows);
  m.def("damping_ratio",
        [](double zeta, double omega) { return optional(damping_ratio(zeta, omega)); });
  // The rows (key, units, doc) of a result's table, by the Python class's name, and (key,
  // type_words, whether a document leaves it out when empty) for the class's attributes.
  m.def("result_fields", [](const std::string& name) {
    return result_rows(name, [](const auto& r) { return py::make_tuple(r.name, r.units, r.doc); });
  });
  m.def("result_types", [](const std::string& name) {
    return result_rows(name, [](const auto& r) {
      using V = typename std::decay_t<decltype(r)>::value_type;
      return py::make_tuple(r.name, type_words<V>(), (r.flags & kFieldOmitWhenEmpty) != 0);
    });
  });
  m.def("models", &model_rows);
  // spec="my.toml": derives the spec now and registers its model (runtime_spec.h).
  m.def("load_spec", [](const std::string& path) {
    const std::string name = flaplag::spec::load_spec(path).name;
    return name;
  });
  m.def("audit_report", [](const std::string& model) {
    return flaplag::spec::audit_report(flaplag::find_model(model).base);
  });
  // lambda of eq 2.25 for C_T at mu with the shaft angle alpha_R (rotor/inflow.h).
  m.def("momentum_inflow", [](double thrust_coefficient, double mu, double shaft_angle) {
    InflowModel::Momentum(thrust_coefficient, shaft_angle).Check();
    return momentum_inflow(thrust_coefficient, mu, shaft_angle);
  });
  m.def("study_parameters", [] {
    py::list l;
    for (const ParameterSpec& s : parameter_table())
      if (is_study_parameter(s.field)) l.append(s.field);
    return l;
  });
}

// Construction from the Python layer's dicts, and what an Analysis was built from.
void bind_construction(py::class_<Analysis>& analysis) {
  analysis
      .def(py::init([](const py::dict& params, const py::dict& transition, int flap_modes,
                       int lag_modes) {
             const RotorParameters p = base_parameters(params, flap_modes, lag_modes);
             const TransitionOptions t = transition_options(transition);
             const OperatingCondition c = OperatingCondition{}.About(linearization_of(params));
             py::gil_scoped_release release;
             return Analysis(p, t, c);
           }),
           py::arg("params"), py::arg("transition"), py::arg("flap_modes") = 1,
           py::arg("lag_modes") = 1)
      .def("parameters", [](const Analysis& a) { return parameters_dict(a.parameters()); })
      .def("transition", [](const Analysis& a) { return to_dict(a.options()); })
      .def("model", [](const Analysis& a) { return to_dict(a.model()); })
      .def("hover", [](const Analysis& a) { return to_dict(a.hover()); });
}

// Stability in forward flight: one mu, a grid or track of mu, the critical mu, one Floquet
// sample.
void bind_stability(py::class_<Analysis>& analysis) {
  analysis
      .def("point",
           [](const Analysis& a, double mu, double scan_step) {
             RotorPoint r;
             {
               py::gil_scoped_release release;
               r = a.point(mu, scan_step);
             }
             return to_dict(r, Context{&a});
           })
      // sweep and track: progress(evaluations done, in all) and Ctrl-C as study and map.
      .def("sweep",
           [](const Analysis& a, double mu0, double mu1, double step, int threads,
              const py::object& progress, std::uint64_t memory_limit,
              const std::optional<double>& damping_criterion) {
             check_criterion(damping_criterion);
             // The grid's own checks first (they name mu0, mu1, step), then its size.
             const std::size_t points = sweep_grid(mu0, mu1, step).size();
             check_memory(sweep_memory(points, a.state_size()), memory_limit, "step",
                          round_trip_text(step));
             const RotorSweep r = run_cancellable<RotorSweep>(
                 [&](const std::atomic<bool>* cancel, ProgressFunction report) -> RotorSweep {
                   try {
                     return a.sweep(mu0, mu1, step, threads, cancel, report);
                   } catch (const Cancelled&) {
                     return RotorSweep{};  // run_cancellable raises what cancelled it
                   }
                 },
                 progress);
             return sweep_dict(a, r, damping_criterion);
           })
      .def("track",
           [](const Analysis& a, const std::vector<double>& mus, double scan_step, int threads,
              const py::object& progress, std::uint64_t memory_limit,
              const std::optional<double>& damping_criterion) {
             check_criterion(damping_criterion);
             if (mus.size() <= static_cast<std::size_t>(kMaxContinuationSteps))
               check_memory(sweep_memory(mus.size(), a.state_size()), memory_limit, "mu",
                            std::to_string(mus.size()) + " advance ratios");
             const RotorSweep r = run_cancellable<RotorSweep>(
                 [&](const std::atomic<bool>* cancel, ProgressFunction report) -> RotorSweep {
                   try {
                     return a.track(mus, scan_step, threads, cancel, report);
                   } catch (const Cancelled&) {
                     return RotorSweep{};
                   }
                 },
                 progress);
             return sweep_dict(a, r, damping_criterion);
           })
      .def("critical",
           [](const Analysis& a, const py::dict& options) {
             const CriticalOptions o = critical_options(options);
             RotorCritical r;
             {
               py::gil_scoped_release release;
               r = a.critical(o);
             }
             return to_dict(r, Context{&a});
           })
      .def("floquet", [](const Analysis& a, double mu, double zeta_tolerance) {
        FloquetSample s;
        {
          py::gil_scoped_release release;
          s = a.floquet(mu, zeta_tolerance);
        }
        return to_dict(s);
      });
}

// The blade's modes, their exported table, and their frequencies over rotor speed.
void bind_modes(py::class_<Analysis>& analysis) {
  analysis
      .def("modes",
           [](const Analysis& a, const py::object& x, int derivative, std::uint64_t memory_limit) {
             return modes_dict(a.modes(), x, derivative, memory_limit);
           })
      .def("mode_table",
           [](const Analysis& a, int stations) {
             // The file `flaplag modes --export-shapes` writes (imported_modes.h); the assumed
             // shape of eq 4.1 is no mode of the blade to hand on.
             if (a.modes().kind == "assumed") {
               throw InvalidInput("modes", "assumed",
                                  "exported mode shapes are the exact (or imported) modes: use "
                                  "modes='exact'");
             }
             return mode_table_text(a.modes(), stations);
           })
      .def("campbell", [](const Analysis& a, const py::dict& options) {
        const CampbellOptions o =
            options_from<CampbellOptions>(options, "unknown option of the Campbell diagram");
        CampbellResult c;
        {
          py::gil_scoped_release release;
          c = campbell_diagram(a.parameters(), a.options(), o);
        }
        return to_dict(c);
      });
}

// The rotor in time: the system at one azimuth, the forced response, the simulated tip, the
// periodic equilibrium.
void bind_time_domain(py::class_<Analysis>& analysis) {
  analysis
      .def("snapshot",
           [](const Analysis& a, double mu, double psi) {
             if (!std::isfinite(psi))
               throw InvalidInput("psi", round_trip_text(psi), "must be a finite angle [rad]");
             SystemSnapshot s;
             {
               py::gil_scoped_release release;
               s = a.snapshot(mu, psi);
             }
             return to_dict(s);
           })
      .def("response",
           [](const Analysis& a, double mu, const py::dict& options, std::uint64_t memory_limit) {
             const ResponseOptions o =
                 options_from<ResponseOptions>(options, "unknown option of the response");
             check_memory(response_memory(o.samples, a.state_size()), memory_limit, "samples",
                          std::to_string(o.samples));
             ForcedResponse f;
             {
               py::gil_scoped_release release;
               f = a.response(mu, o);
             }
             return to_dict(f, Context{&a});
           })
      .def("state_size", &Analysis::state_size)
      .def("simulate",
           [](const Analysis& a, double mu, const std::vector<double>& y0, bool forced,
              const py::dict& options, std::uint64_t memory_limit) {
             const SimulationOptions o =
                 options_from<SimulationOptions>(options, "unknown option of the simulation");
             check_memory(
                 simulation_memory(o.revolutions, o.samples_per_rev, a.state_size(), o.nonlinear),
                 memory_limit, "revolutions", round_trip_text(o.revolutions));
             const Eigen::VectorXd y =
                 Eigen::Map<const Eigen::VectorXd>(y0.data(), static_cast<Eigen::Index>(y0.size()));
             TipSimulation t;
             {
               py::gil_scoped_release release;
               t = a.simulate(mu, y, forced, o);
             }
             return to_dict(t, Context{&a});
           })
      .def("periodic_equilibrium",
           [](const Analysis& a, double mu, const py::dict& options, int samples) {
             const PeriodicEquilibriumOptions o = options_from<PeriodicEquilibriumOptions>(
                 options, "unknown option of the periodic equilibrium");
             if (samples < 2 || samples > 100000)
               throw InvalidInput("samples", std::to_string(samples), "must be 2..100000");
             PeriodicEquilibrium e;
             {
               py::gil_scoped_release release;
               e = a.periodic_equilibrium(mu, o);
             }
             return to_dict(e, Context{&a, samples});
           });
}

// Trim and thrust at one mu.
void bind_trim(py::class_<Analysis>& analysis) {
  analysis
      .def("trim",
           [](const Analysis& a, double mu, const py::dict& options) {
             const TrimOptions o = trim_options(options);
             TrimResult t;
             {
               py::gil_scoped_release release;
               t = trim(a.parameters(), mu, o, nullptr, a.condition().linearization);
             }
             return to_dict(t);
           })
      // inflow: "momentum" (eq 2.25 solved with the thrust), "paper" (eq 2.24) or "given"
      // (lambda = value).
      .def("thrust", [](const Analysis& a, double mu, const std::string& inflow, double value,
                        double shaft_angle) {
        if (!std::isfinite(shaft_angle))
          throw InvalidInput("shaft_angle", round_trip_text(shaft_angle), "must be finite");
        if (inflow != "momentum" && inflow != "paper" && !std::isfinite(value))
          throw InvalidInput("inflow", round_trip_text(value), "must be finite");
        // A given inflow ratio is bounded as the advance ratio is: beyond it the periodic
        // system overflows and the library could only name a coefficient the user never saw.
        if (inflow == "given" && !(std::abs(value) <= kMaxAdvanceRatio))
          throw InvalidInput("inflow", round_trip_text(value),
                             "must be in [-" + round_trip_text(kMaxAdvanceRatio) + ", " +
                                 round_trip_text(kMaxAdvanceRatio) +
                                 "] (an inflow ratio, bounded as mu is)");
        ThrustResult t;
        const Linearization about = a.condition().linearization;
        {
          py::gil_scoped_release release;
          if (inflow == "momentum")
            t = rotor_thrust_momentum(a.parameters(), mu, shaft_angle, {}, about);
          else if (inflow == "paper")
            t = rotor_thrust(a.parameters(), mu, std::numeric_limits<double>::quiet_NaN(), {},
                             about);
          else
            t = rotor_thrust(a.parameters(), mu, value, {}, about);
        }
        return to_dict(t);
      });
}

// The analysis of the same rotor at another operating condition: trimmed at every mu evaluated
// (OperatingCondition::Trimmed; its results carry the trims they rest on), or at fixed controls
// with another inflow model.  Their point, sweep, track and critical are the methods above.
void bind_conditions(py::class_<Analysis>& analysis) {
  analysis
      // The analysis of a's rotor at fixed controls with the inflow model {key: value} of
      // InflowModel's table (kind, thrust_coefficient, shaft_angle; a's options as resolved).
      .def("at_inflow",
           [](const Analysis& a, const py::dict& model) {
             OperatingCondition c = OperatingCondition{}.About(a.condition().linearization);
             c.inflow = options_from<InflowModel>(model, "unknown inflow option");
             return Analysis(a.parameters(), a.options(), c);
           })
      // The analysis of a's rotor trimmed with kind 'thrust' or 'moment' to C_T at the shaft
      // angle alpha_R (the iteration's options at their defaults, as --trim).
      .def("trimmed", [](const Analysis& a, const std::string& kind, double thrust_coefficient,
                         double shaft_angle) {
        const TrimOptions o = trim_options(kind, thrust_coefficient, shaft_angle);
        py::gil_scoped_release release;
        return trimmed(a, o);
      });
}

// flaplag._flaplag.Analysis: one rotor's parameters and transition options, and every computation
// on them.
void bind_analysis(py::module_& m) {
  py::class_<Analysis> analysis(m, "Analysis");
  bind_construction(analysis);
  bind_stability(analysis);
  bind_modes(analysis);
  bind_time_domain(analysis);
  bind_trim(analysis);
  bind_conditions(analysis);
}

// Studies and maps over parameters, and the memory limit they run under.
void bind_studies(py::module_& m) {
  m.def("study", &study);
  m.def("map", &stability_map);
  m.attr("default_memory_limit") = kDefaultMemoryLimit;
  // memory_limit= as given: a number of bytes or a size text ("8G"); the bytes.
  m.def("memory_limit", [](const py::object& v) -> std::uint64_t {
    if (py::isinstance<py::str>(v)) return parse_memory_size("memory_limit", v.cast<std::string>());
    if (py::isinstance<py::bool_>(v) ||
        !(py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v)))
      throw InvalidInput("memory_limit", shown(v),
                         "must be a number of bytes or a size such as '8G' or '512M'");
    return checked_memory_size("memory_limit", v.cast<double>());
  });
}

// The checks of Analysis, study() and map() without the work (for work sent to other
// processes).
void bind_checks(py::module_& m) {
  m.def("check",
        [](const py::dict& params, const py::dict& transition, int flap_modes, int lag_modes) {
          base_parameters(params, flap_modes, lag_modes);
          transition_options(transition);
        });
  m.def("check_study",
        [](const py::dict& params, const py::dict& transition, int flap_modes, int lag_modes,
           const std::string& parameter, const py::handle& values, const py::dict& critical,
           int threads, const py::object& trim, std::uint64_t memory_limit) {
          const RotorParameters base = base_parameters(params, flap_modes, lag_modes);
          transition_options(transition);
          check_study_memory(base, study_options(parameter, values, critical, threads, trim),
                             memory_limit);
        });
  m.def("check_map",
        [](const py::dict& params, const py::dict& transition, int flap_modes, int lag_modes,
           const std::string& x, const py::handle& x_values, const std::string& y,
           const py::handle& y_values, double mu, double scan_step, int threads,
           const py::object& trim, std::uint64_t memory_limit) {
          base_parameters(params, flap_modes, lag_modes);
          transition_options(transition);
          check_map_memory(map_options(x, x_values, y, y_values, mu, scan_step, threads, trim),
                           memory_limit);
        });
}

}  // namespace

void bind_documents(py::module_& m);  // documents.cc
}  // namespace flaplag::python

PYBIND11_MODULE(_flaplag, m) {
  using namespace flaplag::python;
  m.doc() = "flaplag's C++ library (NASA CR-132431 flap-lag stability); use the package flaplag.";

  register_invalid_input(m);
  bind_tables(m);
  bind_analysis(m);
  bind_studies(m);
  bind_checks(m);
  bind_documents(m);
}
