#pragma once
// The crowd fallback (issue #19): when the dynamic masks hide most of the
// view, the few static matches left give a noisy pose, or none. Then the
// tracked pose is pulled toward the constant-velocity prediction, and when
// tracking fails the prediction itself is kept, so the camera keeps a pose
// through the crowd. No map starts from a view the masks hide.
#include <Eigen/Geometry>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "stillslam/map/frame.h"
#include "stillslam/optimize/pose_optimizer.h"

namespace stillslam {

struct SparseViewOptions {
  bool enabled = false;          // Motion.sparseView
  double masked_share = 0.5;     // a view is sparse when its mask covers at least this share
  // ...and tracking found fewer map-point inliers than this: blended. The
  // default blends every sparse view (on the crowd render that beat 50:
  // bench/README.md, issue #19 session 8).
  int inliers = 100000;
  double tracked_weight = 0.2;   // the tracked pose's share of the blend (1: tracked pose only)
  // Off: a sparse view makes no keyframe (its few points lie on a strip of
  // the view, and its pose is the least certain of the path).
  bool keyframes = true;
  // On: a sparse view's pose stages use the motion model's prediction as a
  // prior (TrackerOptions::motion_prior's sigmas) in every stage, without
  // its gate and refit check.
  bool prior = false;
  // > 0: in the trajectory read at the end (System::trajectory), each frame
  // the fallback flagged (tracked, blended or predicted in a sparse view)
  // gets as camera centre the mean of the centres of the frames within this
  // many frames of it (its own map's, as read); its rotation is kept. The
  // tracked poses themselves are not changed. 0: off.
  int smooth_frames = 0;
  // > 0: in a run of sparse views each camera centre is an alpha-beta filter
  // of the tracked centres with this gain (alpha; beta = alpha^2 / (2 - alpha),
  // critically damped), started at the run's first view from the motion per
  // frame averaged over the `filter_frames` frames before it. Online: the
  // tracked pose is re-estimated from its inliers with its centre held at the
  // filtered one (the rotation follows the points); in the trajectory read at
  // the end the same filter runs over the refined centres. Far points alone
  // fix a centre only weakly (a crowd hides the near scene): each sparse
  // view's centre jitters by millimetres. 0: off.
  double filter_gain = 0;
  int filter_frames = 5;
  // How many directions of the camera centre the filter acts on: the
  // `filter_axes` least certain ones of the tracked pose (eigenvectors of the
  // centre's covariance from its inliers, rotation marginalised out); along
  // the others the tracked centre is kept. 3: every direction.
  int filter_axes = 3;
  // > 0: a keyframe made in a tracked sparse view keeps a prior in local BA
  // on its camera centre at creation (after the filter, when on), with this
  // sigma (m) along the `filter_axes` least certain directions of its pose
  // and none along the others (KeyFrame::centre_prior): bundle adjustment
  // cannot slide a crowd stretch of keyframes, anchored only by far points,
  // along the direction those points leave free. 0: off.
  double keyframe_prior_sigma = 0;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// What the fallback did to a frame (stats.json `motion.sparse_view`).
enum class SparseView {
  None = 0,       // not sparse, or the fallback is off
  Tracked = 1,    // sparse, but tracking found enough inliers: its pose as tracked
  Blended = 2,    // sparse with few inliers: the pose pulled toward the prediction
  Predicted = 3,  // sparse and tracking failed: the constant-velocity prediction
  NoStart = 4,    // sparse before the map started: no map starts from it
};

// Share of the frame's pixels under its dynamic mask (0 without a mask).
double masked_share(const Frame& frame);

bool is_sparse_view(const Frame& frame, const SparseViewOptions& options);

// SparseViewOptions::smooth_frames on a trajectory: `centres` (one per
// frame, in order) of the frames flagged in `sparse` become the mean of the
// centres within `half_window` frames that share their `group` (map id),
// each computed from the centres as given.
void smooth_sparse_centres(std::vector<Eigen::Vector3d>& centres, const std::vector<bool>& sparse,
                           const std::vector<std::uint64_t>& group, int half_window);

// SparseViewOptions::filter_gain over one run of sparse views.
class CentreFilter {
 public:
  explicit CentreFilter(double gain = 0);
  bool running() const { return velocity_.has_value(); }
  // The filtered centre of a sparse view `steps` frames after the last one,
  // from its tracked centre; `last` is the last frame's (filtered) centre;
  // `start_velocity` the motion per frame the run starts from (used when the
  // filter is not running yet).
  Eigen::Vector3d step(const Eigen::Vector3d& last, const Eigen::Vector3d& start_velocity,
                       const Eigen::Vector3d& tracked, int steps);
  // A view that is not sparse ends the run.
  void stop() { velocity_.reset(); }

 private:
  double alpha_ = 0, beta_ = 0;
  std::optional<Eigen::Vector3d> velocity_;
};

// SparseViewOptions::filter_gain on a trajectory: the centres (one per
// frame, in order) of the frames flagged in `sparse` become the filter's,
// each run started from the mean motion over the `velocity_frames` centres
// before it that share its `group` (map id). A flagged frame with no earlier
// centre of its group keeps its centre.
// With `projections` (one per frame, or empty for identity) a flagged
// centre moves to the filter's only along its projection:
// c + P (filtered - c).
void filter_sparse_centres(std::vector<Eigen::Vector3d>& centres, const std::vector<bool>& sparse,
                           const std::vector<std::uint64_t>& group, double gain, int velocity_frames,
                           const std::vector<Eigen::Matrix3d>& projections = {});

// Covariance (m^2, world axes) of the camera centre of the pose
// `T_cam_world` estimated from `observations` (each pixel residual with its
// inv_sigma2, the right-image coordinate too when it has one), with the
// rotation marginalised out: the inverse of the centre block's Schur
// complement of the 6x6 information matrix. Fewer than 3 usable
// observations: a zero matrix.
Eigen::Matrix3d centre_covariance(const PinholeCamera& camera, const Eigen::Isometry3d& T_cam_world,
                                  const std::vector<PoseObservation>& observations);

// Projection (world axes) onto the `axes` least certain directions of a
// centre covariance (its eigenvectors of the largest eigenvalues); identity
// for 3 axes or a zero covariance.
Eigen::Matrix3d weak_axes_projection(const Eigen::Matrix3d& covariance, int axes);

// `tracked_weight` of the way from `predicted` to `tracked` (rotation by
// slerp, camera centre linearly); both are T_cam_world.
Eigen::Isometry3d blend_poses(const Eigen::Isometry3d& predicted, const Eigen::Isometry3d& tracked,
                              double tracked_weight);

}  // namespace stillslam
