// STILLSLAM_CHECK family: what passes, what throws, and the message a caller
// sees (file:line, the condition, both values, the caller's text).
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include "stillslam/core/check.h"

namespace stillslam {
namespace {

// The message of the PreconditionError `f` throws; fails the test otherwise.
template <class F>
std::string failure_message(F f) {
  try {
    f();
  } catch (const PreconditionError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no PreconditionError thrown";
  return {};
}

TEST(Check, PassingChecksDoNothing) {
  const std::size_t three = 3;
  EXPECT_NO_THROW(STILLSLAM_CHECK(three == 3, "never shown"));
  EXPECT_NO_THROW(STILLSLAM_CHECK_EQ(three, 3, "never shown"));
  EXPECT_NO_THROW(STILLSLAM_CHECK_NE(three, 4, "never shown"));
  EXPECT_NO_THROW(STILLSLAM_CHECK_LT(-1, three, "never shown"));  // by value, not -1 as size_t
  EXPECT_NO_THROW(STILLSLAM_CHECK_LE(three, 3u, "never shown"));
  EXPECT_NO_THROW(STILLSLAM_CHECK_GT(0.5, 0.25, "never shown"));
  EXPECT_NO_THROW(STILLSLAM_CHECK_GE(three, 3, "never shown"));
}

TEST(Check, MessageNamesFileLineConditionAndText) {
  const int line = __LINE__ + 1;
  const std::string message = failure_message([] { STILLSLAM_CHECK(1 + 1 == 3, "arithmetic is broken"); });
  EXPECT_EQ(message, "tests/core/test_check.cpp:" + std::to_string(line) +
                         ": arithmetic is broken (check failed: 1 + 1 == 3)");
}

TEST(Check, ComparisonMessageShowsBothValues) {
  const std::size_t points = 5;
  const int pixels = 4;
  const int line = __LINE__ + 1;
  const std::string message = failure_message([&] { STILLSLAM_CHECK_EQ(points, pixels, "one pixel per point"); });
  EXPECT_EQ(message, "tests/core/test_check.cpp:" + std::to_string(line) +
                         ": one pixel per point (check failed: points == pixels, 5 vs 4)");
}

TEST(Check, EachComparisonFailsOnItsBoundary) {
  EXPECT_NE(failure_message([] { STILLSLAM_CHECK_NE(2, 2, "ne"); }).find("2 != 2, 2 vs 2"), std::string::npos);
  EXPECT_NE(failure_message([] { STILLSLAM_CHECK_LT(2, 2, "lt"); }).find("2 < 2, 2 vs 2"), std::string::npos);
  EXPECT_NE(failure_message([] { STILLSLAM_CHECK_LE(3, 2, "le"); }).find("3 <= 2, 3 vs 2"), std::string::npos);
  EXPECT_NE(failure_message([] { STILLSLAM_CHECK_GT(2, 2, "gt"); }).find("2 > 2, 2 vs 2"), std::string::npos);
  EXPECT_NE(failure_message([] { STILLSLAM_CHECK_GE(1, 2, "ge"); }).find("1 >= 2, 1 vs 2"), std::string::npos);
  // Mixed signedness compares values: -1 is less than every size_t.
  EXPECT_NE(failure_message([] { STILLSLAM_CHECK_GE(-1, std::size_t{0}, "index"); }).find("-1 vs 0"),
            std::string::npos);
}

TEST(Check, NanFailsOrderingChecks) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(STILLSLAM_CHECK_LE(nan, 1.0, "finite"), PreconditionError);
  EXPECT_THROW(STILLSLAM_CHECK_GE(nan, 1.0, "finite"), PreconditionError);
  EXPECT_THROW(STILLSLAM_CHECK_GT(nan, 0.0, "positive"), PreconditionError);
  EXPECT_THROW(STILLSLAM_CHECK(std::isfinite(nan), "finite"), PreconditionError);
}

TEST(Check, ArgumentsAreEvaluatedOnceAndTheTextOnlyOnFailure) {
  int evaluations = 0;
  int texts = 0;
  auto next = [&] { return ++evaluations; };
  auto text = [&] { ++texts; return std::string("text"); };
  STILLSLAM_CHECK_EQ(next(), 1, text());
  EXPECT_EQ(evaluations, 1);
  EXPECT_EQ(texts, 0);
  EXPECT_THROW(STILLSLAM_CHECK_EQ(next(), 1, text()), PreconditionError);
  EXPECT_EQ(evaluations, 2);
  EXPECT_EQ(texts, 1);
}

TEST(Check, PreconditionErrorIsAStillslamError) {
  // The apps catch stillslam::Error: a failed check is reported like bad input.
  EXPECT_THROW(STILLSLAM_CHECK(false, "reported"), Error);
}

}  // namespace
}  // namespace stillslam
