// flaplag — a build without GiNaC: run-time specs are not available (runtime_spec.h).
#include "flaplag/core/errors.h"
#include "flaplag_spec/runtime_spec.h"

namespace flaplag::spec {

namespace {
const char kWhy[] =
    "this flaplag was built without GiNaC (the generator), which a spec at run time needs; "
    "rebuild with GiNaC (libginac-dev) or add the spec to generator/orderings/";
}

bool available() { return false; }

const model::ModelFamily& load_spec(const std::string& path) {
  throw InvalidInput("spec", path, kWhy);
}

double derivation_seconds(const model::ModelFamily&) { return 0.0; }

std::string audit_report(const std::string& name) { throw InvalidInput("spec", name, kWhy); }

}  // namespace flaplag::spec
