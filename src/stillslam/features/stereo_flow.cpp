#include "stillslam/features/stereo_flow.h"

#include <algorithm>
#include <cmath>
#include <opencv2/video/tracking.hpp>
#include <utility>

namespace stillslam {
namespace {

// Median disparity of the k matched keypoints nearest to `p`.
float guess_disparity(const cv::Point2f& p, const std::vector<cv::Point2f>& seeds,
                      const std::vector<float>& disparities, int k,
                      std::vector<std::pair<float, float>>& scratch) {
  scratch.clear();
  for (std::size_t s = 0; s < seeds.size(); ++s) {
    const cv::Point2f d = seeds[s] - p;
    scratch.emplace_back(d.x * d.x + d.y * d.y, disparities[s]);
  }
  const std::size_t n = std::min(scratch.size(), static_cast<std::size_t>(std::max(1, k)));
  std::partial_sort(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(n), scratch.end());
  std::vector<float> nearest(n);
  for (std::size_t i = 0; i < n; ++i) nearest[i] = scratch[i].second;
  std::nth_element(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(n / 2), nearest.end());
  return nearest[n / 2];
}

// The right image with the left one's global mean and standard deviation.
cv::Mat match_exposure(const cv::Mat& right, const cv::Mat& left) {
  cv::Scalar mean_l, std_l, mean_r, std_r;
  cv::meanStdDev(left, mean_l, std_l);
  cv::meanStdDev(right, mean_r, std_r);
  if (!(std_r[0] > 0)) return right;
  const double gain = std_l[0] / std_r[0];
  cv::Mat out;
  right.convertTo(out, CV_8U, gain, mean_l[0] - gain * mean_r[0]);
  return out;
}

}  // namespace

std::vector<float> flow_right_proposals(const OrbFeatures& left, const std::vector<float>& u_right,
                                        const cv::Mat& left_image, const cv::Mat& right_image,
                                        const StereoFlowOptions& options) {
  std::vector<float> proposals(left.keypoints.size(), -1.f);
  std::vector<cv::Point2f> seeds;
  std::vector<float> seed_disparities;
  std::vector<std::size_t> open;
  for (std::size_t i = 0; i < left.keypoints.size(); ++i) {
    if (u_right[i] >= 0.f) {
      seeds.push_back(left.keypoints[i].pt);
      seed_disparities.push_back(left.keypoints[i].pt.x - u_right[i]);
    } else {
      open.push_back(i);
    }
  }
  if (seeds.empty() || open.empty()) return proposals;

  std::vector<cv::Point2f> from, to;
  from.reserve(open.size());
  to.reserve(open.size());
  std::vector<std::pair<float, float>> scratch;
  for (std::size_t i : open) {
    const cv::Point2f p = left.keypoints[i].pt;
    from.push_back(p);
    to.emplace_back(p.x - guess_disparity(p, seeds, seed_disparities, options.guess_neighbours, scratch), p.y);
  }
  // Each pyramid is built once and serves both directions.
  const cv::Size window(options.window, options.window);
  std::vector<cv::Mat> left_levels, right_levels;
  const int levels = cv::buildOpticalFlowPyramid(left_image, left_levels, window, options.pyramid_levels);
  cv::buildOpticalFlowPyramid(match_exposure(right_image, left_image), right_levels, window, options.pyramid_levels);
  const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01);
  std::vector<unsigned char> ok, ok_back;
  std::vector<float> err;
  cv::calcOpticalFlowPyrLK(left_levels, right_levels, from, to, ok, err, window, levels, stop,
                           cv::OPTFLOW_USE_INITIAL_FLOW);
  std::vector<cv::Point2f> back = from;
  cv::calcOpticalFlowPyrLK(right_levels, left_levels, to, back, ok_back, err, window, levels, stop,
                           cv::OPTFLOW_USE_INITIAL_FLOW);

  for (std::size_t k = 0; k < open.size(); ++k) {
    if (!ok[k] || !ok_back[k]) continue;
    const cv::Point2f round_trip = back[k] - from[k];
    if (std::hypot(round_trip.x, round_trip.y) > options.max_round_trip) continue;
    if (std::abs(to[k].y - from[k].y) > options.max_row_offset) continue;
    if (to[k].x < 0.f || to[k].x > static_cast<float>(right_image.cols - 1)) continue;
    proposals[open[k]] = to[k].x;
  }
  return proposals;
}

}  // namespace stillslam
