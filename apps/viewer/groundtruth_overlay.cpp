#include "viewer/groundtruth_overlay.h"

#include <algorithm>

#include "stillslam/eval/association.h"
#include "stillslam/geometry/pnp.h"

namespace stillslam::viewer {

GroundTruthOverlay::GroundTruthOverlay(const Trajectory& groundtruth) {
  for (const StampedPose& p : groundtruth) {
    gt_stamps_.push_back(p.timestamp);
    gt_centres_.push_back(p.T_world_cam.translation());
  }
}

void GroundTruthOverlay::add(double timestamp, const Eigen::Vector3d& centre, std::uint64_t map_id) {
  Samples& s = estimates_[map_id];
  if (!s.stamps.empty() && timestamp <= s.stamps.back()) return;  // association wants increasing stamps
  s.stamps.push_back(timestamp);
  s.centres.push_back(centre);
}

std::vector<Eigen::Vector3d> GroundTruthOverlay::aligned(std::uint64_t map_id, std::size_t max_points) const {
  const auto it = estimates_.find(map_id);
  if (it == estimates_.end() || max_points == 0) return {};
  const std::vector<IndexPair> pairs = associate(gt_stamps_, it->second.stamps, AssociationOptions{});
  if (pairs.size() < 3) return {};
  std::vector<Eigen::Vector3d> gt, est;
  for (const IndexPair& p : pairs) {
    gt.push_back(gt_centres_[p.gt]);
    est.push_back(it->second.centres[p.est]);
  }
  const Sim3 S_map_gt = align_umeyama(gt, est);
  const std::size_t step = std::max<std::size_t>(1, (gt_centres_.size() + max_points - 1) / max_points);
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i < gt_centres_.size(); i += step) out.push_back(S_map_gt * gt_centres_[i]);
  return out;
}

}  // namespace stillslam::viewer
