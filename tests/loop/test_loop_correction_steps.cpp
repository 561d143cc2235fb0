// Loop correction in three steps (begin under the map lock, the essential
// graph solved without it, finish under it again) on the synthetic circle of
// loop_scene.h: the same map as correct_loop() when nothing happens in
// between, and a keyframe created in between moves with its spanning-tree
// parent.
#include <gtest/gtest.h>

#include "loop/loop_scene.h"
#include "stillslam/loop/loop_correction.h"
#include "stillslam/loop/loop_detector.h"

namespace stillslam {
namespace {

// A scene fed keyframe by keyframe up to its first detected loop.
struct DetectedLoop {
  test::LoopScene scene;
  std::unique_ptr<PlaceRecognizer> recognizer;
  std::optional<LoopDetection> detection;
  int next_keyframe = 0;

  DetectedLoop() : recognizer(std::make_unique<PlaceRecognizer>(std::make_shared<const Vocabulary>(scene.train_vocabulary()))) {
    LoopDetector detector(*recognizer);
    while (!detection && next_keyframe < 42) {
      const KeyFramePtr kf = scene.add_keyframe(next_keyframe++);
      detection = detector.detect(scene.map(), *kf);
      recognizer->add(*kf);
    }
  }
};

void expect_same_poses_and_points(const Map& a, const Map& b, std::uint64_t max_keyframe_id) {
  const auto ka = a.keyframes(), kb = b.keyframes();
  std::size_t compared = 0;
  for (std::size_t k = 0; k < std::min(ka.size(), kb.size()); ++k) {
    if (ka[k]->id() > max_keyframe_id) break;
    ASSERT_EQ(ka[k]->id(), kb[k]->id());
    EXPECT_TRUE(ka[k]->T_cam_world().matrix() == kb[k]->T_cam_world().matrix()) << "keyframe " << ka[k]->id();
    ++compared;
  }
  EXPECT_EQ(compared, max_keyframe_id + 1);
  std::map<std::uint64_t, Eigen::Vector3d> pa;
  for (const auto& p : a.map_points()) {
    if (!p->is_bad() && p->first_keyframe_id() <= max_keyframe_id) pa.emplace(p->id(), p->position());
  }
  std::size_t points = 0;
  for (const auto& p : b.map_points()) {
    if (p->is_bad() || p->first_keyframe_id() > max_keyframe_id) continue;
    const auto it = pa.find(p->id());
    ASSERT_NE(it, pa.end()) << "point " << p->id();
    EXPECT_TRUE(it->second == p->position()) << "point " << p->id();
    ++points;
  }
  EXPECT_EQ(points, pa.size());
  EXPECT_GT(points, 1000u);
}

TEST(LoopCorrectionSteps, InARowTheyGiveCorrectLoopsMap) {
  DetectedLoop a, b;
  ASSERT_TRUE(a.detection && b.detection);
  ASSERT_EQ(a.next_keyframe, b.next_keyframe);
  LoopEdges edges_a, edges_b;
  const LoopCorrectionStats sa = correct_loop(a.scene.map(), *a.detection, edges_a);
  const LoopCorrectionProblem problem = begin_loop_correction(b.scene.map(), *b.detection, edges_b);
  const LoopCorrectionStats sb =
      finish_loop_correction(b.scene.map(), problem, solve_loop_correction(problem), edges_b);
  EXPECT_EQ(sa.fused_points, sb.fused_points);
  EXPECT_EQ(sa.graph_edges, sb.graph_edges);
  EXPECT_EQ(sb.graph_nodes, a.next_keyframe);
  EXPECT_EQ(sb.propagated_keyframes, 0);
  EXPECT_EQ(edges_a, edges_b);
  expect_same_poses_and_points(a.scene.map(), b.scene.map(), static_cast<std::uint64_t>(a.next_keyframe - 1));
  EXPECT_LT(b.scene.max_position_error(), 0.02);
}

TEST(LoopCorrectionSteps, AKeyframeCreatedMeanwhileMovesWithItsParent) {
  DetectedLoop a, b;
  ASSERT_TRUE(a.detection && b.detection);
  const int created = b.next_keyframe;  // the keyframe tracking adds while the graph is solved
  LoopEdges edges_a, edges_b;
  correct_loop(a.scene.map(), *a.detection, edges_a);

  const Eigen::Isometry3d T_query_world_old = b.detection->query->T_cam_world();
  const LoopCorrectionProblem problem = begin_loop_correction(b.scene.map(), *b.detection, edges_b);
  // Tracking localizes the new keyframe against the query's neighbourhood,
  // which begin has already moved: the keyframe and its new points appear in
  // that corrected frame (the scene creates them drifted; move them).
  const Eigen::Isometry3d C = b.detection->T_world_query_corrected * T_query_world_old;
  const KeyFramePtr kf = b.scene.add_keyframe(created);
  const double error_drifted = (kf->camera_center() - b.scene.true_T_world_cam(created).translation()).norm();
  kf->set_pose(kf->T_cam_world() * C.inverse());
  for (const auto& p : kf->map_points()) {
    if (p && p->first_keyframe_id() == kf->id()) p->set_position(C * p->position());
  }
  ASSERT_NE(kf->parent(), nullptr);
  const KeyFrame& parent = *kf->parent();
  const Eigen::Isometry3d T_kf_parent_before = kf->T_cam_world() * parent.T_cam_world().inverse();
  std::vector<std::pair<MapPointPtr, Eigen::Vector3d>> own_points;  // created by kf, in its camera frame
  for (const auto& p : kf->map_points()) {
    if (p && p->first_keyframe_id() == kf->id()) own_points.emplace_back(p, kf->T_cam_world() * p->position());
  }
  ASSERT_GT(own_points.size(), 10u);
  const double error_before = (kf->camera_center() - b.scene.true_T_world_cam(created).translation()).norm();
  const std::vector<Eigen::Isometry3d> solved = solve_loop_correction(problem);
  const LoopCorrectionStats stats = finish_loop_correction(b.scene.map(), problem, solved, edges_b);

  EXPECT_EQ(stats.propagated_keyframes, 1);
  // The keyframes and points that were in the graph end where correct_loop() put them.
  expect_same_poses_and_points(a.scene.map(), b.scene.map(), static_cast<std::uint64_t>(created - 1));
  // The new keyframe kept its pose relative to its parent, its points theirs relative to it.
  const Eigen::Isometry3d T_kf_parent_after = kf->T_cam_world() * parent.T_cam_world().inverse();
  EXPECT_LT((T_kf_parent_after.matrix() - T_kf_parent_before.matrix()).norm(), 1e-9);
  for (const auto& [p, x] : own_points) EXPECT_LT((kf->T_cam_world() * p->position() - x).norm(), 1e-9);
  const double error_after = (kf->camera_center() - b.scene.true_T_world_cam(created).translation()).norm();
  std::printf("keyframe created during the correction (parent %llu): position error %.3f drifted, %.4f in the "
              "corrected neighbourhood, %.4f after finish\n",
              static_cast<unsigned long long>(parent.id()), error_drifted, error_before, error_after);
  EXPECT_GT(error_drifted, 0.1);
  EXPECT_LT(error_after, 0.02);
  // finish moved it (the graph moved its parent after begin).
  EXPECT_GT(std::abs(error_after - error_before), 1e-4);
}

// Tracking created a keyframe that local mapping (paused for the correction)
// has not connected yet: no parent, so it follows the query.
TEST(LoopCorrectionSteps, AKeyframeWithoutParentYetFollowsTheQuery) {
  DetectedLoop b;
  ASSERT_TRUE(b.detection);
  LoopEdges edges;
  const LoopCorrectionProblem problem = begin_loop_correction(b.scene.map(), *b.detection, edges);
  const KeyFrame& query = *b.detection->query;
  Frame frame = b.scene.make_frame(1000, b.scene.true_T_world_cam(b.next_keyframe));
  frame.set_pose(query.T_cam_world());  // where tracking would put it: at the (corrected) query
  const KeyFramePtr kf = b.scene.map().create_keyframe(frame);
  ASSERT_EQ(kf->parent(), nullptr);
  const Eigen::Isometry3d query_before = query.T_cam_world();
  const LoopCorrectionStats stats =
      finish_loop_correction(b.scene.map(), problem, solve_loop_correction(problem), edges);
  EXPECT_EQ(stats.propagated_keyframes, 1);
  EXPECT_GT((query.T_cam_world().matrix() - query_before.matrix()).norm(), 1e-4);  // the graph moved the query
  EXPECT_LT((kf->T_cam_world().matrix() - query.T_cam_world().matrix()).norm(), 1e-9);
}

}  // namespace
}  // namespace stillslam
