#include "stillslam/sim/noise.h"

#include <cmath>

#include "stillslam/core/error.h"

namespace stillslam::sim {

NoiseModel noise_model(int level) {
  NoiseModel m;
  if (level <= 0) return m;
  if (level == 1) {
    m.image_sigma = 2.0;
    m.depth_k = 0.0015;  // ~1.5 mm at 1 m, ~2.4 cm at 4 m (Kinect v1 order)
    m.max_range = 4.5;
    m.edge_jump = 0.04;
    m.edge_hole_prob = 0.6;
    m.dropout_prob = 0.002;
    m.exposure_samples = 3;
    m.exposure_fraction = 0.4;
    return m;
  }
  if (level == 2) {
    m.image_sigma = 5.0;
    m.depth_k = 0.004;
    m.max_range = 3.5;
    m.edge_jump = 0.02;
    m.edge_hole_prob = 1.0;
    m.dropout_prob = 0.02;
    m.exposure_samples = 5;
    m.exposure_fraction = 1.0;
    return m;
  }
  throw Error("--noise " + std::to_string(level) + ": use 0 (none), 1 (realistic) or 2 (heavy)");
}

cv::Mat apply_image_noise(const cv::Mat& bgr, const NoiseModel& model, cv::RNG& rng) {
  cv::Mat out;
  if (model.image_sigma > 0) {
    cv::Mat n(bgr.size(), CV_32FC3);
    rng.fill(n, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(model.image_sigma));
    cv::Mat sum = bgr + n;
    sum.convertTo(out, CV_8UC3);  // rounds and saturates
  } else {
    bgr.convertTo(out, CV_8UC3);
  }
  return out;
}

cv::Mat apply_depth_noise(const cv::Mat& depth, const NoiseModel& model, cv::RNG& rng) {
  cv::Mat out = depth.clone();
  if (model.depth_k <= 0 && model.max_range <= 0 && model.edge_jump <= 0 && model.dropout_prob <= 0) {
    return out;
  }
  for (int v = 0; v < depth.rows; ++v) {
    const float* d = depth.ptr<float>(v);
    float* o = out.ptr<float>(v);
    for (int u = 0; u < depth.cols; ++u) {
      const float z = d[u];
      if (z <= 0) continue;
      bool hole = model.max_range > 0 && z > model.max_range;
      if (!hole && model.edge_jump > 0) {
        // Structured light loses depth where the pattern is shadowed: at jumps.
        float jump = 0;
        for (int dv = -1; dv <= 1; ++dv) {
          const int vv = v + dv;
          if (vv < 0 || vv >= depth.rows) continue;
          const float* dn = depth.ptr<float>(vv);
          for (int du = -1; du <= 1; ++du) {
            const int uu = u + du;
            if (uu < 0 || uu >= depth.cols) continue;
            jump = std::max(jump, std::abs(dn[uu] - z));
          }
        }
        hole = jump > model.edge_jump * z && rng.uniform(0.0, 1.0) < model.edge_hole_prob;
      }
      if (!hole && model.dropout_prob > 0) hole = rng.uniform(0.0, 1.0) < model.dropout_prob;
      o[u] = hole ? 0.0f : static_cast<float>(z + rng.gaussian(model.depth_k * z * z));
    }
  }
  return out;
}

}  // namespace stillslam::sim
