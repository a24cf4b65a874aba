// flaplag — an ordering spec used at run time: derived in-process (GiNaC, the generator's
// library) and evaluated without a build, with the same numbers as the compiled model of the
// same spec.  A component of the CLI and the Python module only: the installed C++ library
// (runtime/) never links GiNaC.
//
// The model of spec file "dir/my.toml" (spec name "my") is the family "spec:my", registered
// with model::register_family(): find_model("spec:my"), find_model("spec:my", M, N) and every
// analysis then use it for any M x N.  The prefix keeps a spec loaded at run time apart from
// the compiled model of the same name (`--spec generator/orderings/paper.toml` is "spec:paper",
// next to the compiled "paper").  A spec's `base` is looked up in the spec file's directory.
#pragma once

#include <string>

#include "flaplag/model_api.h"

namespace flaplag::spec {

// Whether this build can derive specs (false: built without GiNaC).
bool available();

// Reads, derives and registers the spec file `path`; loading the same resolved spec again (by
// any path) returns the family of the first load.  Throws InvalidInput("spec", path, reason)
// when the file cannot be read or is not a valid spec (reason: the spec's own one-line error,
// "my.toml: kept.flap = 0: ..."), when another spec of the same name but other content is
// loaded already, or when this build cannot derive specs.  Thread-safe.
const model::ModelFamily& load_spec(const std::string& path);

// Seconds the derivation of the family took (0 for a family not loaded by load_spec()).
double derivation_seconds(const model::ModelFamily& f);

// The audit report (Markdown) of the family `name` loaded by load_spec() ("spec:my"), as
// generated/<name>.md of a compiled one: every term of the spec's own mode counts in the layout
// of the paper's Appendix C, then every term with its mode indices.  Throws
// InvalidInput("spec", name, ...) for a family not loaded by load_spec().
std::string audit_report(const std::string& name);

}  // namespace flaplag::spec
