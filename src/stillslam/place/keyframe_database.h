#pragma once
// Inverted index word -> keyframes for place recognition (relocalization and
// loop detection). Knows keyframes only by id and BoW vector, so it does not
// depend on map/. Thread-safe: add/erase take a write lock, queries a read lock.
#include <cstdint>
#include <functional>
#include <shared_mutex>
#include <unordered_map>
#include <vector>

#include "stillslam/place/bow_vector.h"

namespace stillslam {

using KeyframeId = std::uint64_t;

struct PlaceQueryOptions {
  std::size_t max_results = 10;  // best candidates returned (0: all)
  double min_score = 0.0;        // drop candidates scoring below this
  int min_common_words = 1;      // drop candidates sharing fewer words with the query
  // Also drop candidates sharing fewer than this fraction of the words the
  // best-sharing (non-excluded) candidate shares; ORB-SLAM's relocalization and
  // loop detection use 0.8 before scoring.
  double min_common_words_ratio = 0.0;
  // Candidates for which this returns true are skipped (e.g. the query
  // keyframe itself and its covisible neighbours).
  std::function<bool(KeyframeId)> exclude;
};

struct PlaceCandidate {
  KeyframeId id = 0;
  double score = 0;      // L1 score (l1_score) of the query and the keyframe
  int common_words = 0;  // words present in both
};

class KeyframeDatabase {
 public:
  KeyframeDatabase() = default;
  KeyframeDatabase(const KeyframeDatabase&) = delete;
  KeyframeDatabase& operator=(const KeyframeDatabase&) = delete;

  // Adds or replaces keyframe `id`. The vector should be L1-normalized (as
  // Vocabulary::transform returns it); it is normalized here otherwise.
  void add(KeyframeId id, const BowVector& bow);
  // No-op for unknown ids.
  void erase(KeyframeId id);
  void clear();
  bool contains(KeyframeId id) const;
  std::size_t size() const;

  // Keyframes sharing words with `bow`, best score first (ties: lower id
  // first). Only keyframes in the inverted lists of the query's words are
  // visited, so the cost grows with shared words, not the database size.
  std::vector<PlaceCandidate> query(const BowVector& bow, const PlaceQueryOptions& options = {}) const;

 private:
  struct Posting {
    KeyframeId id;
    double weight;  // the keyframe's normalized weight of this word
  };
  mutable std::shared_mutex mutex_;
  std::unordered_map<WordId, std::vector<Posting>> inverted_;
  std::unordered_map<KeyframeId, std::vector<WordId>> words_of_;
};

}  // namespace stillslam
