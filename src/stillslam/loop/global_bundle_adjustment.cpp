#include "stillslam/loop/global_bundle_adjustment.h"

#include <unordered_map>

#include "stillslam/map/ba_observations.h"

namespace stillslam {

GlobalBundleAdjustmentProblem snapshot_global_problem(const Map& map) {
  GlobalBundleAdjustmentProblem p;
  BaKeyFrameIndex kf_index;
  for (const KeyFramePtr& kf : map.keyframes()) {
    if (kf->is_bad()) continue;
    kf_index.emplace(kf.get(), p.keyframes.size());
    p.keyframes.push_back(kf);
    p.ba_keyframes.push_back({kf->id(), kf->T_cam_world(), p.ba_keyframes.empty()});  // sorted by id: oldest fixed
  }
  if (p.keyframes.empty()) return p;
  p.setup = std::shared_ptr<const CameraSetup>(p.keyframes.front(), &p.keyframes.front()->setup());
  const ScalePyramid& pyramid = p.setup->pyramid;
  for (const MapPointPtr& mp : map.map_points()) {
    if (mp->is_bad() || mp->is_provisional()) continue;  // moved with its keyframe below
    if (append_ba_observations(*mp, p.points.size(), kf_index, pyramid, p.ba_observations) == 0) continue;
    p.points.push_back(mp);
    p.ba_points.push_back({mp->id(), mp->position()});
  }
  return p;
}

BundleAdjustmentResult solve_global_problem(const GlobalBundleAdjustmentProblem& problem,
                                            const BundleAdjustmentOptions& options) {
  if (problem.keyframes.empty()) return {};
  return bundle_adjust(problem.setup->camera, problem.ba_keyframes, problem.ba_points, problem.ba_observations,
                       options);
}

int apply_global_result(Map& map, const GlobalBundleAdjustmentProblem& problem, const BundleAdjustmentResult& result) {
  if (result.aborted || problem.keyframes.empty() || result.T_cam_world.size() != problem.keyframes.size()) return 0;
  // Correction of each keyframe as a world transform: T_world_cam_new = C * T_world_cam_old.
  std::unordered_map<const KeyFrame*, Eigen::Isometry3d> correction;
  for (std::size_t k = 0; k < problem.keyframes.size(); ++k) {
    const Eigen::Isometry3d C = result.T_cam_world[k].inverse() * problem.ba_keyframes[k].T_cam_world;
    correction.emplace(problem.keyframes[k].get(), C);
  }
  // Keyframes created since the snapshot (ids ascending, so parents come
  // first) take their parent's correction.
  int propagated = 0;
  for (const KeyFramePtr& kf : map.keyframes()) {
    if (correction.count(kf.get())) continue;
    Eigen::Isometry3d C = Eigen::Isometry3d::Identity();
    if (kf->parent()) {
      const auto it = correction.find(kf->parent());
      if (it != correction.end()) C = it->second;
    }
    correction.emplace(kf.get(), C);
    kf->set_pose((C * kf->T_world_cam()).inverse());
    ++propagated;
  }
  for (std::size_t k = 0; k < problem.keyframes.size(); ++k) {
    if (!problem.keyframes[k]->is_bad()) problem.keyframes[k]->set_pose(result.T_cam_world[k]);
  }
  std::unordered_map<const MapPoint*, std::size_t> in_problem;
  for (std::size_t i = 0; i < problem.points.size(); ++i) in_problem.emplace(problem.points[i].get(), i);
  std::unordered_map<std::uint64_t, const KeyFrame*> by_id;
  for (const auto& kf : map.all_keyframes()) by_id.emplace(kf->id(), kf.get());
  const ScalePyramid& pyramid = problem.setup->pyramid;
  for (const MapPointPtr& mp : map.map_points()) {
    if (mp->is_bad()) continue;
    const auto it = in_problem.find(mp.get());
    if (it != in_problem.end()) {
      mp->set_position(result.points[it->second]);
    } else {
      const auto ref = by_id.find(mp->first_keyframe_id());
      if (ref == by_id.end()) continue;
      const auto c = correction.find(ref->second);
      if (c != correction.end()) mp->set_position(c->second * mp->position());
    }
    mp->update_normal_and_depth(pyramid);
  }
  return propagated;
}

}  // namespace stillslam
