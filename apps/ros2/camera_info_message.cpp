#include "camera_info_message.h"

#include <cmath>

#include "ros_time.h"

namespace stillslam::ros2 {

OutgoingCameraInfo::OutgoingCameraInfo(const CameraCalibration& camera, double baseline, std::int64_t stamp_ns,
                                       const std::string& frame_id)
    : frame_id_(frame_id) {
  message_.header.stamp = stamp_from_nanoseconds(stamp_ns);
  message_.header.frame_id = frame_id_.data();
  message_.width = static_cast<std::uint32_t>(camera.width);
  message_.height = static_cast<std::uint32_t>(camera.height);
  message_.distortion_model = model_.data();
  message_.d._maximum = message_.d._length = static_cast<std::uint32_t>(d_.size());
  message_.d._buffer = d_.data();
  message_.d._release = false;
  const double k[9] = {camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1};
  const double r[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const double p[12] = {camera.fx, 0, camera.cx, -camera.fx * baseline, 0, camera.fy, camera.cy, 0, 0, 0, 1, 0};
  std::copy(std::begin(k), std::end(k), message_.k);
  std::copy(std::begin(r), std::end(r), message_.r);
  std::copy(std::begin(p), std::end(p), message_.p);
}

std::optional<std::string> camera_info_mismatch(const sensor_msgs_msg_dds__CameraInfo_& info,
                                                const CameraCalibration& camera) {
  if (camera.width > 0 && (info.width != static_cast<std::uint32_t>(camera.width) ||
                           info.height != static_cast<std::uint32_t>(camera.height))) {
    return "CameraInfo is " + std::to_string(info.width) + "x" + std::to_string(info.height) +
           " but the settings say " + std::to_string(camera.width) + "x" + std::to_string(camera.height);
  }
  const double got[4] = {info.p[0], info.p[5], info.p[2], info.p[6]};
  const double want[4] = {camera.fx, camera.fy, camera.cx, camera.cy};
  const char* names[4] = {"fx", "fy", "cx", "cy"};
  for (int i = 0; i < 4; ++i) {
    if (std::abs(got[i] - want[i]) > 0.01 * std::abs(want[i]) + 1e-9) {
      return std::string("CameraInfo P gives ") + names[i] + " " + std::to_string(got[i]) +
             " but the settings' rectified camera has " + std::to_string(want[i]);
    }
  }
  return std::nullopt;
}

}  // namespace stillslam::ros2
