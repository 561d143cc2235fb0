#pragma once
// Whether a camera's distortion folds the image: a distortion whose mapping
// from ideal to distorted coordinates turns back on itself inside the field
// of view sends two directions to one pixel, and undistorting keypoints,
// the feature grid's bounds and rectification all go wrong. Checked where
// the settings are read so the error can name the coefficient.
#include <optional>
#include <string>

#include "stillslam/geometry/camera_calibration.h"

namespace stillslam {

// Checks the ideal (undistorted) coordinates the image covers, taken from
// width x height (or 2cx x 2cy when the size is unknown) and extended by
// 10 %: for a pinhole (radial-tangential) model the Jacobian determinant of
// the distortion must stay positive there; for KannalaBrandt8 the distorted
// angle must grow with the angle. Returns where it folds ("at pixel (u, v)"),
// or nothing.
std::optional<std::string> distortion_fold(const CameraCalibration& camera);

}  // namespace stillslam
