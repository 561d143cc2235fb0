#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "stillslam/core/error.h"
#include "stillslam/features/orb_extractor.h"
#include "textured_image.h"

namespace stillslam {

TEST(OrbExtractor, CountCloseToRequestedOnTexturedImage) {
  const cv::Mat image = test::textured_image();
  for (int n : {500, 1000, 2000}) {
    OrbOptions o;
    o.n_features = n;
    const OrbFeatures f = OrbExtractor(o).extract(image);
    std::cout << "[ measure ] n_features=" << n << " extracted=" << f.size() << "\n";
    EXPECT_LE(static_cast<int>(f.size()), n);
    EXPECT_GE(static_cast<double>(f.size()), 0.97 * n);
    EXPECT_EQ(f.descriptors.rows, static_cast<int>(f.size()));
    EXPECT_EQ(f.descriptors.cols, 32);
    EXPECT_EQ(f.descriptors.type(), CV_8UC1);
  }
}

TEST(OrbExtractor, KeypointFieldsAreConsistent) {
  const cv::Mat image = test::textured_image();
  const OrbExtractor extractor{OrbOptions{}};
  std::vector<cv::Mat> pyramid;
  const OrbFeatures f = extractor.extract(image, &pyramid);
  ASSERT_EQ(pyramid.size(), 8u);
  EXPECT_EQ(cv::norm(pyramid[0], image, cv::NORM_INF), 0.0);
  std::vector<int> per_level(8, 0);
  int previous_level = 0;
  for (const auto& kp : f.keypoints) {
    ASSERT_GE(kp.octave, previous_level);  // grouped by level, in order
    previous_level = kp.octave;
    ++per_level[static_cast<std::size_t>(kp.octave)];
    const float s = extractor.pyramid().scale[static_cast<std::size_t>(kp.octave)];
    EXPECT_GE(kp.pt.x, 16 * s - 1e-3);
    EXPECT_LE(kp.pt.x, 640 - 16 * s);
    EXPECT_GE(kp.pt.y, 16 * s - 1e-3);
    EXPECT_LE(kp.pt.y, 480 - 16 * s);
    EXPECT_NEAR(kp.size, 31.f * s, 1e-3);
    EXPECT_GE(kp.angle, 0.f);
    EXPECT_LT(kp.angle, 360.f);
    EXPECT_GT(kp.response, 0.f);
  }
  for (int l = 0; l < 8; ++l) {
    EXPECT_LE(per_level[l], extractor.features_per_level()[l]);
    EXPECT_GE(per_level[l], extractor.features_per_level()[l] * 9 / 10) << "level " << l;
  }
}

namespace {

// Keypoint counts in an 8 x 6 partition of a 640 x 480 image.
std::vector<int> cell_counts(const std::vector<cv::KeyPoint>& keypoints) {
  std::vector<int> cells(48, 0);
  for (const auto& kp : keypoints) {
    ++cells[static_cast<std::size_t>(std::min(5, static_cast<int>(kp.pt.y / 80)) * 8 +
                                     std::min(7, static_cast<int>(kp.pt.x / 80)))];
  }
  return cells;
}

double coefficient_of_variation(const std::vector<int>& v) {
  double mean = 0, var = 0;
  for (int x : v) mean += x;
  mean /= static_cast<double>(v.size());
  for (int x : v) var += (x - mean) * (x - mean);
  return std::sqrt(var / static_cast<double>(v.size())) / mean;
}

}  // namespace

TEST(OrbExtractor, EvenSpatialDistribution) {
  const cv::Mat image = test::textured_image(640, 480, 7, 12000, 16.0);  // uniform texture
  const std::vector<int> cells = cell_counts(OrbExtractor(OrbOptions{}).extract(image).keypoints);
  std::vector<cv::KeyPoint> opencv_keypoints;
  cv::ORB::create(1000)->detect(image, opencv_keypoints);
  const std::vector<int> opencv_cells = cell_counts(opencv_keypoints);
  for (int r = 0; r < 6; ++r) {
    std::cout << "[ measure ]";
    for (int c = 0; c < 8; ++c) std::cout << ' ' << cells[static_cast<std::size_t>(r * 8 + c)];
    std::cout << "   cv::ORB:";
    for (int c = 0; c < 8; ++c) std::cout << ' ' << opencv_cells[static_cast<std::size_t>(r * 8 + c)];
    std::cout << "\n";
  }
  const auto [lo, hi] = std::minmax_element(cells.begin(), cells.end());
  const double cv_ours = coefficient_of_variation(cells), cv_opencv = coefficient_of_variation(opencv_cells);
  std::cout << "[ measure ] 8x6 cell counts min=" << *lo << " max=" << *hi << " coefficient of variation "
            << cv_ours << " (cv::ORB " << cv_opencv << ")\n";
  EXPECT_GE(*lo, 3);  // no empty cell (image border cells lose the pyramid levels' borders)
  EXPECT_LE(*hi, 45);
  EXPECT_LT(cv_ours, 0.45);  // measured 0.356; cv::ORB 0.83
}

TEST(OrbExtractor, WeakTextureStillGetsCornersThroughLowThreshold) {
  // Low-contrast copy: FAST at 20 finds little, the per-cell retry at 7 fills in.
  cv::Mat image = test::textured_image();
  image.convertTo(image, CV_8UC1, 0.12, 100);
  OrbOptions o;
  const OrbFeatures with_retry = OrbExtractor(o).extract(image);
  o.min_th_fast = o.ini_th_fast;
  const OrbFeatures without_retry = OrbExtractor(o).extract(image);
  std::cout << "[ measure ] low contrast: with retry " << with_retry.size() << ", without "
            << without_retry.size() << "\n";
  EXPECT_GT(with_retry.size(), 2 * without_retry.size());
  EXPECT_GE(with_retry.size(), 700u);
}

TEST(OrbExtractor, DeterministicAndThreadSafe) {
  const cv::Mat image = test::textured_image();
  const OrbExtractor extractor{OrbOptions{}};
  const OrbFeatures reference = extractor.extract(image);
  OrbFeatures a, b;
  std::thread ta([&] { a = extractor.extract(image); });
  std::thread tb([&] { b = extractor.extract(image); });
  ta.join();
  tb.join();
  for (const OrbFeatures* f : {&a, &b}) {
    ASSERT_EQ(f->size(), reference.size());
    for (std::size_t i = 0; i < reference.size(); ++i) {
      ASSERT_EQ(f->keypoints[i].pt, reference.keypoints[i].pt);
      ASSERT_EQ(f->keypoints[i].angle, reference.keypoints[i].angle);
      ASSERT_EQ(f->keypoints[i].octave, reference.keypoints[i].octave);
    }
    EXPECT_EQ(cv::norm(f->descriptors, reference.descriptors, cv::NORM_HAMMING), 0.0);
  }
}

TEST(OrbExtractor, SameOutputWithOneOrTwoThreads) {
  const cv::Mat image = test::textured_image();
  const OrbExtractor extractor{OrbOptions{}};
  const int threads = cv::getNumThreads();
  cv::setNumThreads(1);
  const OrbFeatures serial = extractor.extract(image);
  cv::setNumThreads(std::max(2, threads));
  const OrbFeatures parallel = extractor.extract(image);
  cv::setNumThreads(threads);
  ASSERT_EQ(serial.size(), parallel.size());
  for (std::size_t i = 0; i < serial.size(); ++i) {
    ASSERT_EQ(serial.keypoints[i].pt, parallel.keypoints[i].pt);
    ASSERT_EQ(serial.keypoints[i].angle, parallel.keypoints[i].angle);
  }
  EXPECT_EQ(cv::norm(serial.descriptors, parallel.descriptors, cv::NORM_HAMMING), 0.0);
}

TEST(OrbExtractor, ExclusionMaskMovesTheWholeBudgetOutsideIt) {
  // A person covering the left 60% of the view: none of the features land on
  // it, and the budget is spent on the rest instead of being lost.
  const cv::Mat image = test::textured_image();
  const OrbExtractor extractor{OrbOptions{}};
  cv::Mat1b person(image.size(), uchar{0});
  person(cv::Rect(0, 0, image.cols * 6 / 10, image.rows)).setTo(255);
  const OrbFeatures all = extractor.extract(image);
  const OrbFeatures outside = extractor.extract(image, person, nullptr);
  std::size_t all_outside = 0;
  for (const cv::KeyPoint& kp : all.keypoints) all_outside += kp.pt.x >= image.cols * 0.6f;
  for (const cv::KeyPoint& kp : outside.keypoints) EXPECT_GE(kp.pt.x, image.cols * 0.6f - 1.0f);
  std::cout << "[ measure ] features outside the mask: filtered after extraction " << all_outside
            << ", extracted outside it " << outside.size() << "\n";
  EXPECT_LT(all_outside, 0.5 * all.size());
  EXPECT_GE(static_cast<double>(outside.size()), 0.8 * all.size());
  EXPECT_EQ(outside.descriptors.rows, static_cast<int>(outside.size()));
  // An empty or all-zero mask changes nothing.
  const OrbFeatures none = extractor.extract(image, cv::Mat1b(image.size(), uchar{0}), nullptr);
  ASSERT_EQ(none.size(), all.size());
  EXPECT_EQ(cv::norm(none.descriptors, all.descriptors, cv::NORM_HAMMING), 0.0);
  EXPECT_THROW(extractor.extract(image, cv::Mat1b(10, 10, uchar{0}), nullptr), Error);
}

TEST(OrbExtractor, BadInputsGiveClearErrors) {
  const OrbExtractor extractor{OrbOptions{}};
  EXPECT_THROW(extractor.extract(cv::Mat()), Error);
  EXPECT_THROW(extractor.extract(cv::Mat(480, 640, CV_8UC3, cv::Scalar::all(0))), Error);
  EXPECT_THROW(extractor.extract(cv::Mat(480, 640, CV_32FC1, cv::Scalar::all(0))), Error);
  // Tiny and flat images are valid input with no features.
  EXPECT_TRUE(extractor.extract(cv::Mat(20, 20, CV_8UC1, cv::Scalar(0))).empty());
  std::vector<cv::Mat> pyramid;
  EXPECT_TRUE(extractor.extract(cv::Mat(2, 3, CV_8UC1, cv::Scalar(7)), &pyramid).empty());
  EXPECT_EQ(pyramid.size(), 8u);
  // A non-continuous ROI of a larger image is fine.
  const cv::Mat big = test::textured_image();
  const OrbFeatures roi = extractor.extract(big(cv::Rect(100, 50, 400, 300)));
  EXPECT_GE(roi.size(), 950u);
  EXPECT_TRUE(extractor.extract(cv::Mat(480, 640, CV_8UC1, cv::Scalar(128))).empty());
}

}  // namespace stillslam
