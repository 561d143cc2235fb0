#pragma once
// Detectors flicker: a person who fills half the view, is cut by the border or
// turns away can vanish from one frame's detections and come back a few frames
// later. MaskHold keeps each dynamic instance the segmenter lost for a few
// input frames (grown a little every input frame to cover its motion), so the
// keypoints on it stay out of pose estimation and mapping meanwhile. Ages and
// growth count input frames (frame indices), not calls: with asynchronous
// segmentation or dropped frames the calls are several frames apart, and a
// person walks on meanwhile. An instance counts as found again when this
// frame's dynamic masks cover enough of it.
#include <opencv2/core.hpp>

#include <vector>

namespace stillslam {

struct MaskHoldOptions {
  int frames = 10;            // input frames a lost instance is held (0: off)
  double min_overlap = 0.3;   // share of a held instance this frame's masks must cover to find it again
  int grow_px_per_frame = 4;  // growth per input frame held (a walking person moves a few pixels a frame)
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

class MaskHold {
 public:
  explicit MaskHold(MaskHoldOptions options = {}) : options_(options) { options_.check(); }

  // instances: this frame's dynamic instance masks (frame-size, 255 inside);
  // frame_index: the frame's input index, increasing from call to call.
  // Returns the held instances not found in this frame (none: empty), each
  // grown by grow_px_per_frame per input frame since the last call; a held
  // instance lost more than `frames` input frames ago is dropped.
  std::vector<cv::Mat1b> update(const std::vector<cv::Mat1b>& instances, cv::Size size, std::size_t frame_index);

  std::size_t held() const { return held_.size(); }

 private:
  struct Held {
    cv::Mat1b mask;
    std::size_t detected = 0;  // frame index it was last detected in
  };
  MaskHoldOptions options_;
  std::vector<Held> held_;
  std::size_t last_index_ = 0;  // of the previous call
};

}  // namespace stillslam
