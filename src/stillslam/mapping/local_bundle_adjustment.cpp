#include "stillslam/mapping/local_bundle_adjustment.h"

#include <algorithm>
#include <unordered_map>
#include <utility>

#include "stillslam/map/ba_observations.h"

namespace stillslam {

LocalBundleAdjustmentProblem gather_local_window(KeyFrame& kf, const LocalWindowOptions& options) {
  auto within = [](std::size_t n, int limit) { return limit <= 0 || n < static_cast<std::size_t>(limit); };
  LocalBundleAdjustmentProblem problem;
  BaKeyFrameIndex kf_index;
  auto add_keyframe = [&](KeyFrame* k, bool fixed) {
    if (!kf_index.emplace(k, problem.keyframes.size()).second) return;
    problem.keyframes.push_back(k->shared_from_this());
    BaKeyframe b;
    b.id = k->id();
    b.T_cam_world = k->T_cam_world();
    b.fixed = fixed || k->is_origin();  // the map's first keyframe anchors the gauge
    if (k->centre_prior()) {
      b.prior_centre = k->centre_prior()->mean;
      b.prior_sqrt_info = k->centre_prior()->sqrt_info;
    }
    problem.ba_keyframes.push_back(b);
  };
  add_keyframe(&kf, false);
  for (KeyFrame* n : kf.covisibles()) {  // by decreasing weight
    if (!within(problem.keyframes.size(), options.max_keyframes)) break;
    if (!n->is_bad()) add_keyframe(n, false);
  }
  const std::size_t num_local = problem.keyframes.size();

  // Points keyframe by keyframe (the new one's first); a point's observations
  // by keyframes outside the window count too, so the budget is an upper bound.
  std::unordered_map<const MapPoint*, std::size_t> point_index;
  std::size_t observation_budget_used = 0;
  bool full = false;
  for (std::size_t k = 0; k < num_local && !full; ++k) {
    for (const MapPointPtr& mp : problem.keyframes[k]->map_points()) {
      if (!mp || mp->is_bad() || mp->is_provisional() || point_index.count(mp.get())) continue;
      if (options.leave_out_kept_points && mp->on_dynamic_instance()) continue;
      const std::size_t n_obs = mp->observations().size();
      if (!within(problem.points.size(), options.max_points) ||
          (options.max_observations > 0 &&
           observation_budget_used + n_obs > static_cast<std::size_t>(options.max_observations))) {
        full = true;
        break;
      }
      observation_budget_used += n_obs;
      point_index.emplace(mp.get(), problem.points.size());
      problem.points.push_back(mp);
      problem.ba_points.push_back({mp->id(), mp->position()});
    }
  }
  // Fixed keyframes: observe window points but are not in the window; those
  // with the most such observations first.
  std::unordered_map<KeyFrame*, int> outside;
  for (const MapPointPtr& mp : problem.points) {
    for (const auto& [k, idx] : mp->observations()) {
      if (!k->is_bad() && !kf_index.count(k)) ++outside[k];
    }
  }
  std::vector<std::pair<int, KeyFrame*>> fixed_candidates;
  for (const auto& [k, n] : outside) fixed_candidates.emplace_back(n, k);
  std::sort(fixed_candidates.begin(), fixed_candidates.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second->id() < b.second->id();
  });
  for (const auto& [n, k] : fixed_candidates) {
    if (!within(problem.keyframes.size() - num_local, options.max_fixed_keyframes)) break;
    add_keyframe(k, true);
  }
  if (num_local == 1 || std::all_of(problem.ba_keyframes.begin(), problem.ba_keyframes.end(),
                                    [](const BaKeyframe& b) { return !b.fixed; })) {
    // Nothing fixed: fix the oldest keyframe of the window to remove the gauge freedom.
    std::size_t oldest = 0;
    for (std::size_t k = 1; k < problem.keyframes.size(); ++k) {
      if (problem.keyframes[k]->id() < problem.keyframes[oldest]->id()) oldest = k;
    }
    problem.ba_keyframes[oldest].fixed = true;
  }

  const ScalePyramid& pyramid = kf.setup().pyramid;
  for (std::size_t p = 0; p < problem.points.size(); ++p) {
    append_ba_observations(*problem.points[p], p, kf_index, pyramid, problem.ba_observations,
                           &problem.observation_index);
  }
  return problem;
}

BundleAdjustmentResult solve_local_window(const PinholeCamera& camera, const LocalBundleAdjustmentProblem& problem,
                                          const BundleAdjustmentOptions& options) {
  return bundle_adjust(camera, problem.ba_keyframes, problem.ba_points, problem.ba_observations, options);
}

LocalBundleAdjustmentStats apply_local_window(const LocalBundleAdjustmentProblem& problem,
                                              const BundleAdjustmentResult& result) {
  LocalBundleAdjustmentStats stats;
  stats.aborted = result.aborted;
  stats.points = static_cast<int>(problem.points.size());
  stats.observations = static_cast<int>(problem.ba_observations.size());
  for (std::size_t o = 0; o < problem.ba_observations.size(); ++o) {
    if (o < result.observation_inlier.size() && result.observation_inlier[o]) continue;
    const BaObservation& obs = problem.ba_observations[o];
    KeyFrame& k = *problem.keyframes[obs.keyframe];
    const MapPointPtr& mp = problem.points[obs.point];
    if (k.map_point(problem.observation_index[o]) == mp) {
      k.erase_map_point(problem.observation_index[o]);
      mp->erase_observation(&k);
      ++stats.outliers;
    }
  }
  for (std::size_t k = 0; k < problem.keyframes.size(); ++k) {
    if (problem.ba_keyframes[k].fixed) {
      ++stats.fixed_keyframes;
      continue;
    }
    ++stats.keyframes;
    if (!problem.keyframes[k]->is_bad()) problem.keyframes[k]->set_pose(result.T_cam_world[k]);
  }
  for (std::size_t p = 0; p < problem.points.size(); ++p) {
    const MapPointPtr& mp = problem.points[p];
    if (mp->is_bad()) continue;
    mp->set_position(result.points[p]);
    mp->update_normal_and_depth(problem.keyframes.front()->setup().pyramid);
  }
  return stats;
}

}  // namespace stillslam
