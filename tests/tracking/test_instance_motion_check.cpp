// The instance motion check on a synthetic scene with known motion: a still
// instance is kept as static after its evidence window, a slowly moving one
// never, with residuals judged against the background of the same frames.
#include <gtest/gtest.h>

#include <random>

#include "stillslam/core/error.h"
#include "stillslam/tracking/instance_motion_check.h"

namespace stillslam {
namespace {

PinholeCamera camera() { return PinholeCamera(pinhole_calibration(500, 500, 320, 240, 640, 480), 40.0); }

struct ScenePoint {
  Eigen::Vector3d p_world;
  std::uint32_t instance;
  Eigen::Vector3d velocity;  // metres per frame
  cv::Mat descriptor;        // fixed per point, so matching finds it again
};

std::vector<ScenePoint> scene(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<ScenePoint> points;
  auto add = [&](int n, const Eigen::Vector3d& centre, double spread, std::uint32_t id, const Eigen::Vector3d& v) {
    for (int i = 0; i < n; ++i) {
      cv::Mat d(1, 32, CV_8U);
      for (int b = 0; b < 32; ++b) d.at<uchar>(0, b) = static_cast<uchar>(byte(rng));
      points.push_back({centre + spread * Eigen::Vector3d(u(rng), u(rng), 0.2 * u(rng)), id, v, d});
    }
  };
  add(200, {0, 0, 4}, 2.0, 0, Eigen::Vector3d::Zero());               // the room
  add(30, {-0.6, 0.1, 2.0}, 0.25, 1, Eigen::Vector3d::Zero());          // a person sitting still
  add(30, {0.6, 0.1, 2.0}, 0.25, 2, {0.1 / 30, 0, 0});                  // a person walking slowly: 0.1 m/s
  return points;
}

MotionCheckFrame frame_at(int k, const std::vector<ScenePoint>& points, std::mt19937& rng, double pixel_noise) {
  const PinholeCamera cam = camera();
  std::normal_distribution<double> noise(0, pixel_noise);
  MotionCheckFrame f;
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();
  T_world_cam.translation() = Eigen::Vector3d(0.01 * k, 0.003 * k, 0);
  T_world_cam.linear() = Eigen::AngleAxisd(0.004 * k, Eigen::Vector3d::UnitY()).toRotationMatrix();
  f.T_cam_world = T_world_cam.inverse();
  f.categories = {{1, "person"}, {2, "person"}};
  for (const ScenePoint& s : points) {
    const Eigen::Vector3d p_cam = f.T_cam_world * (s.p_world + k * s.velocity);
    f.pixels.push_back(cam.project(p_cam) + Eigen::Vector2d(noise(rng), noise(rng)));
    f.depth.push_back(static_cast<float>(p_cam.z()));
    f.instance.push_back(s.instance);
    f.descriptors.push_back(s.descriptor);
  }
  return f;
}

TEST(InstanceMotionCheck, StillInstanceIsKeptMovingInstanceIsNot) {
  std::mt19937 rng(3);
  const std::vector<ScenePoint> points = scene(rng);
  InstanceMotionCheckOptions o;
  o.span = 6;
  o.evidence.default_frames = 10;
  InstanceMotionCheck check(camera(), o);
  int still_static_from = -1;
  for (int k = 0; k < 40; ++k) {
    const MotionCheckResult r = check.add(frame_at(k, points, rng, 0.5));
    if (k < o.span) {
      EXPECT_FALSE(r.compared);
      continue;
    }
    ASSERT_TRUE(r.compared);
    EXPECT_EQ(r.background_matches, 200);
    EXPECT_LT(r.background_median_px, 1.0);  // pixel noise only
    ASSERT_EQ(r.instances.size(), 2u);
    // 0.1 m/s over 6 frames at 2 m: 2 cm -> ~5 px.
    EXPECT_GT(r.instances[1].median_px, 3.0);
    EXPECT_EQ(r.instances[1].verdict, MotionVerdict::Disagrees);
    if (check.is_static(1) && still_static_from < 0) still_static_from = k;
    EXPECT_FALSE(check.is_static(2));
  }
  EXPECT_EQ(still_static_from, o.span + o.evidence.default_frames - 1);
  check.reset();
  EXPECT_FALSE(check.is_static(1));
  EXPECT_FALSE(check.add(frame_at(41, points, rng, 0.5)).compared);
}

// peek() gives the verdicts and residuals add() of the same frame gives,
// and changes nothing: the frames kept and the evidence stay as they were.
TEST(InstanceMotionCheck, PeekJudgesAFrameWithoutKeepingIt) {
  std::mt19937 rng(7);
  const std::vector<ScenePoint> points = scene(rng);
  InstanceMotionCheckOptions o;
  o.span = 6;
  o.evidence.default_frames = 3;
  InstanceMotionCheck check(camera(), o), twin(camera(), o);
  std::vector<MotionCheckFrame> frames;
  for (int k = 0; k < 20; ++k) frames.push_back(frame_at(k, points, rng, 0.5));
  for (int k = 0; k < 20; ++k) {
    SCOPED_TRACE(k);
    const MotionCheckResult peeked = check.peek(frames[k]);
    const MotionCheckResult peeked_again = check.peek(frames[k]);
    const MotionCheckResult added = check.add(frames[k]);
    twin.add(frames[k]);
    EXPECT_EQ(peeked.compared, added.compared);
    EXPECT_EQ(peeked.compared, k >= o.span);
    EXPECT_EQ(peeked.background_matches, added.background_matches);
    EXPECT_DOUBLE_EQ(peeked.background_median_px, added.background_median_px);
    ASSERT_EQ(peeked.instances.size(), added.instances.size());
    ASSERT_EQ(peeked_again.instances.size(), added.instances.size());
    for (std::size_t i = 0; i < added.instances.size(); ++i) {
      EXPECT_EQ(peeked.instances[i].verdict, added.instances[i].verdict);
      EXPECT_DOUBLE_EQ(peeked.instances[i].median_px, added.instances[i].median_px);
      EXPECT_EQ(peeked.instances[i].is_static, added.instances[i].is_static);
      EXPECT_DOUBLE_EQ(peeked_again.instances[i].log_odds, added.instances[i].log_odds);
    }
    // A peek at a later frame leaves the check as its twin, which never peeked.
    if (k + 1 < 20) check.peek(frames[k + 1]);
    EXPECT_EQ(check.is_static(1), twin.is_static(1));
  }
  EXPECT_TRUE(check.is_static(1));
  EXPECT_FALSE(check.is_static(2));
  // The walking person disagrees in a peek as in add().
  const MotionCheckResult last = check.peek(frame_at(20, points, rng, 0.5));
  ASSERT_EQ(last.instances.size(), 2u);
  EXPECT_EQ(last.instances[1].verdict, MotionVerdict::Disagrees);
}

TEST(InstanceMotionCheck, WithoutDepthTheEpipolarResidualStillSeesCrossingMotion) {
  std::mt19937 rng(5);
  std::vector<ScenePoint> points = scene(rng);
  for (ScenePoint& p : points) {
    if (p.instance == 2) p.velocity = {0, 0.2 / 30, 0};  // rising: across the (horizontal) epipolar lines
  }
  InstanceMotionCheck check(camera());
  MotionCheckResult last;
  for (int k = 0; k < 12; ++k) {
    MotionCheckFrame f = frame_at(k, points, rng, 0.3);
    std::fill(f.depth.begin(), f.depth.end(), 0.f);
    last = check.add(std::move(f));
  }
  ASSERT_TRUE(last.compared);
  ASSERT_EQ(last.instances.size(), 2u);
  EXPECT_EQ(last.instances[0].verdict, MotionVerdict::Agrees);
  EXPECT_EQ(last.instances[1].verdict, MotionVerdict::Disagrees);
}

// Matching only within a window around each earlier feature's predicted
// position (InstanceMotionCheckOptions::window_px) finds the same matches as
// all pairs while the motion stays inside it (with and without depth), and
// drops the matches of an instance that moved farther than the window.
TEST(InstanceMotionCheck, MatchingInAWindowFindsWhatAllPairsFind) {
  std::mt19937 rng(7);
  std::vector<ScenePoint> points = scene(rng);
  const auto residuals = [&](double window, bool with_depth, const std::vector<ScenePoint>& pts) {
    InstanceMotionCheckOptions o;
    o.window_px = window;
    InstanceMotionCheck check(camera(), o);
    std::mt19937 noise_rng(11);
    MotionCheckResult last;
    for (int k = 0; k < 8; ++k) {
      MotionCheckFrame f = frame_at(k, pts, noise_rng, 0.5);
      if (!with_depth) std::fill(f.depth.begin(), f.depth.end(), 0.f);
      last = check.add(std::move(f));
    }
    EXPECT_TRUE(last.compared);
    return last;
  };
  for (const bool with_depth : {true, false}) {
    SCOPED_TRACE(with_depth);
    const MotionCheckResult all = residuals(0, with_depth, points);
    const MotionCheckResult window = residuals(40, with_depth, points);
    EXPECT_EQ(all.background_matches, 200);
    EXPECT_EQ(window.background_residuals, all.background_residuals);
    EXPECT_EQ(window.residuals, all.residuals);
  }
  // The slow walker sped up to 2 m/s: ~100 px over the 6 frames at 2 m.
  for (ScenePoint& p : points) {
    if (p.instance == 2) p.velocity = {2.0 / 30, 0, 0};
  }
  const MotionCheckResult all = residuals(0, true, points), window = residuals(40, true, points);
  ASSERT_EQ(all.residuals.at(2).size(), 30u);
  EXPECT_GT(all.residuals.at(2).front(), 80.0);
  EXPECT_EQ(window.residuals.count(2), 0u);
  EXPECT_EQ(window.residuals.at(1), all.residuals.at(1));
  InstanceMotionCheckOptions bad;
  bad.window_px = -1;
  EXPECT_THROW(bad.check(), Error);
}

TEST(InstanceMotionCheck, MismatchedFeatureListsAreAnError) {
  std::mt19937 rng(1);
  InstanceMotionCheck check(camera());
  MotionCheckFrame f = frame_at(0, scene(rng), rng, 0);
  f.depth.pop_back();
  EXPECT_THROW(check.add(f), Error);
}

}  // namespace
}  // namespace stillslam
