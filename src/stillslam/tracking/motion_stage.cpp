#include "stillslam/tracking/motion_stage.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "stillslam/features/brief_pattern.h"
#include "stillslam/map/map_point.h"
#include "stillslam/segmentation/dynamic_mask.h"
#include "stillslam/tracking/instance_box_features.h"

namespace stillslam {

namespace {

// Checked first, so a bad value names its Motion key.
OrbOptions instance_orb(OrbOptions orb, const MotionOptions& options) {
  options.check();
  orb.n_features = options.instance_features;
  orb.check();
  return orb;
}

// Context around an instance's box for the ORB patch and the FAST border.
constexpr int kBoxPad = 2 * (BriefPattern::kRadius + 1);

}  // namespace

MotionStage::MotionStage(const PinholeCamera& camera, const OrbOptions& orb, std::vector<int> dynamic_class_ids,
                         int dilation_px, MotionOptions options)
    : camera_(camera),
      orb_(instance_orb(orb, options)),
      dynamic_class_ids_(std::move(dynamic_class_ids)),
      dilation_px_(dilation_px),
      options_(std::move(options)),
      ids_(InstanceIdOptions{.min_iou = options_.min_iou}),
      check_(camera, options_.check_options()) {}

void MotionStage::reset() {
  check_.reset();
  moving_.clear();
}

std::uint32_t MotionStage::label_at(const cv::Point2f& p) const {
  if (labels_.empty()) return 0;
  const int u = std::clamp(static_cast<int>(std::lround(p.x)), 0, labels_.cols - 1);
  const int v = std::clamp(static_cast<int>(std::lround(p.y)), 0, labels_.rows - 1);
  return static_cast<std::uint32_t>(labels_(v, u));
}

bool MotionStage::masked(std::uint32_t id) const {
  return dynamic_ids_.count(id) ? !check_.is_static(id) : moving_.count(id) > 0;
}

cv::Mat1b MotionStage::mask_for(const std::vector<Detection>& detections, const cv::Mat1b& held, cv::Size size) {
  pending_ = true;
  labels_ = cv::Mat1i::zeros(size);
  categories_.clear();
  dynamic_ids_.clear();
  inside_ = MotionCheckFrame{};
  boxes_.clear();
  std::vector<cv::Mat1b> masks;
  std::vector<int> classes;
  for (const Detection& d : detections) {
    // The same mask the class-only path makes of it (its box without a mask).
    masks.push_back(dynamic_instances({d}, {d.class_id}, size).front());
    classes.push_back(d.class_id);
  }
  const std::set<std::uint32_t> before = [&] {
    std::set<std::uint32_t> s;
    for (const TrackedInstance& t : ids_.tracked()) s.insert(t.id);
    return s;
  }();
  const std::vector<std::uint32_t> ids = ids_.assign(masks, classes);
  // Instances whose ids were dropped take their evidence with them.
  std::set<std::uint32_t> alive;
  for (const TrackedInstance& t : ids_.tracked()) alive.insert(t.id);
  for (std::uint32_t id : before) {
    if (alive.count(id)) continue;
    check_.forget(id);
    moving_.erase(id);
  }
  std::vector<cv::Mat1b> masked_instances;
  for (std::size_t n = 0; n < masks.size(); ++n) {
    const std::uint32_t id = ids[n];
    labels_.setTo(static_cast<int>(id), masks[n]);
    categories_[id] = detections[n].class_name;
    if (std::find(dynamic_class_ids_.begin(), dynamic_class_ids_.end(), classes[n]) != dynamic_class_ids_.end()) {
      dynamic_ids_.insert(id);
    }
    if (masked(id)) {
      masked_instances.push_back(masks[n]);
      boxes_.push_back(cv::boundingRect(masks[n]));
    }
  }
  cv::Mat1b out = dynamic_mask(masked_instances, size, dilation_px_);
  if (!held.empty()) cv::bitwise_or(out, held, out);
  return out;
}

void MotionStage::collect(const cv::Mat& gray, const cv::Mat& depth, const cv::Mat1b& exclude,
                          const std::vector<cv::KeyPoint>& kept, const std::vector<cv::Point2f>& removed,
                          MotionFrameStats& stats) {
  if (!pending_) return;
  stats.judged = true;
  for (std::uint32_t id : dynamic_ids_) stats.static_instances += check_.is_static(id);
  for (const auto& [id, category] : categories_) stats.moving_instances += !dynamic_ids_.count(id) && moving_.count(id);
  for (const cv::Point2f& p : removed) {
    const std::uint32_t id = label_at(p);
    if (id != 0 && !dynamic_ids_.count(id) && moving_.count(id)) {
      ++stats.features_removed_by_motion;
    } else {
      ++stats.features_removed_by_class;
    }
  }
  for (const cv::KeyPoint& kp : kept) {
    const std::uint32_t id = label_at(kp.pt);
    stats.features_kept_by_motion += id != 0 && dynamic_ids_.count(id);
  }
  if (exclude.empty() || cv::countNonZero(exclude) == 0) return;
  // The masked instances' boxes only: their own small budget, apart from the frame's.
  const OrbFeatures f = extract_in_boxes(orb_, orb_.n_features, gray, exclude,
                                         merge_instance_boxes(boxes_, kBoxPad, gray.size()));
  const std::vector<cv::KeyPoint> undistorted = camera_.undistort(f.keypoints);
  std::vector<int> rows;
  for (std::size_t i = 0; i < f.keypoints.size(); ++i) {
    const std::uint32_t id = label_at(f.keypoints[i].pt);
    if (id == 0) continue;  // the dilation margin or a held mask: not an instance's own pixel
    const cv::Point p(std::clamp(static_cast<int>(std::lround(f.keypoints[i].pt.x)), 0, gray.cols - 1),
                      std::clamp(static_cast<int>(std::lround(f.keypoints[i].pt.y)), 0, gray.rows - 1));
    const float z = depth.empty() ? 0.f : depth.at<float>(p);
    inside_.pixels.emplace_back(undistorted[i].pt.x, undistorted[i].pt.y);
    inside_.depth.push_back(z > 0 ? z : -1.f);
    inside_.instance.push_back(id);
    rows.push_back(static_cast<int>(i));
  }
  inside_.descriptors.create(static_cast<int>(rows.size()), f.descriptors.cols, f.descriptors.type());
  for (std::size_t k = 0; k < rows.size(); ++k) f.descriptors.row(rows[k]).copyTo(inside_.descriptors.row(static_cast<int>(k)));
  stats.instance_features = static_cast<int>(rows.size());
}

int MotionStage::on_tracked(const Frame& frame, bool tracked) {
  if (!pending_) return 0;
  pending_ = false;
  if (!tracked || !frame.has_pose()) {
    reset();
    return 0;
  }
  MotionCheckFrame f;
  f.T_cam_world = frame.T_cam_world();
  f.categories = categories_;
  std::vector<std::uint32_t> frame_labels(frame.size());
  for (std::size_t i = 0; i < frame.size(); ++i) {
    frame_labels[i] = label_at(frame.keypoints_raw()[i].pt);
    const cv::Point2f& p = frame.keypoints()[i].pt;
    f.pixels.emplace_back(p.x, p.y);
    f.depth.push_back(frame.depth(i));
    f.instance.push_back(frame_labels[i]);
  }
  f.pixels.insert(f.pixels.end(), inside_.pixels.begin(), inside_.pixels.end());
  f.depth.insert(f.depth.end(), inside_.depth.begin(), inside_.depth.end());
  f.instance.insert(f.instance.end(), inside_.instance.begin(), inside_.instance.end());
  if (inside_.descriptors.empty()) {
    f.descriptors = frame.descriptors().clone();
  } else if (frame.descriptors().empty()) {
    f.descriptors = inside_.descriptors;
  } else {
    cv::vconcat(frame.descriptors(), inside_.descriptors, f.descriptors);
  }
  const MotionCheckResult r = check_.add(std::move(f));
  for (const InstanceMotionState& s : r.instances) {
    const auto id = static_cast<std::uint32_t>(s.id);
    if (dynamic_ids_.count(id)) continue;
    if (s.verdict == MotionVerdict::Disagrees) moving_.insert(id);
    if (s.is_static) moving_.erase(id);
  }
  // Map points seen on an instance that is now judged moving leave the map;
  // those seen on a person kept as static are flagged so no saved map holds them.
  int culled = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (frame_labels[i] == 0) continue;
    const MapPointPtr& mp = frame.map_point(i);
    if (!mp || mp->is_bad()) continue;
    if (masked(frame_labels[i])) {
      mp->set_bad();
      ++culled;
    } else if (dynamic_ids_.count(frame_labels[i])) {
      mp->mark_on_dynamic_instance();
    }
  }
  return culled;
}

}  // namespace stillslam
