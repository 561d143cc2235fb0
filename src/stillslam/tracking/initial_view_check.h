#pragma once
// With segmentation on, a map's first keyframe is checked against the next
// frame before it is created. A detector can miss a person in one frame
// (cut by the image border, filling the view) and find them in the next; a
// first keyframe built on that person would anchor the map on something that
// walks away. The check:
//  - neither frame may be more than max_masked_fraction masked (500 keypoints
//    can sit on a sliver of scene, as the extractor's budget all goes outside
//    the mask);
//  - the first frame's keypoints with depth are matched to the next frame by
//    descriptor, and a PnP RANSAC finds the camera motion between them; if
//    more than max_moving_share of the matches disagree with it, something
//    unmasked moves, and the first frame is rejected;
//  - otherwise keypoints whose match disagrees, or whose 3D point lands in
//    the next frame's dynamic mask, are left out of the first keyframe, and
//    the PnP motion is returned: the tracker starts the next frame from it,
//    which works however far apart the frames are (--realtime drops frames).
// Without masks (both frames unmasked) the same check guards the start
// against movers nothing marks: the first frame is rejected only when the
// camera motion does not hold most of the matches (max_moving_share_unmasked);
// the tracker then keeps only keypoints that some confirming frame matched
// as inliers (`confirmed`) and none found moving (`keep`), when enough of the
// matched keypoints (`matched`) were found moving
// (TrackerOptions::init_unmasked_moving_share), else all of them.
#include <Eigen/Geometry>

#include <string>
#include <vector>

#include "stillslam/map/frame.h"

namespace stillslam {

struct InitialViewCheckOptions {
  double max_masked_fraction = 0.5;
  double max_moving_share = 0.2;
  double max_moving_share_unmasked = 0.7;
  int min_matches = 50;  // fewer: the two frames do not overlap enough to judge
  double max_reprojection_error_px = 2.5;
  // Without masks a close person walking sideways fits, within 2.5 px, a
  // camera motion that also fits the far background (translation plus a
  // compensating turn); 1 px separates them a few frames apart.
  double max_reprojection_error_unmasked_px = 1.0;
  // Without masks a match finds its keypoint moving only beyond
  // max_reprojection_error_unmasked_px x this factor x the scale of the
  // coarser keypoint's pyramid level (confirming stays within the unscaled
  // bound). 2.45 = sqrt(5.991) would be ORB-SLAM3's 95 % chi-square test
  // with the bound as one sigma.
  double moving_factor_unmasked = 2.0;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

struct InitialViewCheck {
  bool accepted = false;
  std::string reason;      // why not, when rejected
  int matches = 0;         // first-frame keypoints with depth matched in the next frame
  int moving = 0;          // of those, disagreeing with the camera motion
  std::vector<bool> keep;  // per first-frame keypoint: may become a map point
  std::vector<bool> confirmed;  // per first-frame keypoint: matched in the next frame, agreeing with the motion
  std::vector<bool> matched;    // per first-frame keypoint: matched in the next frame (with depth)
  // Per first-frame keypoint: the next frame's keypoint of its match when
  // that match is an inlier of the PnP motion (confirmed), else -1.
  std::vector<int> next_keypoint;
  // When accepted: the next frame's pose relative to the first (PnP RANSAC).
  Eigen::Isometry3d T_next_first = Eigen::Isometry3d::Identity();
};

// Both frames from the same camera; `next` needs no pose.
InitialViewCheck check_initial_view(const Frame& first, const Frame& next, const InitialViewCheckOptions& options);

}  // namespace stillslam
