#pragma once
// Whether an object moved, from depth alone (issue #19): an object with
// little texture (a pushed chair) has too few matched features for the
// residual check (instance_motion_check.h), but its pixels have depth. Each
// sampled pixel of the object is put into an earlier view by the tracked
// camera motion; where that view's depth image saw farther than the point
// (by more than the gap), the earlier view saw through the place the object
// now fills: it was not there then. A still object is seen through only at
// its edges (pixel rounding, depth noise); a moved one over the part that
// does not overlap its old place. Pixels the earlier view saw nearer (an
// occluder, or the object's own earlier place in front) say nothing unless
// `count_nearer` is set: then they count too, except where the earlier view
// had a pixel of `earlier_occluders` (the people masked then), so an object
// pushed away from the camera, whose old place hides its new one, is found.
// Images are used as they are: the camera must have no lens distortion.
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include <cstdint>
#include <map>
#include <set>

#include "stillslam/geometry/pinhole_camera.h"

namespace stillslam {

struct FreeSpaceOptions {
  int step_px = 4;                  // sampling grid over the image
  double min_gap_m = 0.05;          // seen farther by more than max(min_gap_m, ...
  double gap_share_of_depth = 0.03; // ... this share of the point's depth)
  bool count_nearer = false;        // also count where the earlier view saw nearer by the gap
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

struct FreeSpaceCount {
  int samples = 0;       // sampled pixels with depth that land in the earlier view with depth there
  int seen_through = 0;  // of those, where the earlier view saw farther
  int seen_nearer = 0;   // of those, where it saw nearer (counted with FreeSpaceOptions::count_nearer only)
  double share() const {
    return samples > 0 ? static_cast<double>(seen_through + seen_nearer) / samples : 0.0;
  }
};

// Per label in `ids` (0: the pixels of no instance), the sampled pixels of
// that label in `labels` (the current view, with `depth` in metres, CV_32F,
// <= 0 or NaN where unknown) against `earlier_depth`, the depth image of the
// view at T_earlier_current from the current camera. `earlier_occluders`
// (CV_8U, non-zero where the earlier view had a masked person; may be empty):
// samples landing there are left out.
std::map<std::uint32_t, FreeSpaceCount> count_seen_through(const PinholeCamera& camera, const cv::Mat& depth,
                                                           const cv::Mat1i& labels,
                                                           const std::set<std::uint32_t>& ids,
                                                           const Eigen::Isometry3d& T_earlier_current,
                                                           const cv::Mat& earlier_depth,
                                                           const FreeSpaceOptions& options = {},
                                                           const cv::Mat1b& earlier_occluders = {});

}  // namespace stillslam
