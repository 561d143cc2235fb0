#include "stillslam/loop/loop_snapshot.h"

#include <algorithm>

namespace stillslam {

LoopSnapshotBuilder::LoopSnapshotBuilder(const KeyFrame& query, std::shared_ptr<const BowDescription> query_words,
                                         std::size_t confirmation_neighbours)
    : confirmation_neighbours_(confirmation_neighbours) {
  snapshot_.query = copy_keyframe(query, true);
  snapshot_.query_words = std::move(query_words);
}

std::int32_t LoopSnapshotBuilder::point(const MapPointPtr& mp) {
  const auto [it, added] = index_.emplace(mp.get(), static_cast<std::int32_t>(snapshot_.points.size()));
  if (!added) return it->second;
  PointCopy& p = snapshot_.points.emplace_back();
  p.point = mp;
  p.position = mp->position();
  p.normal = mp->normal();
  std::copy(mp->descriptor(), mp->descriptor() + p.descriptor.size(), p.descriptor.begin());
  p.min_distance = mp->min_distance();
  p.max_distance = mp->max_distance();
  p.level_reference_distance = mp->level_reference_distance();
  last_seen_by_.push_back(0);
  return it->second;
}

KeyFrameCopy LoopSnapshotBuilder::copy_keyframe(const KeyFrame& kf, bool with_points) {
  KeyFrameCopy c;
  c.keyframe = std::const_pointer_cast<KeyFrame>(kf.shared_from_this());
  c.T_cam_world = kf.T_cam_world();
  if (with_points) {
    c.point_index.assign(kf.size(), -1);
    for (std::size_t i = 0; i < kf.size(); ++i) {
      const MapPointPtr& mp = kf.map_point(i);
      if (mp && !mp->is_bad()) c.point_index[i] = point(mp);
    }
  }
  return c;
}

void LoopSnapshotBuilder::add_candidate(const KeyFramePtr& candidate, std::shared_ptr<const BowDescription> words,
                                        bool needs_confirmation, int needed_confirmations) {
  if (!candidate || candidate->is_bad()) return;
  if (needs_confirmation && !neighbours_copied_) {
    neighbours_copied_ = true;
    for (KeyFrame* k : snapshot_.query.keyframe->best_covisibles(confirmation_neighbours_)) {
      if (!k->is_bad()) snapshot_.neighbours.push_back(copy_keyframe(*k, false));
    }
  }
  LoopCandidateCopy c;
  c.keyframe = copy_keyframe(*candidate, true);
  c.words = std::move(words);
  c.needs_confirmation = needs_confirmation;
  c.needed_confirmations = needed_confirmations;
  // Loop points: the candidate's, then its covisible keyframes' (each once).
  const std::size_t stamp = snapshot_.candidates.size() + 1;
  auto collect = [&](const KeyFrame& kf) {
    for (const MapPointPtr& mp : kf.map_points()) {
      if (!mp || mp->is_bad()) continue;
      const std::int32_t p = point(mp);
      if (last_seen_by_[static_cast<std::size_t>(p)] == stamp) continue;
      last_seen_by_[static_cast<std::size_t>(p)] = stamp;
      c.loop_points.push_back(p);
    }
  };
  collect(*candidate);
  for (KeyFrame* n : candidate->covisibles()) {
    if (!n->is_bad()) collect(*n);
  }
  snapshot_.candidates.push_back(std::move(c));
}

}  // namespace stillslam
