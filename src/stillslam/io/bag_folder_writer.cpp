#include "stillslam/io/bag_folder_writer.h"

#include <Eigen/Core>  // before opencv2/core/eigen.hpp
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgcodecs.hpp>

#include <spdlog/spdlog.h>

#include "stillslam/core/error.h"
#include "stillslam/io/euroc_dataset.h"
#include "stillslam/io/image_io.h"
#include "stillslam/io/ros2_image_convert.h"
#include "stillslam/io/ros2_message_codec.h"
#include "stillslam/io/text_table.h"
#include "stillslam/io/tum_dataset.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

struct TimedFile {
  std::int64_t ns;
  fs::path file;
};

std::vector<TimedFile> euroc_list(const fs::path& camera) {
  std::vector<TimedFile> out;
  const fs::path csv = camera / "data.csv";
  for (const TextRow& row : read_text_table(csv)) {
    if (row.fields.size() < 2) throw Error(csv.string() + ":" + std::to_string(row.line) + ": expected 'timestamp_ns,filename'");
    out.push_back({parse_int64(row.fields[0], csv, row.line), camera / "data" / row.fields[1]});
  }
  return out;
}

std::vector<TimedFile> tum_list(const fs::path& folder, const std::string& list) {
  std::vector<TimedFile> out;
  for (const TextRow& row : read_text_table(folder / list)) {
    if (row.fields.size() < 2) throw Error((folder / list).string() + ":" + std::to_string(row.line) + ": expected 'timestamp file'");
    const double t = parse_double(row.fields[0], folder / list, row.line);
    out.push_back({static_cast<std::int64_t>(std::llround(t * 1e9)), folder / row.fields[1]});
  }
  return out;
}

ros2::CameraInfo camera_info(const CameraCalibration& c, const cv::Mat& R, const cv::Mat& P, const std::string& frame) {
  ros2::CameraInfo info;
  info.header.frame_id = frame;
  info.width = static_cast<std::uint32_t>(c.width);
  info.height = static_cast<std::uint32_t>(c.height);
  info.distortion_model = c.model == CameraModel::KannalaBrandt8 ? "equidistant" : "plumb_bob";
  info.d = c.distortion;
  info.k = {c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1};
  for (int i = 0; i < 9; ++i) info.r[static_cast<std::size_t>(i)] = R.at<double>(i / 3, i % 3);
  for (int i = 0; i < 12; ++i) info.p[static_cast<std::size_t>(i)] = P.at<double>(i / 4, i % 4);
  return info;
}

// CameraInfo of both EuRoC cameras with the stereo rectification of their sensor.yaml files.
std::pair<ros2::CameraInfo, ros2::CameraInfo> euroc_camera_infos(const fs::path& mav0) {
  const EurocCamera c0 = read_euroc_camera(mav0 / "cam0" / "sensor.yaml");
  const EurocCamera c1 = read_euroc_camera(mav0 / "cam1" / "sensor.yaml");
  const Eigen::Isometry3d T_c2_c1 = (c0.T_body_cam.inverse() * c1.T_body_cam).inverse();
  const auto K = [](const CameraCalibration& c) { return cv::Mat(cv::Matx33d(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1)); };
  cv::Mat R, T, R1, R2, P1, P2, Q;
  const Eigen::Matrix3d rot = T_c2_c1.linear();
  const Eigen::Vector3d t = T_c2_c1.translation();
  cv::eigen2cv(rot, R);
  cv::eigen2cv(t, T);
  cv::stereoRectify(K(c0.calibration), cv::Mat(c0.calibration.distortion), K(c1.calibration),
                    cv::Mat(c1.calibration.distortion), cv::Size(c0.calibration.width, c0.calibration.height), R, T,
                    R1, R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY, 0);
  return {camera_info(c0.calibration, R1, P1, "cam0"), camera_info(c1.calibration, R2, P2, "cam1")};
}

class Writer {
 public:
  Writer(BagWriter& bag, const BagFolderWriteOptions& o) : bag_(bag), png_(o.images == "png") {}
  std::uint32_t image_topic(const std::string& name) {
    return bag_.add_topic(name, png_ ? ros2::kCompressedImageType : ros2::kImageType);
  }
  void image(std::uint32_t topic, std::int64_t ns, const cv::Mat& mat, const std::string& frame) {
    ros2::Header h;
    h.set_stamp_ns(ns);
    h.frame_id = frame;
    bag_.write(topic, ns, png_ ? ros2::encode(ros2::mat_to_png(mat, h)) : ros2::encode(ros2::mat_to_image(mat, h)));
    ++messages;
  }
  void info(std::uint32_t topic, std::int64_t ns, ros2::CameraInfo info) {
    info.header.set_stamp_ns(ns);
    bag_.write(topic, ns, ros2::encode(info));
    ++messages;
  }
  std::size_t messages = 0;

 private:
  BagWriter& bag_;
  bool png_;
};

cv::Mat read_unchanged(const fs::path& file) {
  const cv::Mat image = cv::imread(file.string(), cv::IMREAD_UNCHANGED);
  if (image.empty()) throw Error(file.string() + ": cannot read image (missing or not an image)");
  return image;
}

}  // namespace

void BagFolderWriteOptions::check() const {
  bag.check();
  if (images != "raw" && images != "png") throw Error("bag images '" + images + "': use raw or png");
  if (depth_map_factor <= 0) throw Error("depth map factor must be > 0");
}

BagFolderWriteResult write_folder_as_bag(const fs::path& folder, const fs::path& out,
                                         const BagFolderWriteOptions& options) {
  options.check();
  std::error_code ec;
  BagFolderWriteResult result;
  fs::path mav0;
  if (fs::is_regular_file(folder / "mav0" / "cam0" / "data.csv", ec)) mav0 = folder / "mav0";
  else if (fs::is_regular_file(folder / "cam0" / "data.csv", ec)) mav0 = folder;
  const bool tum = fs::is_regular_file(folder / "rgb.txt", ec) && fs::is_regular_file(folder / "depth.txt", ec);
  if (mav0.empty() && !tum) {
    throw Error(folder.string() + ": no EuRoC (mav0/cam0/data.csv) or TUM RGB-D (rgb.txt + depth.txt) layout to write as a bag");
  }
  const auto bag = open_bag_writer(out, options.bag);
  Writer w(*bag, options);
  if (!mav0.empty()) {
    result.layout = "euroc";
    const auto left = euroc_list(mav0 / "cam0");
    const auto right = euroc_list(mav0 / "cam1");
    const auto [info0, info1] = euroc_camera_infos(mav0);
    const auto t0 = w.image_topic("/cam0/image_raw"), t1 = w.image_topic("/cam1/image_raw");
    const auto i0 = bag->add_topic("/cam0/camera_info", ros2::kCameraInfoType);
    const auto i1 = bag->add_topic("/cam1/camera_info", ros2::kCameraInfoType);
    result.image_topics = {"/cam0/image_raw", "/cam1/image_raw"};
    // Each camera's messages in time order, interleaved as recorded.
    std::size_t a = 0, b = 0;
    while (a < left.size() || b < right.size()) {
      if (options.max_frames > 0 && a >= options.max_frames && b >= options.max_frames) break;
      const bool take_left = b >= right.size() || (a < left.size() && left[a].ns <= right[b].ns);
      const TimedFile& f = take_left ? left[a++] : right[b++];
      if (options.max_frames > 0 && (take_left ? a : b) > options.max_frames) continue;
      if (!fs::is_regular_file(f.file, ec)) {
        ++result.missing_images;
        continue;
      }
      w.image(take_left ? t0 : t1, f.ns, read_unchanged(f.file), take_left ? "cam0" : "cam1");
      w.info(take_left ? i0 : i1, f.ns, take_left ? info0 : info1);
      if (take_left) ++result.frames;
    }
  } else {
    result.layout = "tum";
    const auto rgb = tum_list(folder, "rgb.txt");
    const auto depth = tum_list(folder, "depth.txt");
    const auto tr = w.image_topic("/camera/rgb/image_color"), td = w.image_topic("/camera/depth/image");
    result.image_topics = {"/camera/rgb/image_color", "/camera/depth/image"};
    std::size_t a = 0, b = 0;
    while (a < rgb.size() || b < depth.size()) {
      if (options.max_frames > 0 && a >= options.max_frames && b >= options.max_frames) break;
      const bool take_rgb = b >= depth.size() || (a < rgb.size() && rgb[a].ns <= depth[b].ns);
      const TimedFile& f = take_rgb ? rgb[a++] : depth[b++];
      if (options.max_frames > 0 && (take_rgb ? a : b) > options.max_frames) continue;
      if (!fs::is_regular_file(f.file, ec)) {
        ++result.missing_images;
        continue;
      }
      if (take_rgb) {
        w.image(tr, f.ns, read_color_image(f.file), "camera_rgb");
        ++result.frames;
      } else {
        const cv::Mat raw = read_unchanged(f.file);
        if (raw.type() != CV_16UC1) throw Error(f.file.string() + ": depth must be a 16-bit PNG");
        cv::Mat mm;
        raw.convertTo(mm, CV_16U, 1000.0 / options.depth_map_factor);
        w.image(td, f.ns, mm, "camera_depth");
      }
    }
  }
  bag->close();
  result.messages = w.messages;
  if (result.missing_images > 0) {
    spdlog::warn("{}: {} images named in the frame lists are missing and were left out of the bag", folder.string(),
                 result.missing_images);
  }
  return result;
}

}  // namespace stillslam
