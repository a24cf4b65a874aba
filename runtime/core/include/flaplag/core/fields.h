// flaplag — each field of a struct described once (the pattern of Boost.Describe and SymForce).
//
// A struct T is described by a function found by argument-dependent lookup,
//   constexpr auto describe(Tag<T>) { return std::make_tuple(Field{...}, Computed{...}, ...); }
// written next to T, whose rows say, in the order every front end writes them: the key (one
// snake_case name for JSON, CSV, Python and docs/json.md), the value (a data member, or a
// function of the struct for a derived value), the units and a one-line doc.  A front end
// walks the table (for_each_field with an object, for_each_row without one) and writes each
// value by its C++ type; nothing here knows JSON or Python.  Adding a field to a result is one
// member and one row.
//
// Value types a front end must handle: double, int, bool, std::string, described enums (below),
// std::complex<double>, described structs, std::optional and std::vector of these.
// A row of a base's member (&Derived::status is a `Status Outcome::*`) reads the base, so a
// result's table includes the Outcome rows with std::tuple_cat(..., describe(Tag<Outcome>{})).
//
// An enum E is described by `constexpr auto describe(Tag<E>)` returning a std::array of
// EnumName<E> (value, name), every value once; enum_name(v) is its name.
#pragma once

#include <array>
#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>

namespace flaplag {

template <class T>
struct Tag {
  using type = T;
};

// What a front end must know about a value beyond its type.
enum FieldFlags : unsigned {
  kFieldPlain = 0,
  // -inf is a legitimate value (the zeta of a zero multiplier); other non-finite values are not.
  kFieldNegativeInfinity = 1u << 0,
  // Text with field names in backticks (core/outcome.h), shown in the front end's vocabulary.
  kFieldMessage = 1u << 1,
  // A list or optional that documents (JSON) hold only when it is not empty.
  kFieldOmitWhenEmpty = 1u << 2,
};

// A row whose value is a data member (possibly of a base of the described struct).
template <class Owner, class Value>
struct Field {
  using owner_type = Owner;
  using value_type = Value;
  constexpr Field(const char* n, Value Owner::*m, const char* u, const char* d,
                  unsigned f = kFieldPlain)
      : name(n), member(m), units(u), doc(d), flags(f) {}
  const Value& get(const Owner& o) const { return o.*member; }

  const char* name;
  Value Owner::*member;
  const char* units;  // "1/rev", "rad", "-" (dimensionless) or "" (not a quantity)
  const char* doc;
  unsigned flags;
};

// A row whose value is derived from the struct (a plain function: `+[](const T&) {...}`).
template <class Owner, class Value>
struct Computed {
  using owner_type = Owner;
  using value_type = Value;
  constexpr Computed(const char* n, Value (*c)(const Owner&), const char* u, const char* d,
                     unsigned f = kFieldPlain)
      : name(n), compute(c), units(u), doc(d), flags(f) {}
  Value get(const Owner& o) const { return compute(o); }

  const char* name;
  Value (*compute)(const Owner&);
  const char* units;
  const char* doc;
  unsigned flags;
};

template <class E>
struct EnumName {
  E value;
  const char* name;
};

// ---- what is described ------------------------------------------------------------------------

template <class T, class = void>
struct is_described : std::false_type {};
template <class T>
struct is_described<T, std::void_t<decltype(describe(Tag<T>{}))>> : std::true_type {};

template <class T>
inline constexpr bool is_described_struct_v = is_described<T>::value&& std::is_class_v<T>;
template <class T>
inline constexpr bool is_described_enum_v = std::is_enum_v<T>&& is_described<T>::value;

// ---- walking a table --------------------------------------------------------------------------

// visit(row, value) for each row of T's table, in order.
template <class T, class Visitor>
void for_each_field(const T& object, Visitor&& visit) {
  std::apply([&](const auto&... row) { (visit(row, row.get(object)), ...); }, describe(Tag<T>{}));
}

// visit(row) for each row of T's table, in order, without an object (documentation); the value's
// type is typename std::decay_t<decltype(row)>::value_type.
template <class T, class Visitor>
void for_each_row(Visitor&& visit) {
  std::apply([&](const auto&... row) { (visit(row), ...); }, describe(Tag<T>{}));
}

// Number of rows of T's table.
template <class T>
constexpr std::size_t field_count() {
  return std::tuple_size_v<decltype(describe(Tag<T>{}))>;
}

// The name of a described enum value; "" when the table lacks it.
template <class E, std::enable_if_t<is_described_enum_v<E>, int> = 0>
const char* enum_name(E value) {
  for (const EnumName<E>& e : describe(Tag<E>{})) {
    if (e.value == value) return e.name;
  }
  return "";
}

}  // namespace flaplag
