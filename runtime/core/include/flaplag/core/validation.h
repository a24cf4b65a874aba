// flaplag — the one validation mechanism of options structs.
//
// An options struct O derives from Validated<O> and defines
//   std::optional<InvalidInput> Validate() const;  // its first invalid field; nullopt if none
// which never throws.  Validated<O> derives from it the two forms callers use:
//   bool IsValid(std::string* error) const;  // false and "<field> = <value>: <reason>" in *error
//   void Check() const;                      // throws the InvalidInput of Validate()
// Admissible values are data (Range: an interval and its words), public in each struct, so that a
// front end can show them in its help; Requirements turns them into the first InvalidInput.
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include "flaplag/core/errors.h"

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

// The first unmet requirement of a Validate(); later requirements are not looked at.
class Requirements {
 public:
  // Reals are quoted in round-trip text, integers in decimal.
  Requirements& InRange(const char* field, double value, const Range& range);
  Requirements& InRange(const char* field, int value, const Range& range);
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
  std::optional<InvalidInput> first_;
};

template <typename Options>
struct Validated {
  bool IsValid(std::string* error) const {
    const std::optional<InvalidInput> p = static_cast<const Options&>(*this).Validate();
    if (p && error != nullptr) *error = p->what();
    return !p;
  }
  void Check() const {
    if (std::optional<InvalidInput> p = static_cast<const Options&>(*this).Validate()) throw *p;
  }
};

}  // namespace flaplag
