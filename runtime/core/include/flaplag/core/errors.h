// flaplag — invalid input is an exception carrying the offending name, value and reason.
// Numerical outcomes (instability, unconverged search, defective multipliers) are never
// exceptions: they come back in result structs with an Outcome (core/outcome.h).
#pragma once

#include <stdexcept>
#include <string>

namespace flaplag {

// what() is "<name> = <value>: <reason>"; a front end that names the input in its own
// vocabulary takes the three parts from name(), value() and reason() (never from what()).
class InvalidInput : public std::invalid_argument {
 public:
  InvalidInput(std::string what_name, std::string value, std::string reason)
      : std::invalid_argument(what_name + " = " + value + ": " + reason),
        name_(std::move(what_name)),
        value_(std::move(value)),
        reason_(std::move(reason)) {}
  const std::string& name() const { return name_; }
  const std::string& value() const { return value_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string name_;
  std::string value_;
  std::string reason_;
};

}  // namespace flaplag
