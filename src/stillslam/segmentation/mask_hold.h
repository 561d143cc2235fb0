#pragma once
// Detectors flicker: a person who fills half the view, is cut by the border or
// turns away can vanish from one frame's detections and come back a few frames
// later. MaskHold keeps each dynamic instance the segmenter lost for a few
// frames (grown a little every frame to cover its motion), so the keypoints on
// it stay out of pose estimation and mapping meanwhile. An instance counts as
// found again when this frame's dynamic masks cover enough of it.
#include <opencv2/core.hpp>

#include <vector>

namespace stillslam {

struct MaskHoldOptions {
  int frames = 10;            // frames a lost instance is held (0: off)
  double min_overlap = 0.3;   // share of a held instance this frame's masks must cover to find it again
  int grow_px_per_frame = 4;  // growth per held frame (a walking person moves a few pixels a frame)
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

class MaskHold {
 public:
  explicit MaskHold(MaskHoldOptions options = {}) : options_(options) { options_.check(); }

  // instances: this frame's dynamic instance masks (frame-size, 255 inside).
  // Returns the union of the held instances not found in this frame (empty
  // Mat when there are none), to be added to this frame's dynamic mask.
  cv::Mat1b update(const std::vector<cv::Mat1b>& instances, cv::Size size);

  std::size_t held() const { return held_.size(); }

 private:
  struct Held {
    cv::Mat1b mask;
    int age = 0;  // frames since it was last detected
  };
  MaskHoldOptions options_;
  std::vector<Held> held_;
};

}  // namespace stillslam
