#pragma once
// Motion-aware dynamic handling (issue #19): segmented instances keep stable
// ids across segmentations (segmentation/instance_ids.h) and are judged by
// their motion against the tracked camera motion (instance_motion_check.h).
// An instance of a dynamic class (a person) that agrees with the camera
// motion for its class's evidence window is left out of the mask, so its
// features track and make map points; an instance of any other class that
// moves is masked, and map points seen on it are culled. Points seen on a
// person kept as static live Motion.keptPointFrames frames only: a seated
// person sways and breathes, and an old point carries that into the pose.
// Masked instances are still watched through a small set of features
// extracted inside the mask and kept apart from tracking. An object whose
// matched features give no verdict (too few: a plain chair) is judged from
// depth instead (free_space_check.h, Motion.freeSpaceShare): where it is now
// against an earlier view, and with Motion.freeSpaceVacated also where it was
// then against this view (the share of its old place it has left).
//
// An instance that comes back under a new id (it left the view, was hidden,
// or its mask changed too much) where one of its class was last seen takes
// over that one's evidence and keeps its state (instance_places.h); so does an
// older id found far from where that id was and at another one's place (two
// ids swapped by mask overlap), while the one found at its own place blocks
// the hand-over to others.
//
// Per frame, in order: set_prediction() (System, before the frame is built),
// mask_for() (frame builder, fresh segmentation), collect() (frame builder,
// after extraction), judge_predicted() (frame builder, Motion.predictedCheck),
// on_tracked() (after tracking, map lock held). Frames without a fresh
// segmentation skip the stage.
#include <opencv2/core.hpp>

#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "stillslam/features/orb_features.h"
#include "stillslam/features/orb_options.h"
#include "stillslam/geometry/pinhole_camera.h"
#include "stillslam/map/frame.h"
#include "stillslam/segmentation/detection.h"
#include "stillslam/segmentation/instance_ids.h"
#include "stillslam/tracking/instance_motion_check.h"
#include "stillslam/tracking/instance_places.h"
#include "stillslam/tracking/motion_frame_stats.h"
#include "stillslam/tracking/motion_options.h"

namespace stillslam {

class MotionStage {
 public:
  // `orb`: the frame's extraction settings; the features inside masked
  // instances use them with options.instance_features as their budget.
  MotionStage(const PinholeCamera& camera, const OrbOptions& orb, std::vector<int> dynamic_class_ids,
              int dilation_px, MotionOptions options);

  // A fresh segmentation of this frame: stable ids for its instances; returns
  // the mask to extract outside of: the dynamic-class instances not judged
  // static and the other instances judged moving (both dilated), and `held`
  // (MaskHold's lost instances; may be empty).
  cv::Mat1b mask_for(const std::vector<Detection>& detections, const cv::Mat1b& held, cv::Size size);

  // After extraction outside `exclude`: the instances' features inside it for
  // the check (`depth`: CV_32F metres or empty), and this frame's counts of
  // features removed and kept (`kept`: the frame's keypoints, `removed`: the
  // extractor's masked-out corners). No-op without a mask_for() this frame.
  void collect(const cv::Mat& gray, const cv::Mat& depth, const cv::Mat1b& exclude,
               const std::vector<cv::KeyPoint>& kept, const std::vector<cv::Point2f>& removed,
               MotionFrameStats& stats);

  // After tracking (the caller holds the map's update mutex): the check on
  // this frame with its tracked pose; map points on moving instances are
  // culled, and those on a kept person past Motion.keptPointFrames. Lost
  // tracking drops all evidence. Returns the map points culled.
  int on_tracked(const Frame& frame, bool tracked);

  // With Motion.keptFeatures, after mask_for() this frame: the mask the
  // frame's own extraction leaves out (mask_for()'s and the people kept as
  // static, dilated alike), so the frame's features go to the rest of the
  // view; empty when no person is kept (extract outside mask_for()'s mask).
  cv::Mat1b extraction_mask() const { return pending_ ? extraction_mask_ : cv::Mat1b(); }
  // The kept people's own features (up to Motion.keptFeatures, or their
  // area's share with Motion.keptFeaturesAreaFactor, on their pixels) for
  // the frame; empty without extraction_mask().
  OrbFeatures kept_features(const cv::Mat& gray) const;

  // The next frame's pose as tracking predicts it (its motion model, else the
  // last pose), before the frame is built; none after a loss. Taken by the
  // next mask_for().
  void set_prediction(std::optional<Eigen::Isometry3d> T_cam_world) { next_prediction_ = std::move(T_cam_world); }
  // With Motion.predictedCheck, after collect(): the unmasked objects
  // (Motion.watchObjects) judged against the earlier view at this frame's
  // predicted pose, from their features and, without a verdict there, from
  // depth (Motion.freeSpaceShare), as on_tracked() judges them at the tracked
  // pose. Those found moving are masked from this frame on; returns their
  // mask (dilated) for the frame's keypoints to leave out, empty when none.
  cv::Mat1b judge_predicted(const std::vector<cv::KeyPoint>& keypoints, const cv::Mat& descriptors,
                            MotionFrameStats& stats);

  bool is_static(std::uint32_t id) const { return check_.is_static(id); }
  bool is_moving(std::uint32_t id) const { return moving_.count(id) > 0; }
  // This frame's features of its own on unmasked objects (Motion.watchObjects), after collect().
  int watched_features() const {
    int n = 0;
    for (std::uint32_t id : inside_.instance) n += watched_ids_.count(id) > 0;
    return n;
  }
  void reset();

 private:
  // 0: background; else the instance id at the pixel (rounded, clamped).
  std::uint32_t label_at(const cv::Point2f& p) const;
  bool masked(std::uint32_t id) const;
  std::uint32_t evidence_id(std::uint32_t stable) const;
  // Matches this frame's new (or swapped) instances with the places of
  // earlier ones (InstancePlaces::assign; relabelling them in `frame_labels`
  // and the stage's state) and records where every instance is now.
  void place_instances(const Frame& frame, std::vector<std::uint32_t>& frame_labels);
  // Objects without a verdict from their features this frame, judged from
  // depth against the frame span judged frames earlier (free_space_check.h).
  void judge_objects_by_depth(const Frame& frame, const MotionCheckResult& r);
  // The check's frame: `f` holds the pixels, depth and instance ids of the
  // frame's features `rows` (of `descriptors`); adds their descriptors, the
  // pose, the instances' classes and the watched objects' own features (collect()).
  void complete_check_frame(MotionCheckFrame& f, const Eigen::Isometry3d& T_cam_world, const cv::Mat& descriptors,
                            const std::vector<int>& rows) const;
  // The check's state of instance `id` this frame; null when it had no match.
  static const InstanceMotionState* state_of(const MotionCheckResult& r, std::uint32_t id);
  struct DepthView;
  // Of `ids` (0, the background, among them), those found moving from depth
  // between this frame's depth image at T_cam_world and the earlier view.
  std::set<std::uint32_t> moving_by_depth(const Eigen::Isometry3d& T_cam_world, const DepthView& earlier,
                                          const std::set<std::uint32_t>& ids) const;

  PinholeCamera camera_;
  OrbOptions orb_;  // the frame's extraction settings (instance_box_features.h shares out the budget)
  int frame_features_;  // the frame's own ORBextractor.nFeatures
  std::vector<int> dynamic_class_ids_;
  int dilation_px_;
  MotionOptions options_;
  InstanceIds ids_;
  InstanceMotionCheck check_;
  std::set<std::uint32_t> moving_;  // instances of non-dynamic classes judged moving
  InstancePlaces places_;
  std::map<std::uint32_t, std::uint32_t> alias_;  // segmenter's stable id -> the earlier instance it was found to be
  std::map<std::uint32_t, int> age_;              // judged frames since each stable id appeared
  std::int64_t judged_ = 0;                       // frames judged since the last reset
  // Map point id -> the frame it was first matched on a person kept as static (Motion.keptPointFrames).
  std::map<std::uint64_t, std::uint64_t> kept_since_;
  std::optional<Eigen::Isometry3d> next_prediction_;  // set_prediction()
  // This frame (between mask_for() and on_tracked()).
  bool pending_ = false;
  std::optional<Eigen::Isometry3d> prediction_;
  cv::Mat1i labels_;
  std::map<std::uint32_t, std::string> categories_;      // by evidence id
  std::map<std::uint32_t, std::uint32_t> stable_of_;     // evidence id -> stable id
  std::set<std::uint32_t> dynamic_ids_;  // of a dynamic class
  std::vector<cv::Rect> boxes_;          // of the masked and watched instances, where their features are extracted
  cv::Mat1b watched_;                    // pixels of the unmasked objects (options_.watch_objects)
  cv::Mat1b kept_pixels_;                // of the people kept as static (Motion.keptFeatures)
  std::vector<cv::Rect> kept_boxes_;
  int kept_budget_ = 0;                  // this frame's for the kept people (Motion.keptFeatures*)
  cv::Mat1b extraction_mask_;            // mask_for()'s plus the kept people, dilated (Motion.keptFeatures)
  std::set<std::uint32_t> watched_ids_;
  std::map<std::uint32_t, Eigen::Vector3d> mask_points_;  // camera frame, from the depth image (collect())
  std::map<std::uint32_t, int> mask_pixels_;              // pixels with depth of each instance
  MotionCheckFrame inside_;              // the features inside the mask (pixels undistorted)
  cv::Mat depth_;                        // this frame's depth image (collect(); empty without one)
  // The last free_space_span() + 1 judged frames (Motion.freeSpaceShare):
  // pose, depth image and, with Motion.freeSpaceNearer, the masked people's pixels.
  struct DepthView {
    Eigen::Isometry3d T_cam_world;
    cv::Mat depth;
    cv::Mat1b people;
    cv::Mat1i labels;  // with Motion.freeSpaceVacated: the instances then (evidence ids)
  };
  std::deque<DepthView> depth_history_;
};

}  // namespace stillslam
