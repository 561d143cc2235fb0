#include "stillslam/io/image_io.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "stillslam/core/error.h"

namespace stillslam {
namespace {

cv::Mat read(const std::filesystem::path& file, int flags) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw Error(file.string() + ": image file is missing (the frame list names it; check the dataset folder)");
  }
  cv::Mat image;
  try {
    image = cv::imread(file.string(), flags);
  } catch (const cv::Exception& e) {
    throw Error(file.string() + ": cannot decode image (" + e.err + ")");
  }
  if (image.empty()) {
    throw Error(file.string() + ": cannot decode image (unreadable, truncated or not an image; "
                                "re-extract or re-download this file)");
  }
  return image;
}

}  // namespace

cv::Mat read_color_image(const std::filesystem::path& file) {
  cv::Mat image = read(file, cv::IMREAD_COLOR);
  if (image.depth() != CV_8U) image.convertTo(image, CV_8U);
  return image;
}

cv::Mat read_gray_image(const std::filesystem::path& file) {
  cv::Mat image = read(file, cv::IMREAD_GRAYSCALE);
  if (image.depth() != CV_8U) image.convertTo(image, CV_8U);
  return image;
}

cv::Mat read_gray_or_color_image(const std::filesystem::path& file) {
  cv::Mat image = read(file, cv::IMREAD_ANYCOLOR);
  if (image.depth() != CV_8U) image.convertTo(image, CV_8U);
  if (image.channels() == 4) cv::cvtColor(image, image, cv::COLOR_BGRA2BGR);
  return image;
}

cv::Mat read_depth_image(const std::filesystem::path& file, double depth_map_factor) {
  const cv::Mat raw = read(file, cv::IMREAD_UNCHANGED);
  if (raw.type() != CV_16UC1) {
    throw Error(file.string() + ": depth must be a 16-bit single-channel PNG (got " +
                std::to_string(raw.channels()) + " channel(s) of " +
                (raw.depth() == CV_8U ? std::string("8-bit") : std::string("non-16-bit")) +
                " data); depth in metres = value / DepthMapFactor (5000 for TUM). An 8-bit depth "
                "image has lost its range: use the original 16-bit depth files");
  }
  cv::Mat metres;
  raw.convertTo(metres, CV_32F, 1.0 / depth_map_factor);
  return metres;
}

}  // namespace stillslam
