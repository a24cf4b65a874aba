// flaplag CLI — the reference of the JSON documents (docs/json.md), generated from the field
// tables; `refresh-docs` writes it into the source tree and tests/json_docs_test.cpp fails when
// the checked-in file differs.
#pragma once

#include <string>

namespace flaplag::cli {

// The whole of docs/json.md (markdown).
std::string json_reference();

}  // namespace flaplag::cli
