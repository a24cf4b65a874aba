// flaplag-derive — the printed paper as data, for the "Differences from the printed paper"
// section of the audit report.  Each entry records where the derivation and the printed paper
// (NASA CR-132431, OCR text) disagree and carries a check that inspects the derived model.
#pragma once

#include <string>
#include <vector>

#include "flaplag_derive/derive.h"

namespace flaplag::derive {

// Outcome of one check on one derived model:
//   Confirmed     the derived terms have the form stated under "derived";
//   Absent        the model does not contain the terms concerned (e.g. no radial flow);
//   Contradicted  the derived terms exist but do not have the stated form: the derivation or
//                 the entry is wrong and must be investigated (no shipped model may have one).
enum class PaperCheck { Confirmed, Absent, Contradicted };
const char* paper_check_name(PaperCheck c);  // "confirmed", "absent", "CONTRADICTED"

struct PaperDifference {
  std::string id;  // stable key, e.g. "P_ikm", "A31", "f3 L2 drag"
  std::string where, printed, derived, reason;
  PaperCheck status;
};

// Every entry, checked against m, in report order.
std::vector<PaperDifference> paper_differences(const DerivedModel& m);

std::string paper_differences_section(const DerivedModel& m);

}  // namespace flaplag::derive
