#pragma once
// Asynchronous segmentation (Segmentation.mode async) carries masks between
// segmented frames, so a keyframe due on a frame with an old mask may hold
// points on people the carried mask missed. With Segmentation.keyframeHold the
// keyframe is made at once (tracking uses its points, the map stays as dense as
// with per-frame masks) but reaches local mapping only when its frame's own
// mask arrives (the frame is segmented for it, async_masks.h segment_last()):
// first its points inside that mask go (its own new points are culled, its
// matches to older points are unlinked). Keyframes reach local mapping in the
// order they were made: a fresh keyframe waits behind held ones.
//
// Local mapping adds a keyframe's observations of older points when it gets
// the keyframe, so while a keyframe waits here the points it matched do not
// count it in their static-evidence span (tracking/static_evidence.h): in a
// sparse stereo map a held keyframe is often the one that would give them the
// span. With `evidence_while_held` (Segmentation.heldEvidence) each older point
// a waiting keyframe matched notes that keyframe's frame at once
// (MapPoint::note_held_observation); at the release a match unlinked inside
// the keyframe's own mask loses the note again.
#include <opencv2/core.hpp>

#include <cstddef>
#include <deque>
#include <vector>

#include "stillslam/map/keyframe.h"
#include "stillslam/tracking/mask_wait.h"

namespace stillslam {

struct KeyframeHoldRelease {
  std::vector<KeyFramePtr> keyframes;  // in the order they were made
  int culled = 0;    // points the held keyframes made inside their own masks
  int unlinked = 0;  // matches of held keyframes to older points inside their masks
  int unchecked = 0;  // held keyframes whose own mask never came (a newer one did)
};

class KeyframeHold {
 public:
  explicit KeyframeHold(bool evidence_while_held = false) : evidence_while_held_(evidence_while_held) {}
  // A keyframe made with a carried mask from the frame being tracked;
  // raw_pixels: its keypoints in the image (Frame::keypoints_raw), where the
  // mask is looked up. It waits for the input index of its frame (assign()).
  void hold(KeyFramePtr kf, std::vector<cv::Point2f> raw_pixels);
  // The frame of the keyframes held since the last call goes to the
  // segmenter as input frame `frame_index`: they wait for that result.
  // Returns how many were held since the last call.
  int assign(std::size_t frame_index);
  // A keyframe from a fresh enough mask: local mapping gets it now, unless a
  // held one is before it (then it waits behind).
  // Returns the keyframes to pass on now.
  std::vector<KeyFramePtr> pass(KeyFramePtr kf);
  bool empty() const { return queue_.empty(); }
  std::size_t held() const;

  // The segmentation of input frame `frame_index` is the newest result: its
  // dynamic instances (frame size, non-zero inside). Releases, in order, the
  // keyframes up to the first one held for a later frame, checking the one of
  // `frame_index` against the instances (a keyframe not assigned yet stops
  // the release). The caller holds the map's update mutex.
  KeyframeHoldRelease release(std::size_t frame_index, const std::vector<cv::Mat1b>& instances);
  // Everything, unchecked (a new map starts, or the run ends).
  KeyframeHoldRelease release_all();

 private:
  // The older points kf matched note its frame (evidence_while_held_).
  void note_matches(const KeyFrame& kf) const;

  bool evidence_while_held_ = false;
  std::deque<MaskWait> queue_;  // waits: held
};

}  // namespace stillslam
