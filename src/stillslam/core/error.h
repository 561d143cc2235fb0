#pragma once
// One exception type for bad input and unrecoverable conditions. The message
// names the file or key involved and what the user can do about it.
#include <stdexcept>
#include <string>

namespace stillslam {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace stillslam
