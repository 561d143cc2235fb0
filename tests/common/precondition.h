#pragma once
// expect_precondition(f, file, text): `f` throws PreconditionError whose
// message is "<file>:<line>: <text>" (the line is not pinned, so editing
// the checked function above the check does not break the test).
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "stillslam/core/check.h"

namespace stillslam::test {

template <class F>
void expect_precondition(F&& f, const std::string& file, const std::string& text) {
  try {
    f();
  } catch (const PreconditionError& e) {
    const std::string message = e.what();
    const std::string prefix = file + ":";
    ASSERT_EQ(message.rfind(prefix, 0), 0u) << message;
    const std::size_t colon = message.find(": ", prefix.size());
    ASSERT_NE(colon, std::string::npos) << message;
    EXPECT_TRUE(std::regex_match(message.substr(prefix.size(), colon - prefix.size()), std::regex("[0-9]+")))
        << message;
    EXPECT_EQ(message.substr(colon + 2), text);
    return;
  }
  ADD_FAILURE() << "no PreconditionError thrown; expected " << file << ": " << text;
}

}  // namespace stillslam::test
