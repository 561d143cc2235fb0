#include "stillslam/features/orb_extractor.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "stillslam/core/check.h"
#include "stillslam/core/error.h"
#include "stillslam/features/brief_descriptor.h"
#include "stillslam/features/fast_cells.h"
#include "stillslam/features/keypoint_distribution.h"
#include "stillslam/features/level_masks.h"
#include "stillslam/features/orientation.h"
#include "stillslam/features/pyramid_coordinates.h"

namespace stillslam {
namespace {

constexpr float kPatchSize = 31.f;  // keypoint.size at level 0 (BRIEF patch)
// Keypoints keep this distance to the level border so the radius-15 disc and
// the rotated pattern (coordinates within +-15 after rounding) stay inside.
constexpr int kBorder = BriefPattern::kRadius + 1;

// Features per level, a geometric series with ratio 1 / scale_factor (a level
// gets features in proportion to its image side, ORB-SLAM's choice), summing
// to n_features exactly.
std::vector<int> split_features(int n_features, const ScalePyramid& pyramid) {
  const int levels = pyramid.n_levels;
  std::vector<int> per_level(static_cast<std::size_t>(levels), 0);
  if (levels == 1) {
    per_level[0] = n_features;
    return per_level;
  }
  const double f = 1.0 / pyramid.scale_factor;
  const double first = n_features * (1.0 - f) / (1.0 - std::pow(f, levels));
  int assigned = 0;
  for (int l = 0; l < levels - 1; ++l) {
    per_level[static_cast<std::size_t>(l)] = static_cast<int>(std::lround(first * std::pow(f, l)));
    assigned += per_level[static_cast<std::size_t>(l)];
  }
  per_level.back() = std::max(0, n_features - assigned);
  return per_level;
}

struct LevelResult {
  std::vector<cv::KeyPoint> keypoints;  // level coordinates
  cv::Mat descriptors;
  std::vector<cv::KeyPoint> masked;     // level coordinates, when asked for
};

// exclude: empty, or the level-size mask of pixels where no corner may be kept.
// masked_target > 0: also keep that many of the excluded corners (same quadtree).
LevelResult extract_level(const cv::Mat& image, const cv::Mat1b& exclude, int target, int masked_target,
                          const OrbOptions& options, const BriefPattern& pattern) {
  LevelResult out;
  if (target <= 0) return out;
  FastCellOptions fast;
  fast.cell_size = options.fast_cell_size;
  fast.ini_threshold = options.ini_th_fast;
  fast.min_threshold = options.min_th_fast;
  fast.border = kBorder;
  std::vector<cv::KeyPoint> corners = detect_fast_in_cells(image, fast);
  const cv::Rect2f region(static_cast<float>(kBorder), static_cast<float>(kBorder),
                          static_cast<float>(image.cols - 2 * kBorder),
                          static_cast<float>(image.rows - 2 * kBorder));
  if (!exclude.empty()) {
    std::vector<cv::KeyPoint> masked;
    std::erase_if(corners, [&](const cv::KeyPoint& kp) {
      const int x = std::clamp(static_cast<int>(kp.pt.x), 0, exclude.cols - 1);
      const int y = std::clamp(static_cast<int>(kp.pt.y), 0, exclude.rows - 1);
      const bool inside = exclude(y, x) != 0;
      if (inside && masked_target > 0) masked.push_back(kp);
      return inside;
    });
    if (!masked.empty()) {
      for (std::size_t i : distribute_quadtree(masked, region, masked_target)) out.masked.push_back(masked[i]);
    }
  }
  const std::vector<std::size_t> kept = distribute_quadtree(corners, region, target);
  out.keypoints.reserve(kept.size());
  for (std::size_t i : kept) out.keypoints.push_back(corners[i]);
  if (out.keypoints.empty()) return out;

  compute_orientations(image, out.keypoints);
  cv::Mat smoothed;
  cv::GaussianBlur(image, smoothed, cv::Size(7, 7), 2.0, 2.0, cv::BORDER_REFLECT_101);
  out.descriptors.create(static_cast<int>(out.keypoints.size()), 32, CV_8UC1);
  compute_brief(smoothed, out.keypoints, pattern, out.descriptors);
  return out;
}

}  // namespace

std::vector<cv::Mat> build_image_pyramid(const cv::Mat& gray, const ScalePyramid& pyramid) {
  std::vector<cv::Mat> levels(static_cast<std::size_t>(pyramid.n_levels));
  levels[0] = gray.clone();
  for (int l = 1; l < pyramid.n_levels; ++l) {
    const cv::Size size(static_cast<int>(std::lround(gray.cols * pyramid.inv_scale[l])),
                        static_cast<int>(std::lround(gray.rows * pyramid.inv_scale[l])));
    if (size.width < 1 || size.height < 1) {
      levels[l] = cv::Mat(std::max(size.height, 0), std::max(size.width, 0), CV_8UC1);
      continue;
    }
    cv::resize(levels[l - 1], levels[l], size, 0, 0, cv::INTER_LINEAR);
  }
  return levels;
}

OrbExtractor::OrbExtractor(const OrbOptions& options)
    : options_(options),
      pyramid_(options),
      features_per_level_((options.check(), split_features(options.n_features, pyramid_))),
      pattern_(BriefPattern::generate()) {}

OrbFeatures OrbExtractor::extract(const cv::Mat& gray) const { return extract(gray, nullptr); }

OrbFeatures OrbExtractor::extract(const cv::Mat& gray, std::vector<cv::Mat>* pyramid_out) const {
  return extract(gray, cv::Mat1b(), pyramid_out);
}

OrbFeatures OrbExtractor::extract(const cv::Mat& gray, const cv::Mat1b& exclude, std::vector<cv::Mat>* pyramid_out,
                                  std::vector<cv::Point2f>* masked_out) const {
  if (gray.empty() || gray.type() != CV_8UC1) {
    throw Error("ORB extraction needs a non-empty 8-bit single-channel image (got type " +
                std::to_string(gray.type()) + ", " + std::to_string(gray.cols) + "x" +
                std::to_string(gray.rows) + "); convert colour images with cv::cvtColor first");
  }
  if (!exclude.empty()) {
    STILLSLAM_CHECK_EQ(exclude.cols, gray.cols, "ORB extraction: the exclusion mask must have the image's size");
    STILLSLAM_CHECK_EQ(exclude.rows, gray.rows, "ORB extraction: the exclusion mask must have the image's size");
  }
  std::vector<cv::Mat> levels = build_image_pyramid(gray, pyramid_);
  // The mask at each level's size: a corner is dropped when its level pixel
  // shows any excluded full-resolution pixel (level_masks.h).
  std::vector<cv::Mat1b> excluded(levels.size());
  const int excluded_pixels = exclude.empty() ? 0 : cv::countNonZero(exclude);
  // The masked corners reported get the share of each level's budget that the mask covers.
  const double masked_share =
      masked_out ? static_cast<double>(excluded_pixels) / static_cast<double>(gray.total()) : 0.0;
  if (excluded_pixels > 0) {
    std::vector<cv::Size> sizes;
    for (const cv::Mat& level : levels) sizes.push_back(level.empty() ? cv::Size() : level.size());
    excluded = level_masks(exclude, sizes);
  }

  std::vector<LevelResult> results(static_cast<std::size_t>(pyramid_.n_levels));
  // Levels are independent and each writes only its own slot, so the result
  // does not depend on scheduling.
  cv::parallel_for_(cv::Range(0, pyramid_.n_levels), [&](const cv::Range& range) {
    for (int l = range.start; l < range.end; ++l) {
      const int target = features_per_level_[static_cast<std::size_t>(l)];
      const int masked_target = static_cast<int>(std::lround(target * masked_share));
      results[static_cast<std::size_t>(l)] = extract_level(levels[static_cast<std::size_t>(l)],
                                                           excluded[static_cast<std::size_t>(l)], target,
                                                           masked_target, options_, pattern_);
    }
  });

  OrbFeatures features;
  std::size_t total = 0;
  for (const auto& r : results) total += r.keypoints.size();
  features.keypoints.reserve(total);
  features.descriptors.create(static_cast<int>(total), 32, CV_8UC1);
  int row = 0;
  for (int l = 0; l < pyramid_.n_levels; ++l) {
    const LevelResult& r = results[static_cast<std::size_t>(l)];
    const float s = pyramid_.scale[static_cast<std::size_t>(l)];
    const LevelMapping mapping(levels[0].size(), levels[static_cast<std::size_t>(l)].size());
    for (const cv::KeyPoint& kp : r.keypoints) {
      features.keypoints.emplace_back(mapping.to_full(kp.pt), kPatchSize * s, kp.angle, kp.response, l);
    }
    if (masked_out) {
      for (const cv::KeyPoint& kp : r.masked) masked_out->push_back(mapping.to_full(kp.pt));
    }
    if (!r.keypoints.empty()) {
      r.descriptors.copyTo(features.descriptors.rowRange(row, row + r.descriptors.rows));
      row += r.descriptors.rows;
    }
  }
  if (pyramid_out) *pyramid_out = std::move(levels);
  return features;
}

}  // namespace stillslam
