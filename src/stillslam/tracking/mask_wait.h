#pragma once
// Asynchronous segmentation: a keyframe made under a carried mask waits for
// its own frame's mask (keyframe_hold.h, provisional_points.h,
// keyframe_check.h). What they share: the queue entry that learns its frame's
// input index when the frame goes to the segmenter, and the removal of the
// keyframe's points that its own mask shows on a dynamic instance.
#include <opencv2/core.hpp>

#include <cstddef>
#include <deque>
#include <functional>
#include <optional>
#include <vector>

#include "stillslam/map/keyframe.h"

namespace stillslam {

struct MaskWait {
  KeyFramePtr kf;
  std::optional<std::size_t> frame_index;  // its frame's input index, once known
  std::vector<cv::Point2f> raw_pixels;     // its keypoints in the image (Frame::keypoints_raw)
  bool waits = true;  // false: queued behind waiting ones without a mask of its own
};

// The waiting entries without an index came from input frame `frame_index`
// (sent to the segmenter). Returns how many.
int assign_frame_index(std::deque<MaskWait>& queue, std::size_t frame_index);

struct PointsInsideMask {
  int culled = 0;    // points set bad
  int unlinked = 0;  // matches removed from the keyframe
};

// The keyframe's points whose keypoint lies on one of `instances` (frame
// size, non-zero inside) go: culled where `cull` says so, else unlinked from
// the keyframe. The caller holds the map's update mutex.
PointsInsideMask remove_points_inside(KeyFrame& kf, const std::vector<cv::Point2f>& raw_pixels,
                                      const std::vector<cv::Mat1b>& instances,
                                      const std::function<bool(const MapPoint&)>& cull);

}  // namespace stillslam
