#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>

#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>

#include "io/dataset_fixtures.h"
#include "io/temp_dir.h"
#include "stillslam/core/error.h"
#include "stillslam/io/dataset.h"
#include "stillslam/io/euroc_dataset.h"

namespace stillslam {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

const fs::path kClip = fs::path(STILLSLAM_SHARED_DIR) / "data" / "euroc_V1_01_micro";

CameraSettings preset(const std::string& name) {
  return load_camera_settings(fs::path(STILLSLAM_SOURCE_DIR) / "config" / name);
}

// Camera settings without a stereo description: calibration comes from sensor.yaml.
CameraSettings mono_settings() {
  CameraSettings s;
  s.camera.fx = s.camera.fy = 458;
  s.camera.cx = 367;
  s.camera.cy = 248;
  return s;
}

struct RowDifference {
  double median = 1e9;          // median |v_left - v_right| of the matches, pixels
  double within_one_px = 0;     // fraction of matches with |v_left - v_right| <= 1 px
  std::size_t matches = 0;
};

// Row differences of cross-checked ORB matches between two images.
RowDifference row_difference(const cv::Mat& left, const cv::Mat& right) {
  auto orb = cv::ORB::create(1500);
  std::vector<cv::KeyPoint> kl, kr;
  cv::Mat dl, dr;
  orb->detectAndCompute(left, cv::noArray(), kl, dl);
  orb->detectAndCompute(right, cv::noArray(), kr, dr);
  cv::BFMatcher matcher(cv::NORM_HAMMING, true);
  std::vector<cv::DMatch> matches;
  matcher.match(dl, dr, matches);
  std::vector<double> dv;
  for (const cv::DMatch& m : matches) {
    const cv::Point2f pl = kl[m.queryIdx].pt, pr = kr[m.trainIdx].pt;
    const double disparity = pl.x - pr.x;
    // Good matches only, and a plausible disparity, so the statistic measures
    // the geometry rather than mismatches.
    if (m.distance < 40 && disparity > -5 && disparity < 120) dv.push_back(std::abs(pl.y - pr.y));
  }
  if (dv.empty()) return {};
  std::sort(dv.begin(), dv.end());
  const auto close = std::count_if(dv.begin(), dv.end(), [](double d) { return d <= 1.0; });
  return {dv[dv.size() / 2], static_cast<double>(close) / static_cast<double>(dv.size()), dv.size()};
}

class EurocClip : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kClip / "mav0" / "cam0" / "data.csv")) {
      GTEST_SKIP() << "real EuRoC clip not found at " << kClip << " (../shared next to the repo)";
    }
  }
};

TEST_F(EurocClip, ListsImuAndRectifiedCalibration) {
  const auto dataset = open_dataset(kClip, preset("euroc.yaml"));
  EXPECT_EQ(dataset->kind(), "euroc");
  EXPECT_EQ(dataset->sensor(), SensorType::Stereo);
  ASSERT_EQ(dataset->size(), 95u);  // cam1/data.csv lists 4 more stamps than there are frames
  EXPECT_NEAR(dataset->timestamp(0), 1403715273.262142976, 1e-6);
  EXPECT_NEAR(dataset->timestamp(94), 1403715277.962142976, 1e-6);
  const auto& euroc = dynamic_cast<const EurocDataset&>(*dataset);
  EXPECT_EQ(euroc.unpaired_frames(), 0u);
  ASSERT_EQ(euroc.imu().size(), 29120u);
  EXPECT_NEAR(euroc.imu().front().timestamp, 1403715273.262142976, 1e-6);
  EXPECT_NEAR(euroc.imu().front().accel.x(), 9.0874956666666655, 1e-12);
  EXPECT_NEAR(euroc.imu().front().gyro.z(), 0.07749261878854824, 1e-12);

  const auto rect = dataset->rectified_stereo();
  ASSERT_TRUE(rect.has_value());
  EXPECT_TRUE(rect->rectified);
  EXPECT_NEAR(rect->baseline, 0.110078, 1e-5);
  // The rectifying rotation equals LEFT.R of ORB-SLAM's EuRoC.yaml (same
  // calibration). Its intrinsics (fx 435.20, cx 367.45, cy 252.20) came from
  // an older OpenCV's alpha-0 rule; OpenCV 4.6 picks a slightly tighter crop.
  const cv::Matx33d orbslam_left_r(0.999966347530033, -0.001422739138722922, 0.008079580483432283,
                                   0.001365741834644127, 0.9999741760894847, 0.007055629199258132,
                                   -0.008089410156878961, -0.007044357138835809, 0.9999424675829176);
  const auto& euroc_rect = dynamic_cast<const EurocDataset&>(*dataset).rectifier();
  EXPECT_LT(cv::norm(euroc_rect.left_rotation() - orbslam_left_r, cv::NORM_INF), 1e-9);
  EXPECT_NEAR(rect->left.fx, 435.7, 1.0);
  EXPECT_NEAR(rect->left.cx, 366.0, 3.0);
  EXPECT_NEAR(rect->left.cy, 254.6, 3.0);
  // alpha 0: every rectified pixel comes from inside both raw images.
  const cv::Mat white(480, 752, CV_8UC1, cv::Scalar(255));
  EXPECT_EQ(cv::countNonZero(euroc_rect.rectify_left(white) < 128), 0);
  EXPECT_EQ(cv::countNonZero(euroc_rect.rectify_right(white) < 128), 0);
  EXPECT_DOUBLE_EQ(rect->left.fx, rect->right.fx);
  EXPECT_TRUE(rect->left.distortion.empty());
  EXPECT_EQ(rect->left.width, 752);
  EXPECT_EQ(rect->left.height, 480);

  // sensor.yaml gives the same rectification as the preset.
  const auto from_sensor_yaml = open_dataset(kClip, mono_settings())->rectified_stereo();
  ASSERT_TRUE(from_sensor_yaml.has_value());
  EXPECT_NEAR(from_sensor_yaml->left.fx, rect->left.fx, 1e-6);
  EXPECT_NEAR(from_sensor_yaml->baseline, rect->baseline, 1e-9);
  // Opening mav0 directly works too.
  EXPECT_EQ(open_dataset(kClip / "mav0", mono_settings())->size(), 95u);
}

TEST_F(EurocClip, RectifiedRowsAreEpipolarLines) {
  const auto dataset = open_dataset(kClip, preset("euroc.yaml"));
  for (std::size_t i : {std::size_t{0}, std::size_t{60}}) {
    SCOPED_TRACE(i);
    const SensorFrame f = dataset->load(i);
    ASSERT_TRUE(f.valid);
    ASSERT_EQ(f.gray.type(), CV_8UC1);
    ASSERT_EQ(f.right.type(), CV_8UC1);
    ASSERT_EQ(f.color.type(), CV_8UC3);
    EXPECT_EQ(f.gray.size(), cv::Size(752, 480));
    EXPECT_TRUE(f.depth.empty());
    EXPECT_EQ(f.name, std::to_string(1403715273262142976LL + (i == 0 ? 0 : 3000000000LL)) + ".png");

    const RowDifference rectified = row_difference(f.gray, f.right);
    EXPECT_GT(rectified.matches, 150u);
    EXPECT_LT(rectified.median, 0.5);
    EXPECT_GT(rectified.within_one_px, 0.6);
    // The raw pair is several pixels off: the check above is meaningful.
    const cv::Mat raw_left = cv::imread((kClip / "mav0/cam0/data" / f.name).string(), cv::IMREAD_GRAYSCALE);
    const cv::Mat raw_right = cv::imread((kClip / "mav0/cam1/data" / f.name).string(), cv::IMREAD_GRAYSCALE);
    const RowDifference raw = row_difference(raw_left, raw_right);
    EXPECT_GT(raw.matches, 50u);
    EXPECT_GT(raw.median, 2.0);
    EXPECT_LT(raw.within_one_px, 0.3);
    std::cout << "frame " << i << ": |v_l - v_r| rectified median " << rectified.median << " px, within 1 px "
              << rectified.within_one_px << " (" << rectified.matches << " matches); raw median " << raw.median
              << " px, within 1 px " << raw.within_one_px << " (" << raw.matches << " matches)\n";
  }
}

TEST(EurocDataset, GeneratedLayoutPairsAndErrors) {
  TempDir dir;
  const fs::path seq = test::write_euroc_fixture(dir.path(), 4);
  const fs::path mav0 = seq / "mav0";
  // cam1 misses the third frame: that cam0 frame has no partner.
  {
    std::ofstream c1(mav0 / "cam1" / "data.csv");
    c1 << "#timestamp [ns],filename\n";
    for (long long k : {0LL, 1LL, 3LL}) {
      const std::string ts = std::to_string(1403715273262142976LL + 50000000LL * k);
      c1 << ts << "," << ts << ".png\n";
    }
  }
  const auto d = open_dataset(seq, mono_settings());
  ASSERT_EQ(d->size(), 3u);
  const auto& euroc = dynamic_cast<const EurocDataset&>(*d);
  EXPECT_EQ(euroc.unpaired_frames(), 1u);
  EXPECT_EQ(euroc.imu().size(), 40u);
  EXPECT_NEAR(euroc.imu()[3].gyro.x(), 0.03, 1e-12);
  EXPECT_NEAR(euroc.imu()[3].accel.z(), -0.3, 1e-12);
  EXPECT_NEAR(d->timestamp(2) - d->timestamp(0), 0.15, 1e-6);
  EXPECT_NEAR(euroc.raw_stereo().T_c1_c2.translation().x(), 0.110074, 1e-6);
  EXPECT_NEAR(d->rectified_stereo()->baseline, 0.110078, 1e-5);
  EXPECT_EQ(d->load(2).gray.size(), cv::Size(752, 480));

  // A truncated right image is an Error naming it.
  const std::string bad = std::to_string(1403715273262142976LL + 50000000LL) + ".png";
  test::truncate_copy(mav0 / "cam1" / "data" / bad, mav0 / "cam1" / "data" / "tmp.png", 0.3);
  fs::rename(mav0 / "cam1" / "data" / "tmp.png", mav0 / "cam1" / "data" / bad);
  try {
    d->load(1);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cam1/data/" + bad + ": cannot decode image"), std::string::npos)
        << e.what();
  }
  // Wrong image size.
  cv::imwrite((mav0 / "cam1" / "data" / bad).string(), test::textured_image(752, 480, 1, 9));
  cv::imwrite((mav0 / "cam0" / "data" / bad).string(), cv::Mat(100, 100, CV_8UC1, cv::Scalar(3)));
  try {
    d->load(1);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("100x100 but the calibration expects 752x480"), std::string::npos)
        << e.what();
  }
  // Broken sensor.yaml: the key is named.
  std::ofstream(mav0 / "cam1" / "sensor.yaml") << "%YAML:1.0\nintrinsics: [1, 2, 3]\n";
  try {
    open_dataset(seq, mono_settings());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("sensor.yaml: key 'intrinsics'"), std::string::npos) << e.what();
  }
  // Empty camera list.
  std::ofstream(mav0 / "cam0" / "data.csv") << "#timestamp [ns],filename\n";
  try {
    open_dataset(seq, mono_settings());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cam0/data.csv: no stereo frames"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stillslam

namespace stillslam {
namespace {

// `stillslam simulate` writes a TUM and an EuRoC layout into one folder; the
// settings pick one. An already ideal pair passes through rectification
// unchanged.
TEST(OpenDataset, MixedLayoutChosenBySettings) {
  TempDir dir;
  const fs::path seq = test::write_euroc_fixture(dir.path(), 2);
  // Turn the cameras into an ideal rectified pair (the simulator's).
  const std::string ideal = R"(%YAML:1.0
T_BS:
  cols: 4
  rows: 4
  data: [1.0, 0.0, 0.0, X, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]
resolution: [752, 480]
camera_model: pinhole
intrinsics: [450.0, 450.0, 375.5, 239.5]
distortion_model: radial-tangential
distortion_coefficients: [0.0, 0.0, 0.0, 0.0]
)";
  std::string cam1 = ideal;
  cam1.replace(cam1.find('X'), 1, "0.12");
  std::string cam0 = ideal;
  cam0.replace(cam0.find('X'), 1, "0.0");
  std::ofstream(seq / "mav0/cam0/sensor.yaml") << cam0;
  std::ofstream(seq / "mav0/cam1/sensor.yaml") << cam1;
  test::write_tum_fixture(dir.path(), 3);
  fs::copy(dir.path() / "rgbd_dataset_freiburg3_test", seq, fs::copy_options::recursive);

  CameraSettings rgbd = mono_settings();
  EXPECT_EQ(open_dataset(seq, rgbd)->kind(), "tum");
  CameraSettings stereo = mono_settings();
  stereo.stereo = StereoCalibration{};  // any stereo description
  stereo.stereo->rectified = true;
  const auto d = open_dataset(seq, stereo);
  ASSERT_EQ(d->kind(), "euroc");
  const auto rect = d->rectified_stereo();
  EXPECT_NEAR(rect->left.fx, 450.0, 1e-6);
  EXPECT_NEAR(rect->left.cx, 375.5, 1e-6);
  EXPECT_NEAR(rect->left.cy, 239.5, 1e-6);
  EXPECT_NEAR(rect->baseline, 0.12, 1e-9);
  // Remapping is the identity.
  const SensorFrame f = d->load(0);
  const cv::Mat raw = cv::imread((seq / "mav0/cam0/data" / f.name).string(), cv::IMREAD_GRAYSCALE);
  cv::Mat diff;
  cv::absdiff(f.gray, raw, diff);
  EXPECT_EQ(cv::countNonZero(diff), 0);
}

}  // namespace
}  // namespace stillslam
