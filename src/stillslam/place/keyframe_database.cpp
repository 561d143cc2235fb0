#include "stillslam/place/keyframe_database.h"

#include <algorithm>
#include <cmath>
#include <mutex>

namespace stillslam {

void KeyframeDatabase::add(KeyframeId id, const BowVector& bow) {
  std::unique_lock lock(mutex_);
  if (words_of_.count(id)) {
    for (WordId w : words_of_[id]) std::erase_if(inverted_[w], [id](const Posting& p) { return p.id == id; });
  }
  const double norm = bow.l1_norm();
  std::vector<WordId>& words = words_of_[id];
  words.clear();
  words.reserve(bow.size());
  for (const auto& [w, v] : bow) {
    if (v == 0 || norm <= 0) continue;
    inverted_[w].push_back({id, std::abs(v) / norm});
    words.push_back(w);
  }
}

void KeyframeDatabase::erase(KeyframeId id) {
  std::unique_lock lock(mutex_);
  const auto it = words_of_.find(id);
  if (it == words_of_.end()) return;
  for (WordId w : it->second) {
    auto list = inverted_.find(w);
    if (list == inverted_.end()) continue;
    std::erase_if(list->second, [id](const Posting& p) { return p.id == id; });
    if (list->second.empty()) inverted_.erase(list);
  }
  words_of_.erase(it);
}

void KeyframeDatabase::clear() {
  std::unique_lock lock(mutex_);
  inverted_.clear();
  words_of_.clear();
}

bool KeyframeDatabase::contains(KeyframeId id) const {
  std::shared_lock lock(mutex_);
  return words_of_.count(id) > 0;
}

std::size_t KeyframeDatabase::size() const {
  std::shared_lock lock(mutex_);
  return words_of_.size();
}

std::vector<PlaceCandidate> KeyframeDatabase::query(const BowVector& bow, const PlaceQueryOptions& options) const {
  const double norm = bow.l1_norm();
  if (norm <= 0) return {};
  struct Accumulator {
    double shared = 0;  // sum over common words of |q| + |v| - |q - v|
    int common = 0;
  };
  std::unordered_map<KeyframeId, Accumulator> acc;
  {
    std::shared_lock lock(mutex_);
    for (const auto& [w, v] : bow) {
      const auto list = inverted_.find(w);
      if (list == inverted_.end() || v == 0) continue;
      const double q = std::abs(v) / norm;
      for (const Posting& p : list->second) {
        Accumulator& a = acc[p.id];
        a.shared += q + p.weight - std::abs(q - p.weight);
        ++a.common;
      }
    }
  }
  std::vector<PlaceCandidate> out;
  out.reserve(acc.size());
  int most_common = 0;
  for (const auto& [id, a] : acc) {
    if (options.exclude && options.exclude(id)) continue;
    out.push_back({id, std::clamp(0.5 * a.shared, 0.0, 1.0), a.common});
    most_common = std::max(most_common, a.common);
  }
  const double min_common = std::max(static_cast<double>(options.min_common_words),
                                     options.min_common_words_ratio * static_cast<double>(most_common));
  std::erase_if(out, [&](const PlaceCandidate& c) {
    return static_cast<double>(c.common_words) < min_common || c.score < options.min_score;
  });
  const auto better = [](const PlaceCandidate& a, const PlaceCandidate& b) {
    return a.score != b.score ? a.score > b.score : a.id < b.id;
  };
  if (options.max_results > 0 && out.size() > options.max_results) {
    std::partial_sort(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(options.max_results), out.end(), better);
    out.resize(options.max_results);
  } else {
    std::sort(out.begin(), out.end(), better);
  }
  return out;
}

}  // namespace stillslam
