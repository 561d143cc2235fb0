#include "stillslam/tracking/keyframe_budget.h"

#include <algorithm>

#include "stillslam/core/option_check.h"

namespace stillslam {

void KeyFrameBudgetOptions::check() const {
  using namespace option_check;
  in_range("KeyFrameBudgetOptions.per_second", per_second, 0, 1000);
  in_range("KeyFrameBudgetOptions.burst", burst, 1, 1000);
  in_range("KeyFrameBudgetOptions.start_keyframes", start_keyframes, 0, 1000);
  in_range("KeyFrameBudgetOptions.start_seconds", start_seconds, 0, 1000);
}

KeyFrameBudget::KeyFrameBudget(KeyFrameBudgetOptions options) : options_(options) { options_.check(); }

double KeyFrameBudget::balance_at(double timestamp) const {
  if (!started_) return options_.burst;
  // Time going backwards (another input, a new map) adds nothing.
  const double elapsed = std::max(0.0, timestamp - last_timestamp_);
  return std::min(options_.burst, balance_ + elapsed * options_.per_second);
}

bool KeyFrameBudget::in_start(double timestamp) const {
  if (keyframes_ >= options_.start_keyframes) return false;
  return options_.start_seconds <= 0 || keyframes_ == 0 || timestamp - first_timestamp_ < options_.start_seconds;
}

bool KeyFrameBudget::allows(double timestamp) const {
  return options_.per_second <= 0 || in_start(timestamp) || balance_at(timestamp) >= 1;
}

void KeyFrameBudget::spend(double timestamp) {
  if (keyframes_ == 0) first_timestamp_ = timestamp;
  const bool start = in_start(timestamp);
  ++keyframes_;
  if (start) return;  // outside the budget: the bucket stays full
  balance_ = std::max(0.0, balance_at(timestamp) - 1);
  last_timestamp_ = timestamp;
  started_ = true;
}

void KeyFrameBudget::reset() {
  balance_ = 0;
  last_timestamp_ = 0;
  started_ = false;
  keyframes_ = 0;
  first_timestamp_ = 0;
}

}  // namespace stillslam
