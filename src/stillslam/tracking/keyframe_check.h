#pragma once
// Asynchronous segmentation (Segmentation.mode async) with
// Segmentation.startCheck / Segmentation.keyframeCheck: a keyframe made under
// a carried mask goes to local mapping at once (its points are used at once,
// nothing waits), and its frame goes to the segmenter. When that frame's own
// mask is the newest result, the keyframe's points inside it go: the points
// it made itself are culled, its matches to older points are unlinked (as
// keyframe_hold.h does for a held keyframe before local mapping). With
// cull_new_points (Segmentation.checkNewPoints), points made after the
// keyframe (local mapping triangulated them with it before its mask came, or
// a later keyframe made them) that it sees inside its mask are culled too.
#include <opencv2/core.hpp>

#include <cstddef>
#include <deque>
#include <optional>
#include <vector>

#include "stillslam/map/keyframe.h"
#include "stillslam/tracking/mask_wait.h"

namespace stillslam {

struct KeyframeCheckResult {
  int checked = 0;    // keyframes checked with their own masks
  int culled = 0;     // points culled (made by the keyframe, or after it with cull_new_points)
  int unlinked = 0;   // matches to older points inside the mask, removed from the keyframe
  int unchecked = 0;  // keyframes whose own mask never came (a newer one did)
};

class KeyframeCheck {
 public:
  explicit KeyframeCheck(bool cull_new_points = false) : cull_new_points_(cull_new_points) {}

  // A keyframe made under a carried mask, already in the map and on its way
  // to local mapping; raw_pixels: its keypoints in the image
  // (Frame::keypoints_raw), where the mask is looked up. frame_index: its
  // frame's input index when known (the map's first keyframe, made from an
  // earlier frame), else it waits for assign().
  void add(KeyFramePtr kf, std::vector<cv::Point2f> raw_pixels, std::optional<std::size_t> frame_index = {});
  // The keyframes added since the last call without an index came from input
  // frame `frame_index` (sent to the segmenter). Returns how many.
  int assign(std::size_t frame_index);
  bool empty() const { return pending_.empty(); }
  std::size_t size() const { return pending_.size(); }

  // The segmentation of input frame `frame_index` is the newest result: its
  // dynamic instances (frame size, non-zero inside). Checks the keyframes of
  // that frame and drops, unchecked, those of earlier frames (an unassigned
  // keyframe and the ones after it wait). The caller holds the map's update mutex.
  KeyframeCheckResult check(std::size_t frame_index, const std::vector<cv::Mat1b>& instances);
  // Every keyframe dropped unchecked (a new map starts, or the run ends).
  KeyframeCheckResult drop_all();

 private:
  bool cull_new_points_;
  std::deque<MaskWait> pending_;
};

}  // namespace stillslam
