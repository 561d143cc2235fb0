// The viewer's pieces without a server: the JSON of the snapshots,
// the embedded page.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "viewer/groundtruth_overlay.h"
#include "viewer/snapshot_json.h"
#include "viewer/web_files.h"

namespace stillslam::viewer {
namespace {

TEST(SnapshotJson, CountersOverlayAndAtlas) {
  FrameSnapshot f;
  f.index = 7;
  f.state = "ok";
  f.keypoints = {{1.04f, 2.0f}, {3.0f, 4.0f}, {5.0f, 6.0f}};
  f.tracked = {true, false, true};
  f.removed_keypoints = {{10.f, 11.f}};
  FrameSnapshot::Instance person;
  person.class_name = "person";
  person.score = 0.8f;
  person.box = cv::Rect(1, 2, 3, 4);
  person.outline = {{1, 2}, {4, 2}, {4, 6}};
  person.dynamic = true;
  f.instances = {person};
  f.has_pose = true;
  AtlasSnapshot a;
  a.loops_closed = 2;
  MapSnapshot m;
  m.map_id = 3;
  m.active = true;
  m.points = {{0.f, 0.f, 1.f}, {0.1234f, 0.f, 2.f}};
  m.keyframes = {{0, Eigen::Isometry3d::Identity()}, {1, Eigen::Isometry3d::Identity()}};
  m.covisibility = {{0, 1}};
  a.maps = {m};
  a.active_map_id = 3;

  const nlohmann::json s = state_json(&f, &a, RunStatus{.fps = 29.96, .paused = true, .running = true});
  EXPECT_EQ(s["frame"], 7);
  EXPECT_EQ(s["features_kept"], 3);
  EXPECT_EQ(s["features_tracked"], 2);
  EXPECT_EQ(s["features_removed"], 1);
  EXPECT_EQ(s["dynamic_instances"], 1);
  EXPECT_EQ(s["map_points"], 2);
  EXPECT_EQ(s["keyframes"], 2);
  EXPECT_EQ(s["loops_closed"], 2);
  EXPECT_EQ(s["paused"], true);
  EXPECT_DOUBLE_EQ(s["fps"].get<double>(), 30.0);
  ASSERT_EQ(s["pose"].size(), 7u);
  EXPECT_DOUBLE_EQ(s["pose"][6].get<double>(), 1.0);  // qw of the identity
  EXPECT_FALSE(state_json(nullptr, nullptr, {}).contains("map_points"));

  const nlohmann::json o = overlay_json(f);
  EXPECT_EQ(o["kept"].size(), 6u);
  EXPECT_DOUBLE_EQ(o["kept"][0].get<double>(), 1.0);  // rounded to 0.1 px
  EXPECT_EQ(o["tracked"], nlohmann::json({1, 0, 1}));
  EXPECT_EQ(o["removed"], nlohmann::json({10.0, 11.0}));
  ASSERT_EQ(o["instances"].size(), 1u);
  EXPECT_EQ(o["instances"][0]["class"], "person");
  EXPECT_EQ(o["instances"][0]["box"], nlohmann::json({1, 2, 3, 4}));
  EXPECT_EQ(o["instances"][0]["outline"], nlohmann::json({1, 2, 4, 2, 4, 6}));

  const nlohmann::json j = atlas_json(a);
  ASSERT_EQ(j["maps"].size(), 1u);
  EXPECT_EQ(j["maps"][0]["id"], 3);
  EXPECT_EQ(j["maps"][0]["points"].size(), 6u);
  EXPECT_DOUBLE_EQ(j["maps"][0]["points"][3].get<double>(), 0.123);  // 1 mm
  EXPECT_EQ(j["maps"][0]["keyframes"].size(), 14u);
  EXPECT_EQ(j["maps"][0]["covisibility"], nlohmann::json({0, 1}));
}

TEST(GroundTruthOverlay, AlignsTheGroundTruthWithTheMapsTrajectory) {
  // The map's frame is the ground truth's moved by T_map_gt; a second map has too few poses.
  Eigen::Isometry3d T_map_gt = Eigen::Isometry3d::Identity();
  T_map_gt.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.2, 1, 0.1).normalized()).toRotationMatrix();
  T_map_gt.translation() = Eigen::Vector3d(1, -2, 0.5);
  Trajectory gt;
  GroundTruthOverlay overlay({});
  std::vector<Eigen::Vector3d> centres;
  for (int i = 0; i < 40; ++i) {
    StampedPose p;
    p.timestamp = 100 + 0.1 * i;
    p.T_world_cam.translation() = Eigen::Vector3d(std::sin(0.3 * i), 0.1 * i, std::cos(0.2 * i));
    gt.push_back(p);
  }
  GroundTruthOverlay with_gt(gt);
  for (int i = 0; i < 40; i += 2) with_gt.add(gt[i].timestamp + 0.001, T_map_gt * gt[i].T_world_cam.translation(), 3);
  with_gt.add(gt[0].timestamp, Eigen::Vector3d::Zero(), 4);
  const std::vector<Eigen::Vector3d> aligned = with_gt.aligned(3, 1000);
  ASSERT_EQ(aligned.size(), 40u);
  for (int i = 0; i < 40; ++i) {
    EXPECT_LT((aligned[i] - T_map_gt * gt[i].T_world_cam.translation()).norm(), 1e-9) << i;
  }
  EXPECT_EQ(with_gt.aligned(3, 10).size(), 10u);  // thinned
  EXPECT_TRUE(with_gt.aligned(4, 1000).empty());
  EXPECT_TRUE(with_gt.aligned(5, 1000).empty());
  EXPECT_TRUE(overlay.aligned(3, 1000).empty());
}

TEST(WebFiles, PageAndThreeJsAreEmbedded) {
  const WebFile* index = find_web_file("/");
  ASSERT_NE(index, nullptr);
  EXPECT_EQ(index->path, "/index.html");
  EXPECT_NE(index->data.find("id=\"frame-canvas\""), std::string_view::npos);
  const WebFile* three = find_web_file("/vendor/three/three.module.min.js");
  ASSERT_NE(three, nullptr);
  EXPECT_GT(three->data.size(), 500000u);
  EXPECT_EQ(three->content_type, "text/javascript; charset=utf-8");
  EXPECT_NE(find_web_file("/vendor/three/LICENSE"), nullptr);
  EXPECT_EQ(find_web_file("/missing.js"), nullptr);
}

}  // namespace
}  // namespace stillslam::viewer
