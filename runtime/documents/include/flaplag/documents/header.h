// flaplag documents — the header every analysis document starts with (what was computed, and
// how), its status, and the warnings about an analysis, as JSON and as text.
#pragma once

#include <optional>
#include <string>

#include "flaplag/analysis.h"
#include "flaplag/documents/numbers.h"

namespace flaplag::documents {

Json model_json(const model::ModelDescriptor& m);
// What a blade table gave (its stations and groups; a dimensional table's SI data), as the
// header's `blade_table` and as text.
Json blade_table_json(const BladeProperties& b);
std::string blade_table_text(const BladeProperties& b, const RotorParameters& p);
// The header's `inflow` (with the momentum inflow: kind, thrust_coefficient, shaft_angle), and
// lambda at mu with it; nullopt for the default eq 2.24 and a trim's given inflow.
std::optional<Json> inflow_json(const Analysis& an);
std::optional<double> inflow_at(const Analysis& an, double mu);
// The part every analysis output starts with: the command, the model, the mode shapes, the
// method (with_method), the parameters, the blade table, the inflow and the linearization.
Json header_json(const char* command, const Analysis& an, bool with_method = true);
std::string header_text(const Analysis& an, bool with_method = true);
Json status_json(Json j, Status status, const std::string& message);
std::string status_text(Status status, const std::string& message);
// "warning: ..." lines about the hover equilibrium and the validity of the analysis.
std::string warnings_text(const Analysis& an);

}  // namespace flaplag::documents
