#include <gtest/gtest.h>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "invariance_helpers.h"
#include "stillslam/features/orb_extractor.h"
#include "textured_image.h"

namespace stillslam {
namespace {

// Thresholds: measured values (see the [ measure ] lines) minus a margin.
constexpr double kMinCorrectCombo = 200;  // measured 244
constexpr double kMinCorrectRot30 = 320;  // measured 381
constexpr double kMinCorrectS12 = 300;  // measured 350
constexpr double kMinCorrectS15 = 200;  // measured 237
constexpr double kMinPrecCombo = 0.62;  // measured 0.707
constexpr double kMinPrecRot30 = 0.75;  // measured 0.845
constexpr double kMinPrecRot90 = 0.98;  // measured 1.000
constexpr double kMinPrecS12 = 0.75;  // measured 0.837
constexpr double kMinPrecS15 = 0.62;  // measured 0.705
constexpr double kMinRepRot30 = 0.60;  // measured 0.676
constexpr double kMinRepRot90 = 0.88;  // measured 0.940
constexpr double kMinRepS12 = 0.62;  // measured 0.700
constexpr double kMinRepS15 = 0.68;  // measured 0.761

struct Warped {
  cv::Mat image;
  test::PointMap map;
};

// Rotation by `degrees` and scaling by `scale` about the image centre.
Warped similarity(const cv::Mat& image, double degrees, double scale) {
  const cv::Point2f centre(image.cols * 0.5f, image.rows * 0.5f);
  const cv::Mat m = cv::getRotationMatrix2D(centre, degrees, scale);
  Warped w;
  cv::warpAffine(image, w.image, m, image.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
  const cv::Matx23d a = m;
  w.map = [a](const cv::Point2f& p) {
    return cv::Point2f(static_cast<float>(a(0, 0) * p.x + a(0, 1) * p.y + a(0, 2)),
                       static_cast<float>(a(1, 0) * p.x + a(1, 1) * p.y + a(1, 2)));
  };
  return w;
}

void print(const char* name, const test::InvarianceScores& s) {
  std::cout << "[ measure ] " << name << ": visible " << s.visible << " repeatability " << s.repeatability
            << " matches " << s.matches << " correct " << s.correct_matches << " precision " << s.match_precision
            << "\n";
}

class OrbInvariance : public ::testing::Test {
 protected:
  void SetUp() override {
    image_ = test::textured_image();
    reference_ = extractor_.extract(image_);
  }
  cv::Mat image_;
  OrbExtractor extractor_{OrbOptions{}};
  OrbFeatures reference_;
};

}  // namespace

TEST_F(OrbInvariance, Rotation30) {
  const Warped w = similarity(image_, 30, 1.0);
  const auto s = test::invariance_scores(reference_, extractor_.extract(w.image), w.image.size(), w.map);
  print("rotation 30", s);
  EXPECT_GE(s.repeatability, kMinRepRot30);
  EXPECT_GE(s.match_precision, kMinPrecRot30);
  EXPECT_GE(s.correct_matches, kMinCorrectRot30);
}

TEST_F(OrbInvariance, Rotation90ExactAndAnglesShiftBy90) {
  cv::Mat rotated;
  cv::rotate(image_, rotated, cv::ROTATE_90_CLOCKWISE);  // (x, y) -> (H - 1 - y, x)
  const float h = static_cast<float>(image_.rows);
  const test::PointMap map = [h](const cv::Point2f& p) { return cv::Point2f(h - 1.f - p.y, p.x); };
  const OrbFeatures b = extractor_.extract(rotated);
  const auto s = test::invariance_scores(reference_, b, rotated.size(), map);
  print("rotation 90", s);
  EXPECT_GE(s.repeatability, kMinRepRot90);
  EXPECT_GE(s.match_precision, kMinPrecRot90);

  // Same keypoint found at the same level in both images: in image axes (y
  // down) a clockwise turn adds +90 degrees to every orientation.
  int pairs = 0, within_3deg = 0;
  double sum_abs = 0;
  for (const auto& ka : reference_.keypoints) {
    const cv::Point2f p = map(ka.pt);
    for (const auto& kb : b.keypoints) {
      if (kb.octave != ka.octave || cv::norm(kb.pt - p) > 0.5) continue;
      float d = kb.angle - ka.angle - 90.f;
      d = std::fmod(d + 540.f, 360.f) - 180.f;
      ++pairs;
      sum_abs += std::abs(d);
      within_3deg += std::abs(d) <= 3.f;
    }
  }
  std::cout << "[ measure ] rotation 90 orientation: pairs " << pairs << " mean |err| " << sum_abs / pairs
            << " deg, within 3 deg " << static_cast<double>(within_3deg) / pairs << "\n";
  // Measured 894 of ~1000; with keypoints mapped as x * 1.2^l instead of by
  // pixel centres (LevelMapping) high levels stop coinciding: 497.
  EXPECT_GE(pairs, 800);
  EXPECT_GE(static_cast<double>(within_3deg) / pairs, 0.95);
  EXPECT_LE(sum_abs / pairs, 1.0);
}

TEST_F(OrbInvariance, Scale12) {
  const Warped w = similarity(image_, 0, 1.2);
  const auto s = test::invariance_scores(reference_, extractor_.extract(w.image), w.image.size(), w.map);
  print("scale 1.2", s);
  EXPECT_GE(s.repeatability, kMinRepS12);
  EXPECT_GE(s.match_precision, kMinPrecS12);
  EXPECT_GE(s.correct_matches, kMinCorrectS12);
}

TEST_F(OrbInvariance, Scale15) {
  const Warped w = similarity(image_, 0, 1.5);
  const auto s = test::invariance_scores(reference_, extractor_.extract(w.image), w.image.size(), w.map);
  print("scale 1.5", s);
  EXPECT_GE(s.repeatability, kMinRepS15);
  EXPECT_GE(s.match_precision, kMinPrecS15);
  EXPECT_GE(s.correct_matches, kMinCorrectS15);
}

TEST_F(OrbInvariance, RotationAndScaleTogether) {
  const Warped w = similarity(image_, -45, 1.3);
  const auto s = test::invariance_scores(reference_, extractor_.extract(w.image), w.image.size(), w.map);
  print("rotation -45 scale 1.3", s);
  EXPECT_GE(s.match_precision, kMinPrecCombo);
  EXPECT_GE(s.correct_matches, kMinCorrectCombo);
}

}  // namespace stillslam

namespace stillslam {

// The generated (unlearned, Gaussian G II) pattern against OpenCV's learned
// rBRIEF pattern, both computed on our keypoints: correct matches over four
// warps. Measured: ours 1415, OpenCV's pattern 1422 (a learned table buys
// nothing measurable here, so none is used).
TEST(OrbDescriptor, GeneratedPatternMatchesAsWellAsLearnedOne) {
  const cv::Mat image = test::textured_image();
  const OrbExtractor extractor{OrbOptions{}};
  const cv::Ptr<cv::ORB> opencv = cv::ORB::create(5000, 1.2f, 8, 31, 0, 2, cv::ORB::HARRIS_SCORE, 31, 20);
  auto with_opencv_pattern = [&](const cv::Mat& im, const OrbFeatures& f) {
    OrbFeatures out;
    out.keypoints = f.keypoints;
    opencv->compute(im, out.keypoints, out.descriptors);
    return out;
  };
  int ours = 0, learned = 0;
  for (auto [angle, scale] : {std::pair{30.0, 1.0}, {0.0, 1.3}, {-45.0, 1.2}, {10.0, 1.0}}) {
    const Warped w = similarity(image, angle, scale);
    const OrbFeatures a = extractor.extract(image), b = extractor.extract(w.image);
    ours += test::invariance_scores(a, b, w.image.size(), w.map).correct_matches;
    learned += test::invariance_scores(with_opencv_pattern(image, a), with_opencv_pattern(w.image, b),
                                       w.image.size(), w.map)
                   .correct_matches;
  }
  std::cout << "[ measure ] correct matches over 4 warps: generated pattern " << ours << ", OpenCV learned pattern "
            << learned << "\n";
  EXPECT_GE(ours, 0.93 * learned);
  EXPECT_GE(ours, 1300);
}

}  // namespace stillslam
