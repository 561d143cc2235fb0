#pragma once
// Pose from the map points with static evidence (issue #20). A close,
// textured thing that moves (a person no mask covers) fixes the translation
// along the view much better than a static scene a few metres away, so a
// least-squares pose over all matches follows it, and the motion model then
// carries its velocity on. Here the pose is estimated from the matches whose
// map point has been observed consistently over a span of frames (the
// keyframes observing it lie at least min_span_frames apart); new points,
// the motion model's temporary last-frame points and points only one moment
// of the map has seen are classified against that pose (chi2, as the
// optimizer's rounds) but do not move it. The velocity of the next motion
// prediction is then that of the consensus on old points too.
#include "stillslam/map/frame.h"
#include "stillslam/map/map_point.h"
#include "stillslam/optimize/pose_optimizer.h"

namespace stillslam {

class StartEvidence;  // tracking/start_evidence.h

struct StaticEvidenceOptions {
  // Tracking.staticEvidencePose: 0 off (all matches move the pose, ORB-SLAM's
  // rule). On by default: on the issue #20 renders it took --no-segmentation
  // from 0.12-0.78 m to 6-370 mm, at 0.85-1.07x on the static twins and
  // 0.93-1.05x with masks (bench/README.md).
  bool enabled = true;
  // Tracking.staticEvidenceSpan: a map point has static evidence when the
  // keyframes observing it span at least this many frames.
  int min_span_frames = 10;
  // Tracking.staticEvidenceMinPoints: fewer matches (or inliers) with
  // evidence than this: the pose from all matches, as without the rule.
  int min_points = 40;
  // Tracking.staticEvidenceQuietFrames: a point that a frame's final pose
  // rejected as an outlier within this many frames has no evidence (0: no
  // such rule). A thing that stood still long enough to gain evidence and
  // then starts to move is rejected by its first moving parts, and those
  // stop moving the pose. Off by default: mixed on the issue #20 renders
  // (n1 stereo 0.21 -> 0.010 m, wx 0.37 -> 0.45 m, bench/README.md).
  int quiet_frames = 0;
  // Points matched on a person the motion stage keeps as static
  // (MapPoint::on_dynamic_instance, issue #19) are classified against the
  // pose like points without evidence, but do not move it: a seated person
  // sways and breathes. With fewer than min_points trusted matches without
  // them, the pose comes from all matches. Not a Tracking.* key: System sets
  // it from Motion.enabled and Motion.keptPointsOutOfPose.
  bool leave_out_kept_points = false;
  // Matches on a kept person that do move the pose count with this many
  // times their keypoint's sigma (1: as any other match). Not a Tracking.*
  // key: System sets it from Motion.enabled and Motion.keptPointSigma.
  double kept_point_sigma = 1;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// Frames between the first and the last keyframe observing the point (0 for
// points without observations, e.g. temporary ones); a keyframe held from
// local mapping that matched it (MapPoint::held_observation_frame) counts.
std::uint64_t observation_span_frames(const MapPoint& point);

bool has_static_evidence(const MapPoint& point, const StaticEvidenceOptions& options);

// Whether a frame's final pose rejected the point within options.quiet_frames
// frames before `frame_id` (never with quiet_frames 0).
bool recently_rejected(const MapPoint& point, const StaticEvidenceOptions& options, std::uint64_t frame_id);

// refine_pose (tracking/pose_refinement.h) with the rules above: outlier
// flags are set on all matches, the pose comes from those with evidence
// (and, with leave_out_kept_points, not on a kept person; those on a kept
// person weighted by kept_point_sigma).
// Returns the number of inlier observations. A prior (optimize/pose_prior.h)
// joins the optimization when given. `start` (optional): the points a map
// start's check confirmed count as having evidence in its window.
int refine_pose_on_evidence(Frame& frame, const PoseOptimizerOptions& pose, const StaticEvidenceOptions& options,
                            const PosePrior* prior = nullptr, const StartEvidence* start = nullptr);

}  // namespace stillslam
