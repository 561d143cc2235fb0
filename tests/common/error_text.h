#pragma once
// The message of the stillslam::Error a call throws, for tests that check
// what an error says.
#include <gtest/gtest.h>

#include <string>

#include "stillslam/core/error.h"

namespace stillslam::test {

// The Error's message; fails the test (and returns "") when none is thrown.
template <typename Call>
std::string error_of(Call call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an Error";
  return {};
}

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace stillslam::test
