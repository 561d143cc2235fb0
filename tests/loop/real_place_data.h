#pragma once
// Real-data place recognition fixture: the committed vocabulary
// (vocab/orb_vocabulary.bin) and the EuRoC micro clip's rectified stereo
// frames as ORB keyframes (no depth, identity pose: only their features
// matter for place recognition).
#include <filesystem>
#include <memory>
#include <vector>

#include "../features/euroc_stereo.h"
#include "stillslam/features/orb_extractor.h"
#include "stillslam/map/frame.h"
#include "stillslam/map/map.h"
#include "stillslam/place/vocabulary.h"

namespace stillslam::test {

inline std::filesystem::path vocabulary_path(const std::filesystem::path& source_dir) {
  return source_dir / "vocab" / "orb_vocabulary.bin";
}
inline std::filesystem::path euroc_micro_mav0(const std::filesystem::path& shared_dir) {
  return shared_dir / "data" / "euroc_V1_01_micro" / "mav0";
}

class OrbKeyframeFactory {
 public:
  explicit OrbKeyframeFactory(double fx, double cx, double cy, int width, int height) : extractor_(OrbOptions{}) {
    const CameraCalibration calib = pinhole_calibration(fx, fx, cx, cy, width, height);
    setup_ = std::make_shared<CameraSetup>(PinholeCamera(calib, 0.0), ScalePyramid(OrbOptions{}), 0.0);
  }

  Frame frame(std::uint64_t id, const cv::Mat& gray) const {
    OrbFeatures f = extractor_.extract(gray);
    std::vector<float> none(f.size(), -1.f);
    return Frame(id, 0.05 * static_cast<double>(id), setup_, f.keypoints, f.keypoints, f.descriptors, none, none);
  }
  KeyFramePtr keyframe(Map& map, std::uint64_t id, const cv::Mat& gray) const {
    Frame fr = frame(id, gray);
    fr.set_pose(Eigen::Isometry3d::Identity());
    return map.create_keyframe(fr);
  }

 private:
  OrbExtractor extractor_;
  std::shared_ptr<CameraSetup> setup_;
};

}  // namespace stillslam::test
