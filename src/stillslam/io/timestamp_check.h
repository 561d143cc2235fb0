#pragma once
// Frame timestamps of a dataset list, checked as they are read: each must be
// finite, >= 0 and later than the one before, so the trajectory written from
// them is sorted and unique (what `eval` and the in-run ATE need).
#include <cstddef>
#include <filesystem>
#include <string>

namespace stillslam {

class TimestampCheck {
 public:
  // `column` names the stamps in messages ("timestamp", "rgb timestamp").
  explicit TimestampCheck(std::filesystem::path file, std::string column = "timestamp");
  // `value` is the parsed `text` of line `line`; throws Error
  // "<file>:<line>: ..." saying what is wrong and how to fix the list.
  void add(double value, const std::string& text, std::size_t line);

 private:
  std::filesystem::path file_;
  std::string column_;
  bool has_previous_ = false;
  double previous_ = 0;
  std::string previous_text_;
  std::size_t previous_line_ = 0;
};

}  // namespace stillslam
