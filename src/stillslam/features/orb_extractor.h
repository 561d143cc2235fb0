#pragma once
// ORB extraction in the style of ORB-SLAM (Mur-Artal et al.) on top of
// Rublee et al.'s ORB: scale pyramid, FAST per cell with a threshold
// fallback, quadtree spatial distribution per level, intensity-centroid
// orientation and steered BRIEF on a Gaussian-smoothed level image.
#include <opencv2/core.hpp>
#include <vector>

#include "stillslam/features/brief_pattern.h"
#include "stillslam/features/orb_features.h"
#include "stillslam/features/orb_options.h"
#include "stillslam/features/scale_pyramid.h"

namespace stillslam {

class OrbExtractor {
 public:
  // Throws stillslam::Error on invalid options (n_levels < 1, scale_factor
  // <= 1 with several levels, n_features < 1, thresholds out of range).
  explicit OrbExtractor(const OrbOptions& options);

  // gray: CV_8UC1, not empty (throws stillslam::Error otherwise).
  // Keypoints are mapped from their level to full resolution with the
  // pixel-centre convention of LevelMapping (pyramid_coordinates.h).
  // Thread-safe; output is deterministic (levels run in parallel, results are
  // concatenated in level order).
  OrbFeatures extract(const cv::Mat& gray) const;
  // Also returns the pyramid (level l has size round(cols/scale[l]) x
  // round(rows/scale[l]), unblurred), e.g. for stereo patch refinement.
  OrbFeatures extract(const cv::Mat& gray, std::vector<cv::Mat>* pyramid_out) const;
  // Keeps no corner on a non-zero pixel of `exclude` (CV_8UC1, the image's
  // size, or empty): the whole feature budget goes to the rest of the image
  // (dynamic objects masked before extraction, as DynaSLAM does).
  // masked_out (optional) receives, appended in level-0 pixels, the corners
  // dropped for the mask, thinned by the same quadtree to the share of each
  // level's budget the mask covers: the features the mask removed (for display).
  OrbFeatures extract(const cv::Mat& gray, const cv::Mat1b& exclude, std::vector<cv::Mat>* pyramid_out,
                      std::vector<cv::Point2f>* masked_out = nullptr) const;

  const ScalePyramid& pyramid() const { return pyramid_; }
  const OrbOptions& options() const { return options_; }
  // Features requested on each level (geometric series summing to n_features).
  const std::vector<int>& features_per_level() const { return features_per_level_; }

 private:
  OrbOptions options_;
  ScalePyramid pyramid_;
  std::vector<int> features_per_level_;
  BriefPattern pattern_;
};

// Builds the image pyramid used by OrbExtractor (level 0 is `gray` itself,
// each further level resized from the previous one, bilinear).
std::vector<cv::Mat> build_image_pyramid(const cv::Mat& gray, const ScalePyramid& pyramid);

}  // namespace stillslam
