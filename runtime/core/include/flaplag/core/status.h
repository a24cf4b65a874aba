// flaplag — outcome vocabulary shared by the numerics and the rotor analysis.
//
// Numerical outcomes are never exceptions: results carry an Outcome (core/outcome.h) with a
// Status and a message (the model is Ceres' Solver::Summary).
#pragma once

namespace flaplag {

enum class Status { Ok, Warning, Failed };
const char* status_name(Status s);  // "ok", "warning", "failed"

// Flutter: a complex multiplier pair leaves the unit circle (omega continuous).  Periodic: a
// real multiplier does (omega locked to an integer or half-integer per rev; the instability is
// due to the periodic coefficients).
enum class InstabilityKind { Flutter, Periodic };
const char* kind_name(InstabilityKind k);  // "flutter", "periodic"

}  // namespace flaplag
