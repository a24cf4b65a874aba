// flaplag — the number formats of messages and outputs (one place for each).
#pragma once

#include <string>

namespace flaplag {

// Shortest decimal text that reads back as exactly v ("0.1", "1.28303"); "nan", "inf", "-inf"
// for non-finite values, so that text does not depend on the C library.  Used wherever a value
// is reported back to the user (error messages, JSON, CSV, tables).
std::string round_trip_text(double v);

// About six significant digits ("%.6g"), for values quoted inside human-readable messages.
std::string short_text(double v);

}  // namespace flaplag
