#pragma once
// Sensor imperfections for --noise LEVEL (0 none, 1 realistic, 2 heavy):
// image noise, structured-light depth noise (sigma = k z^2, Kinect-like),
// holes at depth edges, beyond the range limit and a few random dropouts,
// and motion blur (several renders across the exposure, see Renderer).
#include <opencv2/core.hpp>

namespace stillslam::sim {

struct NoiseModel {
  double image_sigma = 0;        // grey levels, per channel
  double depth_k = 0;            // sigma_z = depth_k * z^2 (metres)
  double max_range = 0;          // metres; farther depth becomes 0 (0 = no limit)
  double edge_jump = 0;          // relative depth jump that marks an edge (0 = no edge holes)
  double edge_hole_prob = 0;     // probability an edge pixel loses its depth
  double dropout_prob = 0;       // random missing depth pixels
  int exposure_samples = 1;      // poses averaged for motion blur (1 = none)
  double exposure_fraction = 0;  // exposure time / frame interval
};

NoiseModel noise_model(int level);

// bgr: CV_32FC3 in 0..255 -> CV_8UC3 with noise.
cv::Mat apply_image_noise(const cv::Mat& bgr, const NoiseModel& model, cv::RNG& rng);
// depth: CV_32FC1 metres -> noisy CV_32FC1 metres (0 = no data).
cv::Mat apply_depth_noise(const cv::Mat& depth, const NoiseModel& model, cv::RNG& rng);

}  // namespace stillslam::sim
