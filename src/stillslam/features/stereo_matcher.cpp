#include "stillslam/features/stereo_matcher.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>

#include "stillslam/core/check.h"
#include "stillslam/core/error.h"
#include "stillslam/core/option_check.h"
#include "stillslam/features/descriptor.h"
#include "stillslam/features/pyramid_coordinates.h"

namespace stillslam {
namespace {

// Patch costs between two (2w+1)^2 windows, each taken relative to its own
// mean so a brightness offset between the cameras does not matter (zero-mean
// SAD and SSD). SAD picks the integer disparity robustly; SSD is used for the
// sub-pixel fit because, unlike the V-shaped SAD, it is locally quadratic in
// the shift (a parabola through three SAD values is biased toward the
// steeper side by up to a quarter pixel even for exact integer shifts).
struct PatchCost {
  float sad = 0, ssd = 0;
};

PatchCost zero_mean_cost(const cv::Mat& left, int ul, int vl, const cv::Mat& right, int ur, int vr, int w) {
  int sum_l = 0, sum_r = 0;
  for (int dv = -w; dv <= w; ++dv) {
    const std::uint8_t* pl = left.ptr<std::uint8_t>(vl + dv) + ul;
    const std::uint8_t* pr = right.ptr<std::uint8_t>(vr + dv) + ur;
    for (int du = -w; du <= w; ++du) {
      sum_l += pl[du];
      sum_r += pr[du];
    }
  }
  const float offset = static_cast<float>(sum_l - sum_r) / static_cast<float>((2 * w + 1) * (2 * w + 1));
  PatchCost cost;
  for (int dv = -w; dv <= w; ++dv) {
    const std::uint8_t* pl = left.ptr<std::uint8_t>(vl + dv) + ul;
    const std::uint8_t* pr = right.ptr<std::uint8_t>(vr + dv) + ur;
    for (int du = -w; du <= w; ++du) {
      const float diff = static_cast<float>(pl[du] - pr[du]) - offset;
      cost.sad += std::abs(diff);
      cost.ssd += diff * diff;
    }
  }
  return cost;
}

struct Candidate {
  std::size_t left;
  float sad;
};

struct Refined {
  float u_right;  // level-0 pixels
  float sad;
};

// Integer shift by zero-mean SAD within +-search_window level pixels of
// `right_u` (level-0 pixels) on the left keypoint's level, sub-pixel by the
// SSD parabola. None when the patch leaves the image or the minimum is on the
// window's edge.
std::optional<Refined> refine_on_level(const std::vector<cv::Mat>& left_pyramid,
                                       const std::vector<cv::Mat>& right_pyramid, const cv::KeyPoint& kl,
                                       float right_u, const StereoMatchOptions& options,
                                       std::vector<PatchCost>& costs) {
  const int w = options.patch_half_size, window = options.search_window;
  const cv::Mat& img_l = left_pyramid[static_cast<std::size_t>(kl.octave)];
  const cv::Mat& img_r = right_pyramid[static_cast<std::size_t>(kl.octave)];
  const LevelMapping mapping(left_pyramid[0].size(), img_l.size());
  const cv::Point2f level_l = mapping.to_level(kl.pt);
  const int su_l = static_cast<int>(std::lround(level_l.x));
  const int sv_l = static_cast<int>(std::lround(level_l.y));
  const int su_r0 = static_cast<int>(std::lround(mapping.to_level({right_u, kl.pt.y}).x));
  if (sv_l - w < 0 || sv_l + w >= img_l.rows || sv_l + w >= img_r.rows) return std::nullopt;
  if (su_l - w < 0 || su_l + w >= img_l.cols) return std::nullopt;
  if (su_r0 - window - w < 0 || su_r0 + window + w >= img_r.cols) return std::nullopt;

  float best_sad = std::numeric_limits<float>::max();
  int best_inc = 0;
  for (int inc = -window; inc <= window; ++inc) {
    const PatchCost cost = zero_mean_cost(img_l, su_l, sv_l, img_r, su_r0 + inc, sv_l, w);
    costs[static_cast<std::size_t>(inc + window)] = cost;
    if (cost.sad < best_sad) {
      best_sad = cost.sad;
      best_inc = inc;
    }
  }
  // A minimum on the window edge cannot be refined: the true one may be outside.
  if (best_inc == -window || best_inc == window) return std::nullopt;

  float delta = 0.f;
  if (options.subpixel) {
    const float d1 = costs[static_cast<std::size_t>(best_inc + window - 1)].ssd;
    const float d2 = costs[static_cast<std::size_t>(best_inc + window)].ssd;
    const float d3 = costs[static_cast<std::size_t>(best_inc + window + 1)].ssd;
    const float denominator = 2.f * (d1 + d3 - 2.f * d2);
    if (denominator > 0.f) delta = (d1 - d3) / denominator;
    if (delta < -1.f || delta > 1.f) return std::nullopt;
  }
  return Refined{mapping.to_full({static_cast<float>(su_r0 + best_inc) + delta, 0.f}).x, best_sad};
}

}  // namespace

StereoMatches match_stereo(const OrbFeatures& left, const std::vector<cv::Mat>& left_pyramid,
                           const OrbFeatures& right, const std::vector<cv::Mat>& right_pyramid,
                           const ScalePyramid& pyramid, double fx, double bf,
                           const StereoMatchOptions& options) {
  const std::size_t n = left.keypoints.size();
  StereoMatches out;
  out.u_right.assign(n, -1.f);
  out.depth.assign(n, -1.f);
  if (n == 0 || right.keypoints.empty()) return out;
  STILLSLAM_CHECK_EQ(left_pyramid.size(), pyramid.n_levels,
                     "match_stereo: pass the left pyramid OrbExtractor::extract returned");
  STILLSLAM_CHECK_EQ(right_pyramid.size(), pyramid.n_levels,
                     "match_stereo: pass the right pyramid OrbExtractor::extract returned");
  if (!(fx > 0) || !(bf > 0)) {
    throw Error("match_stereo: fx and bf (baseline * fx) must be positive; check Camera.fx and "
                "Stereo.b / Camera.bf in the settings");
  }

  // Right keypoints indexed by every image row of their epipolar band.
  const int rows = left_pyramid[0].rows;
  std::vector<std::vector<std::size_t>> by_row(static_cast<std::size_t>(rows));
  auto valid_level = [&](int octave) { return octave >= 0 && octave < pyramid.n_levels; };
  for (std::size_t i = 0; i < right.keypoints.size(); ++i) {
    const cv::KeyPoint& kp = right.keypoints[i];
    if (!valid_level(kp.octave)) continue;
    const float band = options.row_band * pyramid.scale[static_cast<std::size_t>(kp.octave)];
    const int r0 = std::max(0, static_cast<int>(std::floor(kp.pt.y - band)));
    const int r1 = std::min(rows - 1, static_cast<int>(std::ceil(kp.pt.y + band)));
    for (int r = r0; r <= r1; ++r) by_row[static_cast<std::size_t>(r)].push_back(i);
  }

  const float min_d = options.min_disparity;
  const float max_d = options.max_disparity < 0 ? static_cast<float>(fx) : options.max_disparity;
  std::vector<PatchCost> costs(static_cast<std::size_t>(2 * options.search_window + 1));
  std::vector<Candidate> accepted;
  accepted.reserve(n);

  for (std::size_t i = 0; i < n; ++i) {
    const cv::KeyPoint& kl = left.keypoints[i];
    const int level = kl.octave;
    if (!valid_level(level)) continue;
    const float ul = kl.pt.x, vl = kl.pt.y;
    const int row = static_cast<int>(std::lround(vl));
    if (row < 0 || row >= rows) continue;
    const float min_u = ul - max_d, max_u = ul - min_d;
    if (max_u < 0) continue;

    // Best descriptor among right keypoints of neighbouring scale in range.
    int best_distance = std::numeric_limits<int>::max();
    std::size_t best_right = 0;
    const std::uint8_t* dl = left.descriptors.ptr<std::uint8_t>(static_cast<int>(i));
    for (std::size_t j : by_row[static_cast<std::size_t>(row)]) {
      const cv::KeyPoint& kr = right.keypoints[j];
      if (kr.octave < level - 1 || kr.octave > level + 1) continue;
      if (kr.pt.x < min_u || kr.pt.x > max_u) continue;
      const int d = descriptor_distance(dl, right.descriptors.ptr<std::uint8_t>(static_cast<int>(j)));
      if (d < best_distance) {
        best_distance = d;
        best_right = j;
      }
    }
    if (best_distance >= options.max_descriptor_distance) continue;

    // Patch refinement on the left keypoint's level, around the right keypoint.
    const auto refined = refine_on_level(left_pyramid, right_pyramid, kl, right.keypoints[best_right].pt.x, options, costs);
    if (!refined) continue;
    float u_r = refined->u_right;
    float disparity = ul - u_r;
    if (disparity < min_d || disparity >= max_d) continue;
    if (disparity <= 0.f) {  // at infinity: keep a tiny positive disparity
      disparity = 0.01f;
      u_r = ul - disparity;
    }
    out.u_right[i] = u_r;
    out.depth[i] = static_cast<float>(bf / disparity);
    accepted.push_back({i, refined->sad});
  }

  // Keypoints without a right keypoint: optical flow proposes where to refine.
  if (options.flow_for_unmatched) {
    const std::vector<float> proposals = flow_right_proposals(left, out.u_right, left_pyramid[0], right_pyramid[0], options.flow);
    for (std::size_t i = 0; i < n; ++i) {
      if (proposals[i] < 0.f || !valid_level(left.keypoints[i].octave)) continue;
      const auto refined = refine_on_level(left_pyramid, right_pyramid, left.keypoints[i], proposals[i], options, costs);
      if (!refined) continue;
      const float disparity = left.keypoints[i].pt.x - refined->u_right;
      if (disparity <= 0.f || disparity < min_d || disparity >= max_d) continue;
      out.u_right[i] = refined->u_right;
      out.depth[i] = static_cast<float>(bf / disparity);
      accepted.push_back({i, refined->sad});
    }
  }

  // Outliers: SAD well above the median of all accepted matches.
  if (!accepted.empty()) {
    std::vector<float> all(accepted.size());
    for (std::size_t k = 0; k < accepted.size(); ++k) all[k] = accepted[k].sad;
    std::nth_element(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(all.size() / 2), all.end());
    const float threshold = options.sad_outlier_factor * all[all.size() / 2];
    for (const Candidate& c : accepted) {
      if (c.sad > threshold) {
        out.u_right[c.left] = -1.f;
        out.depth[c.left] = -1.f;
      } else {
        ++out.num_matches;
      }
    }
  }
  return out;
}

StereoMatches stereo_from_depth(const std::vector<cv::KeyPoint>& raw,
                                const std::vector<cv::KeyPoint>& undistorted, const cv::Mat& depth,
                                double bf, double depth_scale) {
  STILLSLAM_CHECK_EQ(raw.size(), undistorted.size(), "stereo_from_depth: one undistorted keypoint per raw keypoint");
  if (depth.type() != CV_32FC1 && depth.type() != CV_16UC1) {
    throw Error("stereo_from_depth: depth image must be CV_32F metres or CV_16U with a depth scale "
                "(DepthMapFactor), got type " + std::to_string(depth.type()));
  }
  if (!(depth_scale > 0)) {
    throw Error("stereo_from_depth: depth scale (DepthMapFactor) must be positive");
  }
  StereoMatches out;
  out.u_right.assign(raw.size(), -1.f);
  out.depth.assign(raw.size(), -1.f);
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const int x = static_cast<int>(std::lround(raw[i].pt.x));
    const int y = static_cast<int>(std::lround(raw[i].pt.y));
    if (x < 0 || y < 0 || x >= depth.cols || y >= depth.rows) continue;
    const double d = depth.type() == CV_32FC1 ? static_cast<double>(depth.at<float>(y, x))
                                              : depth.at<std::uint16_t>(y, x) / depth_scale;
    if (!(d > 0) || !std::isfinite(d)) continue;
    out.depth[i] = static_cast<float>(d);
    out.u_right[i] = static_cast<float>(undistorted[i].pt.x - bf / d);
    ++out.num_matches;
  }
  return out;
}

void StereoMatchOptions::check() const {
  using namespace option_check;
  in_range("StereoMatchOptions.max_descriptor_distance", max_descriptor_distance, 0, 256);
  at_least("StereoMatchOptions.patch_half_size", patch_half_size, 1);
  at_least("StereoMatchOptions.search_window", search_window, 0);
  above("StereoMatchOptions.row_band", row_band, 0);
  at_least("StereoMatchOptions.min_disparity", min_disparity, 0);
  // < 0 means fx (see above); a given maximum must leave room above the minimum.
  if (max_disparity >= 0) above("StereoMatchOptions.max_disparity", max_disparity, min_disparity);
  above("StereoMatchOptions.sad_outlier_factor", sad_outlier_factor, 0);
}

}  // namespace stillslam
