#include "stillslam/io/timestamp_check.h"

#include <cmath>

#include "stillslam/core/error.h"

namespace stillslam {

TimestampCheck::TimestampCheck(std::filesystem::path file, std::string column)
    : file_(std::move(file)), column_(std::move(column)) {}

void TimestampCheck::add(double value, const std::string& text, std::size_t line) {
  const std::string where = file_.string() + ":" + std::to_string(line) + ": " + column_ + " '" + text + "'";
  if (!std::isfinite(value)) {
    throw Error(where + " is not a finite number (correct the stamp or remove the line)");
  }
  if (value < 0) {
    throw Error(where + " is negative (stamps are times since an epoch: correct the stamp or remove the line)");
  }
  if (has_previous_ && !(value > previous_)) {
    throw Error(where + (value == previous_ ? " repeats" : " is earlier than") + " the stamp '" + previous_text_ +
                "' on line " + std::to_string(previous_line_) +
                " (the list must be sorted by time with one line per stamp: sort it, e.g. `sort -n`, and remove "
                "repeated lines)");
  }
  has_previous_ = true;
  previous_ = value;
  previous_text_ = text;
  previous_line_ = line;
}

}  // namespace stillslam
