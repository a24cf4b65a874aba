// flaplag documents — a described struct (core/fields.h) as a JSON object: one writer for every
// result.
//
// Each row becomes the key of its name, in table order, its value written by type: numbers by
// jnum (a non-finite number is null), except a row that allows -inf (zeta_json: "-inf");
// optionals null when empty; complex numbers {"re", "im"}; numbers by name an object, a matrix
// an array of its rows; described enums by name; described
// structs as objects and vectors as arrays of these; message text (kFieldMessage) in the
// command line's vocabulary.  A kFieldOmitWhenEmpty list or optional is left out when empty,
// unless the document asks for it (`present`: the keys a command's options call for, written
// as null or [] when empty).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <complex>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "flaplag/core/field_traits.h"
#include "flaplag/core/fields.h"
#include "flaplag/documents/numbers.h"

namespace flaplag::documents {

// How text with field names in backticks is shown: in the vocabulary of the front end (the
// command line shows `steps` as --steps).
using MessageText = std::function<std::string(const std::string&)>;

template <class T>
Json to_json(const T& object, const MessageText& message,
             const std::vector<std::string>& present = {});

namespace json_detail {

template <class T>
using is_optional = is_optional_field<T>;
template <class T>
using is_vector = is_vector_field<T>;

template <class V>
Json value(const V& v, unsigned flags, const MessageText& message) {
  if constexpr (std::is_same_v<V, double>) {
    return (flags & kFieldNegativeInfinity) ? zeta_json(v) : jnum(v);
  } else if constexpr (std::is_same_v<V, bool> || std::is_same_v<V, int>) {
    return Json(v);
  } else if constexpr (std::is_same_v<V, std::string>) {
    return (flags & kFieldMessage) ? Json(message(v)) : Json(v);
  } else if constexpr (std::is_same_v<V, std::complex<double>>) {
    return complex_json(v);
  } else if constexpr (is_described_enum_v<V>) {
    return Json(enum_name(v));
  } else if constexpr (is_named_values_field<V>::value) {
    Json o = Json::object();
    for (const auto& [name, x] : v) o[name] = jnum(x);
    return o;
  } else if constexpr (std::is_same_v<V, Eigen::MatrixXd>) {
    Json rows = Json::array();
    for (Eigen::Index i = 0; i < v.rows(); ++i) {
      Json row = Json::array();
      for (Eigen::Index k = 0; k < v.cols(); ++k) row.push_back(jnum(v(i, k)));
      rows.push_back(row);
    }
    return rows;
  } else if constexpr (std::is_same_v<V, Eigen::VectorXd>) {
    Json a = Json::array();
    for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(jnum(v[i]));
    return a;
  } else if constexpr (is_optional<V>::value) {
    return v ? value(*v, flags, message) : Json(nullptr);
  } else if constexpr (is_vector<V>::value) {
    Json a = Json::array();
    for (const auto& x : v) a.push_back(value(x, flags, message));
    return a;
  } else {
    static_assert(is_described_struct_v<V>, "a field of a type JSON cannot write");
    return to_json(v, message);
  }
}

}  // namespace json_detail

template <class T>
Json to_json(const T& object, const MessageText& message, const std::vector<std::string>& present) {
  Json j = Json::object();
  for_each_field(object, [&](const auto& row, const auto& v) {
    using V = std::decay_t<decltype(v)>;
    const bool omit = (row.flags & kFieldOmitWhenEmpty) &&
                      std::find(present.begin(), present.end(), row.name) == present.end();
    if constexpr (json_detail::is_vector<V>::value) {
      if (omit && v.empty()) return;
    } else if constexpr (json_detail::is_optional<V>::value) {
      if (omit && !v) return;
    }
    j[row.name] = json_detail::value(v, row.flags, message);
  });
  return j;
}

// The rows `keys` of object's table, in that order (a key the table lacks is a bug of the
// caller: std::logic_error).
template <class T>
Json rows_json(const T& object, const std::vector<const char*>& keys, const MessageText& message) {
  const Json all = to_json(object, message);
  Json j = Json::object();
  for (const char* key : keys) {
    if (!all.contains(key)) throw std::logic_error(std::string("no row `") + key + "`");
    j[key] = all[key];
  }
  return j;
}

}  // namespace flaplag::documents
