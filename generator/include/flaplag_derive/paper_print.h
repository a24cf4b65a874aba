// flaplag-derive — the printed paper as data, for the "Differences from the printed paper"
// section of the audit report.
#pragma once

#include <string>

#include "flaplag_derive/derive.h"

namespace flaplag::derive {

std::string paper_differences_section(const DerivedModel& m);

}  // namespace flaplag::derive
