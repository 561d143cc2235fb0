#pragma once
// Step 3 of loop detection (loop_detector.h) on a LoopSnapshot: reads only
// the snapshot and the keyframes' features (immutable after construction),
// so it runs without the map lock.
#include <optional>

#include "stillslam/loop/loop_detector.h"
#include "stillslam/loop/loop_snapshot.h"

namespace stillslam {

// Direct-index matches between the query's and the candidate's points, SE3 by
// 3D-3D RANSAC, guided search of the loop points with the corrected pose and
// a pose optimization that must keep min_inliers; confirmations stay 0.
std::optional<LoopDetection> verify_candidate(const LoopSnapshot& snapshot, const LoopCandidateCopy& candidate,
                                              const LoopDetectorOptions& options);

// How many of the snapshot's query neighbours (the loop keyframe excluded),
// moved by the detection's correction, match at least
// min_confirmation_matches of the candidate's loop points by projection.
int count_confirmations(const LoopSnapshot& snapshot, const LoopCandidateCopy& candidate,
                        const LoopDetection& detection, const LoopDetectorOptions& options);

}  // namespace stillslam
