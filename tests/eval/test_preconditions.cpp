// eval entry points reject inconsistent input with a PreconditionError.
#include <gtest/gtest.h>

#include "common/precondition.h"
#include "stillslam/eval/alignment.h"
#include "stillslam/eval/metrics.h"

namespace stillslam {
namespace {

Trajectory still_trajectory(std::size_t n) {
  Trajectory t;
  for (std::size_t i = 0; i < n; ++i) t.push_back({static_cast<double>(i), Eigen::Isometry3d::Identity()});
  return t;
}

TEST(EvalPreconditions, MetricsNeedAssociatedTrajectories) {
  test::expect_precondition([] { absolute_translation_errors(still_trajectory(3), still_trajectory(2)); },
                            "src/stillslam/eval/metrics.cpp",
                            "absolute_translation_errors: pass associated trajectories (check failed: gt.size() == "
                            "est.size(), 3 vs 2)");
}

TEST(EvalPreconditions, PosePairsIndexInsideTheTrajectories) {
  test::expect_precondition([] { relative_errors(still_trajectory(3), still_trajectory(3), {{0, 1}, {1, 7}}); },
                            "src/stillslam/eval/metrics.cpp",
                            "relative_errors: a pose pair indexes past the trajectories (check failed: j < gt.size(), "
                            "7 vs 3)");
}

TEST(EvalPreconditions, AlignmentNeedsOneGroundTruthPositionPerEstimate) {
  test::expect_precondition([] { align_positions(Eigen::Matrix3Xd::Zero(3, 4), Eigen::Matrix3Xd::Zero(3, 5),
                                                 AlignmentType::Se3); },
                            "src/stillslam/eval/alignment.cpp",
                            "align_positions: pass one ground-truth position per estimated one (check failed: "
                            "est.cols() == gt.cols(), 4 vs 5)");
}

}  // namespace
}  // namespace stillslam
