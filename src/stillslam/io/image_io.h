#pragma once
// Image reading with errors that name the file and say what to check.
#include <filesystem>

#include <opencv2/core.hpp>

namespace stillslam {

// 8-bit BGR image (cv::imread order, whatever the file's channel count).
cv::Mat read_color_image(const std::filesystem::path& file);
// 8-bit single-channel image.
cv::Mat read_gray_image(const std::filesystem::path& file);
// 8-bit image as stored: single-channel for a gray file, BGR for a colour one
// (alpha dropped), so colour reaches the segmenter when a camera has it.
cv::Mat read_gray_or_color_image(const std::filesystem::path& file);
// A 16-bit depth PNG converted to CV_32F metres (raw / depth_map_factor;
// 0 stays 0 = invalid). An 8-bit or colour file is an error.
cv::Mat read_depth_image(const std::filesystem::path& file, double depth_map_factor);

}  // namespace stillslam
