// flaplag — names of the outcome vocabulary.
#include "flaplag/core/status.h"

namespace flaplag {

const char* status_name(Status s) {
  switch (s) {
    case Status::Ok:
      return "ok";
    case Status::Warning:
      return "warning";
    case Status::Failed:
      return "failed";
  }
  return "unknown";
}

const char* kind_name(InstabilityKind k) {
  return k == InstabilityKind::Periodic ? "periodic" : "flutter";
}

}  // namespace flaplag
