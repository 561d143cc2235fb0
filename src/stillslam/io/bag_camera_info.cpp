#include "stillslam/io/bag_camera_info.h"

#include <spdlog/spdlog.h>

#include "stillslam/core/error.h"
#include "stillslam/io/ros2_message_codec.h"

namespace stillslam {

std::string camera_info_topic(const std::string& image_topic) {
  const auto slash = image_topic.rfind('/');
  return (slash == std::string::npos ? std::string() : image_topic.substr(0, slash)) + "/camera_info";
}

ros2::CameraInfo read_first_camera_info(const BagReader& bag, const std::string& topic) {
  const auto id = bag.find_topic(topic);
  if (!id || bag.topics()[*id].type != ros2::kCameraInfoType || bag.topics()[*id].message_count == 0) {
    std::string infos;
    for (const BagTopic& t : bag.topics()) {
      if (t.type == ros2::kCameraInfoType) infos += (infos.empty() ? "" : ", ") + t.name;
    }
    throw Error(bag.file().string() + ": --camera-info-from-bag needs " + ros2::kCameraInfoType + " messages on " +
                topic + " (the image topic's sibling camera_info); the bag's CameraInfo topics: " +
                (infos.empty() ? "none (use a settings file with the calibration instead)" : infos));
  }
  for (std::size_t i = 0; i < bag.messages().size(); ++i) {
    if (bag.messages()[i].topic == *id) {
      return ros2::decode_camera_info(bag.read(i), bag.file().string() + ": topic " + topic + " message " + std::to_string(i));
    }
  }
  throw Error(bag.file().string() + ": " + topic + " has no messages");
}

CameraCalibration calibration_from(const ros2::CameraInfo& info, const std::string& topic) {
  CameraCalibration c;
  c.fx = info.k[0];
  c.fy = info.k[4];
  c.cx = info.k[2];
  c.cy = info.k[5];
  c.width = static_cast<int>(info.width);
  c.height = static_cast<int>(info.height);
  if (c.fx <= 0 || c.fy <= 0 || c.width <= 0 || c.height <= 0) {
    throw Error("topic " + topic + ": CameraInfo has no calibration (K[0] / K[4] or the image size is 0): calibrate "
                "the camera or give a settings file");
  }
  if (info.distortion_model == "equidistant") {
    c.model = CameraModel::KannalaBrandt8;
    c.distortion.assign(info.d.begin(), info.d.begin() + static_cast<long>(std::min<std::size_t>(4, info.d.size())));
  } else if (info.distortion_model == "plumb_bob" || info.distortion_model == "rational_polynomial" ||
             info.distortion_model.empty()) {
    c.distortion.assign(info.d.begin(), info.d.begin() + static_cast<long>(std::min<std::size_t>(5, info.d.size())));
  } else {
    throw Error("topic " + topic + ": CameraInfo distortion model '" + info.distortion_model +
                "' is not supported (plumb_bob, rational_polynomial, equidistant)");
  }
  bool any = false;
  for (double d : c.distortion) any = any || d != 0;
  if (!any) c.distortion.clear();
  return c;
}

void apply_bag_camera_info(CameraSettings& settings, const BagReader& bag, const std::vector<std::string>& image_topics) {
  if (image_topics.empty()) throw Error("--camera-info-from-bag needs --topics");
  const std::string first = camera_info_topic(image_topics[0]);
  const ros2::CameraInfo left = read_first_camera_info(bag, first);
  settings.camera = calibration_from(left, first);
  if (image_topics.size() < 2 || settings.rgbd) {
    settings.stereo.reset();
    spdlog::info("camera from {}: fx {} fy {} cx {} cy {}, {}x{}", first, settings.camera.fx, settings.camera.fy,
                 settings.camera.cx, settings.camera.cy, settings.camera.width, settings.camera.height);
    return;
  }
  const std::string second = camera_info_topic(image_topics[1]);
  const ros2::CameraInfo right = read_first_camera_info(bag, second);
  const double fx_rect = right.p[0];
  const double baseline = fx_rect > 0 ? -right.p[3] / fx_rect : 0;
  if (baseline <= 0) {
    throw Error("topic " + second + ": CameraInfo P[3] = " + std::to_string(right.p[3]) +
                " gives no baseline (a stereo right camera has P[3] = -fx * baseline): calibrate the pair with ROS "
                "camera_calibration, or give stereo settings");
  }
  // p_rect = R p_cam for each camera; the right rectified frame sits at (baseline, 0, 0) in the left one.
  const auto rotation = [](const std::array<double, 9>& r) {
    Eigen::Matrix3d m;
    m << r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8];
    return m;
  };
  const Eigen::Matrix3d R_left = rotation(left.r), R_right = rotation(right.r);
  StereoCalibration stereo;
  stereo.left = settings.camera;
  stereo.right = calibration_from(right, second);
  stereo.T_c1_c2.linear() = R_left.transpose() * R_right;
  stereo.T_c1_c2.translation() = R_left.transpose() * Eigen::Vector3d(baseline, 0, 0);
  stereo.baseline = baseline;
  stereo.rectified = false;
  settings.stereo = stereo;
  settings.rgbd = false;
  settings.bf = baseline * settings.camera.fx;
  spdlog::info("stereo camera from {} and {}: baseline {} m", first, second, baseline);
}

}  // namespace stillslam
