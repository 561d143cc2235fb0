#pragma once
// Global bundle adjustment after a loop closure, in three steps so that the
// solve can run without the map lock (in the loop closer's background
// thread) while tracking and local mapping go on:
//   snapshot (under the lock) -> solve (no lock, abortable) -> apply (lock).
// apply() moves keyframes and points created after the snapshot with their
// spanning-tree parent's / reference keyframe's correction (ORB-SLAM's
// propagation after RunGlobalBundleAdjustment).
#include <memory>
#include <vector>

#include "stillslam/map/map.h"
#include "stillslam/optimize/bundle_adjustment.h"

namespace stillslam {

struct GlobalBundleAdjustmentProblem {
  std::vector<KeyFramePtr> keyframes;
  std::vector<MapPointPtr> points;
  std::vector<BaKeyframe> ba_keyframes;
  std::vector<BaPoint> ba_points;
  std::vector<BaObservation> ba_observations;
  std::shared_ptr<const CameraSetup> setup;
};

// All active keyframes (the oldest fixed) and points. Caller holds the lock.
GlobalBundleAdjustmentProblem snapshot_global_problem(const Map& map);

BundleAdjustmentResult solve_global_problem(const GlobalBundleAdjustmentProblem& problem,
                                            const BundleAdjustmentOptions& options);

// Writes the result back (no-op when aborted). Caller holds the lock.
// Returns the number of keyframes moved by propagation (not in the snapshot).
int apply_global_result(Map& map, const GlobalBundleAdjustmentProblem& problem, const BundleAdjustmentResult& result);

}  // namespace stillslam
