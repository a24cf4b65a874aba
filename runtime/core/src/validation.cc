// flaplag — requirements of options structs.
#include "flaplag/core/validation.h"

#include "flaplag/core/format.h"

namespace flaplag {

Requirements& Requirements::InRange(const char* field, double value, const Range& range) {
  if (!first_ && !range.interval.Contains(value))
    first_.emplace(field, round_trip_text(value), std::string("must be ") + range.words);
  return *this;
}

Requirements& Requirements::InRange(const char* field, int value, const Range& range) {
  if (!first_ && !range.interval.Contains(value))
    first_.emplace(field, std::to_string(value), std::string("must be ") + range.words);
  return *this;
}

}  // namespace flaplag
