// flaplag — names of the outcome vocabulary.
#include "flaplag/core/status.h"

namespace flaplag {

const char* status_name(Status s) {
  const char* name = enum_name(s);
  return *name ? name : "unknown";
}

const char* kind_name(InstabilityKind k) { return enum_name(k); }

}  // namespace flaplag
