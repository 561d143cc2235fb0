#include "stillslam/io/ros2_image_convert.h"

#include <algorithm>
#include <cstring>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "stillslam/core/error.h"

namespace stillslam::ros2 {
namespace {

constexpr const char* kSupportedRaw = "mono8, 8UC1, rgb8, bgr8, 8UC3, bgra8, rgba8, mono16, 16UC1 (depth mm), 32FC1 (depth m)";
constexpr const char* kSupportedCompressed =
    "jpeg, png (8-bit gray or colour), '16UC1; compressedDepth png', '32FC1; compressedDepth png'";
constexpr std::size_t kCompressedDepthHeader = 12;  // int32 format + float depth quantization[2]

std::string where(const std::string& topic) { return "topic " + topic; }

cv::Mat decode_png_or_jpeg(const std::uint8_t* data, std::size_t n, int flags, const std::string& topic,
                           const std::string& format) {
  cv::Mat image;
  try {
    image = cv::imdecode(cv::Mat(1, static_cast<int>(n), CV_8UC1, const_cast<std::uint8_t*>(data)), flags);
  } catch (const cv::Exception& e) {
    throw Error(where(topic) + ": cannot decode the '" + format + "' image (" + e.err + ")");
  }
  if (image.empty()) throw Error(where(topic) + ": cannot decode the '" + format + "' image (corrupt or truncated data)");
  return image;
}

// The OpenCV type of a raw encoding, and the colour conversion to BGR (-1: none); type -1: not supported.
std::pair<int, int> raw_type(const std::string& e) {
  if (e == "mono8" || e == "8UC1") return {CV_8UC1, -1};
  if (e == "bgr8" || e == "8UC3") return {CV_8UC3, -1};
  if (e == "rgb8") return {CV_8UC3, cv::COLOR_RGB2BGR};
  if (e == "bgra8" || e == "8UC4") return {CV_8UC4, cv::COLOR_BGRA2BGR};
  if (e == "rgba8") return {CV_8UC4, cv::COLOR_RGBA2BGR};
  if (e == "mono16" || e == "16UC1") return {CV_16UC1, -1};
  if (e == "32FC1") return {CV_32FC1, -1};
  return {-1, -1};
}

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

std::optional<std::string> unsupported_encoding(const std::string& encoding, const std::string& topic) {
  if (raw_type(encoding).first >= 0) return std::nullopt;
  return where(topic) + ": image encoding '" + encoding + "' is not supported (supported: " + kSupportedRaw +
         "); convert the topic, e.g. with image_proc, or record a supported encoding";
}

}  // namespace

std::optional<std::string> unsupported(const Image& m, const std::string& topic) {
  return unsupported_encoding(m.encoding, topic);
}

std::optional<std::string> unsupported(const CompressedImage& m, const std::string& topic) {
  const std::string& f = m.format;
  const bool depth = f.find("compressedDepth") != std::string::npos;
  const bool ok = depth ? f.find("rvl") == std::string::npos && f.find("RVL") == std::string::npos &&
                              (starts_with(f, "16UC1") || starts_with(f, "mono16") || starts_with(f, "32FC1"))
                        : f.find("jpeg") != std::string::npos || f.find("jpg") != std::string::npos ||
                              f.find("png") != std::string::npos;
  if (ok) return std::nullopt;
  return where(topic) + ": compressed image format '" + f + "' is not supported (supported: " + kSupportedCompressed + ")";
}

cv::Mat image_to_mat(const Image& m, const std::string& topic) {
  return image_to_mat(ImageView{m.height, m.width, m.encoding, m.is_bigendian, m.step, m.data.data(), m.data.size()},
                      topic);
}

cv::Mat image_to_mat(const ImageView& m, const std::string& topic) {
  if (const auto why = unsupported_encoding(m.encoding, topic)) throw Error(*why);
  const std::string& e = m.encoding;
  const auto [type, conversion] = raw_type(e);
  const std::size_t row_bytes = static_cast<std::size_t>(m.width) * CV_ELEM_SIZE(type);
  if (m.width == 0 || m.height == 0 || m.step < row_bytes ||
      m.size < static_cast<std::size_t>(m.step) * (m.height - 1) + row_bytes) {
    throw Error(where(topic) + ": image " + std::to_string(m.width) + "x" + std::to_string(m.height) + " '" + e +
                "' with step " + std::to_string(m.step) + " needs " +
                std::to_string(static_cast<std::size_t>(m.step) * m.height) + " bytes of data, the message has " +
                std::to_string(m.size));
  }
  cv::Mat mat(static_cast<int>(m.height), static_cast<int>(m.width), type);
  for (int y = 0; y < mat.rows; ++y) {
    std::memcpy(mat.ptr(y), m.data + static_cast<std::size_t>(y) * m.step, row_bytes);
  }
  const bool host_big = false;
  if (CV_ELEM_SIZE1(type) > 1 && (m.is_bigendian != 0) != host_big) {
    // Byte-swap every element.
    const std::size_t size1 = CV_ELEM_SIZE1(type);
    for (int y = 0; y < mat.rows; ++y) {
      std::uint8_t* p = mat.ptr(y);
      for (std::size_t i = 0; i + size1 <= row_bytes; i += size1) std::reverse(p + i, p + i + size1);
    }
  }
  if (conversion >= 0) cv::cvtColor(mat, mat, conversion);
  return mat;
}

cv::Mat compressed_image_to_mat(const CompressedImage& m, const std::string& topic) {
  if (const auto why = unsupported(m, topic)) throw Error(*why);
  const std::string& f = m.format;
  if (f.find("compressedDepth") != std::string::npos) {
    if (m.data.size() <= kCompressedDepthHeader) {
      throw Error(where(topic) + ": compressedDepth image of " + std::to_string(m.data.size()) +
                  " bytes is shorter than its 12-byte header");
    }
    const cv::Mat png = decode_png_or_jpeg(m.data.data() + kCompressedDepthHeader, m.data.size() - kCompressedDepthHeader,
                                           cv::IMREAD_UNCHANGED, topic, f);
    if (png.type() != CV_16UC1) throw Error(where(topic) + ": compressedDepth PNG is not 16-bit single channel");
    if (!starts_with(f, "32FC1")) return png;  // 16UC1: millimetres
    // 32FC1: quantized inverse depth, depth = a / (v - b); 0 = no measurement.
    float quant[2];
    std::memcpy(quant, m.data.data() + 4, sizeof(quant));
    cv::Mat depth(png.size(), CV_32FC1, cv::Scalar(0));
    for (int y = 0; y < png.rows; ++y) {
      for (int x = 0; x < png.cols; ++x) {
        const auto v = png.at<std::uint16_t>(y, x);
        if (v != 0) depth.at<float>(y, x) = quant[0] / (static_cast<float>(v) - quant[1]);
      }
    }
    return depth;
  }
  cv::Mat image = decode_png_or_jpeg(m.data.data(), m.data.size(), cv::IMREAD_UNCHANGED, topic, f);
  if (image.depth() != CV_8U) {
    throw Error(where(topic) + ": compressed '" + f + "' image is not 8-bit (use compressedDepth for depth)");
  }
  if (image.channels() == 4) cv::cvtColor(image, image, cv::COLOR_BGRA2BGR);
  return image;
}

std::string ros_encoding(const cv::Mat& mat) {
  switch (mat.type()) {
    case CV_8UC1: return "mono8";
    case CV_8UC3: return "bgr8";
    case CV_16UC1: return "16UC1";
    case CV_32FC1: return "32FC1";
    default: break;
  }
  throw Error("no ROS image encoding for OpenCV type " + std::to_string(mat.type()) +
              " (mono8, bgr8, 16UC1 and 32FC1 are written)");
}

Image mat_to_image(const cv::Mat& mat, const Header& header) {
  Image m;
  m.header = header;
  m.encoding = ros_encoding(mat);
  m.height = static_cast<std::uint32_t>(mat.rows);
  m.width = static_cast<std::uint32_t>(mat.cols);
  m.step = static_cast<std::uint32_t>(mat.cols * mat.elemSize());
  m.data.resize(static_cast<std::size_t>(m.step) * m.height);
  for (int y = 0; y < mat.rows; ++y) std::memcpy(m.data.data() + static_cast<std::size_t>(y) * m.step, mat.ptr(y), m.step);
  return m;
}

CompressedImage mat_to_png(const cv::Mat& mat, const Header& header) {
  CompressedImage m;
  m.header = header;
  std::vector<std::uint8_t> png;
  if (!cv::imencode(".png", mat, png)) throw Error("mat_to_png: PNG encoding failed");
  if (mat.type() == CV_16UC1) {
    m.format = "16UC1; compressedDepth png";
    m.data.assign(kCompressedDepthHeader, 0);  // format 0, no quantization (used by 32FC1 only)
    m.data.insert(m.data.end(), png.begin(), png.end());
  } else {
    m.format = "png";
    m.data = std::move(png);
  }
  return m;
}

}  // namespace stillslam::ros2
