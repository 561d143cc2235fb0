// map entry points reject inconsistent input with a PreconditionError.
#include <gtest/gtest.h>

#include "common/precondition.h"
#include "common/synthetic_camera.h"
#include "stillslam/map/frame.h"

namespace stillslam {
namespace {

TEST(MapPreconditions, FrameNeedsOneDepthPerKeypoint) {
  const std::vector<cv::KeyPoint> keypoints = {cv::KeyPoint(10, 10, 31), cv::KeyPoint(20, 20, 31)};
  const cv::Mat descriptors(2, 32, CV_8UC1, cv::Scalar(3));
  const std::vector<float> u_right(2, -1.f);
  const std::vector<float> one_depth(1, 2.f);
  test::expect_precondition(
      [&] { Frame(1, 0.1, test::synthetic_camera_setup(), keypoints, keypoints, descriptors, u_right, one_depth); },
      "src/stillslam/map/frame.cpp",
      "Frame: one depth per keypoint (-1 where unknown) (check failed: depth_.size() == keypoints_.size(), 1 vs 2)");
}

TEST(MapPreconditions, FrameNeedsOneDescriptorPerKeypoint) {
  const std::vector<cv::KeyPoint> keypoints = {cv::KeyPoint(10, 10, 31), cv::KeyPoint(20, 20, 31)};
  const std::vector<float> none(2, -1.f);
  test::expect_precondition(
      [&] { Frame(1, 0.1, test::synthetic_camera_setup(), keypoints, keypoints, cv::Mat(3, 32, CV_8UC1), none, none); },
      "src/stillslam/map/frame.cpp",
      "Frame: one descriptor row per keypoint (check failed: descriptors_.rows == keypoints_.size(), 3 vs 2)");
}

}  // namespace
}  // namespace stillslam
