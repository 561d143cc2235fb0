#pragma once
// CPU ray caster for scenes made of textured quads. Each pixel's centre ray
// gives exact depth and the ground-truth dynamic mask and, with a mip-mapped
// bilinear texture lookup, the colour; pixels where the centre rays change
// surface (edges, cut-out outlines) are re-shot with supersampling x
// supersampling rays (anti-aliasing). With motion blur, colour averages rays
// from several poses across the exposure instead. Quads are one-sided: a quad
// is visible when axis_u x axis_v points away from the camera (axis_u right,
// axis_v down as seen). Rows are rendered in parallel (cv::parallel_for_).
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <vector>

#include "stillslam/geometry/camera_calibration.h"
#include "stillslam/sim/quad.h"
#include "stillslam/sim/texture.h"

namespace stillslam::sim {

struct RenderedView {
  cv::Mat bgr;          // CV_32FC3, 0..255
  cv::Mat depth;        // CV_32FC1, metres along the optical axis (z), 0 = nothing hit
  cv::Mat dynamic_ids;  // CV_16UC1, Quad::dynamic_id of the surface hit by the centre ray
  cv::Mat mask() const; // CV_8UC1, 255 where dynamic_ids != 0
};

class Renderer {
 public:
  Renderer(const CameraCalibration& camera, std::vector<MipTexture> textures);

  // Pinhole, pixel (u, v) centre at integer coordinates (OpenCV convention).
  // supersampling: colour rays per pixel per axis (1 = centre ray only).
  RenderedView render(const std::vector<Quad>& quads, const Eigen::Isometry3d& T_world_cam,
                      int supersampling) const;
  // As render(), but colour averages rays from every pose in exposure_poses
  // (stratified with the sub-pixel offsets); depth and mask come from T_world_cam.
  RenderedView render_blurred(const std::vector<Quad>& quads, const Eigen::Isometry3d& T_world_cam,
                              const std::vector<Eigen::Isometry3d>& exposure_poses,
                              int supersampling) const;

  const CameraCalibration& camera() const { return camera_; }
  const std::vector<MipTexture>& textures() const { return textures_; }

 private:
  CameraCalibration camera_;
  std::vector<MipTexture> textures_;
};

}  // namespace stillslam::sim
