#include "stillslam/tracking/static_evidence.h"

#include <algorithm>
#include <limits>

#include "stillslam/core/option_check.h"
#include "stillslam/map/keyframe.h"
#include "stillslam/optimize/reprojection_costs.h"
#include "stillslam/tracking/pose_refinement.h"
#include "stillslam/tracking/start_evidence.h"

namespace stillslam {

std::uint64_t observation_span_frames(const MapPoint& point) {
  std::uint64_t first = std::numeric_limits<std::uint64_t>::max(), last = 0;
  for (const auto& [kf, index] : point.observations()) {
    first = std::min(first, kf->frame_id());
    last = std::max(last, kf->frame_id());
  }
  // A held keyframe's match (MapPoint::held_observation_frame) counts as an observation.
  if (!point.observations().empty() && point.held_observation_frame() > 0) {
    last = std::max(last, point.held_observation_frame());
  }
  return last > first ? last - first : 0;
}

bool has_static_evidence(const MapPoint& point, const StaticEvidenceOptions& options) {
  const std::size_t observed = point.observations().size() + (point.held_observation_frame() > 0 ? 1 : 0);
  return !point.is_bad() && observed >= 2 &&
         observation_span_frames(point) >= static_cast<std::uint64_t>(options.min_span_frames);
}

bool recently_rejected(const MapPoint& point, const StaticEvidenceOptions& options, std::uint64_t frame_id) {
  const auto last = point.last_outlier_frame();
  return options.quiet_frames > 0 && last && *last < frame_id &&
         frame_id - *last <= static_cast<std::uint64_t>(options.quiet_frames);
}

int refine_pose_on_evidence(Frame& frame, const PoseOptimizerOptions& pose, const StaticEvidenceOptions& options,
                            const PosePrior* prior, const StartEvidence* start) {
  if (!options.enabled && !options.leave_out_kept_points && options.kept_point_sigma == 1) {
    return refine_pose(frame, pose, prior);
  }
  const double kept_weight = 1 / (options.kept_point_sigma * options.kept_point_sigma);
  const CameraSetup& setup = frame.setup();
  std::vector<PoseObservation> trusted, others;
  std::vector<std::size_t> trusted_index, other_index;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const MapPointPtr& mp = frame.map_point(i);
    if (!mp) continue;
    PoseObservation obs = pose_observation(frame, i);
    if (mp->on_dynamic_instance()) obs.inv_sigma2 *= kept_weight;
    const bool evidence = !options.enabled ||
                          ((has_static_evidence(*mp, options) || (start && start->holds(*mp, frame.id()))) &&
                           !recently_rejected(*mp, options, frame.id()));
    if (evidence && !(options.leave_out_kept_points && mp->on_dynamic_instance())) {
      trusted.push_back(obs);
      trusted_index.push_back(i);
    } else {
      others.push_back(obs);
      other_index.push_back(i);
    }
  }
  if (static_cast<int>(trusted.size()) < options.min_points) return refine_pose(frame, pose, prior);
  const PoseOptimizationResult result = optimize_pose(setup.camera, frame.T_cam_world(), trusted, pose, prior);
  // The old points disagree among themselves (the map moved, or they are
  // mismatched): no consensus to lean on.
  if (result.num_inliers < options.min_points) return refine_pose(frame, pose, prior);
  frame.set_pose(result.T_cam_world);
  for (std::size_t k = 0; k < trusted_index.size(); ++k) frame.set_outlier(trusted_index[k], !result.inlier[k]);
  const Intrinsics intrinsics(setup.camera);
  int inliers = result.num_inliers;
  for (std::size_t k = 0; k < others.size(); ++k) {
    const PoseObservation& o = others[k];
    const bool stereo = o.u_right >= 0 && intrinsics.bf > 0;
    const ReprojectionCheck c = check_reprojection(intrinsics, result.T_cam_world, o.point_world, o.pixel,
                                                   stereo ? o.u_right : -1.0, o.inv_sigma2);
    const bool inlier = c.in_front() && c.chi2 <= (stereo ? pose.chi2_stereo : pose.chi2_mono);
    frame.set_outlier(other_index[k], !inlier);
    inliers += inlier;
  }
  return inliers;
}

void StaticEvidenceOptions::check() const {
  using namespace option_check;
  at_least("StaticEvidenceOptions.min_span_frames", min_span_frames, 0);
  at_least("StaticEvidenceOptions.min_points", min_points, 3);
  at_least("StaticEvidenceOptions.quiet_frames", quiet_frames, 0);
  in_range("StaticEvidenceOptions.kept_point_sigma", kept_point_sigma, 1, 100);
}

}  // namespace stillslam
