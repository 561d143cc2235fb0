// Reference values of the TUM RGB-D tools (greedy association within 0.02 s,
// rigid Horn/Umeyama alignment) on real trajectories from ../shared.
#include <gtest/gtest.h>

#include <filesystem>

#include "stillslam/eval/evaluate.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

// The references are printed with 6 decimals; we reproduce them to rounding.
constexpr double kTolerance = 1e-6;

fs::path trajectories_dir() { return fs::path(STILLSLAM_SHARED_DIR) / "data" / "trajectories"; }

#define SKIP_WITHOUT_SHARED()                                                                         \
  if (!fs::exists(trajectories_dir())) {                                                              \
    GTEST_SKIP() << "shared data not found at " << trajectories_dir() << "; reference tests need it"; \
  }

EvaluationResult run(const std::string& gt, const std::string& est, AlignmentType alignment) {
  EvaluationOptions options;
  options.alignment = alignment;
  return evaluate(read_trajectory(trajectories_dir() / gt), read_trajectory(trajectories_dir() / est), options);
}

TEST(ReferenceValues, Fr2DeskOrbSe3) {
  SKIP_WITHOUT_SHARED();
  const auto r = run("fr2_desk_groundtruth.txt", "fr2_desk_ORB.txt", AlignmentType::Se3);
  EXPECT_EQ(r.pairs, 2223u);
  EXPECT_NEAR(r.ape_stats.rmse, 0.008144, kTolerance);
  EXPECT_NEAR(r.ape_stats.mean, 0.007514, kTolerance);
  EXPECT_NEAR(r.ape_stats.median, 0.007432, kTolerance);
  EXPECT_NEAR(r.ape_stats.max, 0.024329, kTolerance);
  EXPECT_NEAR(r.alignment.scale, 1.0, 0.0);
}

TEST(ReferenceValues, Fr2DeskOrbSim3) {
  SKIP_WITHOUT_SHARED();
  const auto r = run("fr2_desk_groundtruth.txt", "fr2_desk_ORB.txt", AlignmentType::Sim3);
  EXPECT_EQ(r.pairs, 2223u);
  EXPECT_NEAR(r.ape_stats.rmse, 0.006186, kTolerance);
}

TEST(ReferenceValues, Fr1XyzRgbdSlam) {
  SKIP_WITHOUT_SHARED();
  const auto r = run("freiburg1_xyz-groundtruth.txt", "freiburg1_xyz-rgbdslam.txt", AlignmentType::Se3);
  EXPECT_EQ(r.pairs, 786u);
  EXPECT_NEAR(r.ape_stats.rmse, 0.013473, kTolerance);
  EXPECT_NEAR(r.ape_stats.mean, 0.012029, kTolerance);
  EXPECT_NEAR(r.ape_stats.median, 0.011176, kTolerance);
  EXPECT_NEAR(r.ape_stats.max, 0.034727, kTolerance);
}

TEST(ReferenceValues, Fr2DeskMonocularKeyframes) {
  SKIP_WITHOUT_SHARED();
  const auto se3 = run("fr2_desk_groundtruth.txt", "fr2_desk_ORB_kf_mono.txt", AlignmentType::Se3);
  EXPECT_EQ(se3.pairs, 122u);
  EXPECT_NEAR(se3.ape_stats.rmse, 0.948813, kTolerance);
  const auto sim3 = run("fr2_desk_groundtruth.txt", "fr2_desk_ORB_kf_mono.txt", AlignmentType::Sim3);
  EXPECT_EQ(sim3.pairs, 122u);
  EXPECT_NEAR(sim3.ape_stats.rmse, 0.007900, kTolerance);
  EXPECT_GT(sim3.alignment.scale, 0.0);
}

TEST(ReferenceValues, Fr2DeskOrbRpeOneFrame) {
  SKIP_WITHOUT_SHARED();
  const auto r = run("fr2_desk_groundtruth.txt", "fr2_desk_ORB.txt", AlignmentType::Se3);
  EXPECT_EQ(r.rpe_pairs.size(), r.pairs - 1);
  EXPECT_NEAR(r.rpe_trans_stats.rmse, 0.003582, kTolerance);
  EXPECT_NEAR(r.rpe_rot_stats.rmse, 0.2865, 1e-4);  // reference has 4 decimals
}

}  // namespace
}  // namespace stillslam
