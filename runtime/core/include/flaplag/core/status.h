// flaplag — outcome vocabulary shared by the numerics and the rotor analysis.
//
// Numerical outcomes are never exceptions: results carry an Outcome (core/outcome.h) with a
// Status and a message (the model is Ceres' Solver::Summary).
#pragma once

#include <array>

#include "flaplag/core/fields.h"

namespace flaplag {

enum class Status { Ok, Warning, Failed };
const char* status_name(Status s);  // "ok", "warning", "failed"
constexpr auto describe(Tag<Status>) {
  return std::array<EnumName<Status>, 3>{
      {{Status::Ok, "ok"}, {Status::Warning, "warning"}, {Status::Failed, "failed"}}};
}

// Flutter: a complex multiplier pair leaves the unit circle (omega continuous).  Periodic: a
// real multiplier does (omega locked to an integer or half-integer per rev; the instability is
// due to the periodic coefficients).
enum class InstabilityKind { Flutter, Periodic };
const char* kind_name(InstabilityKind k);  // "flutter", "periodic"
constexpr auto describe(Tag<InstabilityKind>) {
  return std::array<EnumName<InstabilityKind>, 2>{
      {{InstabilityKind::Flutter, "flutter"}, {InstabilityKind::Periodic, "periodic"}}};
}

}  // namespace flaplag
