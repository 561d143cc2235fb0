// geometry entry points reject inconsistent input with a PreconditionError.
#include <gtest/gtest.h>

#include "common/precondition.h"
#include "geometry/synthetic_scene.h"
#include "stillslam/geometry/pnp.h"

namespace stillslam {
namespace {

TEST(GeometryPreconditions, PnpNeedsOnePixelPerPoint) {
  const PinholeCamera cam(testing::tum_like_calibration());
  test::expect_precondition([&] { solve_pnp_ransac(cam, {{0, 0, 1}, {1, 0, 1}}, {{3, 4}}); },
                            "src/stillslam/geometry/pnp.cpp",
                            "solve_pnp_ransac: pass one pixel per point (check failed: points_world.size() == "
                            "pixels_undistorted.size(), 2 vs 1)");
}

TEST(GeometryPreconditions, AlignmentNeedsMatchedPairs) {
  const std::vector<Eigen::Vector3d> three = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  test::expect_precondition([&] { align_ransac(three, {{0, 0, 0}}); }, "src/stillslam/geometry/pnp.cpp",
                            "align_ransac: pass matched pairs (check failed: src.size() == dst.size(), 3 vs 1)");
  test::expect_precondition([&] { align_umeyama({{0, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {1, 0, 0}}); },
                            "src/stillslam/geometry/pnp.cpp",
                            "align_umeyama: needs at least 3 point pairs (check failed: src.size() >= 3u, 2 vs 3)");
}

}  // namespace
}  // namespace stillslam
