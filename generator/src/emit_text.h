// flaplag-derive (internal) — the pieces of C++ text both emitters write: factor enumerators,
// exact rationals as double expressions, string literals.
#pragma once

#include <ginac/ginac.h>

#include <sstream>
#include <string>

#include "flaplag_derive/derive.h"

namespace flaplag::derive::detail {

inline const char* factor_enum(FactorKind k) {
  switch (k) {
    case FactorKind::Eta:
      return "Factor::Eta";
    case FactorKind::EtaPrime:
      return "Factor::EtaPrime";
    case FactorKind::Gamma:
      return "Factor::Gamma";
    case FactorKind::GammaPrime:
      return "Factor::GammaPrime";
    case FactorKind::X0:
      return "Factor::X0";
    case FactorKind::Arm:
      return "Factor::Arm";
    case FactorKind::Twist:
      return "Factor::Twist";
  }
  return "";
}

// An exact rational as C++: "3.0 / 4.0" (the division is done in double, the same way by every
// emitter and by the run-time interpreter).
inline std::string rational_cpp(const GiNaC::numeric& q) {
  std::ostringstream os;
  const GiNaC::numeric num = q.numer(), den = q.denom();
  os << num << ".0";
  if (den != 1) os << " / " << den << ".0";
  return os.str();
}

inline std::string c_string(const std::string& s) {
  std::ostringstream os;
  os << '"';
  for (char ch : s) {
    if (ch == '"' || ch == '\\') os << '\\';
    if (ch == '\n') {
      os << "\\n";
      continue;
    }
    os << ch;
  }
  os << '"';
  return os.str();
}

}  // namespace flaplag::derive::detail
