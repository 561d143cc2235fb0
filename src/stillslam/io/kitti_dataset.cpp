#include "stillslam/io/kitti_dataset.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "stillslam/core/error.h"
#include "stillslam/core/option_check.h"
#include "stillslam/io/image_io.h"
#include "stillslam/io/text_table.h"
#include "stillslam/io/timestamp_check.h"

namespace stillslam {
namespace {

std::string image_name(std::size_t i) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%06zu.png", i);
  return buffer;
}

// calib.txt is the sequence's own calibration; settings with other numbers
// were made for another sequence (KITTI 00-02, 03 and 04-12 differ), and
// running with either set silently would be wrong half the time.
void require_same_calibration(const StereoCalibration& calib, const CameraSettings& settings,
                              const std::filesystem::path& calib_txt) {
  if (settings.camera.fx <= 0) return;  // the settings give no intrinsics
  const auto differs = [](double a, double b) { return std::abs(a - b) > 1e-4 * std::max(1.0, std::abs(a)); };
  struct Value {
    const char* name;
    const char* keys;
    double calib, settings;
  };
  const double calib_bf = calib.baseline * calib.left.fx;
  const Value values[] = {
      {"fx", "Camera.fx / Camera1.fx", calib.left.fx, settings.camera.fx},
      {"fy", "Camera.fy / Camera1.fy", calib.left.fy, settings.camera.fy},
      {"cx", "Camera.cx / Camera1.cx", calib.left.cx, settings.camera.cx},
      {"cy", "Camera.cy / Camera1.cy", calib.left.cy, settings.camera.cy},
      {"bf", "Camera.bf, or Stereo.b times fx", calib_bf, settings.bf > 0 ? settings.bf : calib_bf}};
  for (const Value& v : values) {
    if (!differs(v.calib, v.settings)) continue;
    throw Error(calib_txt.string() + ": gives " + v.name + " " + option_check::text(v.calib) + " but " +
                (settings.file.empty() ? std::string("the settings") : settings.file.string()) + " say " +
                option_check::text(v.settings) + " (" + v.keys +
                "): use the settings made for this sequence (config/kitti_00-02.yaml, kitti_03.yaml or "
                "kitti_04-12.yaml), or make the settings agree with calib.txt");
  }
}

}  // namespace

StereoCalibration read_kitti_calibration(const std::filesystem::path& calib_txt) {
  std::vector<double> P0, P1;
  for (const TextRow& row : read_text_table(calib_txt)) {
    if (row.fields[0] != "P0:" && row.fields[0] != "P1:") continue;
    if (row.fields.size() != 13) {
      throw Error(calib_txt.string() + ":" + std::to_string(row.line) + ": " + row.fields[0] +
                  " must have 12 numbers (a 3x4 projection matrix)");
    }
    auto& P = row.fields[0] == "P0:" ? P0 : P1;
    P.clear();
    for (std::size_t k = 1; k < 13; ++k) P.push_back(parse_double(row.fields[k], calib_txt, row.line));
  }
  if (P0.empty() || P1.empty()) throw Error(calib_txt.string() + ": needs lines 'P0:' and 'P1:'");
  if (P0[0] <= 0 || P0[5] <= 0) throw Error(calib_txt.string() + ": P0 must have positive focal lengths");
  const double baseline = -P1[3] / P1[0];
  if (!(baseline > 0)) throw Error(calib_txt.string() + ": P1(0,3) must be -fx * baseline < 0");
  StereoCalibration s;
  s.left.fx = P0[0];
  s.left.fy = P0[5];
  s.left.cx = P0[2];
  s.left.cy = P0[6];
  s.right = s.left;
  s.baseline = baseline;
  s.T_c1_c2.translation() = Eigen::Vector3d(baseline, 0, 0);
  s.rectified = true;
  return s;
}

KittiDataset::KittiDataset(const std::filesystem::path& folder, const CameraSettings& settings,
                           const DatasetOptions& options)
    : FileDataset(options.skip_bad_frames), folder_(folder) {
  const auto times_file = folder / "times.txt";
  TimestampCheck stamps(times_file);
  for (const TextRow& row : read_text_table(times_file)) {
    times_.push_back(parse_double(row.fields[0], times_file, row.line));
    stamps.add(times_.back(), row.fields[0], row.line);
  }
  if (times_.empty()) throw Error(times_file.string() + ": no frames (empty times.txt)");

  std::error_code ec;
  if (std::filesystem::is_regular_file(folder / "calib.txt", ec)) {
    stereo_ = read_kitti_calibration(folder / "calib.txt");
    require_same_calibration(stereo_, settings, folder / "calib.txt");
  } else if (settings.bf > 0) {
    stereo_.left = settings.camera;
    stereo_.left.distortion.clear();
    stereo_.right = stereo_.left;
    stereo_.baseline = settings.baseline();
    stereo_.T_c1_c2.translation() = Eigen::Vector3d(stereo_.baseline, 0, 0);
    stereo_.rectified = true;
  } else {
    throw Error((folder / "calib.txt").string() +
                ": missing, and the settings give no baseline (add Camera.bf or Stereo.b)");
  }
  // The image size is the first left image's (KITTI sizes differ between sequences).
  const cv::Mat first = cv::imread((folder / "image_0" / image_name(0)).string(), cv::IMREAD_GRAYSCALE);
  const int width = first.empty() ? settings.camera.width : first.cols;
  const int height = first.empty() ? settings.camera.height : first.rows;
  stereo_.left.width = stereo_.right.width = width;
  stereo_.left.height = stereo_.right.height = height;
}

std::string KittiDataset::frame_name(std::size_t i) const { return image_name(i); }

SensorFrame KittiDataset::read_frame(std::size_t i) const {
  SensorFrame frame;
  frame.name = image_name(i);
  frame.gray = read_gray_image(folder_ / "image_0" / frame.name);
  frame.right = read_gray_image(folder_ / "image_1" / frame.name);
  if (frame.right.size() != frame.gray.size()) {
    throw Error((folder_ / "image_1" / frame.name).string() + ": right image size differs from the left one");
  }
  cv::cvtColor(frame.gray, frame.color, cv::COLOR_GRAY2BGR);
  return frame;
}

}  // namespace stillslam
