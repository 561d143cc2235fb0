#pragma once
// Immutable snapshots of what the system is doing, posted by the tracking
// thread after each frame (publisher.h) for readers on other threads: a
// progress line, a viewer, a ROS 2 node. They hold copies (and cv::Mat
// references to images nobody writes any more), never map objects, so a
// reader needs no lock of the map.
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

namespace stillslam {

struct FrameSnapshot {
  std::size_t index = 0;        // in the input sequence
  std::uint64_t frame_id = 0;   // frames processed so far - 1
  double timestamp = 0;         // seconds
  std::string state;            // "not_initialized", "ok", "lost"
  std::string reason;           // how it was tracked or why not
  bool has_pose = false;
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();
  std::uint64_t map_id = 0;     // the active map after this frame
  // This frame started the map from an earlier one: the frames the start
  // waited on (published without a pose), posed now, oldest first (the ROS 2
  // node sends their pose, tf and path before this frame's).
  struct EarlierPose {
    std::size_t index = 0;  // the frame's input index
    double timestamp = 0;
    Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();
  };
  std::vector<EarlierPose> start_frames_posed;
  bool keyframe = false;        // the frame became a keyframe
  cv::Mat image;                // the colour (or gray) input image, shared
  cv::Mat1b dynamic_mask;       // the mask its features were kept out of (empty without segmentation)
  std::vector<cv::Point2f> keypoints;  // the features tracking saw (outside the mask)
  std::vector<bool> tracked;    // per keypoint: matched to a map point and not an outlier
  std::vector<cv::Point2f> removed_keypoints;  // features dropped because they fell in the dynamic mask
  struct Instance {
    std::string class_name;
    int class_id = -1;
    float score = 0;
    cv::Rect box;                    // input-image pixels
    std::vector<cv::Point> outline;  // largest external contour of the instance mask, input pixels
    bool dynamic = false;            // its class is in the dynamic set (its pixels were masked)
  };
  std::vector<Instance> instances;
  int keypoints_with_depth = 0;
  int detections = 0;           // detections of the segmenter (all classes)
  double mask_coverage = 0;     // fraction of the image in the dynamic mask
  double held_coverage = 0;     // of which held over from instances the segmenter lost (MaskHold)
  int matches = 0, inliers = 0;
  double total_ms = 0;          // this frame, frame building + tracking (+ synchronous mapping)
};

struct MapSnapshot {
  std::uint64_t map_id = 0;
  bool active = false;
  struct KeyFrame {
    std::uint64_t id = 0;
    Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();
  };
  std::vector<KeyFrame> keyframes;                   // by id
  std::vector<std::pair<std::size_t, std::size_t>> covisibility;  // indices into keyframes, strong edges
  std::vector<Eigen::Vector3f> points;               // map point positions
  std::vector<Eigen::Vector3d> trajectory;           // camera centres of the frames tracked in this map
};

struct AtlasSnapshot {
  std::uint64_t frame_id = 0;  // the frame after which it was taken
  std::vector<MapSnapshot> maps;
  std::uint64_t active_map_id = 0;
  int loops_closed = 0;
  int merges = 0;
  int new_maps = 0;
  std::size_t num_keyframes() const;
  std::size_t num_points() const;
};

}  // namespace stillslam
