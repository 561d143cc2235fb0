#pragma once
// What tracking does with a keyframe it wants while local mapping is busy
// (ORB-SLAM3's AcceptKeyFrames false: the mapper refuses keyframes while
// busy). Tracking about to fail: the keyframe is queued (up to three), and the
// running local BA is interrupted only when the frame is urgent (few inliers)
// and another keyframe already waits (the mapper is falling behind). Too few
// close points tracked (the RGB-D/stereo exception): one keyframe queues
// behind the BA. Otherwise the keyframe waits (tracking asks again on the next
// frame) instead of aborting the BA.
#include <cstddef>

namespace stillslam {

struct KeyFrameAdmission {
  bool insert = false;
  bool interrupt_bundle_adjustment = false;
};

// mapper_idle: the mapper accepts keyframes now; tracking_weak: the frame
// tracks fewer than a quarter of the reference keyframe's points;
// need_close: too few close points tracked and enough new ones seen;
// queued: keyframes already waiting for the mapper; urgent: the frame has
// fewer inliers than TrackerOptions::interrupt_inliers.
KeyFrameAdmission admit_keyframe(bool mapper_idle, bool tracking_weak, bool need_close, std::size_t queued,
                                 bool urgent);

}  // namespace stillslam
