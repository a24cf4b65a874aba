// flaplag — what a described field's member type is, for the front ends' generic writers
// (documents/json_fields.h, the Python module): an optional, a vector, or a value.
#pragma once

#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace flaplag {

template <class T>
struct is_optional_field : std::false_type {};
template <class T>
struct is_optional_field<std::optional<T>> : std::true_type {};
template <class T>
struct is_vector_field : std::false_type {};
template <class T>
struct is_vector_field<std::vector<T>> : std::true_type {};
// Numbers by name, in order (a JSON object, a Python dict): test before is_vector_field.
template <class T>
struct is_named_values_field : std::false_type {};
template <>
struct is_named_values_field<std::vector<std::pair<std::string, double>>> : std::true_type {};

}  // namespace flaplag
