#pragma once
// When the asynchronous segmentation stage gets a frame (Segmentation.mode
// async). The rules, in order:
//   1. nothing segmented yet: segment this frame;
//   2. `interval` frames or more since the last request: segment this frame
//      (a busy stage then skips its older queued request);
//   3. an urgent request (a keyframe candidate deferred for an old mask, or
//      weak tracking) while the stage is idle: segment this frame.
// Otherwise the frame goes on with a propagated mask.
#include <cstddef>
#include <optional>

namespace stillslam {

// Waiting: not by the rules; the frame's newest mask was too old (async_masks.h).
// Keyframe: after tracking, a keyframe made from the frame waits for its own mask
// (Segmentation.keyframeHold, tracking/keyframe_hold.h).
enum class ScheduleReason { None, First, Interval, Urgent, Waiting, Keyframe };
const char* to_string(ScheduleReason reason);

class SegmentationScheduler {
 public:
  // interval >= 1 (1: every frame).
  explicit SegmentationScheduler(int interval);

  // Marks the next frame urgent (rule 3); cleared once a frame is requested.
  void request_urgent() { urgent_ = true; }
  bool urgent() const { return urgent_; }

  // Decides for the input frame `frame_index` (increasing) and, when it is to
  // be segmented, records it as requested.
  ScheduleReason decide(std::size_t frame_index, bool stage_busy);
  // A request made outside the rules (a frame that must wait for its mask).
  void record_request(std::size_t frame_index);

 private:
  int interval_;
  bool urgent_ = false;
  std::optional<std::size_t> last_request_;
};

}  // namespace stillslam
