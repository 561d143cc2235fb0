// evaluate() on synthetic trajectories whose errors are known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "stillslam/core/error.h"
#include "stillslam/eval/evaluate.h"

namespace stillslam {
namespace {

// A camera on a helix that keeps turning: 30 Hz, non-degenerate in 3D.
Trajectory helix(std::size_t n) {
  Trajectory t(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = static_cast<double>(i) / 30.0;
    t[i].timestamp = 1000.0 + s;
    t[i].T_world_cam.translation() = Eigen::Vector3d(std::cos(0.7 * s), std::sin(0.7 * s), 0.2 * s);
    t[i].T_world_cam.linear() = (Eigen::AngleAxisd(0.7 * s, Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(0.3 * std::sin(s), Eigen::Vector3d::UnitX()))
                                    .toRotationMatrix();
  }
  return t;
}

// est_i = S * gt_i with S a similarity (rotation R, translation t, scale s).
Trajectory moved(const Trajectory& gt, double scale) {
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  const Eigen::Vector3d t(4.0, -2.0, 7.5);
  Trajectory est = gt;
  for (StampedPose& p : est) {
    p.T_world_cam.linear() = R * p.T_world_cam.linear();
    p.T_world_cam.translation() = scale * (R * p.T_world_cam.translation()) + t;
  }
  return est;
}

EvaluationOptions with_alignment(AlignmentType type) {
  EvaluationOptions options;
  options.alignment = type;
  return options;
}

TEST(SyntheticEvaluation, RigidlyMovedCopyHasZeroError) {
  const Trajectory gt = helix(300);
  const EvaluationResult r = evaluate(gt, moved(gt, 1.0), with_alignment(AlignmentType::Se3));
  EXPECT_EQ(r.pairs, 300u);
  EXPECT_LT(r.ape_stats.max, 1e-9);
  EXPECT_LT(r.rpe_trans_stats.max, 1e-9);
  EXPECT_LT(r.rpe_rot_stats.max, 1e-6);
  EXPECT_DOUBLE_EQ(r.alignment.scale, 1.0);
  // Without alignment the same copy is far off.
  EXPECT_GT(evaluate(gt, moved(gt, 1.0), with_alignment(AlignmentType::None)).ape_stats.rmse, 5.0);
}

TEST(SyntheticEvaluation, ScaledCopyNeedsSim3) {
  const Trajectory gt = helix(300);
  const Trajectory est = moved(gt, 0.37);
  const EvaluationResult sim3 = evaluate(gt, est, with_alignment(AlignmentType::Sim3));
  EXPECT_LT(sim3.ape_stats.max, 1e-9);
  EXPECT_NEAR(sim3.alignment.scale, 1.0 / 0.37, 1e-9);
  EXPECT_LT(sim3.rpe_trans_stats.max, 1e-9);  // the RPE sees the rescaled estimate
  const EvaluationResult se3 = evaluate(gt, est, with_alignment(AlignmentType::Se3));
  EXPECT_GT(se3.ape_stats.rmse, 0.3);
  EXPECT_GT(se3.rpe_trans_stats.rmse, 0.005);
}

TEST(SyntheticEvaluation, IsotropicNoiseGivesItsExpectedSize) {
  const Trajectory gt = helix(3000);
  Trajectory est = gt;
  std::mt19937 rng(7);
  const double sigma = 0.01;
  std::normal_distribution<double> noise(0.0, sigma);
  for (StampedPose& p : est) p.T_world_cam.translation() += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  const EvaluationResult r = evaluate(gt, est, with_alignment(AlignmentType::Se3));
  // |3D gaussian| has rms sigma*sqrt(3) and mean sigma*sqrt(8/pi).
  EXPECT_NEAR(r.ape_stats.rmse, sigma * std::sqrt(3.0), 0.03 * sigma * std::sqrt(3.0));
  EXPECT_NEAR(r.ape_stats.mean, sigma * std::sqrt(8.0 / M_PI), 0.03 * sigma * std::sqrt(8.0 / M_PI));
  // Relative translation over one step differences two independent draws: rms sigma*sqrt(6).
  EXPECT_NEAR(r.rpe_trans_stats.rmse, sigma * std::sqrt(6.0), 0.03 * sigma * std::sqrt(6.0));
  EXPECT_LT(r.rpe_rot_stats.max, 1e-6);
}

TEST(SyntheticEvaluation, ConstantDriftGivesExactRelativeError) {
  const Trajectory gt = helix(200);
  Trajectory est = gt;
  const Eigen::Vector3d v(0.003, -0.004, 0.0);  // 5 mm per frame in the world frame
  for (std::size_t i = 0; i < est.size(); ++i) est[i].T_world_cam.translation() += static_cast<double>(i) * v;
  EvaluationOptions options = with_alignment(AlignmentType::None);
  const EvaluationResult one = evaluate(gt, est, options);
  EXPECT_NEAR(one.rpe_trans_stats.min, 0.005, 1e-12);
  EXPECT_NEAR(one.rpe_trans_stats.max, 0.005, 1e-12);
  EXPECT_EQ(one.rpe_pairs.size(), 199u);
  options.rpe.delta = 10;
  const EvaluationResult ten = evaluate(gt, est, options);
  EXPECT_NEAR(ten.rpe_trans_stats.rmse, 0.05, 1e-12);
  EXPECT_EQ(ten.rpe_pairs.size(), 19u);  // ids 0, 10, ..., 190
  EXPECT_NEAR(one.ape_stats.max, 199 * 0.005, 1e-9);
}

TEST(SyntheticEvaluation, RotationDriftGivesExactAngle) {
  // A camera turning in place about its optical axis; the estimate turns 0.1 deg per frame more.
  Trajectory gt(100), est(100);
  for (std::size_t i = 0; i < gt.size(); ++i) {
    const double k = static_cast<double>(i);
    gt[i].timestamp = est[i].timestamp = k * 0.05;
    gt[i].T_world_cam.linear() = Eigen::AngleAxisd(0.02 * k, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    est[i].T_world_cam.linear() = Eigen::AngleAxisd((0.02 + 0.1 * M_PI / 180.0) * k, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  }
  EvaluationOptions options = with_alignment(AlignmentType::None);
  options.rpe.delta = 3;
  const EvaluationResult r = evaluate(gt, est, options);
  EXPECT_NEAR(r.rpe_rot_stats.min, 0.3, 1e-9);
  EXPECT_NEAR(r.rpe_rot_stats.max, 0.3, 1e-9);
  EXPECT_LT(r.rpe_trans_stats.max, 1e-12);
}

TEST(SyntheticEvaluation, TimeOffsetAndSubsetAssociate) {
  const Trajectory gt = helix(300);
  Trajectory est;
  for (std::size_t i = 0; i < gt.size(); i += 3) {
    StampedPose p = gt[i];
    p.timestamp += 0.004;  // a small clock offset stays inside max_dt
    est.push_back(p);
  }
  const EvaluationResult r = evaluate(gt, est, with_alignment(AlignmentType::Se3));
  EXPECT_EQ(r.pairs, 100u);
  EXPECT_LT(r.ape_stats.max, 1e-9);
}

TEST(SyntheticEvaluation, FailsClearlyWithoutMatchesOrMotion) {
  const Trajectory gt = helix(50);
  Trajectory late = gt;
  for (StampedPose& p : late) p.timestamp += 100.0;
  EXPECT_THROW(evaluate(gt, late, with_alignment(AlignmentType::Se3)), Error);
  Trajectory still = gt;
  for (StampedPose& p : still) p.T_world_cam.translation().setZero();
  EXPECT_THROW(evaluate(gt, still, with_alignment(AlignmentType::Se3)), Error);
  EXPECT_NO_THROW(evaluate(gt, still, with_alignment(AlignmentType::None)));
  EXPECT_THROW(evaluate(gt, Trajectory(gt.begin(), gt.begin() + 2), with_alignment(AlignmentType::Se3)), Error);
}

}  // namespace
}  // namespace stillslam
