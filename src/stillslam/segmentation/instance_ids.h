#pragma once
// Stable ids for segmented instances: a detector numbers its instances anew
// in every frame, but evidence about an instance (is this person still? see
// tracking/motion_evidence.h) must follow the same person from frame to
// frame. Each new segmentation's instances are matched to the tracked ones
// (their last masks, carried to this frame, e.g. by MaskPropagator) by mask
// overlap within the same class, best overlap first; a matched instance keeps
// its id, an unmatched one gets a new id, and a tracked instance not seen for
// `forget_after` segmentations is dropped.
#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

namespace stillslam {

struct InstanceIdOptions {
  double min_iou = 0.3;   // overlap needed to be the same instance
  int forget_after = 3;   // segmentations an instance may be missed before its id is dropped
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

struct TrackedInstance {
  std::uint32_t id = 0;
  int class_id = -1;
  cv::Mat1b mask;  // frame-size, 255 inside: where it is now
  int missed = 0;  // segmentations since it was last matched
};

class InstanceIds {
 public:
  explicit InstanceIds(InstanceIdOptions options = {});

  // One segmentation: masks (frame-size, 255 inside) and class ids of its
  // instances. Returns the id of each, in the same order. The tracked
  // instances take the new masks; the missed ones keep theirs.
  std::vector<std::uint32_t> assign(const std::vector<cv::Mat1b>& masks, const std::vector<int>& class_ids);

  // Replaces the masks of tracked instances by where they are now (e.g.
  // propagated to the frame about to be segmented), by id; unknown ids are ignored.
  void move(std::uint32_t id, cv::Mat1b mask);

  const std::vector<TrackedInstance>& tracked() const { return tracked_; }

 private:
  InstanceIdOptions options_;
  std::vector<TrackedInstance> tracked_;
  std::uint32_t next_id_ = 1;
};

// Intersection over union of two binary masks of the same size (0 when both are empty).
double mask_iou(const cv::Mat1b& a, const cv::Mat1b& b);

}  // namespace stillslam
