#pragma once
// What tracking does with a keyframe it wants while local mapping is busy
// (ORB-SLAM3's AcceptKeyFrames false): a running local BA is interrupted only
// when tracking is about to fail; the RGB-D/stereo close-point exception
// queues one keyframe behind the BA; otherwise the keyframe waits (tracking
// asks again on the next frame) instead of aborting the BA.
#include <cstddef>

namespace stillslam {

struct KeyFrameAdmission {
  bool insert = false;
  bool interrupt_bundle_adjustment = false;
};

// mapper_idle: the mapper accepts keyframes now; tracking_weak: the frame
// tracks fewer than a quarter of the reference keyframe's points;
// need_close: too few close points tracked and enough new ones seen;
// queued: keyframes already waiting for the mapper.
KeyFrameAdmission admit_keyframe(bool mapper_idle, bool tracking_weak, bool need_close, std::size_t queued);

}  // namespace stillslam
