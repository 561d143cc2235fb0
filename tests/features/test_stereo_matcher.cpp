#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <opencv2/imgproc.hpp>

#include "stillslam/core/error.h"
#include "stillslam/features/orb_extractor.h"
#include "stillslam/features/stereo_matcher.h"
#include "textured_image.h"

namespace stillslam {
namespace {

constexpr double kFx = 458.0;
constexpr double kBf = 0.11 * kFx;  // EuRoC-like baseline of 11 cm

using DisparityField = std::function<double(double u, double v)>;

// A rectified pair of one textured plane: the left image samples the texture
// at x + 0.3 (so both images are interpolated alike), the right one at
// x + 0.3 + disparity(x, y), so the field is a function of right-image pixels.
struct Pair {
  cv::Mat left, right;
};

Pair make_pair(const DisparityField& disparity) {
  const cv::Mat texture = test::textured_image(720, 480, 21, 1400, 50.0);
  cv::Mat map_lx(480, 640, CV_32FC1), map_rx(480, 640, CV_32FC1), map_y(480, 640, CV_32FC1);
  for (int y = 0; y < 480; ++y) {
    for (int x = 0; x < 640; ++x) {
      map_lx.at<float>(y, x) = static_cast<float>(x + 0.3);
      map_rx.at<float>(y, x) = static_cast<float>(x + 0.3 + disparity(x, y));
      map_y.at<float>(y, x) = static_cast<float>(y);
    }
  }
  Pair p;
  cv::remap(texture, p.left, map_lx, map_y, cv::INTER_LINEAR);
  cv::remap(texture, p.right, map_rx, map_y, cv::INTER_LINEAR);
  return p;
}

// The descriptor + patch path alone (the default; the flow tests turn flow on).
StereoMatchOptions descriptor_only() { return StereoMatchOptions{}; }

StereoMatchOptions with_flow() {
  StereoMatchOptions o;
  o.flow_for_unmatched = true;
  return o;
}

// True disparity at left keypoint `p`: the field is indexed by the right
// image's column, so solve D = f(u - D, v).
double true_disparity(const DisparityField& disparity, const cv::Point2f& p) {
  double d = disparity(p.x, p.y);
  for (int it = 0; it < 30; ++it) d = disparity(p.x - d, p.y);
  return d;
}

struct StereoScores {
  int matches = 0;
  double within_1pct = 0;      // fraction of matches with |depth error| < 1%
  double mean_abs_disp_err = 0;
};

StereoScores run(const Pair& pair, const DisparityField& disparity, const StereoMatchOptions& options) {
  const OrbExtractor extractor{OrbOptions{}};
  std::vector<cv::Mat> pyr_l, pyr_r;
  const OrbFeatures left = extractor.extract(pair.left, &pyr_l);
  const OrbFeatures right = extractor.extract(pair.right, &pyr_r);
  const StereoMatches m = match_stereo(left, pyr_l, right, pyr_r, extractor.pyramid(), kFx, kBf, options);
  StereoScores s;
  int good = 0, counted = 0;
  for (std::size_t i = 0; i < left.size(); ++i) {
    if (m.depth[i] < 0) {
      EXPECT_LT(m.u_right[i], 0.f);
      continue;
    }
    ++counted;
    const cv::Point2f p = left.keypoints[i].pt;
    const double d_true = true_disparity(disparity, p);
    const double depth_true = kBf / d_true;
    good += std::abs(m.depth[i] - depth_true) < 0.01 * depth_true;
    s.mean_abs_disp_err += std::abs((p.x - m.u_right[i]) - d_true);
    EXPECT_NEAR(m.depth[i], kBf / (p.x - m.u_right[i]), 1e-3 * m.depth[i]);
  }
  EXPECT_EQ(counted, m.num_matches);
  s.matches = counted;
  s.within_1pct = counted ? static_cast<double>(good) / counted : 0;
  s.mean_abs_disp_err = counted ? s.mean_abs_disp_err / counted : 0;
  return s;
}

// Matches that optical flow added (none without it), with their errors.
struct FlowScores {
  int descriptor_matches = 0, flow_matches = 0, wrong = 0;  // wrong: |disparity error| > 1 px
  int dropped = 0;                                          // descriptor matches lost to the outlier test
  double mean_abs_disp_err = 0;                             // over the right ones
};

FlowScores run_flow(const Pair& pair, const DisparityField& disparity) {
  const OrbExtractor extractor{OrbOptions{}};
  std::vector<cv::Mat> pyr_l, pyr_r;
  const OrbFeatures left = extractor.extract(pair.left, &pyr_l);
  const OrbFeatures right = extractor.extract(pair.right, &pyr_r);
  const StereoMatches without = match_stereo(left, pyr_l, right, pyr_r, extractor.pyramid(), kFx, kBf, descriptor_only());
  const StereoMatches with = match_stereo(left, pyr_l, right, pyr_r, extractor.pyramid(), kFx, kBf, with_flow());
  FlowScores s;
  s.descriptor_matches = without.num_matches;
  for (std::size_t i = 0; i < left.size(); ++i) {
    if (without.depth[i] > 0) {
      // Flow matches join the median-SAD outlier test, so a descriptor match
      // may drop out, but none changes.
      if (with.depth[i] > 0) {
        EXPECT_EQ(with.u_right[i], without.u_right[i]) << "flow must not change descriptor matches";
      } else {
        ++s.dropped;
      }
      continue;
    }
    if (with.depth[i] < 0) continue;
    ++s.flow_matches;
    const cv::Point2f p = left.keypoints[i].pt;
    EXPECT_NEAR(with.depth[i], kBf / (p.x - with.u_right[i]), 1e-3 * with.depth[i]);
    const double error = std::abs((p.x - with.u_right[i]) - true_disparity(disparity, p));
    if (error > 1.0) {
      ++s.wrong;
    } else {
      s.mean_abs_disp_err += error;
    }
  }
  EXPECT_EQ(with.num_matches, s.descriptor_matches - s.dropped + s.flow_matches);
  const int right_ones = s.flow_matches - s.wrong;
  s.mean_abs_disp_err = right_ones > 0 ? s.mean_abs_disp_err / right_ones : 0;
  return s;
}

void print(const char* name, const FlowScores& s) {
  std::cout << "[ measure ] " << name << ": descriptor matches " << s.descriptor_matches << ", flow adds "
            << s.flow_matches << " (" << s.wrong << " off by > 1 px; " << s.dropped
            << " descriptor matches dropped), mean |disparity error| "
            << s.mean_abs_disp_err << " px\n";
}

void print(const char* name, const StereoScores& s) {
  std::cout << "[ measure ] " << name << ": matches " << s.matches << " within 1% depth " << s.within_1pct
            << " mean |disparity error| " << s.mean_abs_disp_err << " px\n";
}

}  // namespace

TEST(StereoMatcher, ConstantSubpixelDisparity) {
  const DisparityField disparity = [](double, double) { return 23.37; };  // depth 2.156 m
  const Pair pair = make_pair(disparity);
  const StereoScores sub = run(pair, disparity, descriptor_only());
  StereoMatchOptions integer_only = descriptor_only();
  integer_only.subpixel = false;
  const StereoScores integer = run(pair, disparity, integer_only);
  print("constant 23.37 px, sub-pixel", sub);
  print("constant 23.37 px, integer", integer);
  // Measured: 661 matches, 99.4% within 1%, 0.051 px (integer only: 0.62 px).
  EXPECT_GE(sub.matches, 600);
  EXPECT_GE(sub.within_1pct, 0.95);
  EXPECT_LT(sub.mean_abs_disp_err, 0.08);
  EXPECT_LT(sub.mean_abs_disp_err, 0.3 * integer.mean_abs_disp_err);
}

TEST(StereoMatcher, SlantedPlane) {
  // Disparity from 12 to ~43 px across the image (depth 4.2 m to 1.2 m).
  const DisparityField disparity = [](double u, double v) { return 12.0 + 0.03 * u + 0.025 * v; };
  const Pair pair = make_pair(disparity);
  const StereoScores sub = run(pair, disparity, descriptor_only());
  StereoMatchOptions integer_only = descriptor_only();
  integer_only.subpixel = false;
  const StereoScores integer = run(pair, disparity, integer_only);
  print("slanted plane, sub-pixel", sub);
  print("slanted plane, integer", integer);
  // Measured: 642 matches, 97.2% within 1%, 0.077 px (integer only: 0.42 px).
  EXPECT_GE(sub.matches, 580);
  EXPECT_GE(sub.within_1pct, 0.92);
  EXPECT_LT(sub.mean_abs_disp_err, 0.11);
  EXPECT_LT(sub.mean_abs_disp_err, 0.3 * integer.mean_abs_disp_err);
}

TEST(StereoMatcher, DisparityRangeIsRespected) {
  const DisparityField disparity = [](double, double) { return 23.37; };
  const Pair pair = make_pair(disparity);
  StereoMatchOptions o;
  o.max_disparity = 20.f;  // the true disparity is outside the allowed range
  const OrbExtractor extractor{OrbOptions{}};
  std::vector<cv::Mat> pyr_l, pyr_r;
  const OrbFeatures left = extractor.extract(pair.left, &pyr_l);
  const OrbFeatures right = extractor.extract(pair.right, &pyr_r);
  const StereoMatches m = match_stereo(left, pyr_l, right, pyr_r, extractor.pyramid(), kFx, kBf, o);
  std::cout << "[ measure ] max disparity 20 on a 23.37 px pair: " << m.num_matches << " matches\n";
  EXPECT_LE(m.num_matches, 10);
  for (std::size_t i = 0; i < left.size(); ++i) {
    if (m.depth[i] > 0) {
      EXPECT_LT(left.keypoints[i].pt.x - m.u_right[i], 20.f);
    }
  }
  EXPECT_THROW(match_stereo(left, pyr_l, right, {}, extractor.pyramid(), kFx, kBf), Error);
  EXPECT_THROW(match_stereo(left, pyr_l, right, pyr_r, extractor.pyramid(), kFx, 0.0), Error);
}

TEST(StereoFlow, FillsUnmatchedKeypoints) {
  const DisparityField disparity = [](double u, double v) { return 12.0 + 0.03 * u + 0.025 * v; };
  const FlowScores s = run_flow(make_pair(disparity), disparity);
  print("slanted plane, optical flow", s);
  EXPECT_GE(s.flow_matches, 220);  // measured 274 on top of 639
  EXPECT_LE(s.wrong, 2);
  EXPECT_LT(s.mean_abs_disp_err, 0.12);  // measured 0.091 px (descriptor matches: 0.075)
}

TEST(StereoFlow, RejectsWhatTheRightCameraDoesNotSee) {
  // The right half of the right image shows another texture: left keypoints
  // whose match would land there have no true match.
  const DisparityField disparity = [](double, double) { return 23.37; };
  Pair pair = make_pair(disparity);
  const cv::Mat other = test::textured_image(640, 480, 7, 1400, 50.0);
  other(cv::Rect(320, 0, 320, 480)).copyTo(pair.right(cv::Rect(320, 0, 320, 480)));
  const FlowScores s = run_flow(pair, disparity);
  print("right half replaced, optical flow", s);
  EXPECT_GE(s.flow_matches, 100);  // the left part still gets its matches
  EXPECT_LE(s.wrong, s.flow_matches / 50);  // measured 1 of 182
}

TEST(StereoFromDepth, VirtualRightCoordinate) {
  std::vector<cv::KeyPoint> raw = {cv::KeyPoint(10.f, 20.f, 7.f), cv::KeyPoint(30.4f, 5.6f, 7.f),
                                   cv::KeyPoint(50.f, 50.f, 7.f), cv::KeyPoint(-3.f, 5.f, 7.f)};
  std::vector<cv::KeyPoint> undistorted = raw;
  undistorted[0].pt.x = 11.f;
  cv::Mat depth(40, 40, CV_32FC1, cv::Scalar(0.f));
  depth.at<float>(20, 10) = 2.f;
  depth.at<float>(6, 30) = 0.5f;
  const StereoMatches m = stereo_from_depth(raw, undistorted, depth, 40.0);
  EXPECT_EQ(m.num_matches, 2);
  EXPECT_FLOAT_EQ(m.depth[0], 2.f);
  EXPECT_FLOAT_EQ(m.u_right[0], 11.f - 20.f);
  EXPECT_FLOAT_EQ(m.u_right[1], 30.4f - 80.f);
  EXPECT_LT(m.depth[2], 0.f);  // outside the depth image
  EXPECT_LT(m.depth[3], 0.f);

  cv::Mat depth16(40, 40, CV_16UC1, cv::Scalar(0));
  depth16.at<std::uint16_t>(20, 10) = 10000;  // TUM: 5000 per metre
  const StereoMatches m16 = stereo_from_depth(raw, raw, depth16, 40.0, 5000.0);
  EXPECT_EQ(m16.num_matches, 1);
  EXPECT_FLOAT_EQ(m16.depth[0], 2.f);
  EXPECT_THROW(stereo_from_depth(raw, raw, cv::Mat(40, 40, CV_8UC1), 40.0), Error);
}

}  // namespace stillslam
