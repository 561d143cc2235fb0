#pragma once
// Place recognition over keyframes: a shared vocabulary, the inverted index
// (KeyframeDatabase) and a side table keyframe id -> bag of words + direct
// index, computed once from the keyframe's descriptors when it is added.
// Used by relocalization (frame -> keyframes) and loop detection (keyframe ->
// older keyframes). Thread-safe: one mutex guards the side table; the
// database has its own lock. Knows keyframes only through their descriptors,
// which never change after construction (map/keyframe.h): no call needs the
// map lock.
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <optional>
#include <unordered_map>
#include <vector>

#include "stillslam/map/keyframe.h"
#include "stillslam/place/keyframe_database.h"
#include "stillslam/place/vocabulary.h"

namespace stillslam {

struct PlaceRecognizerOptions {
  // Tree depth of the direct index (see Vocabulary::transform); ORB-SLAM
  // groups 4 levels above the leaves of a 6-level tree, i.e. depth 2.
  int direct_index_level = 2;
  std::size_t max_relocalization_candidates = 10;
  std::size_t max_loop_candidates = 10;
  // Candidates must share at least this fraction of the best candidate's
  // common-word count (ORB-SLAM: 0.8).
  double min_common_words_ratio = 0.8;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// Bag of words and direct index of one image.
struct BowDescription {
  BowVector bow;
  FeatureVector features;
};

class PlaceRecognizer {
 public:
  explicit PlaceRecognizer(std::shared_ptr<const Vocabulary> vocabulary, PlaceRecognizerOptions options = {});
  PlaceRecognizer(const PlaceRecognizer&) = delete;
  PlaceRecognizer& operator=(const PlaceRecognizer&) = delete;

  const Vocabulary& vocabulary() const { return *vocabulary_; }
  const PlaceRecognizerOptions& options() const { return options_; }

  // Words and direct index of an N x 32 descriptor matrix (no state touched).
  BowDescription describe(const cv::Mat& descriptors) const;
  // The keyframe's descriptors as one matrix.
  static cv::Mat descriptors_of(const KeyFrame& keyframe);

  // Describes the keyframe and indexes it; replaces an earlier entry of the
  // same id. Returns the description.
  std::shared_ptr<const BowDescription> add(const KeyFrame& keyframe);
  // Forgets a keyframe (culled); no-op for unknown ids.
  void erase(KeyframeId id);
  bool contains(KeyframeId id) const;
  std::size_t size() const;
  // The stored description, or nullptr.
  std::shared_ptr<const BowDescription> description(KeyframeId id) const;

  // Keyframes resembling a frame: every indexed keyframe sharing words, kept
  // when it has >= min_common_words_ratio of the best common-word count,
  // best score first, at most max_relocalization_candidates.
  std::vector<PlaceCandidate> relocalization_candidates(const BowVector& frame_bow) const;

  // Keyframes resembling `keyframe` (which must be indexed or is described on
  // the fly) that are not itself nor in `covisible`, scoring at least the
  // lowest score of the keyframe against its covisible neighbours (the
  // neighbours define how similar "the same place" looks). With no scored
  // neighbour the threshold is 0. Best first, at most max_results (default
  // max_loop_candidates; 0 = all).
  std::vector<PlaceCandidate> loop_candidates(const KeyFrame& keyframe, const std::vector<KeyframeId>& covisible,
                                              std::optional<std::size_t> max_results = std::nullopt) const;
  // The same for keyframe `self` described by `bow` (no map access).
  std::vector<PlaceCandidate> loop_candidates(KeyframeId self, const BowVector& bow,
                                              const std::vector<KeyframeId>& covisible,
                                              std::optional<std::size_t> max_results = std::nullopt) const;
  // The threshold loop_candidates uses.
  double min_covisible_score(const BowVector& bow, const std::vector<KeyframeId>& covisible) const;

 private:
  std::vector<PlaceCandidate> filter_by_common_words(std::vector<PlaceCandidate> candidates,
                                                     std::size_t max_results) const;

  std::shared_ptr<const Vocabulary> vocabulary_;
  PlaceRecognizerOptions options_;
  KeyframeDatabase database_;
  mutable std::mutex mutex_;
  std::unordered_map<KeyframeId, std::shared_ptr<const BowDescription>> descriptions_;
};

}  // namespace stillslam
