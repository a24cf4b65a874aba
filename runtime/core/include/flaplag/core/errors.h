// flaplag — invalid input is an exception carrying the offending name and value.
// Numerical outcomes (instability, unconverged search, defective multipliers) are never
// exceptions: they come back in result structs with a Status and a message.
#pragma once

#include <stdexcept>
#include <string>

namespace flaplag {

class InvalidInput : public std::invalid_argument {
 public:
  InvalidInput(std::string what_name, std::string value, const std::string& reason)
      : std::invalid_argument(what_name + " = " + value + ": " + reason),
        name_(std::move(what_name)),
        value_(std::move(value)),
        reason_(reason) {}
  const std::string& name() const { return name_; }
  const std::string& value() const { return value_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string name_;
  std::string value_;
  std::string reason_;
};


}  // namespace flaplag
