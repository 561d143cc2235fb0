#pragma once
// Precondition checks at library entry points:
//   STILLSLAM_CHECK(cond, msg)
//   STILLSLAM_CHECK_EQ / _NE / _LT / _LE / _GT / _GE(a, b, msg)
// When the check fails they throw PreconditionError with the source
// file:line, the condition as written, both values for the comparisons and
// `msg` (anything a std::string can be built from, evaluated only on failure):
//   src/stillslam/geometry/pnp.cpp:42: solve_pnp_ransac: one pixel per point
//   (check failed: points_world.size() == pixels_undistorted.size(), 5 vs 4)
// Each argument is evaluated once. Integer comparisons of mixed signedness
// compare the values (std::cmp_less), so -1 < 3u holds.
//
// A failed precondition is a bug in the caller or bad input that reached a
// library function unchecked, never a state to continue from. It is an
// exception rather than an abort so the apps report it the way they report
// any bad input (one message, non-zero exit) and a threaded run still shuts
// down and writes its trajectory. PreconditionError derives from Error so
// every existing `catch (const Error&)` reports it; it is its own type so a
// test (or a caller) can tell a broken contract from bad user data such as a
// missing file or a malformed settings key.
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "stillslam/core/error.h"

namespace stillslam {

class PreconditionError : public Error {
 public:
  using Error::Error;
};

namespace check_detail {

// The path from src/stillslam/ (or tests/) on: __FILE__ is absolute or
// relative to the build folder depending on how the file was compiled.
inline std::string_view short_path(std::string_view file) {
  for (std::string_view root : {std::string_view("/src/stillslam/"), std::string_view("/tests/")}) {
    const auto at = file.rfind(root);
    if (at != std::string_view::npos) return file.substr(at + 1);
  }
  return file;
}

[[noreturn]] inline void fail(const char* file, int line, const std::string& message, const std::string& check) {
  std::ostringstream text;
  text << short_path(file) << ':' << line << ": " << message << " (check failed: " << check << ')';
  throw PreconditionError(text.str());
}

template <class A, class B>
[[noreturn]] void fail_compare(const char* file, int line, const std::string& message, const char* a_text,
                               const char* op, const char* b_text, const A& a, const B& b) {
  std::ostringstream check;
  check << a_text << ' ' << op << ' ' << b_text << ", ";
  // Bytes print as numbers, not as characters.
  if constexpr (sizeof(A) == 1 && std::is_integral_v<A>) check << static_cast<int>(a); else check << a;
  check << " vs ";
  if constexpr (sizeof(B) == 1 && std::is_integral_v<B>) check << static_cast<int>(b); else check << b;
  fail(file, line, message, check.str());
}

template <class T>
constexpr bool plain_integer = std::is_integral_v<T> && !std::is_same_v<T, bool> && !std::is_same_v<T, char>;

// The comparisons, on integers of any signedness by value (std::cmp_*),
// otherwise with the type's own operator (a NaN fails every check but NE).
template <class A, class B>
constexpr bool equal(const A& a, const B& b) {
  if constexpr (plain_integer<A> && plain_integer<B>) return std::cmp_equal(a, b);
  else return a == b;
}
template <class A, class B>
constexpr bool less(const A& a, const B& b) {
  if constexpr (plain_integer<A> && plain_integer<B>) return std::cmp_less(a, b);
  else return a < b;
}
template <class A, class B>
constexpr bool less_equal(const A& a, const B& b) {
  if constexpr (plain_integer<A> && plain_integer<B>) return std::cmp_less_equal(a, b);
  else return a <= b;
}

}  // namespace check_detail
}  // namespace stillslam

#define STILLSLAM_CHECK(cond, msg)                                                          \
  do {                                                                                      \
    if (!(cond)) ::stillslam::check_detail::fail(__FILE__, __LINE__, (msg), #cond);        \
  } while (false)

// `holds` compares stillslam_check_a_ and stillslam_check_b_ (check_detail).
#define STILLSLAM_CHECK_COMPARE_(a, b, op, holds, msg)                                              \
  do {                                                                                              \
    const auto& stillslam_check_a_ = (a);                                                           \
    const auto& stillslam_check_b_ = (b);                                                           \
    if (!(holds))                                                                                   \
      ::stillslam::check_detail::fail_compare(__FILE__, __LINE__, (msg), #a, op, #b, stillslam_check_a_, \
                                              stillslam_check_b_);                                  \
  } while (false)

#define STILLSLAM_CHECK_EQ(a, b, msg) \
  STILLSLAM_CHECK_COMPARE_(a, b, "==", ::stillslam::check_detail::equal(stillslam_check_a_, stillslam_check_b_), msg)
#define STILLSLAM_CHECK_NE(a, b, msg) \
  STILLSLAM_CHECK_COMPARE_(a, b, "!=", !::stillslam::check_detail::equal(stillslam_check_a_, stillslam_check_b_), msg)
#define STILLSLAM_CHECK_LT(a, b, msg) \
  STILLSLAM_CHECK_COMPARE_(a, b, "<", ::stillslam::check_detail::less(stillslam_check_a_, stillslam_check_b_), msg)
#define STILLSLAM_CHECK_LE(a, b, msg) \
  STILLSLAM_CHECK_COMPARE_(a, b, "<=", ::stillslam::check_detail::less_equal(stillslam_check_a_, stillslam_check_b_), msg)
#define STILLSLAM_CHECK_GT(a, b, msg) \
  STILLSLAM_CHECK_COMPARE_(a, b, ">", ::stillslam::check_detail::less(stillslam_check_b_, stillslam_check_a_), msg)
#define STILLSLAM_CHECK_GE(a, b, msg) \
  STILLSLAM_CHECK_COMPARE_(a, b, ">=", ::stillslam::check_detail::less_equal(stillslam_check_b_, stillslam_check_a_), msg)
