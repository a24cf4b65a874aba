// flaplag — the floor of the damping exponent (internal to the numerics).
#pragma once

#include <cmath>
#include <limits>

#include "flaplag/core/constants.h"

namespace flaplag::detail {

// ln of the smallest normal double over 2 pi: the zeta of a multiplier that underflowed; below it
// a multiplier is indistinguishable from 0 (whose zeta is -inf).
inline const double kZetaFloor = std::log(std::numeric_limits<double>::min()) / kTwoPi;

}  // namespace flaplag::detail
