#pragma once
// The one primitive of the simulator: a planar textured rectangle (parallelogram).
#include <Eigen/Core>
#include <cstdint>

namespace stillslam::sim {

struct Quad {
  // World point at texture coordinate (0,0); axis_u spans texture x (columns),
  // axis_v spans texture y (rows). Lengths are the rectangle's sides in metres.
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis_u = Eigen::Vector3d::UnitX();
  Eigen::Vector3d axis_v = Eigen::Vector3d::UnitY();
  int texture = 0;                       // index into the renderer's texture list
  // Sub-rectangle of the texture mapped onto the quad (normalized coordinates).
  float u0 = 0, v0 = 0, u1 = 1, v1 = 1;
  float brightness = 1.0f;               // cheap stand-in for lighting
  bool alpha_tested = false;             // cut-outs: transparent texels are holes
  // Non-zero for moving things: the id appears in the ground-truth mask.
  std::uint16_t dynamic_id = 0;
};

}  // namespace stillslam::sim
