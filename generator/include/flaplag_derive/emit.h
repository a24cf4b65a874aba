// flaplag-derive — deterministic emission of the derived model: C++ source and audit report.
#pragma once

#include <string>

#include "flaplag_derive/derive.h"

namespace flaplag::derive {

// C identifier for a model name ("lag-order-2" -> "lag_order_2").
std::string model_ident(const std::string& name);

// The generated translation unit: integral tables, coefficient and equilibrium functions and
// the descriptor accessor `const flaplag::model::ModelDescriptor& flaplag_model_<ident>()`.
std::string emit_cpp(const DerivedModel& m);

// The audit report (Markdown): every retained term with factor, eps order, origin, radial-flow
// flag, spanwise integral and paper name; absorbed terms; equilibrium; differences from print.
std::string emit_report(const DerivedModel& m);

// Text of a term's factor, e.g. "-1/2 mu^2 theta" (aero terms with (gamma/2)(l/R)^2 removed
// when strip_aero_scale is set).
std::string factor_text(const DerivedModel& m, const Term& t, bool strip_aero_scale);

}  // namespace flaplag::derive
