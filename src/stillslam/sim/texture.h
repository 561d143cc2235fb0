#pragma once
// A photo texture with a mip pyramid, sampled bilinearly. Always stored as
// 8-bit BGRA so opaque photos and alpha cut-outs share one code path.
#include <opencv2/core.hpp>
#include <vector>

namespace stillslam::sim {

struct Rgba {
  float b = 0, g = 0, r = 0, a = 0;
};

class MipTexture {
 public:
  MipTexture() = default;
  // image: CV_8UC3 (opaque) or CV_8UC4 (alpha). Builds levels down to ~8 px.
  explicit MipTexture(const cv::Mat& image);

  int width() const { return levels_.empty() ? 0 : levels_[0].cols; }
  int height() const { return levels_.empty() ? 0 : levels_[0].rows; }
  int levels() const { return static_cast<int>(levels_.size()); }
  const cv::Mat& level(int i) const { return levels_[i]; }

  // (x, y) in normalized texture coordinates [0,1]^2 (x right, y down).
  Rgba sample(float x, float y, int level) const;
  // Bilinear alpha of level 0 >= 50%: the ground-truth coverage test (smooth outline
  // even when a small cut-out is magnified).
  bool opaque(float x, float y) const;

 private:
  std::vector<cv::Mat> levels_;
};

}  // namespace stillslam::sim
