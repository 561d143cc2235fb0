#include "stillslam/io/euroc_dataset.h"

#include <opencv2/imgproc.hpp>
#include <spdlog/spdlog.h>

#include "stillslam/core/error.h"
#include "stillslam/io/image_io.h"
#include "stillslam/io/text_table.h"
#include "stillslam/io/timestamp_association.h"
#include "stillslam/io/timestamp_check.h"
#include "stillslam/io/yaml_reader.h"

namespace stillslam {
namespace {

cv::Mat to_gray(const cv::Mat& image) {
  if (image.channels() == 1) return image;
  cv::Mat gray;
  cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

struct TimedImage {
  double timestamp;
  std::string file;
};

std::vector<TimedImage> read_camera_list(const std::filesystem::path& csv) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(csv, ec)) {
    throw Error(csv.string() + ": missing (EuRoC camera list '#timestamp [ns],filename')");
  }
  std::vector<TimedImage> out;
  // Checked on the seconds the trajectory gets; messages quote the nanoseconds.
  TimestampCheck stamps(csv, "timestamp [ns]");
  for (const TextRow& row : read_text_table(csv)) {
    if (row.fields.size() < 2) {
      throw Error(csv.string() + ":" + std::to_string(row.line) + ": expected 'timestamp_ns,filename'");
    }
    out.push_back({static_cast<double>(parse_int64(row.fields[0], csv, row.line)) * 1e-9, row.fields[1]});
    stamps.add(out.back().timestamp, row.fields[0], row.line);
  }
  return out;
}

std::vector<ImuSample> read_imu(const std::filesystem::path& csv) {
  std::vector<ImuSample> out;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(csv, ec)) return out;  // IMU is optional for visual SLAM
  for (const TextRow& row : read_text_table(csv)) {
    if (row.fields.size() < 7) {
      throw Error(csv.string() + ":" + std::to_string(row.line) + ": expected 'timestamp_ns,wx,wy,wz,ax,ay,az'");
    }
    ImuSample s;
    s.timestamp = static_cast<double>(parse_int64(row.fields[0], csv, row.line)) * 1e-9;
    for (int k = 0; k < 3; ++k) {
      s.gyro[k] = parse_double(row.fields[1 + k], csv, row.line);
      s.accel[k] = parse_double(row.fields[4 + k], csv, row.line);
    }
    out.push_back(s);
  }
  return out;
}

}  // namespace

EurocCamera read_euroc_camera(const std::filesystem::path& sensor_yaml) {
  const YamlReader yaml(sensor_yaml);
  EurocCamera cam;
  const std::string model = yaml.optional_string("camera_model").value_or("pinhole");
  if (model != "pinhole") yaml.fail("camera_model", "must be 'pinhole' (got '" + model + "')");
  const auto intrinsics = yaml.optional_numbers("intrinsics");
  if (!intrinsics || intrinsics->size() != 4) yaml.fail("intrinsics", "must be [fu, fv, cu, cv]");
  CameraCalibration& c = cam.calibration;
  c.fx = (*intrinsics)[0];
  c.fy = (*intrinsics)[1];
  c.cx = (*intrinsics)[2];
  c.cy = (*intrinsics)[3];
  if (c.fx <= 0 || c.fy <= 0) yaml.fail("intrinsics", "must have positive focal lengths");
  const std::string dist_model = yaml.optional_string("distortion_model").value_or("radial-tangential");
  if (dist_model == "equidistant") {
    c.model = CameraModel::KannalaBrandt8;
  } else if (dist_model != "radial-tangential" && dist_model != "radtan" && dist_model != "plumb_bob") {
    yaml.fail("distortion_model", "must be 'radial-tangential' or 'equidistant' (got '" + dist_model + "')");
  }
  if (const auto d = yaml.optional_numbers("distortion_coefficients")) c.distortion = *d;
  if (const auto res = yaml.optional_numbers("resolution")) {
    if (res->size() != 2 || (*res)[0] <= 0 || (*res)[1] <= 0) yaml.fail("resolution", "must be [width, height]");
    c.width = static_cast<int>((*res)[0]);
    c.height = static_cast<int>((*res)[1]);
  }
  const auto T = yaml.optional_matrix("T_BS");
  if (!T || T->rows() != 4 || T->cols() != 4) yaml.fail("T_BS", "must be a 4x4 matrix (camera in body frame)");
  cam.T_body_cam.linear() = T->topLeftCorner<3, 3>();
  cam.T_body_cam.translation() = T->topRightCorner<3, 1>();
  return cam;
}

EurocDataset::EurocDataset(const std::filesystem::path& mav0, const CameraSettings& settings,
                           const DatasetOptions& options)
    : FileDataset(options.skip_bad_frames), mav0_(mav0) {
  // Pair cam0 and cam1 by timestamp (identical in EuRoC, tolerant otherwise).
  const auto left = read_camera_list(mav0 / "cam0" / "data.csv");
  const auto right = read_camera_list(mav0 / "cam1" / "data.csv");
  std::vector<double> tl, tr;
  for (const auto& l : left) tl.push_back(l.timestamp);
  for (const auto& r : right) tr.push_back(r.timestamp);
  for (const auto& [il, ir] : associate_timestamps(tl, tr, options.max_dt)) {
    frames_.push_back({left[il].timestamp, left[il].file, right[ir].file});
  }
  unpaired_ = left.size() - frames_.size();
  // As ORB-SLAM3, frames are the pairs found; the images left out are said.
  if (unpaired_ > 0 || right.size() > frames_.size()) {
    spdlog::warn("{} lists {} images and {} lists {}: {} stereo pairs within {} s, {} cam0 and {} cam1 images "
                 "without a partner are dropped",
                 (mav0 / "cam0" / "data.csv").string(), left.size(), (mav0 / "cam1" / "data.csv").string(),
                 right.size(), frames_.size(), options.max_dt, unpaired_, right.size() - frames_.size());
  }
  if (frames_.empty()) {
    throw Error((mav0 / "cam0" / "data.csv").string() +
                ": no stereo frames (empty list, or no cam1 image within " + std::to_string(options.max_dt) +
                " s of a cam0 image)");
  }
  imu_ = read_imu(mav0 / "imu0" / "data.csv");

  cv::Size size;
  if (settings.stereo && !settings.stereo->rectified) {
    raw_ = *settings.stereo;
    size = cv::Size(raw_.left.width, raw_.left.height);
  } else {
    const EurocCamera cam0 = read_euroc_camera(mav0 / "cam0" / "sensor.yaml");
    const EurocCamera cam1 = read_euroc_camera(mav0 / "cam1" / "sensor.yaml");
    raw_.left = cam0.calibration;
    raw_.right = cam1.calibration;
    raw_.T_c1_c2 = cam0.T_body_cam.inverse() * cam1.T_body_cam;
    raw_.baseline = raw_.T_c1_c2.translation().norm();
    raw_.rectified = false;
    size = cv::Size(raw_.left.width, raw_.left.height);
  }
  if (size.width <= 0 || size.height <= 0) size = cv::Size(settings.camera.width, settings.camera.height);
  if (size.width <= 0 || size.height <= 0) size = read_gray_image(mav0 / "cam0" / "data" / frames_[0].left).size();
  rectifier_ = std::make_unique<StereoRectifier>(raw_, size);
}

SensorFrame EurocDataset::read_frame(std::size_t i) const {
  const StereoFrame& f = frames_[i];
  SensorFrame frame;
  frame.name = f.left;
  const auto left_file = mav0_ / "cam0" / "data" / f.left;
  const auto right_file = mav0_ / "cam1" / "data" / f.right;
  // Colour left images (a colour stereo rig in EuRoC layout) are kept for the
  // segmenter, which misses far more people in gray; ORB runs on gray.
  // Both sides turn to gray the same way (libpng's own gray conversion differs).
  const cv::Mat left_as_stored = read_gray_or_color_image(left_file);
  const cv::Mat left = to_gray(left_as_stored);
  const cv::Mat right = to_gray(read_gray_or_color_image(right_file));
  for (const auto& [image, file] : {std::pair{&left, &left_file}, std::pair{&right, &right_file}}) {
    if (image->size() != rectifier_->size()) {
      throw Error(file->string() + ": image is " + std::to_string(image->cols) + "x" +
                  std::to_string(image->rows) + " but the calibration expects " +
                  std::to_string(rectifier_->size().width) + "x" + std::to_string(rectifier_->size().height));
    }
  }
  frame.gray = rectifier_->rectify_left(left);
  frame.right = rectifier_->rectify_right(right);
  if (left_as_stored.channels() == 3) {
    frame.color = rectifier_->rectify_left(left_as_stored);
  } else {
    cv::cvtColor(frame.gray, frame.color, cv::COLOR_GRAY2BGR);
  }
  return frame;
}

}  // namespace stillslam
