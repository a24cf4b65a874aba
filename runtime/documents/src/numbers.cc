// flaplag documents — the printers of numbers that may not be finite.
#include "flaplag/documents/numbers.h"

#include <cmath>
#include <limits>

#include "flaplag/core/status.h"
#include "flaplag/documents/output.h"
#include "flaplag/numerics/continuation.h"

namespace flaplag::documents {
//
// The library promises finite results, with two documented exceptions: the zeta of a zero
// multiplier is -inf, and optional diagnostics are absent rather than NaN; a result that breaks
// the promise has a non-ok status from the library itself (check_finite).  The printers show
// such values as "-" (text), an empty field (CSV) or null (JSON).  num() itself refuses
// non-finite values, so a value no check covered ends the run as an internal error instead of
// printing "nan".

bool finite(double v) { return std::isfinite(v); }
bool finite(std::complex<double> z) { return finite(z.real()) && finite(z.imag()); }
bool zeta_ok(double zeta) {
  return finite(zeta) || zeta == -std::numeric_limits<double>::infinity();
}

std::string cell(double v) { return finite(v) ? num(v) : "-"; }
std::string zeta_cell(double zeta) { return zeta_ok(zeta) ? zeta_text(zeta) : "-"; }
Json jnum(double v) { return finite(v) ? Json(v) : Json(nullptr); }
// zeta of a zero multiplier is -inf, which JSON cannot hold: it is written as the string "-inf".
Json zeta_json(double zeta) {
  if (finite(zeta)) return Json(zeta);
  return zeta_ok(zeta) ? Json("-inf") : Json(nullptr);
}
Json complex_json(std::complex<double> z) {
  return Json{{"re", jnum(z.real())}, {"im", jnum(z.imag())}};
}

std::string complex_text(std::complex<double> z) {
  if (!finite(z)) return "-";
  return num(z.real()) + (std::signbit(z.imag()) ? " - " : " + ") + num(std::abs(z.imag())) + "i";
}

Json optional_json(const std::optional<double>& v) { return v ? jnum(*v) : Json(nullptr); }
std::string optional_text(const std::optional<double>& v) { return v ? cell(*v) : "-"; }

// The locked frequency of a periodic-kind exponent (classify_crossing: omega within 1e-3 of a
// multiple of 1/2) as "0", "1/2", "1", "3/2", ...; "" when omega is not locked.
std::string locked_text(double omega) {
  if (!finite(omega) || classify_crossing(omega) != InstabilityKind::Periodic) return "";
  const long k = std::lround(2.0 * omega);
  if (k % 2 == 0) return std::to_string(k / 2);
  return std::to_string(k) + "/2";
}

std::string ratio_cell(double zeta, double omega) {
  const std::optional<double> r = damping_ratio(zeta, omega);
  return r ? num(100.0 * *r) : "-";
}
Json ratio_json(double zeta, double omega) { return optional_json(damping_ratio(zeta, omega)); }

Json stable_json(const std::optional<bool>& v) { return v ? Json(*v) : Json(nullptr); }
std::string stable_text(const std::optional<bool>& v) { return !v ? "unknown" : *v ? "yes" : "NO"; }

}  // namespace flaplag::documents
