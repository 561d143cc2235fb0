#pragma once
// Segmentation runs at its own rate, slower than the camera; MaskPropagator
// carries the last fresh instance masks to the frames in between. Per instance:
// points inside the (eroded) mask are moved by the predicted camera motion with
// their depth, then tracked by sparse pyramidal LK optical flow from there (the
// instance's own motion); a robust 2D motion model (median translation, or a
// RANSAC similarity when enough points agree) warps the mask. The union mask is
// dilated by a margin that grows with the mask's age. After the first call,
// propagation chains frame to frame (the last propagated masks and points).
// Images are undistorted (rectified for stereo), so the camera is a pinhole.
// A mask cut by the image border is taken to go on beyond it when warped.
// Not thread-safe: one owner calls reset() and propagate().
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace stillslam {

// Undistorted pinhole intrinsics (segmentation/ does not depend on geometry/:
// pass PinholeCamera's fx(), fy(), cx(), cy()).
struct MaskPropagationCamera {
  double fx = 0, fy = 0, cx = 0, cy = 0;
  double bf = 0;  // stereo: fx times the baseline (metres); depth = bf / disparity. 0: not stereo
};

// MaskPropagation.* settings.
struct MaskPropagationOptions {
  // Motion used: 0 none (hold the old mask, margin only), 1 camera motion only,
  // 2 camera motion then optical flow (the default).
  int mode = 2;
  int margin_px = 4;             // union dilation at age 0 (pixels)
  double margin_px_per_frame = 1.0;  // added per frame of age
  int max_margin_px = 30;        // margin cap
  int points_per_instance = 60;  // good features to track per instance
  int min_point_distance_px = 6; // between features
  int erode_px = 3;              // features are taken inside the mask eroded by this (border points see background)
  int lk_window_px = 15;         // LK window side (odd)
  int lk_levels = 3;             // LK pyramid levels above the base
  double fb_max_error_px = 1.0;  // forward-backward check (0: off)
  int min_tracked_points = 5;    // fewer: the instance falls back to camera motion (or none)
  int min_points_similarity = 10;  // from this many tracked points on: RANSAC similarity, else median translation
  double ransac_threshold_px = 2.0;
  double min_depth_m = 0.1, max_depth_m = 20.0;  // depths outside are unknown
  // An instance's 8-connected parts of at least this many pixels are tracked
  // apart (the smaller ones together as one more part); 0: each instance whole.
  // One mask over several people (merged detections, a union of masks) then
  // follows each person instead of fitting one motion to all.
  int split_min_px = 400;
  // Stereo (a rectified right image given with the fresh frame, the camera's
  // bf > 0): each fresh instance's depth is the median of a block-matching
  // disparity (cv::StereoBM) over its mask, instead of the median of the
  // sparse depths under it; flow points without a depth of their own take
  // theirs from it too. Sparse keypoint depths are few inside a person
  // whose keypoints a carried mask removed; the dense ones are not.
  bool stereo_block_depth = false;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// A fresh segmentation of one frame.
struct SegmentedFrame {
  std::uint64_t frame_id = 0;
  cv::Mat1b gray;  // the segmented frame's image
  // Metres; 0 or non-finite = unknown. May be sparse (stereo: keypoint depths
  // written at their pixels); an instance's pixels without depth use the median
  // depth of those with depth. Empty: no depth (camera motion then unused).
  cv::Mat1f depth;
  // Stereo: the rectified right image (empty: none). Used with
  // stereo_block_depth and the camera's bf.
  cv::Mat1b right;
  std::vector<cv::Mat1b> instances;  // frame-size, 255 inside, undilated; one per dynamic instance
  std::optional<Eigen::Isometry3d> T_cam_world;
};

enum class InstanceMotion { none, camera, flow };

struct PropagatedInstance {
  cv::Mat1b mask;  // frame-size, undilated
  InstanceMotion motion = InstanceMotion::none;
  int tracked_points = 0;  // flow points that passed the checks (inliers of the motion model)
  float depth = 0;  // the instance's median depth in this frame (metres; 0: unknown)
};

struct PropagatedMasks {
  std::vector<PropagatedInstance> instances;  // the fresh frame's non-empty instances (split into parts: split_min_px), in order
  cv::Mat1b union_mask;  // union of the instances dilated by margin(age); frame-size (zeros when no instance)
  int age = 0;           // frame_id - the fresh frame's id
  int margin_px = 0;
};

class MaskPropagator {
 public:
  // Throws OptionError for bad options, stillslam::Error for fx or fy <= 0.
  MaskPropagator(const MaskPropagationCamera& camera, MaskPropagationOptions options);

  // Starts from a fresh segmentation (replaces everything carried so far).
  // Throws stillslam::Error for an empty gray image, or instance / depth sizes
  // that differ from it.
  void reset(SegmentedFrame fresh);

  // Carries the last masks to frame `frame_id` (> the last frame propagated to;
  // the first call after reset may span several frames). `depth` as in
  // SegmentedFrame (may be empty); `T_cam_world` the predicted pose of this
  // frame (nullopt: no camera motion is used). Throws stillslam::Error when
  // empty() or for a gray image of another size, a frame_id not after the last
  // one, or a depth of another size.
  PropagatedMasks propagate(std::uint64_t frame_id, const cv::Mat1b& gray, const cv::Mat1f& depth,
                            const std::optional<Eigen::Isometry3d>& T_cam_world);

  // After tracking: the refined pose of the frame last propagated to, so the
  // next step's camera motion starts from it.
  void set_last_pose(const Eigen::Isometry3d& T_cam_world);

  bool empty() const { return gray_.empty(); }  // no fresh segmentation yet
  const MaskPropagationOptions& options() const { return options_; }
  int margin_px(int age) const;  // margin_px + margin_px_per_frame * age, capped

 private:
  struct Track {
    cv::Mat1b mask;                   // the instance in the last frame (undilated)
    std::vector<cv::Point2f> points;  // features inside it in the last frame
    std::vector<float> depth;         // their depth (0: unknown)
    float median_depth = 0;           // of the instance (0: unknown)
  };
  MaskPropagationCamera camera_;
  MaskPropagationOptions options_;
  cv::Mat1b gray_;  // the last frame (fresh or propagated to)
  std::vector<cv::Mat> pyramid_;  // its LK pyramid (empty until needed)
  std::uint64_t frame_id_ = 0;
  std::uint64_t fresh_id_ = 0;
  std::optional<Eigen::Isometry3d> T_cam_world_;
  std::vector<Track> tracks_;
};

}  // namespace stillslam
