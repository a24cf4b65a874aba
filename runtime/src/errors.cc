// flaplag — formatting of offending values for InvalidInput messages.
#include "flaplag/errors.h"

#include <cmath>
#include <cstdio>

namespace flaplag {

std::string format_value(double v) {
  // %.17g round-trips every double, so a message reproduces the exact input; non-finite values
  // get fixed spellings so messages do not depend on the C library.
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace flaplag
