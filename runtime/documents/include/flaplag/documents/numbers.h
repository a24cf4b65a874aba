// flaplag documents — numbers that may not be finite, as text, CSV cells and JSON values.
//
// The library promises finite results, with two documented exceptions: the zeta of a zero
// multiplier is -inf, and optional diagnostics are absent rather than NaN; it checks the promise
// itself and gives a result that breaks it a non-ok status (numerics/continuation.h
// check_finite).  The printers show such values as "-" (text), an empty field (CSV) or null
// (JSON).
#pragma once

#include <complex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace flaplag::documents {

// Every document is written in the order its keys are set.
using Json = nlohmann::ordered_json;

bool finite(double v);
bool finite(std::complex<double> z);
bool zeta_ok(double zeta);  // finite, or the -inf of a zero multiplier
std::string cell(double v);
std::string zeta_cell(double zeta);
Json jnum(double v);
Json zeta_json(double zeta);  // -inf as the string "-inf"
Json complex_json(std::complex<double> z);
std::string complex_text(std::complex<double> z);
Json optional_json(const std::optional<double>& v);
std::string optional_text(const std::optional<double>& v);
std::string locked_text(double omega);  // "0", "1/2", "1", ... or "" when not locked
// The damping ratio -zeta/|lambda| as text: in percent of critical (JSON and CSV: a fraction).
std::string ratio_cell(double zeta, double omega);
Json ratio_json(double zeta, double omega);
Json stable_json(const std::optional<bool>& v);
std::string stable_text(const std::optional<bool>& v);

}  // namespace flaplag::documents
