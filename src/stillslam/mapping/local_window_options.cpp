#include "stillslam/mapping/local_window_options.h"

#include "stillslam/core/option_check.h"

namespace stillslam {

void LocalWindowOptions::check() const {
  using namespace option_check;
  at_least("LocalWindowOptions.max_keyframes", max_keyframes, 0);
  at_least("LocalWindowOptions.max_fixed_keyframes", max_fixed_keyframes, 0);
  at_least("LocalWindowOptions.max_points", max_points, 0);
  at_least("LocalWindowOptions.max_observations", max_observations, 0);
}

}  // namespace stillslam
