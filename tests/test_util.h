// Shared test helpers: relative-error checks that print expected and actual.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace flaplag::testing {

inline ::testing::AssertionResult RelClose(double expected, double actual, double rel_tol,
                                           double abs_floor = 0.0) {
  const double err = std::abs(actual - expected);
  const double scale = std::max(std::abs(expected), abs_floor);
  if (err <= rel_tol * scale || err <= abs_floor * rel_tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "expected " << expected << ", actual " << actual << ", relative error "
         << (scale > 0 ? err / scale : err) << " > " << rel_tol;
}

inline ::testing::AssertionResult AbsClose(double expected, double actual, double tol) {
  const double err = std::abs(actual - expected);
  if (err <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "expected " << expected << ", actual " << actual << ", |error| " << err << " > " << tol;
}

}  // namespace flaplag::testing
