#include "stillslam/segmentation/segmentation_scheduler.h"

#include "stillslam/core/option_check.h"

namespace stillslam {

const char* to_string(ScheduleReason reason) {
  switch (reason) {
    case ScheduleReason::None: return "none";
    case ScheduleReason::First: return "first";
    case ScheduleReason::Interval: return "interval";
    case ScheduleReason::Urgent: return "urgent";
    case ScheduleReason::Waiting: return "waiting";
    case ScheduleReason::Keyframe: return "keyframe";
  }
  return "none";
}

SegmentationScheduler::SegmentationScheduler(int interval) : interval_(interval) {
  option_check::at_least("SegmentationOptions.interval", interval_, 1);
}

ScheduleReason SegmentationScheduler::decide(std::size_t frame_index, bool stage_busy) {
  ScheduleReason reason = ScheduleReason::None;
  if (!last_request_) {
    reason = ScheduleReason::First;
  } else if (frame_index >= *last_request_ + static_cast<std::size_t>(interval_)) {
    reason = ScheduleReason::Interval;
  } else if (urgent_ && !stage_busy && frame_index > *last_request_) {
    reason = ScheduleReason::Urgent;
  }
  if (reason != ScheduleReason::None) record_request(frame_index);
  return reason;
}

void SegmentationScheduler::record_request(std::size_t frame_index) {
  last_request_ = frame_index;
  urgent_ = false;
}

}  // namespace stillslam
