// The crowd fallback (tracking/sparse_view.h): a view the masks hide gets the
// constant-velocity prediction when tracking fails, a blend of tracked and
// predicted pose when few inliers are left, and never starts a map.
#include <gtest/gtest.h>

#include <algorithm>

#include "map/synthetic_scene.h"
#include "stillslam/core/error.h"
#include "stillslam/tracking/sparse_view.h"
#include "stillslam/tracking/tracker.h"

namespace stillslam {
namespace {

cv::Mat1b mask_of_left_part(double share) {
  cv::Mat1b mask(480, 640, std::uint8_t{0});
  mask.colRange(0, static_cast<int>(std::lround(share * 640))).setTo(255);
  return mask;
}

Eigen::Vector3d centre(const Frame& f) { return f.T_cam_world().inverse().translation(); }

TEST(SparseView, BlendMovesTheCameraCentreAndRotationPartWay) {
  const Eigen::Isometry3d predicted = test::pose_at(0.0, 0.0, 0.0);
  const Eigen::Isometry3d tracked = test::pose_at(0.1, 0.02, 10.0);
  const auto c = [](const Eigen::Isometry3d& T) { return Eigen::Vector3d(T.inverse().translation()); };
  EXPECT_LT((c(blend_poses(predicted, tracked, 0.0)) - c(predicted)).norm(), 1e-12);
  EXPECT_LT((c(blend_poses(predicted, tracked, 1.0)) - c(tracked)).norm(), 1e-12);
  const Eigen::Isometry3d half = blend_poses(predicted, tracked, 0.25);
  EXPECT_LT((c(half) - (0.75 * c(predicted) + 0.25 * c(tracked))).norm(), 1e-12);
  const double angle = Eigen::AngleAxisd(predicted.rotation().transpose() * tracked.rotation()).angle();
  const double part = Eigen::AngleAxisd(predicted.rotation().transpose() * half.rotation()).angle();
  EXPECT_NEAR(part, 0.25 * angle, 1e-9);
  EXPECT_GT(angle, 0.1);
}

TEST(SparseView, SparseWhenTheMaskCoversTheShare) {
  test::SyntheticScene scene(500);
  Frame f = scene.make_frame(0, test::pose_at(0));
  SparseViewOptions o;
  o.enabled = true;
  EXPECT_FALSE(is_sparse_view(f, o));  // no mask
  f.set_dynamic_mask(mask_of_left_part(0.6));
  EXPECT_NEAR(masked_share(f), 0.6, 1e-3);
  EXPECT_TRUE(is_sparse_view(f, o));
  o.masked_share = 0.7;
  EXPECT_FALSE(is_sparse_view(f, o));
  o.masked_share = 0.5;
  o.enabled = false;
  EXPECT_FALSE(is_sparse_view(f, o));
}

TEST(SparseView, OptionsOutOfRangeNameTheField) {
  SparseViewOptions o;
  o.tracked_weight = 1.5;
  try {
    o.check();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("SparseViewOptions.tracked_weight"), std::string::npos) << e.what();
  }
}

struct SparseTracker {
  test::SyntheticScene scene{2500};
  Map map;
  Tracker tracker;
  std::uint64_t id = 0;
  explicit SparseTracker(double tracked_weight, int inliers)
      : tracker(map, options(tracked_weight, inliers), {}) {}
  explicit SparseTracker(const TrackerOptions& o) : tracker(map, o, {}) {}
  static TrackerOptions options(double tracked_weight, int inliers) {
    TrackerOptions o;
    o.init_min_keypoints = 300;
    o.sparse_view.enabled = true;
    o.sparse_view.tracked_weight = tracked_weight;
    o.sparse_view.inliers = inliers;
    return o;
  }
  // Starts the map and tracks frames 0.01 m apart along x, unmasked.
  void start(int frames) {
    for (int i = 0; i < frames; ++i) {
      Frame f = scene.make_frame(id, test::pose_at(0.01 * static_cast<double>(id)));
      ++id;
      f.set_dynamic_mask(mask_of_left_part(0));
      tracker.track(f);
    }
    ASSERT_EQ(tracker.state(), TrackingState::Ok);
  }
};

TEST(SparseView, TrackingFailsInAHiddenViewThePredictionIsKept) {
  SparseTracker t(0.5, 50);
  t.start(8);
  const std::size_t keyframes = t.map.num_keyframes();
  // Another scene's few points: nothing matches the map.
  test::SyntheticScene elsewhere(60, 99);
  Frame f = elsewhere.make_frame(t.id, test::pose_at(0.5));
  f.set_dynamic_mask(mask_of_left_part(0.7));
  const TrackingResult r = t.tracker.track(f);
  ASSERT_EQ(r.state, TrackingState::Ok) << r.reason;
  EXPECT_EQ(r.sparse_view, SparseView::Predicted);
  EXPECT_FALSE(r.new_keyframe);
  EXPECT_EQ(t.map.num_keyframes(), keyframes);
  // Constant velocity: 0.01 m further along x than the last frame (frame 0 is the origin).
  EXPECT_LT((centre(f) - Eigen::Vector3d(0.01 * static_cast<double>(t.id), 0, 0)).norm(), 1e-4);
  EXPECT_EQ(f.num_matches(), 0);
  // The same frame without the fallback is lost.
  SparseTracker off(0.5, 50);
  off.start(8);
  Frame g = elsewhere.make_frame(off.id, test::pose_at(0.5));
  g.set_dynamic_mask(mask_of_left_part(0.3));  // not sparse: no fallback
  EXPECT_EQ(off.tracker.track(g).state, TrackingState::Lost);
}

TEST(SparseView, FewInliersBlendTheTrackedPoseWithThePrediction) {
  // Every sparse frame counts as having few inliers.
  SparseTracker t(0.5, 100000);
  t.start(8);
  // The camera jumps 4 mm beyond the constant-velocity prediction.
  const double x = 0.01 * static_cast<double>(t.id) + 0.004;
  Frame f = t.scene.make_frame(t.id, test::pose_at(x));
  f.set_dynamic_mask(mask_of_left_part(0.6));
  const TrackingResult r = t.tracker.track(f);
  ASSERT_EQ(r.state, TrackingState::Ok) << r.reason;
  EXPECT_EQ(r.sparse_view, SparseView::Blended);
  EXPECT_NEAR(centre(f).x(), x - 0.002, 1e-4);
  // A view that is not sparse keeps its tracked pose.
  ++t.id;
  Frame g = t.scene.make_frame(t.id, test::pose_at(x + 0.01));
  g.set_dynamic_mask(mask_of_left_part(0.2));
  const TrackingResult rg = t.tracker.track(g);
  EXPECT_EQ(rg.sparse_view, SparseView::None);
  EXPECT_NEAR(centre(g).x(), x + 0.01, 1e-4);
}

TEST(SparseView, NoMapStartsFromAHiddenView) {
  SparseTracker t(0.5, 50);
  TrackerOptions o = SparseTracker::options(0.5, 50);
  o.init_wait_frames = 2;
  Tracker tracker(t.map, o, {});
  // Beyond the start's wait, a mostly masked view still starts nothing.
  for (int i = 0; i < 6; ++i) {
    Frame f = t.scene.make_frame(static_cast<std::uint64_t>(i), test::pose_at(0));
    f.set_dynamic_mask(mask_of_left_part(0.7));
    const TrackingResult r = tracker.track(f);
    EXPECT_EQ(r.state, TrackingState::NotInitialized);
    EXPECT_EQ(r.sparse_view, SparseView::NoStart);
    EXPECT_NE(r.reason.find("70 %"), std::string::npos) << r.reason;
  }
  EXPECT_EQ(t.map.num_keyframes(), 0u);
}

// SparseViewOptions::keyframes off: a sparse view makes no keyframe where one
// is due; the next view that is not sparse makes it.
TEST(SparseView, WithoutKeyframesASparseViewMakesNone) {
  const auto run = [](bool keyframes) {
    TrackerOptions o = SparseTracker::options(1.0, 0);
    o.sparse_view.keyframes = keyframes;
    o.close_points_tracked_min = 100000;  // any untracked close point asks for a keyframe, no budget
    o.close_points_untracked_min = 0;
    o.keyframe_budget.per_second = 0;
    SparseTracker t(o);
    t.start(4);
    std::vector<bool> made;
    for (double share : {0.6, 0.6, 0.6, 0.2, 0.2, 0.2}) {
      Frame f = t.scene.make_frame(t.id, test::pose_at(0.01 * static_cast<double>(t.id)));
      ++t.id;
      f.set_dynamic_mask(mask_of_left_part(share));
      const TrackingResult r = t.tracker.track(f);
      EXPECT_EQ(r.state, TrackingState::Ok) << r.reason;
      made.push_back(r.new_keyframe);
    }
    return made;
  };
  const auto count = [](const std::vector<bool>& made, std::size_t from, std::size_t to) {
    return std::count(made.begin() + static_cast<std::ptrdiff_t>(from), made.begin() + static_cast<std::ptrdiff_t>(to), true);
  };
  // On (the default): the sparse views make the keyframes that are due.
  const std::vector<bool> on = run(true);
  EXPECT_GE(count(on, 0, 3), 2);
  // Off: none in the three sparse views; the views after them make the one due.
  const std::vector<bool> off = run(false);
  EXPECT_EQ(count(off, 0, 3), 0);
  EXPECT_GE(count(off, 3, 6), 1);
}

// SparseViewOptions::prior: a sparse view's camera jumps 30 mm beyond the
// constant-velocity prediction (past the motion prior's 20 mm gate, so that
// the gated prior is tried too, and rejected by its refit: the points agree).
// With the fallback's prior the pose stays nearer the prediction.
TEST(SparseView, WithThePriorASparseViewLeansOnThePrediction) {
  const auto jump = [](bool prior) {
    TrackerOptions o = SparseTracker::options(1.0, 0);  // no blend
    o.sparse_view.prior = prior;
    SparseTracker t(o);
    t.start(8);
    const double predicted = 0.01 * static_cast<double>(t.id);
    Frame f = t.scene.make_frame(t.id, test::pose_at(predicted + 0.03));
    f.set_dynamic_mask(mask_of_left_part(0.6));
    const TrackingResult r = t.tracker.track(f);
    EXPECT_EQ(r.state, TrackingState::Ok) << r.reason;
    EXPECT_EQ(r.motion_prior.applied > 0, prior);
    return centre(f).x() - predicted;  // the pose's offset from the prediction
  };
  const double free = jump(false);
  const double held = jump(true);
  EXPECT_NEAR(free, 0.03, 1e-4);  // as tracked
  EXPECT_LT(held, free - 0.005) << held;  // 22 mm measured
  EXPECT_GT(held, 0.0);
}

// SparseViewOptions::smooth_frames: a straight path at constant velocity
// whose flagged frames jitter by +-10 mm across the path. Their centres come
// back to within the jitter's remainder; unflagged frames, and the centres of
// another map, are not used or changed.
TEST(SparseView, SmoothingTheFlaggedCentresTakesOutTheirJitter) {
  std::vector<Eigen::Vector3d> truth, centres;
  std::vector<bool> sparse;
  std::vector<std::uint64_t> maps;
  for (int i = 0; i < 40; ++i) {
    truth.emplace_back(0.01 * i, 0, 0);
    const bool flagged = i >= 10 && i < 30;
    const double jitter = flagged ? (i % 2 == 0 ? 0.01 : -0.01) : 0.0;
    centres.push_back(truth.back() + Eigen::Vector3d(0, jitter, 0));
    sparse.push_back(flagged);
    maps.push_back(i < 35 ? 1 : 2);
  }
  centres[36] += Eigen::Vector3d(0, 1, 0);  // another map's frame, far off: never averaged in
  sparse[34] = true;                         // its window reaches into map 2
  const std::vector<Eigen::Vector3d> given = centres;
  smooth_sparse_centres(centres, sparse, maps, 3);
  for (int i = 0; i < 40; ++i) {
    const double error = (centres[i] - truth[i]).norm();
    if (i >= 13 && i < 27) {
      EXPECT_LT(error, 0.0015) << i;  // a window of 7: 1 of the 10 mm left
    } else if (!sparse[i]) {
      EXPECT_EQ(centres[i], given[i]) << i;
    }
  }
  // Frames 31..34 of map 1 only (the window is one-sided there).
  EXPECT_LT((centres[34] - (given[31] + given[32] + given[33] + given[34]) / 4).norm(), 1e-12);
  // Off: nothing moves.
  std::vector<Eigen::Vector3d> off = given;
  smooth_sparse_centres(off, sparse, maps, 0);
  EXPECT_EQ(off, given);
}

// SparseViewOptions::filter_gain on a trajectory: the same path with the
// flagged frames jittering by +-10 mm across it. The filter (gain 0.5) starts
// from the motion over the 5 frames before the run and leaves a fraction of
// the jitter; unflagged frames, and a run's first frame of another map, keep
// their centres.
TEST(SparseView, TheCentreFilterTakesOutMostOfTheJitter) {
  std::vector<Eigen::Vector3d> truth, centres;
  std::vector<bool> sparse;
  std::vector<std::uint64_t> maps;
  for (int i = 0; i < 40; ++i) {
    truth.emplace_back(0.01 * i, 0, 0);
    const bool flagged = (i >= 10 && i < 30) || i == 35;
    const double jitter = flagged ? (i % 2 == 0 ? 0.01 : -0.01) : 0.0;
    centres.push_back(truth.back() + Eigen::Vector3d(0, jitter, 0));
    sparse.push_back(flagged);
    maps.push_back(i < 35 ? 1 : 2);
  }
  const std::vector<Eigen::Vector3d> given = centres;
  filter_sparse_centres(centres, sparse, maps, 0.5, 5);
  double sum = 0;
  for (int i = 0; i < 40; ++i) {
    if (!sparse[i] || i == 35) {
      EXPECT_EQ(centres[i], given[i]) << i;  // map 2's first frame has no earlier centre of its map
      continue;
    }
    EXPECT_LT(std::abs(centres[i].x() - truth[i].x()), 1e-9) << i;  // no jitter along the path: no lag
    sum += (centres[i] - truth[i]).squaredNorm();
  }
  const double rms = std::sqrt(sum / 20);
  EXPECT_LT(rms, 0.006) << rms;  // of the 10 mm
  EXPECT_GT(rms, 0.001) << rms;  // a causal filter: some is left
  std::vector<Eigen::Vector3d> off = given;
  filter_sparse_centres(off, sparse, maps, 0, 5);
  EXPECT_EQ(off, given);
}

// SparseViewOptions::filter_gain online: after 8 frames 10 mm apart along x,
// a sparse view lies 6 mm ahead of the path. The filter (gain 0.5) predicts
// the path from the motion over the 5 frames before, and holds the tracked
// centre half way, 3 mm ahead; without it the pose is as tracked.
TEST(SparseView, TheFilterHoldsASparseViewsCentreHalfWayToItsPrediction) {
  const auto ahead = [](double gain) {
    TrackerOptions o = SparseTracker::options(1.0, 0);  // no blend
    o.sparse_view.filter_gain = gain;
    SparseTracker t(o);
    t.start(8);
    const double path = 0.01 * static_cast<double>(t.id);
    Frame f = t.scene.make_frame(t.id, test::pose_at(path + 0.006));
    f.set_dynamic_mask(mask_of_left_part(0.6));
    const TrackingResult r = t.tracker.track(f);
    EXPECT_EQ(r.state, TrackingState::Ok) << r.reason;
    EXPECT_EQ(r.sparse_view, SparseView::Tracked);
    return centre(f).x() - path;
  };
  EXPECT_NEAR(ahead(0), 0.006, 1e-4);
  EXPECT_NEAR(ahead(0.5), 0.003, 3e-4);
}

// centre_covariance against the information matrix built from central
// finite differences of the same residuals (u, v and u_right of each
// observation, whitened) under R' = Exp(omega) R, C' = C + dc, with the
// rotation marginalised out the same way.
TEST(SparseView, TheCentreCovarianceMatchesFiniteDifferences) {
  test::SyntheticScene scene(400);
  const Eigen::Isometry3d T = test::pose_at(0.05, 0.02, 7.0).inverse();
  Frame f = scene.make_frame(0, T.inverse());
  const PinholeCamera& cam = f.setup().camera;
  ASSERT_GT(cam.bf(), 0);
  std::vector<PoseObservation> obs;
  for (const Eigen::Vector3d& X : scene.points()) {
    const Eigen::Vector3d p = T * X;
    if (p.z() <= 0.1) continue;
    PoseObservation o;
    o.point_world = X;
    o.pixel = cam.project(p);
    if (o.pixel.x() < 0 || o.pixel.x() > 640 || o.pixel.y() < 0 || o.pixel.y() > 480) continue;
    if (obs.size() % 2 == 0) o.u_right = cam.project_right_u(p);  // half with depth
    o.inv_sigma2 = obs.size() % 3 == 0 ? 1.0 : 1.0 / 1.44;
    obs.push_back(o);
  }
  ASSERT_GT(obs.size(), 100u);
  const auto residuals = [&](const Eigen::Matrix<double, 6, 1>& d) {
    Eigen::Isometry3d Tp = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d w = d.head<3>();
    const Eigen::Matrix3d Rp = (w.norm() > 0 ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix()
                                             : Eigen::Matrix3d::Identity()) * T.linear();
    const Eigen::Vector3d C = T.inverse().translation() + d.tail<3>();
    Tp.linear() = Rp;
    Tp.translation() = -(Rp * C);
    std::vector<double> r;
    for (const PoseObservation& o : obs) {
      const Eigen::Vector3d p = Tp * o.point_world;
      const double s = std::sqrt(o.inv_sigma2);
      r.push_back(s * cam.project(p).x());
      r.push_back(s * cam.project(p).y());
      if (o.u_right >= 0) r.push_back(s * cam.project_right_u(p));
    }
    return Eigen::Map<Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size())).eval();
  };
  const double h = 1e-6;
  const Eigen::Index m = residuals(Eigen::Matrix<double, 6, 1>::Zero()).size();
  Eigen::MatrixXd J(m, 6);
  for (int k = 0; k < 6; ++k) {
    Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
    d[k] = h;
    const Eigen::VectorXd plus = residuals(d);
    d[k] = -h;
    J.col(k) = (plus - residuals(d)) / (2 * h);
  }
  const Eigen::Matrix<double, 6, 6> H = J.transpose() * J;
  const Eigen::Matrix3d info =
      H.bottomRightCorner<3, 3>() - H.bottomLeftCorner<3, 3>() * H.topLeftCorner<3, 3>().inverse() * H.topRightCorner<3, 3>();
  const Eigen::Matrix3d expected = info.inverse();
  const Eigen::Matrix3d got = centre_covariance(cam, T, obs);
  EXPECT_LT((got - expected).norm(), 1e-4 * expected.norm()) << got << "\n" << expected;
  // Too few observations: no covariance.
  EXPECT_TRUE(centre_covariance(cam, T, {obs[0], obs[1]}).isZero());
}

TEST(SparseView, TheWeakAxesAreTheLargestEigenvectorsOfTheCovariance) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d cov = R * Eigen::Vector3d(1e-6, 9e-6, 4e-6).asDiagonal() * R.transpose();
  const Eigen::Vector3d weakest = R.col(1), next = R.col(2);
  EXPECT_LT((weak_axes_projection(cov, 1) - weakest * weakest.transpose()).norm(), 1e-9);
  EXPECT_LT((weak_axes_projection(cov, 2) - weakest * weakest.transpose() - next * next.transpose()).norm(), 1e-9);
  EXPECT_EQ(weak_axes_projection(cov, 3), Eigen::Matrix3d::Identity());
  EXPECT_EQ(weak_axes_projection(Eigen::Matrix3d::Zero(), 1), Eigen::Matrix3d::Identity());
}

// SparseViewOptions::filter_axes on a trajectory: jitter along y and z; with
// each flagged frame's projection onto y the filter takes out y's jitter as
// with every axis, and z keeps its jitter exactly.
TEST(SparseView, OnOneAxisTheFilterLeavesTheOthersAsGiven) {
  std::vector<Eigen::Vector3d> centres;
  std::vector<bool> sparse;
  std::vector<std::uint64_t> maps(40, 1);
  for (int i = 0; i < 40; ++i) {
    const bool flagged = i >= 10 && i < 30;
    const double jitter = flagged ? (i % 2 == 0 ? 0.01 : -0.01) : 0.0;
    centres.emplace_back(0.01 * i, jitter, -jitter);
    sparse.push_back(flagged);
  }
  const std::vector<Eigen::Vector3d> given = centres;
  std::vector<Eigen::Vector3d> all = given;
  filter_sparse_centres(all, sparse, maps, 0.5, 5);
  const Eigen::Vector3d y = Eigen::Vector3d::UnitY();
  const std::vector<Eigen::Matrix3d> onto_y(40, y * y.transpose());
  filter_sparse_centres(centres, sparse, maps, 0.5, 5, onto_y);
  double y_rms = 0, y_all_rms = 0;
  for (int i = 10; i < 30; ++i) {
    EXPECT_NEAR(centres[i].z(), given[i].z(), 1e-15) << i;
    EXPECT_NEAR(centres[i].x(), given[i].x(), 1e-12) << i;
    y_rms += centres[i].y() * centres[i].y();
    y_all_rms += all[i].y() * all[i].y();
  }
  y_rms = std::sqrt(y_rms / 20);
  y_all_rms = std::sqrt(y_all_rms / 20);
  EXPECT_LT(y_rms, 0.006) << y_rms;  // of the 10 mm
  EXPECT_LT(std::abs(y_rms - y_all_rms), 0.002) << y_rms << " " << y_all_rms;
}

// SparseViewOptions::filter_axes online: with one axis the published centre
// differs from the unfiltered one only along the frame's least certain
// direction, which the result reports.
TEST(SparseView, OnOneAxisTheOnlineFilterMovesTheCentreAlongTheWeakDirection) {
  const auto run = [](double gain, int axes, Eigen::Matrix3d* projection) {
    TrackerOptions o = SparseTracker::options(1.0, 0);
    o.sparse_view.filter_gain = gain;
    o.sparse_view.filter_axes = axes;
    SparseTracker t(o);
    t.start(8);
    const double path = 0.01 * static_cast<double>(t.id);
    Frame f = t.scene.make_frame(t.id, test::pose_at(path + 0.006, 0.004));
    f.set_dynamic_mask(mask_of_left_part(0.6));
    const TrackingResult r = t.tracker.track(f);
    EXPECT_EQ(r.sparse_view, SparseView::Tracked) << r.reason;
    if (projection) *projection = r.sparse_filter_projection;
    return Eigen::Vector3d(centre(f));
  };
  Eigen::Matrix3d P;
  const Eigen::Vector3d tracked = run(0, 3, nullptr), one_axis = run(0.5, 1, &P), all = run(0.5, 3, nullptr);
  EXPECT_NEAR(P.trace(), 1.0, 1e-9);  // rank one
  EXPECT_LT((P * P - P).norm(), 1e-9);
  const Eigen::Vector3d moved = one_axis - tracked;
  EXPECT_LT(((Eigen::Matrix3d::Identity() - P) * moved).norm(), 3e-4) << moved.transpose();
  EXPECT_GT((all - tracked).norm(), 0.002);  // every axis: half of the 7 mm off the path
  // Along the weak direction both filters move the centre alike.
  EXPECT_NEAR((P * moved).norm(), (P * (all - tracked)).norm(), 5e-4);
  EXPECT_GT((P * moved).norm(), 0.001) << "weak direction " << (P * Eigen::Vector3d(1, 1, 1)).transpose();
}

// SparseViewOptions::keyframe_prior_sigma: the keyframes made in the sparse
// views carry a centre prior at their centre at creation, with sqrt_info the
// weak axis over sigma; keyframes made in views that are not sparse carry none.
TEST(SparseView, KeyframesMadeInSparseViewsKeepACentrePrior) {
  TrackerOptions o = SparseTracker::options(1.0, 0);
  o.sparse_view.keyframe_prior_sigma = 0.002;
  o.sparse_view.filter_axes = 1;
  o.close_points_tracked_min = 100000;  // any untracked close point asks for a keyframe, no budget
  o.close_points_untracked_min = 0;
  o.keyframe_budget.per_second = 0;
  SparseTracker t(o);
  t.start(4);
  int with_prior = 0, sparse_keyframes = 0, plain_keyframes = 0;
  for (double share : {0.6, 0.6, 0.6, 0.2, 0.2, 0.2}) {
    Frame f = t.scene.make_frame(t.id, test::pose_at(0.01 * static_cast<double>(t.id)));
    ++t.id;
    f.set_dynamic_mask(mask_of_left_part(share));
    const TrackingResult r = t.tracker.track(f);
    ASSERT_EQ(r.state, TrackingState::Ok) << r.reason;
    if (!r.new_keyframe) continue;
    const auto& prior = f.reference_keyframe()->centre_prior();
    if (share < 0.5) {
      ++plain_keyframes;
      EXPECT_FALSE(prior.has_value());
      continue;
    }
    ++sparse_keyframes;
    ASSERT_TRUE(prior.has_value());
    ++with_prior;
    EXPECT_LT((prior->mean - centre(f)).norm(), 1e-12);
    const Eigen::Matrix3d P = prior->sqrt_info * 0.002;
    EXPECT_NEAR(P.trace(), 1.0, 1e-9);
    EXPECT_LT((P * P - P).norm(), 1e-9);
  }
  EXPECT_GE(sparse_keyframes, 2);
  EXPECT_EQ(with_prior, sparse_keyframes);
  EXPECT_GE(plain_keyframes, 1);
}

}  // namespace
}  // namespace stillslam
