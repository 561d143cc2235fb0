#pragma once
// Final trajectory refinement. A frame's pose is estimated once, against the
// map as it was at that instant; a young map (right after initialization, or
// while people hide most of the view) can be off by several millimetres, and
// the frame keeps that error through its keyframe-relative pose. Here each
// tracked frame keeps its inlier observations, and when the trajectory is
// read its pose is re-estimated by motion-only BA against the same map points
// as they are then (after local BA, fusion, loop correction): every frame is
// registered against the final map, as in structure from motion.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "stillslam/geometry/pinhole_camera.h"
#include "stillslam/map/frame.h"
#include "stillslam/optimize/pose_optimizer.h"

namespace stillslam {

struct TrajectoryRefinementOptions {
  // Off: the trajectory is the tracked poses, and frames keep nothing
  // (each tracked frame costs 32 bytes per inlier, a point pointer and its
  // keypoint: ~16 kB at 500).
  bool enabled = true;
  // Fewer surviving observations (or inliers after the re-estimate) than
  // this: the frame keeps its tracked pose.
  int min_inliers = 30;
  // Points on a person the motion stage kept as static
  // (MapPoint::on_dynamic_instance, issue #19) leave the re-estimate when at
  // least min_inliers other observations remain (System sets it from
  // Motion.enabled and Motion.keptPointsOutOfPose).
  bool leave_out_kept_points = false;
  // Those points, when they take part, count with this many times their
  // keypoint's sigma (System sets it from Motion.keptPointSigma).
  double kept_point_sigma = 1;
  PoseOptimizerOptions pose;
};

// A tracked frame's inlier observations of map points.
struct FrameObservations {
  struct Observation {
    float x = 0, y = 0;   // undistorted keypoint
    float u_right = -1;   // >= 0: stereo / RGB-D observation
    std::uint8_t level = 0;
  };
  std::vector<MapPointPtr> points;  // same order as observations
  std::vector<Observation> observations;
};

// The frame's matched map points that are inliers and real map points (not
// the tracker's temporary odometry points).
FrameObservations collect_frame_observations(const Frame& frame);

// Motion-only BA from T_cam_world against the observed points' current
// positions. Points fused into others count as the point that replaced them;
// culled points are left out, and so are points on a kept person when the
// options say so and enough others remain. nullopt when too few observations or inliers
// remain (keep the tracked pose). The caller holds the points' map lock.
std::optional<Eigen::Isometry3d> refine_frame_pose(const CameraSetup& setup, const Eigen::Isometry3d& T_cam_world,
                                                   const FrameObservations& frame,
                                                   const TrajectoryRefinementOptions& options);

}  // namespace stillslam
