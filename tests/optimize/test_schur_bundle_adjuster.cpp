// The hand-written Schur solver (BaSolver::Schur) against known answers and
// against the Ceres path on the same synthesized problems.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <atomic>
#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "geometry/synthetic_scene.h"
#include "stillslam/optimize/bundle_adjustment.h"
#include "stillslam/optimize/schur_bundle_adjuster.h"

namespace stillslam {
namespace {

enum class Depth { Mono, Stereo, Mixed };

struct Scene {
  std::vector<Eigen::Isometry3d> true_poses;
  std::vector<Eigen::Vector3d> true_points;
  std::vector<BaKeyframe> keyframes;
  std::vector<BaPoint> points;
  std::vector<BaObservation> observations;
};

struct SceneSpec {
  int keyframes = 8;
  int fixed = 2;
  int points = 300;
  Depth depth = Depth::Mixed;
  double pixel_noise = 1.0;
  int outlier_every = 20;  // 0: none
  unsigned seed = 1;
};

// Keyframes along a 1.4 m path; free ones 5 cm / 1 deg off, points 5 cm off.
Scene make_scene(const PinholeCamera& cam, const SceneSpec& spec) {
  std::mt19937 rng(spec.seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  Scene s;
  for (int k = 0; k < spec.keyframes; ++k) {
    const double a = 1.4 * k / std::max(1, spec.keyframes - 1);
    s.true_poses.push_back(testing::camera_pose({a - 0.7, 0.05 * std::sin(4 * a), 0.1 * a}, {0.01 * k, -0.02 * k, 0.0}));
    Eigen::Isometry3d noisy = s.true_poses.back();
    if (k >= spec.fixed) {
      const Eigen::Vector3d dt(n01(rng), n01(rng), n01(rng)), dw(n01(rng), n01(rng), n01(rng));
      noisy.translation() += 0.05 * dt.normalized();
      noisy.linear() = so3_exp(dw.normalized() * (M_PI / 180.0)) * noisy.linear();
    }
    s.keyframes.push_back({static_cast<std::uint64_t>(k), noisy, k < spec.fixed});
  }
  std::size_t count = 0;
  for (const auto& p : testing::random_points(rng, spec.points)) {
    std::vector<BaObservation> obs;
    const bool stereo = spec.depth == Depth::Stereo || (spec.depth == Depth::Mixed && s.true_points.size() % 2 == 0);
    for (std::size_t k = 0; k < s.true_poses.size(); ++k) {
      const Eigen::Vector3d pc = s.true_poses[k] * p;
      const Eigen::Vector2d uv = cam.project(pc);
      if (pc.z() < 0.5 || !cam.in_image(uv)) continue;
      BaObservation o;
      o.keyframe = k;
      o.point = s.points.size();
      o.pixel = uv + spec.pixel_noise * Eigen::Vector2d(n01(rng), n01(rng));
      if (stereo) o.u_right = cam.project_right_u(pc) + spec.pixel_noise * n01(rng);
      o.inv_sigma2 = (k % 3 == 0) ? 1.0 : 1.0 / 1.44;  // two pyramid levels
      if (spec.outlier_every > 0 && ++count % static_cast<std::size_t>(spec.outlier_every) == 0) {
        o.pixel += Eigen::Vector2d(25.0, -15.0);
        if (o.u_right >= 0) o.u_right += 25.0;
      }
      obs.push_back(o);
    }
    if (obs.size() < 3) continue;
    s.observations.insert(s.observations.end(), obs.begin(), obs.end());
    s.true_points.push_back(p);
    const Eigen::Vector3d dp(n01(rng), n01(rng), n01(rng));
    s.points.push_back({s.points.size(), p + 0.05 * dp.normalized()});
  }
  return s;
}

BundleAdjustmentOptions with(BaSolver solver) {
  BundleAdjustmentOptions o;
  o.solver = solver;
  return o;
}

BundleAdjustmentResult run(const PinholeCamera& cam, const Scene& s, const BundleAdjustmentOptions& o) {
  return bundle_adjust(cam, s.keyframes, s.points, s.observations, o);
}

const char* name(Depth d) { return d == Depth::Mono ? "mono" : d == Depth::Stereo ? "stereo" : "mixed"; }

TEST(SchurBundleAdjuster, NoiseFreeProblemsConvergeToTheTruth) {
  const PinholeCamera cam(testing::tum_like_calibration(), 40.0);
  for (const Depth depth : {Depth::Mono, Depth::Stereo, Depth::Mixed}) {
    SceneSpec spec;
    spec.depth = depth;
    spec.pixel_noise = 0;
    spec.outlier_every = 0;
    const Scene s = make_scene(cam, spec);
    BundleAdjustmentOptions o = with(BaSolver::Schur);
    o.iterations = 30;
    o.outlier_rounds = 0;
    o.function_tolerance = 1e-12;
    const BundleAdjustmentResult r = run(cam, s, o);
    EXPECT_GT(r.initial_cost, 1e3) << name(depth);
    EXPECT_LT(r.final_cost, 1e-12) << name(depth);
    for (std::size_t k = 0; k < s.keyframes.size(); ++k) {
      EXPECT_LT(testing::translation_error(r.T_cam_world[k], s.true_poses[k]), 1e-7) << name(depth) << " kf " << k;
      EXPECT_LT(testing::rotation_error_deg(r.T_cam_world[k], s.true_poses[k]), 1e-6) << name(depth) << " kf " << k;
    }
    double worst = 0;
    for (std::size_t i = 0; i < s.points.size(); ++i) worst = std::max(worst, (r.points[i] - s.true_points[i]).norm());
    EXPECT_LT(worst, 1e-6) << name(depth);
    EXPECT_TRUE(std::all_of(r.observation_inlier.begin(), r.observation_inlier.end(), [](bool b) { return b; }));
  }
}

// Noisy scenes with 5 % outliers, ORB-SLAM's local-BA schedule (Huber pass,
// outlier classification, a pass without them): both solvers reach the same
// minimum and flag the same observations.
TEST(SchurBundleAdjuster, AgreesWithCeres) {
  const PinholeCamera cam(testing::tum_like_calibration(), 40.0);
  for (const Depth depth : {Depth::Mono, Depth::Stereo, Depth::Mixed}) {
    for (const bool split : {true, false}) {
      SceneSpec spec;
      spec.depth = depth;
      spec.seed = 7;
      const Scene s = make_scene(cam, spec);
      BundleAdjustmentOptions o = with(BaSolver::Ceres);
      o.split_stereo = split;
      o.function_tolerance = 1e-10;
      o.iterations = 20;
      o.iterations_after_outliers = 20;
      const BundleAdjustmentResult c = run(cam, s, o);
      o.solver = BaSolver::Schur;
      const BundleAdjustmentResult h = run(cam, s, o);
      const std::string what = std::string(name(depth)) + (split ? " split" : " 3-row");
      EXPECT_GT(c.initial_cost, 20 * c.final_cost) << what;
      EXPECT_NEAR(h.initial_cost, c.initial_cost, 1e-9 * c.initial_cost) << what;
      EXPECT_NEAR(h.final_cost, c.final_cost, 1e-6 * c.final_cost) << what;
      EXPECT_EQ(h.observation_inlier, c.observation_inlier) << what;
      int outliers = 0;
      for (const bool b : h.observation_inlier) outliers += !b;
      EXPECT_GT(outliers, static_cast<int>(s.observations.size() / 25)) << what;
      for (std::size_t k = 0; k < s.keyframes.size(); ++k) {
        EXPECT_LT(testing::translation_error(h.T_cam_world[k], c.T_cam_world[k]), 1e-6) << what << " kf " << k;
        EXPECT_LT(testing::rotation_error_deg(h.T_cam_world[k], c.T_cam_world[k]), 1e-5) << what << " kf " << k;
      }
      // Fixed keyframes come back bit for bit.
      for (std::size_t k = 0; k < 2; ++k) EXPECT_EQ(h.T_cam_world[k].matrix(), s.keyframes[k].T_cam_world.matrix());
    }
  }
}

// The default schedule (10 + 10 iterations, function tolerance 1e-6) stops
// both solvers early, at nearly the same cost.
TEST(SchurBundleAdjuster, DefaultScheduleMatchesCeres) {
  const PinholeCamera cam(testing::tum_like_calibration(), 40.0);
  SceneSpec spec;
  spec.seed = 11;
  const Scene s = make_scene(cam, spec);
  const BundleAdjustmentResult c = run(cam, s, with(BaSolver::Ceres));
  const BundleAdjustmentResult h = run(cam, s, with(BaSolver::Schur));
  EXPECT_NEAR(h.final_cost, c.final_cost, 1e-4 * c.final_cost);
  EXPECT_EQ(h.observation_inlier, c.observation_inlier);
  EXPECT_NEAR(h.iterations, c.iterations, 2);
  EXPECT_GT(h.applied_steps, 2);
  for (std::size_t k = 0; k < s.keyframes.size(); ++k) {
    EXPECT_LT(testing::translation_error(h.T_cam_world[k], c.T_cam_world[k]), 1e-4) << k;
    EXPECT_LT(testing::translation_error(h.T_cam_world[k], s.true_poses[k]), 0.015) << k;
  }
}

// No fixed keyframe: the gauge is free (7 dof for mono), only LM's damping
// keeps the system regular. The solve must stay finite and fit the data as
// well as Ceres.
TEST(SchurBundleAdjuster, GaugeFreeProblemDoesNotBlowUp) {
  const PinholeCamera cam(testing::tum_like_calibration(), 40.0);
  for (const Depth depth : {Depth::Mono, Depth::Mixed}) {
    SceneSpec spec;
    spec.fixed = 0;
    spec.depth = depth;
    spec.seed = 5;
    const Scene s = make_scene(cam, spec);
    const BundleAdjustmentResult c = run(cam, s, with(BaSolver::Ceres));
    const BundleAdjustmentResult h = run(cam, s, with(BaSolver::Schur));
    for (const auto& T : h.T_cam_world) EXPECT_TRUE(T.matrix().allFinite()) << name(depth);
    for (const auto& p : h.points) EXPECT_TRUE(p.allFinite()) << name(depth);
    EXPECT_GT(h.initial_cost, 20 * h.final_cost) << name(depth);
    EXPECT_LT(h.final_cost, 1.01 * c.final_cost) << name(depth);
    // The gauge drifts at most a little: keyframe 0 stays near where it started.
    EXPECT_LT(testing::translation_error(h.T_cam_world[0], s.keyframes[0].T_cam_world), 0.05) << name(depth);
  }
}

TEST(SchurBundleAdjuster, AbortMidPassKeepsOrDiscardsAsAsked) {
  const PinholeCamera cam(testing::tum_like_calibration(), 40.0);
  SceneSpec spec;
  spec.seed = 35;
  const Scene s = make_scene(cam, spec);
  BundleAdjustmentOptions one_step = with(BaSolver::Schur);
  one_step.iterations = 1;
  one_step.outlier_rounds = 0;
  const BundleAdjustmentResult stepped = run(cam, s, one_step);
  ASSERT_EQ(stepped.applied_steps, 1);
  ASSERT_EQ(stepped.iterations, 1);
  for (const bool keep : {true, false}) {
    std::atomic<bool> abort{false};
    int calls = 0;
    BundleAdjustmentOptions o = with(BaSolver::Schur);
    o.abort = &abort;
    o.keep_progress_on_abort = keep;
    o.on_iteration = [&] {
      if (++calls == 2) abort = true;  // call 1: iteration 0, call 2: after iteration 1
    };
    const BundleAdjustmentResult r = run(cam, s, o);
    EXPECT_TRUE(r.aborted) << keep;
    EXPECT_EQ(calls, 2) << keep;
    EXPECT_EQ(r.iterations, 1) << keep;
    EXPECT_EQ(r.applied_steps, keep ? 1 : 0) << keep;
    for (std::size_t k = 0; k < s.keyframes.size(); ++k) {
      const Eigen::Isometry3d& expected = keep ? stepped.T_cam_world[k] : s.keyframes[k].T_cam_world;
      EXPECT_TRUE(r.T_cam_world[k].isApprox(expected, 1e-12)) << keep << " keyframe " << k;
    }
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      const Eigen::Vector3d& expected = keep ? stepped.points[i] : s.points[i].position_world;
      EXPECT_EQ(r.points[i], expected) << keep << " point " << i;
    }
  }
  // Set before the start: no pass runs, nothing moves.
  std::atomic<bool> abort{true};
  BundleAdjustmentOptions o = with(BaSolver::Schur);
  o.abort = &abort;
  const BundleAdjustmentResult r = run(cam, s, o);
  EXPECT_TRUE(r.aborted);
  EXPECT_EQ(r.iterations, 0);
  for (std::size_t i = 0; i < s.points.size(); ++i) EXPECT_EQ(r.points[i], s.points[i].position_world);
}

TEST(SchurBundleAdjuster, RepeatsBitForBit) {
  const PinholeCamera cam(testing::tum_like_calibration(), 40.0);
  SceneSpec spec;
  spec.seed = 3;
  const Scene s = make_scene(cam, spec);
  const BundleAdjustmentResult a = run(cam, s, with(BaSolver::Schur));
  const BundleAdjustmentResult b = run(cam, s, with(BaSolver::Schur));
  for (std::size_t k = 0; k < s.keyframes.size(); ++k) EXPECT_EQ(a.T_cam_world[k].matrix(), b.T_cam_world[k].matrix());
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.final_cost, b.final_cost);
}

// A point that starts behind one of its cameras: that observation is left
// out of the first pass and flagged an outlier, as on the Ceres path.
TEST(SchurBundleAdjuster, PointsBehindTheCameraAreLeftOut) {
  const PinholeCamera cam(testing::tum_like_calibration(), 40.0);
  SceneSpec spec;
  spec.seed = 9;
  spec.outlier_every = 0;
  Scene s = make_scene(cam, spec);
  // Point 0 behind keyframe 0 (and so behind the keyframes near it).
  const Eigen::Isometry3d T = s.keyframes[0].T_cam_world;
  s.points[0].position_world = T.inverse() * Eigen::Vector3d(0.1, 0.1, -1.0);
  const BundleAdjustmentResult c = run(cam, s, with(BaSolver::Ceres));
  const BundleAdjustmentResult h = run(cam, s, with(BaSolver::Schur));
  EXPECT_EQ(h.observation_inlier, c.observation_inlier);
  EXPECT_NEAR(h.final_cost, c.final_cost, 1e-4 * c.final_cost);
  for (std::size_t i = 0; i < s.observations.size(); ++i) {
    if (s.observations[i].point == 0 && s.observations[i].keyframe == 0) {
      EXPECT_FALSE(h.observation_inlier[i]);
    }
  }
}

// Above kSchurMaxFreeKeyframes free keyframes the pass goes to Ceres: the
// result is Ceres' bit for bit.
TEST(SchurBundleAdjuster, LargeProblemsGoToCeres) {
  const PinholeCamera cam(testing::tum_like_calibration(), 40.0);
  SceneSpec spec;
  spec.keyframes = kSchurMaxFreeKeyframes + 4;
  spec.points = 150;
  spec.seed = 4;
  const Scene s = make_scene(cam, spec);
  BundleAdjustmentOptions o = with(BaSolver::Ceres);
  o.iterations = 3;
  o.outlier_rounds = 0;
  const BundleAdjustmentResult c = run(cam, s, o);
  o.solver = BaSolver::Schur;
  const BundleAdjustmentResult h = run(cam, s, o);
  EXPECT_EQ(h.final_cost, c.final_cost);
  EXPECT_EQ(h.points, c.points);
}

// The point blocks' inverses: bit for bit what LLT::solve(Identity) gives
// (the BA's results must not move), on well and badly conditioned matrices.
TEST(SchurBundleAdjuster, CholeskyInverseIsBitIdenticalToEigens) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  for (int n = 0; n < 2000; ++n) {
    Eigen::Matrix3d A;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) A(r, c) = u(rng);
    }
    const double scale = std::pow(10.0, 8.0 * u(rng));  // 1e-8 .. 1e8
    Eigen::Matrix3d V = scale * (A * A.transpose());
    for (int d = 0; d < 3; ++d) V(d, d) += scale * 1e-6 * (n % 7);
    const Eigen::LLT<Eigen::Matrix3d> llt(V);
    if (llt.info() != Eigen::Success) continue;
    const Eigen::Matrix3d expected = llt.solve(Eigen::Matrix3d::Identity());
    const Eigen::Matrix3d got = inverse_from_cholesky(llt.matrixL());
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        ASSERT_EQ(std::memcmp(&got(r, c), &expected(r, c), sizeof(double)), 0)
            << "matrix " << n << " entry (" << r << ", " << c << "): " << got(r, c) << " vs " << expected(r, c);
      }
    }
    ++checked;
  }
  EXPECT_GT(checked, 1900);
  // And it is an inverse.
  Eigen::Matrix3d V;
  V << 4, 1, 0.5, 1, 3, 0.25, 0.5, 0.25, 2;
  const Eigen::Matrix3d inv = inverse_from_cholesky(Eigen::LLT<Eigen::Matrix3d>(V).matrixL());
  EXPECT_LT((inv * V - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-14);
}

// BaKeyframe's centre prior: a free keyframe whose prior lies 20 mm off its
// true centre along x (sigma 0.01 mm, no rows along y and z) on a
// noise-free scene ends there along x; both solvers reach the same answer.
// Without the prior it ends at the truth.
TEST(SchurBundleAdjuster, ACentrePriorHoldsAFreeKeyframeAlongItsAxesOnly) {
  const PinholeCamera cam(testing::tum_like_calibration(), 40.0);
  SceneSpec spec;
  spec.pixel_noise = 0;
  spec.outlier_every = 0;
  Scene s = make_scene(cam, spec);
  const std::size_t held = 5;
  const Eigen::Vector3d truth = s.true_poses[held].inverse().translation();
  s.keyframes[held].prior_centre = truth + Eigen::Vector3d(0.02, 0, 0);
  s.keyframes[held].prior_sqrt_info = Eigen::Vector3d(1, 0, 0).asDiagonal();
  s.keyframes[held].prior_sqrt_info /= 1e-5;
  BundleAdjustmentOptions o = with(BaSolver::Ceres);
  o.iterations = 30;
  o.outlier_rounds = 0;
  o.function_tolerance = 1e-12;
  const BundleAdjustmentResult c = run(cam, s, o);
  o.solver = BaSolver::Schur;
  const BundleAdjustmentResult h = run(cam, s, o);
  for (const BundleAdjustmentResult* r : {&c, &h}) {
    const Eigen::Vector3d centre = r->T_cam_world[held].inverse().translation();
    EXPECT_NEAR(centre.x(), truth.x() + 0.02, 5e-4);
    EXPECT_GT(std::abs(centre.x() - truth.x()), 0.019);
  }
  for (std::size_t k = 0; k < s.keyframes.size(); ++k) {
    EXPECT_LT(testing::translation_error(h.T_cam_world[k], c.T_cam_world[k]), 1e-6) << "kf " << k;
  }
  // Without the prior the same keyframe returns to the truth.
  s.keyframes[held].prior_sqrt_info.setZero();
  const BundleAdjustmentResult free = run(cam, s, o);
  EXPECT_LT((free.T_cam_world[held].inverse().translation() - truth).norm(), 1e-6);
}

}  // namespace
}  // namespace stillslam
