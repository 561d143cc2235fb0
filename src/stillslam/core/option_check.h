#pragma once
// The checks every Options struct's check() is made of. A failed check throws
// an OptionError that names the field ("TrackerOptions.init_min_keypoints"),
// its value and the valid range, so a settings binder can report it under
// the YAML key bound to that field.
#include <cmath>
#include <sstream>
#include <string>

#include "stillslam/core/error.h"

namespace stillslam {

class OptionError : public Error {
 public:
  OptionError(std::string field, std::string value, std::string requirement)
      : Error(field + " is " + value + ": " + requirement),
        field_(std::move(field)),
        value_(std::move(value)),
        requirement_(std::move(requirement)) {}
  const std::string& field() const { return field_; }
  const std::string& value() const { return value_; }
  const std::string& requirement() const { return requirement_; }  // "must be ..."

 private:
  std::string field_, value_, requirement_;
};

namespace option_check {

// Shortest decimal text of a number (integers without a fraction).
inline std::string text(double value) {
  std::ostringstream out;
  out.precision(7);
  out << value;
  return out.str();
}

// value >= min
inline void at_least(const std::string& field, double value, double min) {
  if (!(value >= min)) throw OptionError(field, text(value), "must be >= " + text(min));
}

// value > min
inline void above(const std::string& field, double value, double min) {
  if (!(value > min)) throw OptionError(field, text(value), "must be > " + text(min));
}

// min <= value <= max
inline void in_range(const std::string& field, double value, double min, double max) {
  if (!(value >= min && value <= max)) {
    throw OptionError(field, text(value), "must be in [" + text(min) + ", " + text(max) + "]");
  }
}

// min < value <= max
inline void in_half_open(const std::string& field, double value, double min, double max) {
  if (!(value > min && value <= max)) {
    throw OptionError(field, text(value), "must be in (" + text(min) + ", " + text(max) + "]");
  }
}

// min < value < max
inline void in_open(const std::string& field, double value, double min, double max) {
  if (!(value > min && value < max)) {
    throw OptionError(field, text(value), "must be in (" + text(min) + ", " + text(max) + ")");
  }
}

}  // namespace option_check
}  // namespace stillslam
