// flaplag — the table (core/fields.h) of a compiled model's descriptor: what a result says about
// the model it was computed with (the command line's "model" object, Python's ModelInfo).  Here
// rather than next to ModelDescriptor because model_api.h, the contract of the generated code,
// depends on nothing.
#pragma once

#include <string>
#include <tuple>

#include "flaplag/core/fields.h"
#include "flaplag/model_api.h"

namespace flaplag::model {

constexpr auto describe(Tag<ModelDescriptor>) {
  return std::make_tuple(
      Computed{"name", +[](const ModelDescriptor& m) { return std::string(m.name); }, "",
               "the model, e.g. paper or paper-2x2"},
      Computed{"base", +[](const ModelDescriptor& m) { return std::string(m.base); }, "",
               "its family (one per ordering spec): models of one family differ only in their "
               "mode counts"},
      Computed{"spec_file", +[](const ModelDescriptor& m) { return std::string(m.spec_file); }, "",
               "the ordering spec it was derived from"},
      Computed{"summary", +[](const ModelDescriptor& m) { return std::string(m.summary); }, "",
               "one line: orders, term classes, modes"},
      Field{"flap_modes", &ModelDescriptor::flap_modes, "", "M, the flap modes"},
      Field{"lag_modes", &ModelDescriptor::lag_modes, "", "N, the lag modes"},
      Field{"harmonics", &ModelDescriptor::n_harmonics, "",
            "H, the harmonics of the coefficients of A(psi) and f(psi)"});
}

}  // namespace flaplag::model
