#pragma once
// The first frames after a map start that the next frames checked without
// masks (Tracking.initUnmaskedConfirmFrames, tracking/initial_view_check.h).
// No map point can have static evidence yet (static_evidence.h: observing
// keyframes spanning staticEvidenceSpan frames), so every pose stage would
// fall back to all matches, and the first tracked frames would follow the
// movers the check left out of the first keyframe through their own
// visual-odometry points and the points of the keyframes made there. The
// check is evidence of its own: the first keyframe's points it kept agreed
// with the camera motion over the checked frames. For
// Tracking.initUnmaskedTrustFrames frames after the start those points count
// as having static evidence (the others are only classified against the pose
// they give), and the tracker takes no visual-odometry or keyframe depth
// point where a match was rejected, nor a keyframe depth point that the
// previous tracked frame did not see where the camera motion puts it.
#include <cstdint>
#include <unordered_set>
#include <vector>

#include "stillslam/map/map_point.h"

namespace stillslam {

class StartEvidence {
 public:
  // `points`: the first keyframe's map points (null entries skipped); the
  // window covers the frames with ids up to and including `last_frame`.
  void begin(const std::vector<MapPointPtr>& points, std::uint64_t last_frame);
  void reset();
  // Whether `frame_id` lies in the window.
  bool active(std::uint64_t frame_id) const { return active_ && frame_id <= last_frame_; }
  // Whether the point is one of the start's checked points and `frame_id` in the window.
  bool holds(const MapPoint& point, std::uint64_t frame_id) const;

 private:
  std::unordered_set<std::uint64_t> ids_;
  std::uint64_t last_frame_ = 0;
  bool active_ = false;
};

}  // namespace stillslam
