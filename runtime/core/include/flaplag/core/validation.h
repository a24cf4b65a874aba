// flaplag — the one validation mechanism of options structs.
//
// Every options struct O defines one check,
//   std::optional<InvalidInput> Validate() const;  // its first invalid field; nullopt if none
// which never throws, and the two forms callers use, both made from it (the structs stay
// aggregates):
//   bool IsValid(std::string* error) const { return IsValidReport(Validate(), error); }
//   void Check() const { ThrowIfInvalid(Validate()); }
// IsValid is Ceres' form: false and "<field> = <value>: <reason>" in *error.  Check throws that
// InvalidInput.  Admissible values are data (Range: an interval and its words), public in each
// struct, so that a front end can show them in its help; Requirements turns them into the first
// InvalidInput.  An options struct described by a table of Option rows (core/fields.h) checks
// every row that has a Range with one call, InRanges(*this), in the order of the table, and
// states its cross-field requirements by hand.
#pragma once

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

#include "flaplag/core/errors.h"
#include "flaplag/core/fields.h"

namespace flaplag {

// Admissible values of a number: finite and between lo and hi (a bound may be infinite).
struct Interval {
  double lo;
  double hi;
  bool lo_open;  // true: value > lo; false: value >= lo
  bool hi_open;  // true: value < hi; false: value <= hi
  bool Contains(double v) const {
    return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
};

// An interval with the words that state it ("in (0, 1e-2]", "1..1000", "> 0"): the reason of a
// value outside it is "must be <words>".
struct Range {
  Interval interval;
  const char* words;
};

// The bound of a half-line, and the range used most: a positive number.
inline constexpr double kUnbounded = std::numeric_limits<double>::infinity();
inline constexpr Range kPositive{{0.0, kUnbounded, true, false}, "> 0"};

// The first unmet requirement of a Validate(); later requirements are not looked at.
class Requirements {
 public:
  // Reals are quoted in round-trip text, integers in decimal.
  Requirements& InRange(const char* field, double value, const Range& range);
  Requirements& InRange(const char* field, int value, const Range& range);
  // InRange for every Option row of T's table with a Range (a number: int or double, or an
  // optional one, checked when set), in order.
  template <class T>
  Requirements& InRanges(const T& object) {
    for_each_field(object, [&](const auto& row, const auto& value) { InRangeRow(row, value); });
    return *this;
  }
  // The same for the row called `name` only: a Validate() whose cross-field checks come between
  // its rows checks each row where it did before it had a table, so that of several bad fields
  // the same one is named first.
  template <class T>
  Requirements& InRanges(const T& object, std::string_view name) {
    for_each_field(object, [&](const auto& row, const auto& value) {
      if (name == row.name) InRangeRow(row, value);
    });
    return *this;
  }
  // A requirement in words: `problem` () -> InvalidInput is called only when ok is false.
  template <typename Problem>
  Requirements& Require(bool ok, const Problem& problem) {
    if (!first_ && !ok) first_.emplace(problem());
    return *this;
  }
  // The first problem of a nested options struct (its Validate()).
  Requirements& Include(const std::optional<InvalidInput>& nested) {
    if (!first_ && nested) first_.emplace(*nested);
    return *this;
  }
  std::optional<InvalidInput> Result() const { return first_; }

 private:
  template <class Row, class V>
  void InRangeRow(const Row& row, const V& value) {
    if constexpr (std::is_same_v<V, double> || std::is_same_v<V, int>) {
      if (const Range* range = row_range(row)) InRange(row.name, value, *range);
    } else if constexpr (std::is_same_v<V, std::optional<double>>) {
      if (const Range* range = row_range(row); range != nullptr && value)
        InRange(row.name, *value, *range);
    }
  }

  std::optional<InvalidInput> first_;
};

// The two forms of every options struct (above).
inline bool IsValidReport(const std::optional<InvalidInput>& problem, std::string* error) {
  if (problem && error != nullptr) *error = problem->what();
  return !problem;
}
inline void ThrowIfInvalid(const std::optional<InvalidInput>& problem) {
  if (problem) throw *problem;
}

}  // namespace flaplag
