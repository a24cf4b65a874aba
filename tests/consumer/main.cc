// A consumer of the installed flaplag library: the paper's typical case (Fig 3) must lose
// stability in lag flutter at mu_c = 0.754 (the paper; 0.7543 with the reference method).
#include <cmath>
#include <cstdio>
#include <cstring>

#include "flaplag/analysis.h"
#include "flaplag/version.h"

int main() {
  if (std::strcmp(flaplag::kVersion, EXPECTED_VERSION) != 0) {
    std::printf("FAIL: flaplag/version.h says %s, the package %s\n", flaplag::kVersion,
                EXPECTED_VERSION);
    return 1;
  }
  const flaplag::Analysis analysis(flaplag::RotorParameters{}, flaplag::TransitionOptions{});
  const flaplag::CriticalResult crit = analysis.critical(flaplag::CriticalOptions{});
  if (!crit.mu_c) {
    std::printf("FAIL: no mu_c (%s)\n", crit.message.c_str());
    return 1;
  }
  std::printf("flaplag %s (%s): mu_c = %.6f, mode %s\n", flaplag::kVersion, flaplag::kGitCommit,
              *crit.mu_c, crit.mode.c_str());
  if (std::fabs(*crit.mu_c - 0.7543) > 1e-3 || crit.mode != "lag") {
    std::printf("FAIL: expected mu_c within 1e-3 of 0.7543 (lag flutter)\n");
    return 1;
  }
  return 0;
}
