#pragma once
// Local bundle adjustment around a keyframe, in three phases so the map lock
// is not held while the solver runs: gather (under the lock) copies the window —
// the keyframe and its covisible keyframes, their points, and as fixed
// keyframes the others observing those points, each bounded by
// LocalWindowOptions — into plain structs; solve
// (no lock) runs bundle_adjust; apply (under the lock) writes poses and
// points back and removes the observations flagged as outliers.
#include <atomic>
#include <vector>

#include "stillslam/map/map.h"
#include "stillslam/mapping/local_window_options.h"
#include "stillslam/optimize/bundle_adjustment.h"

namespace stillslam {

struct LocalBundleAdjustmentProblem {
  std::vector<KeyFramePtr> keyframes;  // same order as ba_keyframes
  std::vector<MapPointPtr> points;     // same order as ba_points
  std::vector<std::size_t> observation_index;  // keypoint index per ba_observation
  std::vector<BaKeyframe> ba_keyframes;
  std::vector<BaPoint> ba_points;
  std::vector<BaObservation> ba_observations;
};

struct LocalBundleAdjustmentStats {
  int keyframes = 0, fixed_keyframes = 0, points = 0, observations = 0, outliers = 0;
  bool aborted = false;
};

// Caller holds the map's update mutex.
LocalBundleAdjustmentProblem gather_local_window(KeyFrame& kf, const LocalWindowOptions& options = {});
// No lock needed.
BundleAdjustmentResult solve_local_window(const PinholeCamera& camera, const LocalBundleAdjustmentProblem& problem,
                                          const BundleAdjustmentOptions& options);
// Caller holds the map's update mutex.
LocalBundleAdjustmentStats apply_local_window(const LocalBundleAdjustmentProblem& problem,
                                              const BundleAdjustmentResult& result);

}  // namespace stillslam
