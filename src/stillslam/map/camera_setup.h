#pragma once
// Everything a frame needs to know about the sensor: the (undistorted, for
// stereo rectified) pinhole camera with its baseline, the ORB scale pyramid
// and the depth below which stereo/RGB-D points count as "close" (ORB-SLAM's
// ThDepth, in metres). Shared read-only by frames and keyframes.
#include "stillslam/features/scale_pyramid.h"
#include "stillslam/geometry/pinhole_camera.h"

namespace stillslam {

struct CameraSetup {
  PinholeCamera camera;
  ScalePyramid pyramid;
  double close_depth = 0;  // metres

  CameraSetup(PinholeCamera cam, ScalePyramid pyr, double close)
      : camera(std::move(cam)), pyramid(std::move(pyr)), close_depth(close) {}
};

}  // namespace stillslam
