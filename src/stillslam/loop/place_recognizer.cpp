#include "stillslam/loop/place_recognizer.h"

#include <algorithm>
#include <unordered_set>

#include "stillslam/core/error.h"
#include "stillslam/core/option_check.h"

namespace stillslam {

PlaceRecognizer::PlaceRecognizer(std::shared_ptr<const Vocabulary> vocabulary, PlaceRecognizerOptions options)
    : vocabulary_(std::move(vocabulary)), options_(options) {
  options_.check();
  if (!vocabulary_ || vocabulary_->empty()) {
    throw Error("PlaceRecognizer: the vocabulary is empty; load one with Vocabulary::load (vocab/orb_vocabulary.bin)");
  }
}

BowDescription PlaceRecognizer::describe(const cv::Mat& descriptors) const {
  BowDescription d;
  if (descriptors.empty()) return d;
  vocabulary_->transform(descriptors, d.bow, d.features, options_.direct_index_level);
  return d;
}

cv::Mat PlaceRecognizer::descriptors_of(const KeyFrame& keyframe) {
  cv::Mat out(static_cast<int>(keyframe.size()), 32, CV_8U);
  for (std::size_t i = 0; i < keyframe.size(); ++i) {
    std::copy(keyframe.descriptor(i), keyframe.descriptor(i) + 32, out.ptr<std::uint8_t>(static_cast<int>(i)));
  }
  return out;
}

std::shared_ptr<const BowDescription> PlaceRecognizer::add(const KeyFrame& keyframe) {
  auto d = std::make_shared<const BowDescription>(describe(descriptors_of(keyframe)));
  {
    std::lock_guard<std::mutex> lock(mutex_);
    descriptions_[keyframe.id()] = d;
  }
  database_.add(keyframe.id(), d->bow);
  return d;
}

void PlaceRecognizer::erase(KeyframeId id) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    descriptions_.erase(id);
  }
  database_.erase(id);
}

bool PlaceRecognizer::contains(KeyframeId id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return descriptions_.count(id) > 0;
}

std::size_t PlaceRecognizer::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return descriptions_.size();
}

std::shared_ptr<const BowDescription> PlaceRecognizer::description(KeyframeId id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = descriptions_.find(id);
  return it == descriptions_.end() ? nullptr : it->second;
}

std::vector<PlaceCandidate> PlaceRecognizer::filter_by_common_words(std::vector<PlaceCandidate> candidates,
                                                                    std::size_t max_results) const {
  int max_common = 0;
  for (const auto& c : candidates) max_common = std::max(max_common, c.common_words);
  const double min_common = options_.min_common_words_ratio * max_common;
  std::erase_if(candidates, [&](const PlaceCandidate& c) { return c.common_words < min_common; });
  // The database returns best score first; filtering keeps that order.
  if (max_results > 0 && candidates.size() > max_results) candidates.resize(max_results);
  return candidates;
}

std::vector<PlaceCandidate> PlaceRecognizer::relocalization_candidates(const BowVector& frame_bow) const {
  PlaceQueryOptions q;
  q.max_results = 0;
  return filter_by_common_words(database_.query(frame_bow, q), options_.max_relocalization_candidates);
}

double PlaceRecognizer::min_covisible_score(const BowVector& bow, const std::vector<KeyframeId>& covisible) const {
  double min_score = 1.0;
  bool any = false;
  for (KeyframeId id : covisible) {
    const auto d = description(id);
    if (!d) continue;
    min_score = std::min(min_score, vocabulary_->score(bow, d->bow));
    any = true;
  }
  return any ? min_score : 0.0;
}

std::vector<PlaceCandidate> PlaceRecognizer::loop_candidates(const KeyFrame& keyframe,
                                                             const std::vector<KeyframeId>& covisible,
                                                             std::optional<std::size_t> max_results) const {
  auto d = description(keyframe.id());
  if (!d) d = std::make_shared<const BowDescription>(describe(descriptors_of(keyframe)));
  return loop_candidates(keyframe.id(), d->bow, covisible, max_results);
}

std::vector<PlaceCandidate> PlaceRecognizer::loop_candidates(KeyframeId self, const BowVector& bow,
                                                             const std::vector<KeyframeId>& covisible,
                                                             std::optional<std::size_t> max_results) const {
  const double min_score = min_covisible_score(bow, covisible);
  const std::unordered_set<KeyframeId> excluded(covisible.begin(), covisible.end());
  PlaceQueryOptions q;
  q.max_results = 0;
  q.min_score = min_score;
  q.exclude = [&](KeyframeId id) { return id == self || excluded.count(id) > 0; };
  return filter_by_common_words(database_.query(bow, q), max_results.value_or(options_.max_loop_candidates));
}

void PlaceRecognizerOptions::check() const {
  using namespace option_check;
  at_least("PlaceRecognizerOptions.direct_index_level", direct_index_level, 0);
  at_least("PlaceRecognizerOptions.max_relocalization_candidates", static_cast<double>(max_relocalization_candidates), 1);
  at_least("PlaceRecognizerOptions.max_loop_candidates", static_cast<double>(max_loop_candidates), 1);
  in_range("PlaceRecognizerOptions.min_common_words_ratio", min_common_words_ratio, 0, 1);
}

}  // namespace stillslam
