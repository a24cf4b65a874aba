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
// An options struct is described the same way with Option rows: a data member with its units,
// doc and the admissible Range (core/validation.h) when it has one.  The struct's Validate()
// checks every row's range (Requirements::InRanges), front ends show the range words in their
// help, set the member by its row and take defaults from a default-constructed struct.
//
// An enum E is described by `constexpr auto describe(Tag<E>)` returning a std::array of
// EnumName<E> (value, name), every value once; enum_name(v) is its name.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
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

struct Range;  // core/validation.h

// A row of an options struct: a data member a front end sets, with the Range that admits its
// values (nullptr: any value of its type, or a check by hand in Validate()).
template <class Owner, class Value>
struct Option {
  using owner_type = Owner;
  using value_type = Value;
  constexpr Option(const char* n, Value Owner::*m, const char* u, const char* d,
                   const Range* r = nullptr)
      : name(n), member(m), units(u), doc(d), range(r) {}
  const Value& get(const Owner& o) const { return o.*member; }
  Value& get(Owner& o) const { return o.*member; }

  const char* name;
  Value Owner::*member;
  const char* units;
  const char* doc;
  const Range* range;
  unsigned flags = kFieldPlain;
};

// The range of a row: an Option's, nullptr for every other row.
template <class Owner, class Value>
constexpr const Range* row_range(const Option<Owner, Value>& row) {
  return row.range;
}
template <class Row>
constexpr const Range* row_range(const Row&) {
  return nullptr;
}

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

// The row of T's table called `name`: visit(row) is called for it; false when T has none.
template <class T, class Visitor>
bool visit_row(std::string_view name, Visitor&& visit) {
  bool found = false;
  for_each_row<T>([&](const auto& row) {
    if (!found && std::string_view(row.name) == name) {
      found = true;
      visit(row);
    }
  });
  return found;
}

// The name of a described enum value; "" when the table lacks it.
template <class E, std::enable_if_t<is_described_enum_v<E>, int> = 0>
const char* enum_name(E value) {
  for (const EnumName<E>& e : describe(Tag<E>{})) {
    if (e.value == value) return e.name;
  }
  return "";
}

// The value of a described enum called `name` into *value; false when the table has none.
template <class E, std::enable_if_t<is_described_enum_v<E>, int> = 0>
bool enum_from_name(std::string_view name, E* value) {
  for (const EnumName<E>& e : describe(Tag<E>{})) {
    if (std::string_view(e.name) == name) {
      *value = e.value;
      return true;
    }
  }
  return false;
}

// The names of a described enum joined by `sep`, in table order ("rk4, hsu" or "rk4|hsu").
template <class E, std::enable_if_t<is_described_enum_v<E>, int> = 0>
std::string enum_names(const char* sep = ", ") {
  std::string names;
  for (const EnumName<E>& e : describe(Tag<E>{})) {
    if (!names.empty()) names += sep;
    names += e.name;
  }
  return names;
}

}  // namespace flaplag
