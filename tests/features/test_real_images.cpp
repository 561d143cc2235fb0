// Real images from ../shared (skipped with a message when absent): a COCO
// photo for invariance, the EuRoC micro clip for extraction and stereo.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "euroc_stereo.h"
#include "invariance_helpers.h"
#include "stillslam/features/orb_extractor.h"
#include "stillslam/features/stereo_matcher.h"

namespace stillslam {
namespace {

const std::filesystem::path kShared = STILLSLAM_SHARED_DIR;

}  // namespace

TEST(RealImages, CocoPhotoRotationAndScale) {
  const auto path = kShared / "images/coco128/images/train2017/000000000110.jpg";
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
  if (image.empty()) GTEST_SKIP() << "needs " << path << " (the shared data folder next to the repository)";
  cv::resize(image, image, cv::Size(640, 480), 0, 0, cv::INTER_AREA);
  const OrbExtractor extractor{OrbOptions{}};
  const OrbFeatures a = extractor.extract(image);
  EXPECT_GE(a.size(), 970u);
  const cv::Point2f centre(320.f, 240.f);
  const cv::Mat m = cv::getRotationMatrix2D(centre, 30, 1.3);
  cv::Mat warped;
  cv::warpAffine(image, warped, m, image.size());
  const cv::Matx23d t = m;
  const auto s = test::invariance_scores(a, extractor.extract(warped), warped.size(), [t](const cv::Point2f& p) {
    return cv::Point2f(static_cast<float>(t(0, 0) * p.x + t(0, 1) * p.y + t(0, 2)),
                       static_cast<float>(t(1, 0) * p.x + t(1, 1) * p.y + t(1, 2)));
  });
  std::cout << "[ measure ] coco 000000000110 rotation 30 scale 1.3: visible " << s.visible << " repeatability "
            << s.repeatability << " matches " << s.matches << " correct " << s.correct_matches << " precision "
            << s.match_precision << "\n";
  EXPECT_GE(s.repeatability, 0.50);  // measured 0.556
  EXPECT_GE(s.match_precision, 0.52);  // measured 0.585
  EXPECT_GE(s.correct_matches, 170);  // measured 196
}

TEST(RealImages, EurocStereoPairs) {
  const auto mav0 = kShared / "data/euroc_V1_01_micro/mav0";
  if (!std::filesystem::exists(mav0 / "cam1/sensor.yaml")) {
    GTEST_SKIP() << "needs " << mav0 << " (the shared data folder next to the repository)";
  }
  const test::EurocStereo data = test::load_euroc_stereo(mav0, 5);
  ASSERT_EQ(data.left.size(), 5u);
  EXPECT_NEAR(data.bf / data.fx, 0.110, 0.002);  // EuRoC baseline 11 cm
  OrbOptions options;
  options.n_features = 1200;  // EuRoC.yaml
  const OrbExtractor extractor(options);
  for (std::size_t i = 0; i < data.left.size(); ++i) {
    std::vector<cv::Mat> pl, pr;
    const OrbFeatures l = extractor.extract(data.left[i], &pl);
    const OrbFeatures r = extractor.extract(data.right[i], &pr);
    EXPECT_GE(l.size(), 1150u);
    const StereoMatches m = match_stereo(l, pl, r, pr, extractor.pyramid(), data.fx, data.bf);
    std::vector<float> depths;
    for (float d : m.depth) {
      if (d > 0) depths.push_back(d);
    }
    std::sort(depths.begin(), depths.end());
    const float median = depths[depths.size() / 2];
    std::cout << "[ measure ] EuRoC pair " << i << ": " << l.size() << " keypoints, " << m.num_matches
              << " stereo matches, median depth " << median << " m\n";
    // The Vicon room seen from V1_01's start: walls and floor 1-4 m away.
    EXPECT_GE(m.num_matches, 580);  // measured 638-665 (916-936 with Stereo.flowMatching)
    EXPECT_GT(median, 1.5f);
    EXPECT_LT(median, 3.0f);
  }
}

// Optical flow checked against the descriptor path on real images: every
// other descriptor match is withheld, flow proposes a right column for it, and
// the proposal must land near the descriptor match (the patch refinement then
// searches +-5 level pixels around it).
TEST(RealImages, EurocFlowProposalsAgreeWithDescriptorMatches) {
  const auto mav0 = kShared / "data/euroc_V1_01_micro/mav0";
  if (!std::filesystem::exists(mav0 / "cam1/sensor.yaml")) {
    GTEST_SKIP() << "needs " << mav0 << " (the shared data folder next to the repository)";
  }
  const test::EurocStereo data = test::load_euroc_stereo(mav0, 5);
  OrbOptions options;
  options.n_features = 1200;
  const OrbExtractor extractor(options);
  const StereoMatchOptions descriptors_only;  // the default
  int withheld = 0, proposed = 0, within_1px = 0;
  for (std::size_t i = 0; i < data.left.size(); ++i) {
    std::vector<cv::Mat> pl, pr;
    const OrbFeatures l = extractor.extract(data.left[i], &pl);
    const OrbFeatures r = extractor.extract(data.right[i], &pr);
    const StereoMatches reference = match_stereo(l, pl, r, pr, extractor.pyramid(), data.fx, data.bf, descriptors_only);
    std::vector<float> u_right = reference.u_right;
    std::vector<std::size_t> held;
    for (std::size_t k = 0, n = 0; k < l.size(); ++k) {
      if (u_right[k] >= 0 && n++ % 2 == 0) {
        u_right[k] = -1.f;
        held.push_back(k);
      }
    }
    const std::vector<float> proposals = flow_right_proposals(l, u_right, pl[0], pr[0], StereoFlowOptions{});
    for (std::size_t k : held) {
      ++withheld;
      if (proposals[k] < 0) continue;
      ++proposed;
      within_1px += std::abs(proposals[k] - reference.u_right[k]) < 1.f;
    }
  }
  const double proposed_share = static_cast<double>(proposed) / withheld;
  const double agree_share = static_cast<double>(within_1px) / std::max(1, proposed);
  std::cout << "[ measure ] EuRoC, " << withheld << " withheld descriptor matches: flow proposes " << proposed_share
            << ", of which " << agree_share << " within 1 px of the descriptor match\n";
  EXPECT_GT(proposed_share, 0.7);
  EXPECT_GT(agree_share, 0.9);
}

}  // namespace stillslam
