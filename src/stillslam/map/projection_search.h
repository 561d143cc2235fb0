#pragma once
// Guided matching by projection: map points are projected with a pose
// estimate and matched to the frame's keypoints near the projection, at the
// pyramid levels their distance predicts (ORB-SLAM's SearchByProjection).
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "stillslam/map/frame.h"
#include "stillslam/map/map_point.h"

namespace stillslam {

// Where a map point should appear in a frame.
struct ProjectedPoint {
  MapPointPtr point;
  Eigen::Vector2d pixel;
  double u_right = -1;  // virtual right coordinate (needs a baseline)
  int level = 0;        // predicted pyramid level
  double view_cos = 1;  // cosine between viewing ray and the point's normal
};

// The point's projection when it lies in the frame's frustum: in front, inside
// the image, within its scale-invariance distances and seen at less than
// acos(min_view_cos) from its mean viewing direction. Needs the frame pose.
std::optional<ProjectedPoint> project_in_frustum(const Frame& frame, const MapPointPtr& point,
                                                 double min_view_cos = 0.5);

// Motion-model tracking: matches the map points of `last` (posed) into
// `current` (posed with the prediction). radius_factor scales the window
// (pixels at level 0). Levels are restricted by the camera's motion along its
// axis; an orientation-consistency histogram removes outliers. Returns the
// number of new matches in `current`.
int search_by_projection(Frame& current, const Frame& last, float radius_factor,
                         bool check_orientation = true);

// Local-map tracking: matches projected points (from project_in_frustum) to
// unmatched keypoints of `current`, window th * (2.5 or 4 by view angle) *
// level scale, with a best/second-best ratio test on equal levels.
int search_by_projection(Frame& current, const std::vector<ProjectedPoint>& points, float th,
                         float ratio = 0.8f);

}  // namespace stillslam
