// Pose from the map points with static evidence (tracking/static_evidence.h):
// the span rule, the pose of one frame, and the tracker on a static scene
// with a near textured cluster that walks in and comes towards the camera.
#include <gtest/gtest.h>

#include "map/synthetic_scene.h"
#include "stillslam/core/option_check.h"
#include "stillslam/map/map.h"
#include "stillslam/tracking/motion_prior.h"
#include "stillslam/tracking/static_evidence.h"
#include "stillslam/tracking/tracker.h"

namespace stillslam {
namespace {

// A keyframe of `frame` (any pose) in `map`.
KeyFramePtr keyframe_of(Map& map, const test::SyntheticScene& scene, std::uint64_t frame_id) {
  Frame frame = scene.make_frame(frame_id, test::pose_at(0));
  frame.set_pose(test::pose_at(0));
  return map.create_keyframe(frame);
}

TEST(StaticEvidence, SpanOfTheObservingKeyframes) {
  test::SyntheticScene scene(300);
  Map map;
  const KeyFramePtr a = keyframe_of(map, scene, 3), b = keyframe_of(map, scene, 9), c = keyframe_of(map, scene, 20);
  MapPointPtr mp = map.create_map_point(Eigen::Vector3d(0, 0, 3), a.get());
  StaticEvidenceOptions options;
  options.min_span_frames = 10;
  EXPECT_EQ(observation_span_frames(*mp), 0u);
  mp->add_observation(a.get(), 0);
  EXPECT_EQ(observation_span_frames(*mp), 0u);
  EXPECT_FALSE(has_static_evidence(*mp, options));
  mp->add_observation(b.get(), 0);
  EXPECT_EQ(observation_span_frames(*mp), 6u);
  EXPECT_FALSE(has_static_evidence(*mp, options));
  mp->add_observation(c.get(), 0);
  EXPECT_EQ(observation_span_frames(*mp), 17u);
  EXPECT_TRUE(has_static_evidence(*mp, options));
  options.min_span_frames = 18;
  EXPECT_FALSE(has_static_evidence(*mp, options));
  // A temporary point (no observations) never has evidence, even with span 0.
  options.min_span_frames = 0;
  EXPECT_FALSE(has_static_evidence(MapPoint(1, Eigen::Vector3d(0, 0, 3), nullptr), options));
}

TEST(StaticEvidence, OptionsAreChecked) {
  StaticEvidenceOptions options;
  options.min_span_frames = -1;
  EXPECT_THROW(options.check(), OptionError);
  options = {};
  options.min_points = 2;
  EXPECT_THROW(options.check(), OptionError);
  options = {};
  options.quiet_frames = -1;
  EXPECT_THROW(options.check(), OptionError);
}

// Frames of the static scene plus a near cluster (its own scene moved to a
// 0.7 x 0.6 x 0.4 m box around `center`), when `cluster_in`.
struct ClusterWorld {
  test::SyntheticScene background{2500, 7};
  test::SyntheticScene cluster{900, 11};
  explicit ClusterWorld(const Eigen::Vector3d& center = Eigen::Vector3d(0, 0, 1)) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> x(-0.35, 0.35), y(-0.3, 0.3), z(-0.2, 0.2);
    for (std::size_t i = 0; i < cluster.points().size(); ++i) {
      cluster.move_point(i, center + Eigen::Vector3d(x(rng), y(rng), z(rng)) - cluster.points()[i]);
    }
  }
  void move_cluster(const Eigen::Vector3d& d) {
    for (std::size_t i = 0; i < cluster.points().size(); ++i) cluster.move_point(i, d);
  }
  Frame make_frame(std::uint64_t id, const Eigen::Isometry3d& T, bool cluster_in,
                   std::vector<bool>* on_cluster = nullptr) const {
    const Frame a = background.make_frame(id, T);
    if (!cluster_in) {
      if (on_cluster) on_cluster->assign(a.size(), false);
      return a;
    }
    const Frame b = cluster.make_frame(id, T);
    std::vector<cv::KeyPoint> kps = a.keypoints();
    kps.insert(kps.end(), b.keypoints().begin(), b.keypoints().end());
    std::vector<float> u_right = a.u_right(), depth = a.depth();
    u_right.insert(u_right.end(), b.u_right().begin(), b.u_right().end());
    depth.insert(depth.end(), b.depth().begin(), b.depth().end());
    cv::Mat desc;
    cv::vconcat(a.descriptors(), b.descriptors(), desc);
    if (on_cluster) {
      on_cluster->assign(a.size(), false);
      on_cluster->resize(kps.size(), true);
    }
    return Frame(id, a.timestamp(), background.setup(), kps, kps, desc, u_right, depth);
  }
};

// The pose of one frame: the background's points have evidence, the
// cluster's are new (one keyframe) and moved 4 cm towards the camera.
TEST(StaticEvidence, PoseFollowsThePointsWithEvidence) {
  ClusterWorld world;
  Map map;
  const Eigen::Isometry3d T = test::pose_at(0.02);
  std::vector<bool> on_cluster;
  Frame frame = world.make_frame(31, T, true, &on_cluster);
  world.move_cluster(Eigen::Vector3d(0, 0, 0.04));  // where the cluster was when its points were made
  Frame before = world.make_frame(31, T, true);
  before.set_pose(T);
  ASSERT_EQ(before.size(), frame.size());
  // Two keyframes 30 frames apart (their keypoints are only indexed here).
  Frame early_frame = world.make_frame(0, T, true), late_frame = world.make_frame(30, T, true);
  early_frame.set_pose(T);
  late_frame.set_pose(T);
  const KeyFramePtr early = map.create_keyframe(early_frame), late = map.create_keyframe(late_frame);
  for (std::size_t i = 0; i < frame.size(); ++i) {
    MapPointPtr mp = map.create_map_point(*before.unproject(i), late.get());
    mp->add_observation(late.get(), i);
    if (!on_cluster[i]) mp->add_observation(early.get(), i);
    frame.set_map_point(i, mp);
  }
  const int cluster_matches = static_cast<int>(std::count(on_cluster.begin(), on_cluster.end(), true));
  ASSERT_GT(cluster_matches, 400);

  StaticEvidenceOptions options;
  options.enabled = true;
  auto error_of = [&](const StaticEvidenceOptions& o, int* cluster_inliers) {
    Frame f = frame;
    f.set_pose(test::pose_at(0.02) * Eigen::Translation3d(0.01, -0.01, 0.02));  // a prediction 2.4 cm off
    refine_pose_on_evidence(f, PoseOptimizerOptions{}, o);
    *cluster_inliers = 0;
    for (std::size_t i = 0; i < f.size(); ++i) *cluster_inliers += on_cluster[i] && !f.is_outlier(i);
    return (f.T_cam_world().inverse().translation() - T.inverse().translation()).norm();
  };
  int cluster_inliers_on = 0, cluster_inliers_off = 0;
  const double on = error_of(options, &cluster_inliers_on);
  options.enabled = false;
  const double off = error_of(options, &cluster_inliers_off);
  std::printf("pose error %.5f m with the rule (%d cluster inliers), %.5f m without (%d)\n", on,
              cluster_inliers_on, off, cluster_inliers_off);
  EXPECT_LT(on, 1e-4);  // exact background measurements
  EXPECT_LT(cluster_inliers_on, cluster_matches / 2);
  EXPECT_GT(off, 5e-3);
}

// A person kept as static by the motion stage (issue #19): the cluster's
// points have evidence like the background's but are flagged
// on_dynamic_instance, and the person moved 4 cm since they were made. With
// leave_out_kept_points they do not move the pose but stay matched (inliers
// where they still fit); with fewer than min_points other matches the pose
// comes from all of them.
TEST(StaticEvidence, PointsOnAKeptPersonDoNotMoveThePose) {
  ClusterWorld world;
  Map map;
  const Eigen::Isometry3d T = test::pose_at(0.02);
  std::vector<bool> on_cluster;
  Frame frame = world.make_frame(31, T, true, &on_cluster);
  world.move_cluster(Eigen::Vector3d(0, 0, 0.04));
  Frame before = world.make_frame(31, T, true);
  before.set_pose(T);
  ASSERT_EQ(before.size(), frame.size());
  Frame early_frame = world.make_frame(0, T, true), late_frame = world.make_frame(30, T, true);
  early_frame.set_pose(T);
  late_frame.set_pose(T);
  const KeyFramePtr early = map.create_keyframe(early_frame), late = map.create_keyframe(late_frame);
  std::vector<std::size_t> background;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    MapPointPtr mp = map.create_map_point(*before.unproject(i), late.get());
    mp->add_observation(late.get(), i);
    mp->add_observation(early.get(), i);
    if (on_cluster[i]) {
      mp->mark_on_dynamic_instance();
    } else {
      background.push_back(i);
    }
    frame.set_map_point(i, mp);
  }
  const int cluster_matches = static_cast<int>(std::count(on_cluster.begin(), on_cluster.end(), true));
  ASSERT_GT(cluster_matches, 400);

  auto error_of = [&](Frame f, const StaticEvidenceOptions& o, int* cluster_inliers) {
    f.set_pose(test::pose_at(0.02) * Eigen::Translation3d(0.01, -0.01, 0.02));
    refine_pose_on_evidence(f, PoseOptimizerOptions{}, o);
    *cluster_inliers = 0;
    for (std::size_t i = 0; i < f.size(); ++i) *cluster_inliers += on_cluster[i] && f.map_point(i) && !f.is_outlier(i);
    return (f.T_cam_world().inverse().translation() - T.inverse().translation()).norm();
  };
  StaticEvidenceOptions options;
  int in_on = 0, in_off = 0;
  options.leave_out_kept_points = true;
  const double on = error_of(frame, options, &in_on);
  options.leave_out_kept_points = false;
  const double off = error_of(frame, options, &in_off);
  std::printf("pose error %.6f m leaving the kept person out (%d of %d of its matches inliers), %.6f m with it\n",
              on, in_on, cluster_matches, off);
  EXPECT_LT(on, 1e-4);
  EXPECT_GT(off, 2e-3);
  // Its matches are still classified against the pose: those the sway left near fit.
  EXPECT_GT(in_on, 0);
  // Without the static evidence rule too.
  options.enabled = false;
  options.leave_out_kept_points = true;
  EXPECT_LT(error_of(frame, options, &in_on), 1e-4);
  // Kept in the pose with 5x their sigma: a fraction of the pull.
  options.enabled = true;
  options.leave_out_kept_points = false;
  options.kept_point_sigma = 5;
  int in_weighted = 0;
  const double weighted = error_of(frame, options, &in_weighted);
  std::printf("pose error %.6f m with the kept person's matches at 5x sigma (%d inliers)\n", weighted, in_weighted);
  EXPECT_LT(weighted, off / 3);
  EXPECT_GT(weighted, on);

  // Only 30 background matches (under min_points 40): all matches move the pose.
  Frame sparse = frame;
  for (std::size_t k = 30; k < background.size(); ++k) sparse.set_map_point(background[k], nullptr);
  options = StaticEvidenceOptions{};
  options.leave_out_kept_points = true;
  const double sparse_on = error_of(sparse, options, &in_on);
  options.leave_out_kept_points = false;
  const double sparse_off = error_of(sparse, options, &in_off);
  EXPECT_NEAR(sparse_on, sparse_off, 1e-9);
  EXPECT_GT(sparse_on, 2e-3);
}

struct ClusterRun {
  double max_error = 0;  // camera position, m, over the frames after the cluster came in
  double final_error = 0;
  int lost_frames = 0;
};

// The camera moves 1 cm a frame sideways and turns 1.5 degrees a frame
// (keyframes come as the view changes); from frame 30 on the cluster is in
// view 1 m ahead and comes 4 cm a frame towards the camera (a person walking
// up to it, 32 cm in all).
ClusterRun track_cluster(const TrackerOptions& options) {
  const double yaw = 36 * 1.5 * M_PI / 180;  // the view direction in the middle of the cluster's frames
  const Eigen::Vector3d view(std::sin(yaw), 0, std::cos(yaw));
  ClusterWorld world(Eigen::Vector3d(0.36, 0, 0) + view);
  Map map;
  // As local mapping registers a keyframe: its tracked points get its observation.
  LocalMappingLink link;
  link.insert_keyframe = [](KeyFramePtr kf, const Frame&) {
    for (std::size_t i = 0; i < kf->size(); ++i) {
      const MapPointPtr mp = kf->map_point(i);
      if (mp && !mp->is_bad() && !mp->is_observed_by(kf.get())) mp->add_observation(kf.get(), i);
    }
  };
  Tracker tracker(map, options, link);
  ClusterRun run;
  for (int i = 0; i < 39; ++i) {
    const bool in = i >= 30;
    if (i > 30) world.move_cluster(-0.04 * view);
    const Eigen::Isometry3d T = test::pose_at(0.01 * i, 0, 1.5 * i);
    Frame frame = world.make_frame(static_cast<std::uint64_t>(i), T, in);
    const TrackingResult r = tracker.track(frame);
    if (r.state != TrackingState::Ok) {
      ++run.lost_frames;
      continue;
    }
    const Eigen::Isometry3d expected = T * test::pose_at(0).inverse();
    const double err = (frame.T_cam_world().inverse().translation() - expected.inverse().translation()).norm();
    if (in) run.max_error = std::max(run.max_error, err);
    run.final_error = err;
  }
  return run;
}

TEST(StaticEvidence, TrackerFollowsTheStaticSceneNotTheNearCluster) {
  TrackerOptions options;
  options.init_min_keypoints = 300;
  options.init_unmasked_confirm_frames = 0;  // every frame tracked from the first
  options.static_evidence.enabled = true;
  const ClusterRun on = track_cluster(options);
  options.static_evidence.enabled = false;
  const ClusterRun off = track_cluster(options);
  std::printf("max error %.5f m with the rule (final %.5f, %d lost), %.5f m without (final %.5f, %d lost)\n",
              on.max_error, on.final_error, on.lost_frames, off.max_error, off.final_error, off.lost_frames);
  EXPECT_EQ(on.lost_frames, 0);
  EXPECT_LT(on.max_error, 1e-3);
  EXPECT_GT(off.max_error, 0.1);  // 0.32 m when written: it follows the cluster
}

// A cluster that stood still long enough for its points to gain evidence
// (observed 30 frames apart, like the background) and has started to move
// (4 cm towards the camera): the frame before rejected its points. With
// Tracking.staticEvidenceQuietFrames they do not move the pose.
TEST(StaticEvidence, QuietFramesDropPointsRejectedJustBefore) {
  ClusterWorld world;
  Map map;
  const Eigen::Isometry3d T = test::pose_at(0.02);
  std::vector<bool> on_cluster;
  Frame frame = world.make_frame(31, T, true, &on_cluster);
  world.move_cluster(Eigen::Vector3d(0, 0, 0.04));
  Frame before = world.make_frame(31, T, true);
  before.set_pose(T);
  Frame early_frame = world.make_frame(0, T, true), late_frame = world.make_frame(29, T, true);
  early_frame.set_pose(T);
  late_frame.set_pose(T);
  const KeyFramePtr early = map.create_keyframe(early_frame), late = map.create_keyframe(late_frame);
  for (std::size_t i = 0; i < frame.size(); ++i) {
    MapPointPtr mp = map.create_map_point(*before.unproject(i), early.get());
    mp->add_observation(early.get(), i);
    mp->add_observation(late.get(), i);
    if (on_cluster[i]) mp->record_outlier_frame(30);
    frame.set_map_point(i, mp);
  }
  StaticEvidenceOptions options;
  options.enabled = true;
  auto error_of = [&](const StaticEvidenceOptions& o, int* cluster_inliers) {
    Frame f = frame;
    f.set_pose(test::pose_at(0.02) * Eigen::Translation3d(0.01, -0.01, 0.02));
    refine_pose_on_evidence(f, PoseOptimizerOptions{}, o);
    *cluster_inliers = 0;
    for (std::size_t i = 0; i < f.size(); ++i) *cluster_inliers += on_cluster[i] && !f.is_outlier(i);
    return (f.T_cam_world().inverse().translation() - T.inverse().translation()).norm();
  };
  int quiet_inliers = 0, plain_inliers = 0;
  options.quiet_frames = 10;
  const double quiet = error_of(options, &quiet_inliers);
  options.quiet_frames = 0;
  const double plain = error_of(options, &plain_inliers);
  std::printf("pose error %.5f m with quiet frames (%d cluster inliers), %.5f m without (%d)\n", quiet,
              quiet_inliers, plain, plain_inliers);
  EXPECT_LT(quiet, 1e-4);
  EXPECT_GT(plain, 5e-3);
  // Rejected 11 frames before: evidence again.
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (on_cluster[i]) frame.map_point(i)->record_outlier_frame(20);
  }
  options.quiet_frames = 10;
  EXPECT_GT(error_of(options, &quiet_inliers), 5e-3);
}

TEST(StaticEvidence, RecentlyRejected) {
  MapPoint mp(1, Eigen::Vector3d(0, 0, 3), nullptr);
  StaticEvidenceOptions options;
  options.quiet_frames = 10;
  EXPECT_FALSE(recently_rejected(mp, options, 50));
  mp.record_outlier_frame(40);
  EXPECT_TRUE(recently_rejected(mp, options, 50));
  EXPECT_FALSE(recently_rejected(mp, options, 51));
  EXPECT_FALSE(recently_rejected(mp, options, 40));  // this frame's own rejection is not known yet
  options.quiet_frames = 0;
  EXPECT_FALSE(recently_rejected(mp, options, 45));
}


// A cluster that earned evidence while still (observed 30 frames apart, like
// the background) and has moved 4 cm towards the camera; a sixth of its
// keypoints are matched (about 150, the share of the walking_xyz capture).
// The motion model predicts the true pose.


constexpr int kClusterEvery = 2;
struct MovedClusterFrame {
  Frame frame;
  std::vector<bool> on_cluster;
  Eigen::Isometry3d T = test::pose_at(0.02);
  Map map;
  MovedClusterFrame() {
    ClusterWorld world;
    frame = world.make_frame(31, T, true, &on_cluster);
    world.move_cluster(Eigen::Vector3d(0, 0, 0.04));
    Frame before = world.make_frame(31, T, true);
    before.set_pose(T);
    Frame early_frame = world.make_frame(0, T, true), late_frame = world.make_frame(30, T, true);
    early_frame.set_pose(T);
    late_frame.set_pose(T);
    const KeyFramePtr early = map.create_keyframe(early_frame), late = map.create_keyframe(late_frame);
    int cluster_keypoint = 0;
    for (std::size_t i = 0; i < frame.size(); ++i) {
      if (on_cluster[i] && cluster_keypoint++ % kClusterEvery != 0) continue;
      MapPointPtr mp = map.create_map_point(*before.unproject(i), early.get());
      mp->add_observation(early.get(), i);
      mp->add_observation(late.get(), i);
      frame.set_map_point(i, mp);
    }
  }
  // Camera-centre error of the stage pose, started at the prediction.
  double error(const MotionPriorOptions& options, bool* applied) const {
    Frame f = frame;
    f.set_pose(T);
    const std::optional<PosePrior> prior = motion_prior(T, options);
    MotionPriorStep step;
    refine_pose_with_prior(f, PoseOptimizerOptions{}, StaticEvidenceOptions{}, prior, options, &step);
    *applied = step.applied;
    return (camera_centre(f.T_cam_world()) - camera_centre(T)).norm();
  }
};

TEST(MotionPrior, HoldsThePredictionAgainstAClusterWithEvidence) {
  const MovedClusterFrame scene;
  MotionPriorOptions options;
  options.refit = false;  // the gate alone
  options.sigma_translation = 0;  // off
  bool applied = true;
  const double off = scene.error(options, &applied);
  EXPECT_FALSE(applied);
  options.sigma_translation = 0.001;
  options.gate = 0;  // always
  const double on = scene.error(options, &applied);
  EXPECT_TRUE(applied);
  std::printf("pose error %.5f m without the prior, %.5f m with sigma 1 mm\n", off, on);
  EXPECT_GT(off, 3e-3);  // 3.8 mm when written
  EXPECT_LT(on, off / 3);  // 0.9 mm
}

TEST(MotionPrior, GateAppliesThePriorOnlyBeyondItsDistance) {
  const MovedClusterFrame scene;
  MotionPriorOptions options;
  options.refit = false;  // the gate alone
  options.sigma_translation = 0;  // off
  bool applied = false;
  const double off = scene.error(options, &applied);
  options.sigma_translation = 0.001;
  options.gate = 0;
  const double always = scene.error(options, &applied);
  // The pose without the prior lands `off` from the prediction.
  options.gate = off / 2;
  const double gated = scene.error(options, &applied);
  EXPECT_TRUE(applied);
  EXPECT_DOUBLE_EQ(gated, always);
  options.gate = off * 2;
  const double beyond = scene.error(options, &applied);
  EXPECT_FALSE(applied);
  EXPECT_DOUBLE_EQ(beyond, off);
}

// The static scene alone, every point with evidence, and a prediction 3 cm
// off the true pose along the view (a velocity from noisy poses): the
// points give the true pose, and only the prior moves it.
struct OffPredictionFrame {
  Frame frame;
  Eigen::Isometry3d T = test::pose_at(0.02);
  Eigen::Isometry3d predicted = T;
  Map map;
  OffPredictionFrame() {
    ClusterWorld world;
    frame = world.make_frame(31, T, false);
    Frame early_frame = world.make_frame(0, T, false), late_frame = world.make_frame(30, T, false);
    early_frame.set_pose(T);
    late_frame.set_pose(T);
    const KeyFramePtr early = map.create_keyframe(early_frame), late = map.create_keyframe(late_frame);
    for (std::size_t i = 0; i < frame.size(); ++i) {
      MapPointPtr mp = map.create_map_point(*early_frame.unproject(i), early.get());
      mp->add_observation(early.get(), i);
      mp->add_observation(late.get(), i);
      frame.set_map_point(i, mp);
    }
    predicted.translation().z() += 0.03;
  }
  double error(const MotionPriorOptions& options, MotionPriorStep* step) const {
    Frame f = frame;
    f.set_pose(predicted);
    refine_pose_with_prior(f, PoseOptimizerOptions{}, StaticEvidenceOptions{}, motion_prior(predicted, options),
                           options, step);
    return (camera_centre(f.T_cam_world()) - camera_centre(T)).norm();
  }
};

TEST(MotionPrior, RefitKeepsThePriorOnlyWhenTheRejectedPointsMovedThePose) {
  MotionPriorOptions options;
  options.sigma_translation = 0.001;
  options.gate = 0.02;
  options.refit = false;
  MotionPriorStep step;
  // Static scene, prediction 3 cm off: the prior pulls the pose towards it.
  const OffPredictionFrame still;
  const double pulled = still.error(options, &step);
  EXPECT_TRUE(step.applied);
  EXPECT_NEAR(step.offset, 0.03, 1e-3);  // the points alone: the true pose
  EXPECT_EQ(step.refit_offset, -1);
  // With the refit the points it keeps go back to the true pose, 3 cm from
  // the prediction: the pose without the prior.
  options.refit = true;
  const double refit = still.error(options, &step);
  EXPECT_FALSE(step.applied);
  EXPECT_NEAR(step.refit_offset, 0.03, 1e-3);
  // The capture of MovedClusterFrame: without the cluster points the prior
  // rejects, the rest stay at the prediction.
  const MovedClusterFrame moved;
  options.gate = 0.001;
  options.refit = false;
  bool applied = false;
  const double always = moved.error(options, &applied);
  options.refit = true;
  const double capture = moved.error(options, &applied);
  EXPECT_TRUE(applied);
  EXPECT_DOUBLE_EQ(capture, always);
  std::printf("still scene: error %.5f m with the prior, %.6f m with the refit; capture: %.5f m\n", pulled, refit,
              capture);
  EXPECT_GT(pulled, 2e-3);  // 3.8 mm when written
  EXPECT_LT(refit, 1e-4);
}

TEST(MotionPrior, OffWithoutSigmaAndOptionsAreChecked) {
  MotionPriorOptions options;
  EXPECT_TRUE(options.enabled());  // 1 mm, gate 2 cm, refit check
  EXPECT_EQ(options.sigma_translation, 0.001);
  EXPECT_EQ(options.gate, 0.02);
  EXPECT_TRUE(options.refit);
  options.sigma_translation = 0;
  EXPECT_FALSE(motion_prior(Eigen::Isometry3d::Identity(), options));
  options.sigma_translation = 0.002;
  options.sigma_rotation = 0.03;
  options.dead_zone = 0.001;
  const std::optional<PosePrior> prior = motion_prior(test::pose_at(0.1), options);
  ASSERT_TRUE(prior);
  EXPECT_TRUE(prior->T_cam_world.isApprox(test::pose_at(0.1)));
  EXPECT_EQ(prior->sigma_translation, 0.002);
  EXPECT_EQ(prior->sigma_rotation, 0.03);
  EXPECT_EQ(prior->dead_zone, 0.001);
  options.check();
  MotionPriorOptions bad = options;
  bad.sigma_translation = -0.001;
  EXPECT_THROW(bad.check(), OptionError);
  bad = options;
  bad.dead_zone = -0.001;
  EXPECT_THROW(bad.check(), OptionError);
  bad = options;
  bad.gate = -0.001;
  EXPECT_THROW(bad.check(), OptionError);
  bad = options;
  bad.sigma_rotation = 0;
  EXPECT_THROW(bad.check(), OptionError);
}

}  // namespace
}  // namespace stillslam
