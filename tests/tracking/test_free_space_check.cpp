// The depth test of moved objects (tracking/free_space_check.h) on depth
// images rendered here: a wall 3 m away and a 0.4 x 0.4 m box 2 m away, the
// camera 10 cm to the side between the two views.
#include <gtest/gtest.h>

#include "stillslam/core/option_check.h"
#include "stillslam/tracking/free_space_check.h"

namespace stillslam {
namespace {

constexpr double kWall = 3.0, kBoxZ = 2.0, kHalf = 0.2;

const PinholeCamera& camera() {
  static const PinholeCamera c(pinhole_calibration(500, 500, 320, 240, 640, 480));
  return c;
}

// Depth image of a camera at world x = cam_x (looking along +z) with the box
// centred at world x = box_x; labels: 1 on the box's pixels.
cv::Mat1f render(double cam_x, double box_x, cv::Mat1i* labels = nullptr, double box_z = kBoxZ) {
  cv::Mat1f depth(480, 640);
  if (labels) *labels = cv::Mat1i::zeros(480, 640);
  for (int v = 0; v < 480; ++v) {
    for (int u = 0; u < 640; ++u) {
      const Eigen::Vector3d ray = camera().unproject(Eigen::Vector2d(u, v), 1.0);
      const double x = cam_x + ray.x() * box_z, y = ray.y() * box_z;
      const bool on_box = std::abs(x - box_x) <= kHalf && std::abs(y) <= kHalf;
      depth(v, u) = static_cast<float>(on_box ? box_z : kWall);
      if (labels && on_box) (*labels)(v, u) = 1;
    }
  }
  return depth;
}

// T_cam_world of a camera at world x = cam_x.
Eigen::Isometry3d T_cam_world(double cam_x) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation().x() = -cam_x;
  return T;
}

FreeSpaceCount box_count(double box_then, double box_now, double background_share_max = 0) {
  cv::Mat1i labels;
  const cv::Mat1f now = render(0.1, box_now, &labels), then = render(0.0, box_then);
  const Eigen::Isometry3d T_then_now = T_cam_world(0.0) * T_cam_world(0.1).inverse();
  const auto c = count_seen_through(camera(), now, labels, {0, 1}, T_then_now, then);
  EXPECT_LE(c.at(0).share(), background_share_max);
  return c.at(1);
}

TEST(FreeSpaceCheck, AStillBoxIsSeenThroughOnlyAtItsEdges) {
  const FreeSpaceCount still = box_count(0.0, 0.0);
  std::printf("still box: %d samples, %.3f seen through\n", still.samples, still.share());
  EXPECT_GT(still.samples, 500);
  EXPECT_LT(still.share(), 0.03);
}

TEST(FreeSpaceCheck, AMovedBoxIsSeenThroughWhereItWasNot) {
  // Pushed 20 cm: half of its face is where the earlier view saw the wall.
  const FreeSpaceCount moved = box_count(0.0, 0.2);
  std::printf("box moved 20 cm: %d samples, %.3f seen through\n", moved.samples, moved.share());
  EXPECT_NEAR(moved.share(), 0.5, 0.05);
  // Moved 60 cm: none of it overlaps its old place.
  EXPECT_GT(box_count(0.0, 0.6).share(), 0.97);
}

TEST(FreeSpaceCheck, APoseErrorSeesThroughOnlyAnEdgeOfAStillBox) {
  cv::Mat1i labels;
  const cv::Mat1f now = render(0.1, 0.0, &labels), then = render(0.0, 0.0);
  // The tracked motion 5 cm short: the box's points land 12 px beside it,
  // an eighth of its width, on the wall.
  const Eigen::Isometry3d wrong = T_cam_world(0.0) * T_cam_world(0.05).inverse();
  const auto c = count_seen_through(camera(), now, labels, {0, 1}, wrong, then);
  std::printf("pose 5 cm off: box %.3f, background %.3f\n", c.at(1).share(), c.at(0).share());
  EXPECT_NEAR(c.at(1).share(), 0.125, 0.03);
  EXPECT_EQ(c.at(0).seen_through, 0);  // the wall is the farthest thing: never seen through
}

// Pushed 25 cm away from the camera: its new place lies behind its old one,
// never seen through; with count_nearer the earlier view saw (nearly) all of
// it nearer, unless a person masked then stood there.
TEST(FreeSpaceCheck, ABoxPushedAwayIsSeenNearerWithCountNearer) {
  cv::Mat1i labels;
  const cv::Mat1f now = render(0.1, 0.0, &labels, kBoxZ + 0.25), then = render(0.0, 0.0);
  const Eigen::Isometry3d T_then_now = T_cam_world(0.0) * T_cam_world(0.1).inverse();
  const auto off = count_seen_through(camera(), now, labels, {0, 1}, T_then_now, then);
  EXPECT_GT(off.at(1).samples, 400);
  EXPECT_EQ(off.at(1).seen_through, 0);
  EXPECT_EQ(off.at(1).seen_nearer, 0);
  FreeSpaceOptions o;
  o.count_nearer = true;
  const auto on = count_seen_through(camera(), now, labels, {0, 1}, T_then_now, then, o);
  std::printf("box pushed away 25 cm: %d samples, %.3f seen nearer\n", on.at(1).samples, on.at(1).share());
  EXPECT_GT(on.at(1).share(), 0.9);
  EXPECT_EQ(on.at(1).seen_through, 0);
  EXPECT_LT(on.at(0).share(), 0.02);  // the wall: only the strip the old box hid
  // The same box still (at its old depth): nothing nearer, nothing through.
  cv::Mat1i still_labels;
  const cv::Mat1f still = render(0.1, 0.0, &still_labels);
  EXPECT_LT(count_seen_through(camera(), still, still_labels, {0, 1}, T_then_now, then, o).at(1).share(), 0.03);
  // A person masked in the earlier view over the box's old place: those samples are left out.
  cv::Mat1b people = cv::Mat1b::zeros(480, 640);
  people(cv::Rect(0, 0, 640, 480)) = 255;
  const auto hidden = count_seen_through(camera(), now, labels, {0, 1}, T_then_now, then, o, people);
  EXPECT_EQ(hidden.at(1).samples, 0);
}

// The check the other way round (the motion stage's Motion.freeSpaceVacated):
// the box's pixels in the earlier view put into the current one. Pushed
// 20 cm, half of its old place now shows the wall; still, only its edges.
TEST(FreeSpaceCheck, AMovedBoxLeftItsOldPlace) {
  cv::Mat1i then_labels, still_labels;
  const cv::Mat1f then = render(0.0, 0.0, &then_labels), now = render(0.1, 0.2), still = render(0.1, 0.0);
  const Eigen::Isometry3d T_now_then = T_cam_world(0.1) * T_cam_world(0.0).inverse();
  const auto moved = count_seen_through(camera(), then, then_labels, {0, 1}, T_now_then, now);
  std::printf("box moved 20 cm: %.3f of its old place left\n", moved.at(1).share());
  EXPECT_NEAR(moved.at(1).share(), 0.5, 0.05);
  EXPECT_LT(count_seen_through(camera(), then, then_labels, {0, 1}, T_now_then, still).at(1).share(), 0.03);
}

TEST(FreeSpaceCheck, OptionsAreChecked) {
  FreeSpaceOptions o;
  o.step_px = 0;
  EXPECT_THROW(o.check(), OptionError);
  o = {};
  o.min_gap_m = -1;
  EXPECT_THROW(o.check(), OptionError);
}

}  // namespace
}  // namespace stillslam
