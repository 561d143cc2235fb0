#include "stillslam/loop/loop_closer_options.h"

#include "stillslam/core/option_check.h"

namespace stillslam {

void LoopCloserOptions::check() const {
  detector.check();
  correction.check();
  global_bundle_adjustment.check();
}

}  // namespace stillslam
