#include "stillslam/mapping/local_mapper_options.h"

#include "stillslam/core/option_check.h"

namespace stillslam {

const char* to_string(BundleAdjustmentAbort cause) {
  switch (cause) {
    case BundleAdjustmentAbort::Tracking:
      return "tracking";
    case BundleAdjustmentAbort::Pause:
      return "pause";
    case BundleAdjustmentAbort::None:
      break;
  }
  return "none";
}

void LocalMapperOptions::check() const {
  point_culling.check();
  triangulation.check();
  fusion.check();
  keyframe_culling.check();
  bundle_adjustment.check();
  window.check();
  busy.check();
  option_check::in_range("LocalMapperOptions.iterations_before_interrupt", iterations_before_interrupt, 0, 100);
  option_check::in_range("LocalMapperOptions.thread_nice", thread_nice, 0, 19);
  option_check::in_range("LocalMapperOptions.bundle_adjustments_per_second", bundle_adjustments_per_second, 0, 1000);
}

}  // namespace stillslam
