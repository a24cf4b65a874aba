// flaplag — what a described field's member type is, for the front ends' generic writers
// (cli/json_fields.h, the Python module): an optional, a vector, or a value.
#pragma once

#include <optional>
#include <type_traits>
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

}  // namespace flaplag
