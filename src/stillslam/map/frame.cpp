#include "stillslam/map/frame.h"

#include "stillslam/core/check.h"
#include "stillslam/map/keyframe.h"

namespace stillslam {

Frame::Frame(std::uint64_t id, double timestamp, std::shared_ptr<const CameraSetup> setup,
             std::vector<cv::KeyPoint> keypoints_raw, std::vector<cv::KeyPoint> keypoints,
             cv::Mat descriptors, std::vector<float> u_right, std::vector<float> depth)
    : id_(id),
      timestamp_(timestamp),
      setup_(std::move(setup)),
      keypoints_raw_(std::move(keypoints_raw)),
      keypoints_(std::move(keypoints)),
      descriptors_(std::move(descriptors)),
      u_right_(std::move(u_right)),
      depth_(std::move(depth)),
      map_points_(keypoints_.size()),
      outlier_(keypoints_.size(), 0) {
  STILLSLAM_CHECK(setup_ != nullptr, "Frame: pass the camera setup");
  STILLSLAM_CHECK_EQ(keypoints_raw_.size(), keypoints_.size(), "Frame: one raw keypoint per undistorted keypoint");
  STILLSLAM_CHECK_EQ(descriptors_.rows, keypoints_.size(), "Frame: one descriptor row per keypoint");
  STILLSLAM_CHECK_EQ(u_right_.size(), keypoints_.size(), "Frame: one u_right per keypoint (-1 where unknown)");
  STILLSLAM_CHECK_EQ(depth_.size(), keypoints_.size(), "Frame: one depth per keypoint (-1 where unknown)");
  grid_ = std::make_shared<FeatureGrid>(keypoints_, setup_->camera.undistorted_bounds());
}

int Frame::num_with_depth() const {
  int n = 0;
  for (float z : depth_) n += z > 0 ? 1 : 0;
  return n;
}

void Frame::clear_map_points() {
  for (auto& mp : map_points_) mp.reset();
  std::fill(outlier_.begin(), outlier_.end(), 0);
}

int Frame::num_matches() const {
  int n = 0;
  for (std::size_t i = 0; i < map_points_.size(); ++i) n += (map_points_[i] && !outlier_[i]) ? 1 : 0;
  return n;
}

std::optional<Eigen::Vector3d> Frame::unproject(std::size_t i) const {
  const float z = depth_[i];
  if (z <= 0 || !T_cam_world_) return std::nullopt;
  const cv::Point2f& pt = keypoints_[i].pt;
  return T_cam_world_->inverse() * setup_->camera.unproject(Eigen::Vector2d(pt.x, pt.y), z);
}

void Frame::set_dynamic_mask(cv::Mat1b mask) {
  dynamic_mask_ = std::move(mask);
  masked_fraction_ = dynamic_mask_.empty() ? 0.f
                                           : static_cast<float>(cv::countNonZero(dynamic_mask_)) /
                                                 static_cast<float>(dynamic_mask_.total());
}

}  // namespace stillslam
