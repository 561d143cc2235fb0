// Vocabulary::train: hierarchical k-majority clustering, breadth first so the
// children of every node get consecutive ids, then idf weights.
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <string>

#include "stillslam/core/error.h"
#include "stillslam/place/k_majority.h"
#include "stillslam/place/vocabulary.h"

namespace stillslam {

using place_detail::Descriptor256;

namespace {

// Per-node random stream: the tree does not depend on the order nodes are
// processed in (SplitMix64 finalizer as the mixing function).
std::uint64_t mix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

}  // namespace

class VocabularyBuilder {
 public:
  static Vocabulary build(const std::vector<cv::Mat>& images, const VocabularyOptions& o) {
    if (o.branching < 2 || o.branching > 255)
      throw Error("vocabulary training: branching factor k must be in [2, 255], got " + std::to_string(o.branching));
    if (o.levels < 1 || o.levels > 16)
      throw Error("vocabulary training: levels L must be in [1, 16], got " + std::to_string(o.levels));
    if (o.max_iterations < 0) throw Error("vocabulary training: max_iterations must be >= 0");

    std::vector<Descriptor256> data;
    std::vector<std::uint32_t> image_of;  // training image index per descriptor
    std::uint32_t used_images = 0;
    for (const auto& m : images) {
      auto rows = place_detail::pack_rows(m, "vocabulary training");
      if (rows.empty()) continue;
      data.insert(data.end(), rows.begin(), rows.end());
      image_of.insert(image_of.end(), rows.size(), used_images++);
    }
    if (data.empty()) throw Error("vocabulary training: no descriptors in any of the " +
                                  std::to_string(images.size()) + " images");

    Vocabulary v;
    v.branching_ = o.branching;
    v.levels_ = o.levels;
    v.weighting_ = o.weighting;
    v.training_images_ = used_images;
    v.training_descriptors_ = data.size();
    grow_tree(v, data, o);
    v.index_tree();
    compute_weights(v, data, image_of, used_images);
    return v;
  }

 private:
  struct Pending {
    NodeId node;
    int depth;
    std::vector<std::uint32_t> members;
  };

  static NodeId add_node(Vocabulary& v, const Descriptor256& d) {
    v.descriptors_.push_back(d);
    v.first_child_.push_back(0);
    v.child_count_.push_back(0);
    return static_cast<NodeId>(v.descriptors_.size() - 1);
  }

  static void grow_tree(Vocabulary& v, const std::vector<Descriptor256>& data, const VocabularyOptions& o) {
    std::deque<Pending> queue;
    std::vector<std::uint32_t> all(data.size());
    for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
    queue.push_back({add_node(v, Descriptor256{}), 0, std::move(all)});
    while (!queue.empty()) {
      Pending p = std::move(queue.front());
      queue.pop_front();
      std::vector<place_detail::BinaryCluster> clusters;
      if (p.depth < o.levels && p.members.size() > 1) {
        std::mt19937_64 rng(mix(o.seed ^ mix(p.node)));
        clusters = place_detail::cluster_k_majority(data, p.members, o.branching, o.max_iterations, rng);
      }
      // One cluster means identical descriptors: splitting further is useless.
      if (clusters.size() < 2) {
        v.word_node_.push_back(p.node);
        continue;
      }
      v.first_child_[p.node] = static_cast<NodeId>(v.descriptors_.size());
      v.child_count_[p.node] = static_cast<std::uint32_t>(clusters.size());
      for (auto& c : clusters) {
        const NodeId id = add_node(v, c.centre);
        queue.push_back({id, p.depth + 1, std::move(c.members)});
      }
    }
    // Words numbered in node order (leaves were met in breadth-first order
    // already, but sort to make the invariant explicit).
    std::sort(v.word_node_.begin(), v.word_node_.end());
  }

  static void compute_weights(Vocabulary& v, const std::vector<Descriptor256>& data,
                              const std::vector<std::uint32_t>& image_of, std::uint32_t images) {
    const std::size_t words = v.word_node_.size();
    v.word_weight_.assign(words, 1.0);
    if (v.weighting_ != WordWeighting::kTfIdf && v.weighting_ != WordWeighting::kIdf) return;
    // N_w: number of training images containing word w.
    std::vector<std::uint32_t> images_with(words, 0);
    std::vector<std::uint32_t> last_image(words, std::numeric_limits<std::uint32_t>::max());
    for (std::size_t i = 0; i < data.size(); ++i) {
      const WordId w = v.word_of(reinterpret_cast<const std::uint8_t*>(data[i].data()));
      if (last_image[w] != image_of[i]) {
        last_image[w] = image_of[i];
        ++images_with[w];
      }
    }
    for (std::size_t w = 0; w < words; ++w)
      v.word_weight_[w] = images_with[w] > 0 ? std::log(static_cast<double>(images) / images_with[w]) : 0.0;
  }
};

Vocabulary Vocabulary::train(const std::vector<cv::Mat>& descriptors_per_image, const VocabularyOptions& options) {
  return VocabularyBuilder::build(descriptors_per_image, options);
}

}  // namespace stillslam
