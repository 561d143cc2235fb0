#pragma once
// Asynchronous segmentation with Segmentation.provisionalPoints: a keyframe
// made under a carried mask older than Segmentation.keyframeMaskAge goes to
// local mapping at once, but the depth points it made are provisional
// (MapPoint::is_provisional, set by the tracker): out of tracking, bundle
// adjustment, fusion and culling. Its frame goes to the segmenter
// (async_masks.h segment_last()); when that frame's own mask is the newest
// result, the provisional points inside it are culled and the rest confirmed
// (ordinary points from then on), and the keyframe's matches to older points
// inside it are unlinked. Unlike keyframe_hold.h, nothing waits.
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "stillslam/map/keyframe.h"
#include "stillslam/tracking/mask_wait.h"

namespace stillslam {

struct ProvisionalCheck {
  int culled = 0;     // provisional points inside their frame's own mask
  int confirmed = 0;  // provisional points outside it (or never checked)
  int unlinked = 0;   // matches to older points inside the mask
  int unchecked = 0;  // keyframes whose own mask never came (a newer one did): confirmed as they are
  // The keyframes whose points were settled (not culled keyframes): their
  // confirmed points were never fused; the caller has local mapping fuse them
  // (LocalMapper::fuse_confirmed).
  std::vector<KeyFramePtr> settled;
};

class ProvisionalPoints {
 public:
  // A keyframe with provisional points, made from the frame being tracked;
  // raw_pixels: its keypoints in the image (Frame::keypoints_raw), where the
  // mask is looked up. It waits for its frame's input index (assign()).
  void add(KeyFramePtr kf, std::vector<cv::Point2f> raw_pixels);
  // The keyframes added since the last call came from input frame
  // `frame_index` (sent to the segmenter). Returns how many.
  int assign(std::size_t frame_index);
  bool empty() const { return pending_.empty(); }
  std::size_t size() const { return pending_.size(); }

  // The segmentation of input frame `frame_index` is the newest result: its
  // dynamic instances (frame size, non-zero inside). Checks the keyframes of
  // that frame and confirms, unchecked, those of earlier frames.
  // next_keyframe_id: the id the next keyframe will get (confirmed points are
  // culled by their age from there). The caller holds the map's update mutex.
  ProvisionalCheck check(std::size_t frame_index, const std::vector<cv::Mat1b>& instances,
                         std::uint64_t next_keyframe_id);
  // Every keyframe confirmed unchecked (a new map starts, or the run ends).
  ProvisionalCheck confirm_all(std::uint64_t next_keyframe_id);

 private:
  std::deque<MaskWait> pending_;
};

}  // namespace stillslam
