#pragma once
// Small generated datasets in the real on-disk layouts, for reader tests.
#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

namespace stillslam::test {

// Deterministic textured 8-bit image (seeded random blocks), `channels` 1 or 3.
cv::Mat textured_image(int width, int height, int channels, int seed);

// Writes a file holding only the first `fraction` of `source`'s bytes.
void truncate_copy(const std::filesystem::path& source, const std::filesystem::path& target, double fraction);

// TUM RGB-D layout with `frames` frames: rgb.txt, depth.txt, rgb/, depth/.
// Frame k: rgb time 100 + k/30, depth time +0.004 s; 64x48 images; depth
// raw value 5000 + 100*k everywhere except pixel (0,0) = 0. One extra rgb
// entry without a depth partner at the end. Returns the folder.
std::filesystem::path write_tum_fixture(const std::filesystem::path& root, int frames);

// KITTI odometry layout: times.txt, calib.txt (sequence 00 values),
// image_0/, image_1/ (96x32). Returns the folder.
std::filesystem::path write_kitti_fixture(const std::filesystem::path& root, int frames, bool with_calib);

// EuRoC layout (mav0/cam0, cam1 with sensor.yaml copied from the real clip's
// calibration, imu0) with `frames` 752x480 frames. Returns the sequence root
// (the folder holding mav0).
std::filesystem::path write_euroc_fixture(const std::filesystem::path& root, int frames);

}  // namespace stillslam::test
