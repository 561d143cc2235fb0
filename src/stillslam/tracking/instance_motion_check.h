#pragma once
// The motion check of segmented instances over a few frames: each frame
// brings its features outside every instance (the background) and those
// inside each instance (with the instance's stable id, segmentation/
// instance_ids.h), with its tracked pose. The features are matched with
// those of the frame `span` frames earlier (the background with the
// background, an instance with the same instance or with what was background
// then), each match gets its
// residual against the camera motion between the two poses
// (motion_residual.h: with the earlier frame's depth, else epipolar), and
// MotionEvidence judges each instance against the background of the same
// frame pair. A span of several frames lets slow motion add up above the noise.
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include <cstdint>
#include <deque>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "stillslam/geometry/pinhole_camera.h"
#include "stillslam/tracking/motion_evidence.h"

namespace stillslam {

struct InstanceMotionCheckOptions {
  int span = 6;                // frames between the two views compared
  int max_hamming = 50;        // descriptor distance of a match
  float ratio = 0.8f;          // best < ratio * second best
  // A feature is matched only with the earlier frame's features whose
  // position predicted by the camera motion (with their depth, else at
  // infinity) lies within this many pixels (each axis); 0: with all of them.
  double window_px = 0;
  MotionEvidenceOptions evidence;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// The features of one frame as the check needs them (pixels undistorted).
struct MotionCheckFrame {
  Eigen::Isometry3d T_cam_world = Eigen::Isometry3d::Identity();  // tracked
  std::vector<Eigen::Vector2d> pixels;
  std::vector<float> depth;              // metres, <= 0: none
  std::vector<std::uint32_t> instance;   // 0: background, else the instance's stable id
  cv::Mat descriptors;                   // one 32-byte ORB row per feature
  std::map<std::uint32_t, std::string> categories;  // class name of each instance in this frame
  std::set<std::uint32_t> objects;  // instances judged as objects (MotionEvidenceOptions::object_moving_*)
};

struct MotionCheckResult {
  bool compared = false;   // false until `span` frames are there
  int background_matches = 0;
  double background_median_px = 0;
  std::vector<InstanceMotionState> instances;  // those with a match this frame
  std::map<std::uint32_t, std::vector<double>> residuals;  // per instance, for diagnostics
  std::vector<double> background_residuals;
};

class InstanceMotionCheck {
 public:
  InstanceMotionCheck(const PinholeCamera& camera, InstanceMotionCheckOptions options = {});

  // Adds the frame and compares it with the one `span` frames before it.
  // Throws stillslam::Error when the per-feature vectors differ in length.
  MotionCheckResult add(MotionCheckFrame frame);

  // The verdicts add(frame) would give (`frame` against the one that would
  // then lie `span` frames before it), with nothing kept or changed: a
  // frame judged at a predicted pose before it is tracked. Not compared
  // (empty) until span frames are there.
  MotionCheckResult peek(const MotionCheckFrame& frame) const;

  bool is_static(std::uint32_t id) const { return evidence_.is_static(static_cast<int>(id)); }
  void forget(std::uint32_t id) { evidence_.forget(static_cast<int>(id)); }
  // Whether the instance has been judged at all (has evidence, even none yet).
  bool has_evidence(std::uint32_t id) const { return evidence_.has(static_cast<int>(id)); }
  // The frames kept so far call instance `from` `to` (an instance found to be
  // one seen before, instance_places.h); `from`'s own evidence is dropped.
  void relabel(std::uint32_t from, std::uint32_t to);
  // Starts over (a new map, tracking lost): frames kept so far are dropped, the evidence too.
  void reset();

 private:
  // The residuals of cur's matches with prev (background and per instance).
  void compare(const MotionCheckFrame& prev, const MotionCheckFrame& cur, MotionCheckResult& result) const;
  static void check_lengths(const MotionCheckFrame& frame);

  PinholeCamera camera_;
  InstanceMotionCheckOptions options_;
  MotionEvidence evidence_;
  std::deque<MotionCheckFrame> frames_;
};

}  // namespace stillslam
