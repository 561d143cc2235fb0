#include "stillslam/loop/merge_detector.h"

namespace stillslam {

MergeDetector::MergeDetector(const PlaceRecognizer& recognizer, LoopDetectorOptions options)
    : recognizer_(recognizer), options_(options), verifier_(recognizer, options) {
  options_.check();
}

std::optional<LoopDetection> MergeDetector::detect(const Map& other, const KeyFrame& query) {
  auto it = detectors_.find(other.id());
  if (it == detectors_.end()) it = detectors_.emplace(other.id(), LoopDetector(recognizer_, options_)).first;
  LoopDetector& detector = it->second;
  if (query.is_bad() || other.num_keyframes() == 0) return std::nullopt;
  // An empty candidate list also breaks the consistency chain.
  const std::vector<KeyFramePtr> consistent = detector.consistent_candidates(detector.candidates(other, query));
  if (consistent.empty()) return std::nullopt;
  return detector.verify(query, consistent);
}

std::optional<LoopDetection> MergeDetector::verify(const KeyFrame& query, const KeyFramePtr& candidate) const {
  if (query.is_bad() || !candidate || candidate->is_bad()) return std::nullopt;
  return verifier_.verify(query, {candidate});
}

}  // namespace stillslam
