#pragma once
// The EuRoC micro clip (../shared/data/euroc_V1_01_micro) as rectified
// stereo pairs, rectified from the dataset's own sensor.yaml calibration
// (intrinsics, radial-tangential distortion, T_BS extrinsics).
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

namespace stillslam::test {

namespace fs = std::filesystem;

inline std::vector<double> read_doubles(const cv::FileNode& node) {
  std::vector<double> v;
  node >> v;
  return v;
}

struct EurocStereo {
  std::vector<cv::Mat> left, right;  // rectified
  double fx = 0, bf = 0;
};

// First `max_frames` pairs, sorted by timestamp.
inline EurocStereo load_euroc_stereo(const fs::path& mav0, std::size_t max_frames = SIZE_MAX) {
  EurocStereo out;
  cv::Mat K[2], D[2], T_BS[2];
  for (int c = 0; c < 2; ++c) {
    cv::FileStorage fs_cam((mav0 / ("cam" + std::to_string(c)) / "sensor.yaml").string(), cv::FileStorage::READ);
    const auto intr = read_doubles(fs_cam["intrinsics"]);
    K[c] = (cv::Mat_<double>(3, 3) << intr[0], 0, intr[2], 0, intr[1], intr[3], 0, 0, 1);
    D[c] = cv::Mat(read_doubles(fs_cam["distortion_coefficients"])).clone();
    T_BS[c] = cv::Mat(read_doubles(fs_cam["T_BS"]["data"])).clone().reshape(1, 4);
  }
  const cv::Mat T_c1_c0 = T_BS[1].inv() * T_BS[0];
  const cv::Mat R = T_c1_c0(cv::Rect(0, 0, 3, 3)).clone(), t = T_c1_c0(cv::Rect(3, 0, 1, 3)).clone();
  const cv::Size size(752, 480);
  cv::Mat R1, R2, P1, P2, Q;
  cv::stereoRectify(K[0], D[0], K[1], D[1], size, R, t, R1, R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY, 0);
  cv::Mat m0x, m0y, m1x, m1y;
  cv::initUndistortRectifyMap(K[0], D[0], R1, P1, size, CV_32FC1, m0x, m0y);
  cv::initUndistortRectifyMap(K[1], D[1], R2, P2, size, CV_32FC1, m1x, m1y);
  out.fx = P1.at<double>(0, 0);
  out.bf = -P2.at<double>(0, 3);
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(mav0 / "cam0" / "data")) files.push_back(e.path().filename());
  std::sort(files.begin(), files.end());
  if (files.size() > max_frames) files.resize(max_frames);
  for (const auto& f : files) {
    const cv::Mat l = cv::imread((mav0 / "cam0" / "data" / f).string(), cv::IMREAD_GRAYSCALE);
    const cv::Mat r = cv::imread((mav0 / "cam1" / "data" / f).string(), cv::IMREAD_GRAYSCALE);
    if (l.empty() || r.empty()) continue;
    cv::Mat lr, rr;
    cv::remap(l, lr, m0x, m0y, cv::INTER_LINEAR);
    cv::remap(r, rr, m1x, m1y, cv::INTER_LINEAR);
    out.left.push_back(lr);
    out.right.push_back(rr);
  }
  return out;
}

}  // namespace stillslam::test
