#include "stillslam/loop/loop_detector.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

#include "stillslam/core/option_check.h"
#include "stillslam/loop/loop_verification.h"

namespace stillslam {

LoopDetector::LoopDetector(const PlaceRecognizer& recognizer, LoopDetectorOptions options)
    : recognizer_(recognizer), options_(options) {
  options_.check();
}

void LoopDetector::loop_closed(std::uint64_t query_id) {
  last_loop_id_ = query_id;
  groups_.clear();
  candidate_counts_.clear();
}

std::shared_ptr<const BowDescription> LoopDetector::words_of(const KeyFrame& query) const {
  auto words = recognizer_.description(query.id());
  if (!words) {
    words = std::make_shared<const BowDescription>(recognizer_.describe(PlaceRecognizer::descriptors_of(query)));
  }
  return words;
}

std::vector<KeyFramePtr> LoopDetector::candidates(const Map& map, const KeyFrame& query) const {
  return candidates(map, query, words_of(query)->bow);
}

std::vector<KeyFramePtr> LoopDetector::candidates(const Map& map, const KeyFrame& query, const BowVector& bow) const {
  std::vector<KeyframeId> covisible;
  for (KeyFrame* k : query.covisibles()) covisible.push_back(k->id());
  const std::vector<PlaceCandidate> found = recognizer_.loop_candidates(query.id(), bow, covisible, 0);
  std::unordered_map<KeyframeId, double> score;
  for (const auto& c : found) score.emplace(c.id, c.score);

  // Accumulate over each candidate's covisible group; the group's best-scoring
  // member represents it.
  struct Group {
    double accumulated = 0;
    KeyFramePtr best;
    double best_score = -1;
  };
  std::vector<Group> groups;
  double best_accumulated = 0;
  for (const auto& c : found) {
    KeyFramePtr kf = map.keyframe(c.id);
    if (!kf || kf->is_bad()) continue;
    Group g;
    g.accumulated = c.score;
    g.best = kf;
    g.best_score = c.score;
    for (KeyFrame* n : kf->best_covisibles(options_.group_size)) {
      const auto it = score.find(n->id());
      if (it == score.end() || n->is_bad()) continue;
      g.accumulated += it->second;
      if (it->second > g.best_score) {
        g.best_score = it->second;
        g.best = n->shared_from_this();
      }
    }
    best_accumulated = std::max(best_accumulated, g.accumulated);
    groups.push_back(std::move(g));
  }
  std::vector<KeyFramePtr> out;
  std::unordered_set<const KeyFrame*> seen;
  for (const Group& g : groups) {
    if (g.accumulated < options_.group_score_ratio * best_accumulated) continue;
    if (seen.insert(g.best.get()).second) out.push_back(g.best);
  }
  return out;
}

std::vector<KeyFramePtr> LoopDetector::consistent_candidates(const std::vector<KeyFramePtr>& candidates) {
  std::vector<ConsistentGroup> current;
  std::vector<KeyFramePtr> enough;
  std::vector<bool> previous_extended(groups_.size(), false);
  candidate_counts_.clear();
  for (const KeyFramePtr& candidate : candidates) {
    int& best_count = candidate_counts_[candidate->id()];
    best_count = 1;
    ConsistentGroup group;
    group.keyframes.insert(candidate->id());
    for (KeyFrame* n : candidate->covisibles()) group.keyframes.insert(n->id());
    bool consistent_for_some = false;
    bool accepted = false;
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      const bool overlaps = std::any_of(group.keyframes.begin(), group.keyframes.end(),
                                        [&](std::uint64_t id) { return groups_[g].keyframes.count(id) > 0; });
      if (!overlaps) continue;
      consistent_for_some = true;
      const int count = groups_[g].count + 1;
      best_count = std::max(best_count, count);
      if (!previous_extended[g]) {
        current.push_back({group.keyframes, count});
        previous_extended[g] = true;
      }
      if (count >= options_.consistency_threshold && !accepted) {
        enough.push_back(candidate);
        accepted = true;
      }
    }
    if (!consistent_for_some) {
      current.push_back({group.keyframes, 1});
      if (options_.consistency_threshold <= 1) enough.push_back(candidate);
    }
  }
  groups_ = std::move(current);
  return enough;
}

std::optional<LoopDetection> LoopDetector::detect(const Map& map, const KeyFrame& query) {
  const std::optional<LoopSnapshot> snapshot = prepare(map, query);
  if (!snapshot) return std::nullopt;
  std::optional<LoopDetection> detection = verify(*snapshot);
  if (!detection) return std::nullopt;
  return recheck(map, std::move(*detection));
}

std::optional<LoopSnapshot> LoopDetector::prepare(const Map& map, const KeyFrame& query) {
  const auto enough_keyframes = static_cast<std::size_t>(std::max(options_.min_keyframes_between_loops, 0));
  if (map.num_keyframes() <= enough_keyframes ||
      (last_loop_id_ && query.id() < *last_loop_id_ + enough_keyframes)) {
    return std::nullopt;
  }
  std::shared_ptr<const BowDescription> words = words_of(query);
  const std::vector<KeyFramePtr> found = candidates(map, query, words->bow);
  if (found.empty()) {
    spdlog::debug("loop detection, keyframe {}: no BoW candidate", query.id());
    groups_.clear();
    return std::nullopt;
  }
  const std::vector<KeyFramePtr> consistent = consistent_candidates(found);
  spdlog::debug("loop detection, keyframe {}: {} BoW candidates (best {}), {} consistent", query.id(), found.size(),
                found.front()->id(), consistent.size());
  LoopSnapshotBuilder builder(query, std::move(words), options_.confirmation_neighbours);
  for (const KeyFramePtr& c : consistent) builder.add_candidate(c, recognizer_.description(c->id()));
  if (options_.confirmation_neighbours > 0) {
    for (const KeyFramePtr& c : found) {
      if (std::find(consistent.begin(), consistent.end(), c) != consistent.end()) continue;
      const auto count = candidate_counts_.find(c->id());
      const int needed = options_.consistency_threshold - (count != candidate_counts_.end() ? count->second : 1);
      builder.add_candidate(c, recognizer_.description(c->id()), true, needed);
    }
  }
  if (builder.empty()) return std::nullopt;
  return builder.take();
}

std::optional<LoopDetection> LoopDetector::verify(const LoopSnapshot& snapshot) const {
  for (const LoopCandidateCopy& candidate : snapshot.candidates) {
    std::optional<LoopDetection> d = verify_candidate(snapshot, candidate, options_);
    if (!d) continue;
    if (!candidate.needs_confirmation) return d;
    d->confirmations = count_confirmations(snapshot, candidate, *d, options_);
    spdlog::debug("loop candidate {} for {}: confirmed by {} covisible keyframes (need {})", d->loop->id(),
                  d->query->id(), d->confirmations, candidate.needed_confirmations);
    if (d->confirmations >= candidate.needed_confirmations) return d;
  }
  return std::nullopt;
}

std::optional<LoopDetection> LoopDetector::verify(const KeyFrame& query,
                                                  const std::vector<KeyFramePtr>& candidates) const {
  LoopSnapshotBuilder builder(query, words_of(query), 0);
  for (const KeyFramePtr& c : candidates) {
    if (c) builder.add_candidate(c, recognizer_.description(c->id()));
  }
  return verify(builder.take());
}

std::optional<LoopDetection> LoopDetector::recheck(const Map& map, LoopDetection detection) const {
  if (!detection.query || !detection.loop || detection.query->is_bad() || detection.loop->is_bad() ||
      map.keyframe(detection.loop->id()) != detection.loop) {
    return std::nullopt;
  }
  int kept = 0;
  for (MapPointPtr& mp : detection.matched_points) {
    if (mp && mp->is_bad()) mp.reset();
    if (mp) ++kept;
  }
  if (kept < options_.min_inliers) return std::nullopt;
  detection.inliers = kept;
  std::erase_if(detection.loop_points, [](const MapPointPtr& mp) { return mp->is_bad(); });
  return detection;
}

void LoopDetectorOptions::check() const {
  using namespace option_check;
  at_least("LoopDetectorOptions.min_keyframes_between_loops", min_keyframes_between_loops, 0);
  at_least("LoopDetectorOptions.consistency_threshold", consistency_threshold, 1);
  at_least("LoopDetectorOptions.group_size", static_cast<double>(group_size), 1);
  in_range("LoopDetectorOptions.group_score_ratio", group_score_ratio, 0, 1);
  at_least("LoopDetectorOptions.min_bow_matches", min_bow_matches, 1);
  above("LoopDetectorOptions.projection_window", projection_window, 0);
  at_least("LoopDetectorOptions.min_inliers", min_inliers, 1);
  at_least("LoopDetectorOptions.min_confirmation_matches", min_confirmation_matches, 0);
}

}  // namespace stillslam
