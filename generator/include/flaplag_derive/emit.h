// flaplag-derive — deterministic emission of the derived model: C++ source and audit report.
#pragma once

#include <string>
#include <vector>

#include "flaplag_derive/derive.h"

namespace flaplag::derive {

// C identifier for a model name ("lag-order-2" -> "lag_order_2").
std::string model_ident(const std::string& name);

// The generated translation unit: integral tables, coefficient and equilibrium functions and
// the descriptor accessor `const flaplag::model::ModelDescriptor& flaplag_model_<ident>()`.
std::string emit_cpp(const DerivedModel& m);

struct GenericModel;
// The generated translation unit of a model family (generic.h): integral templates, functions
// with loops over the mode indices and the accessor
// `const flaplag::model::ModelFamily& flaplag_family_<ident>()`.
std::string emit_family_cpp(const GenericModel& g);
// The audit report's section on a family: every term with its mode indices.
std::string emit_family_report(const GenericModel& g);

// The audit report (Markdown, src/report.cc), laid out like Appendix C: one block per entry
// A_ij and f_i with every retained term (factor, eps order, origin, radial-flow flag, spanwise
// integral, paper name, value at the typical case); the generalized mass, the absorbed terms,
// the hover equilibrium and the differences from the printed paper.
std::string emit_report(const DerivedModel& m);

// Text of a term's factor, e.g. "-1/2 mu^2 theta" (aero terms with (gamma/2)(l/R)^2 removed
// when strip_aero_scale is set).  beta_power > 0: the term's precone and droop powers are
// replaced by (precone + droop)^beta_power (the paper's (beta_P + beta_D)).
std::string factor_text(const DerivedModel& m, const Term& t, bool strip_aero_scale,
                        int beta_power = 0);

// A monomial of the full state of the nonlinear loads, e.g. "g1 h1'" or "g1^2" ("1": degree 0).
std::string monomial_text(const DerivedModel& m, const std::vector<int>& powers);

// The audit report's section on the nonlinear generalized loads (src/nonlinear_report.cc);
// "" for models without them.
std::string nonlinear_report_section(const DerivedModel& m);

// The "generated -- do not edit" header of both outputs, each line starting with `comment`.
std::string generated_header(const DerivedModel& m, const std::string& comment);

}  // namespace flaplag::derive
