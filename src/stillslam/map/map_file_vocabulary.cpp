// vocabulary_fingerprint (map_file.h): what a map file records about the
// vocabulary its keyframes were indexed with. Built from the public API only,
// so it does not depend on how the vocabulary file is laid out.
#include <array>
#include <cstring>

#include "stillslam/core/fnv1a.h"
#include "stillslam/map/map_file.h"
#include "stillslam/place/vocabulary.h"

namespace stillslam {

namespace {

// splitmix64: a fixed, platform-independent stream of probe descriptors.
std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

std::uint64_t vocabulary_fingerprint(const Vocabulary& vocabulary) {
  Fnv1a h;
  h.add(static_cast<std::int32_t>(vocabulary.k()));
  h.add(static_cast<std::int32_t>(vocabulary.depth()));
  h.add(static_cast<std::uint64_t>(vocabulary.size()));
  h.add(static_cast<std::uint64_t>(vocabulary.node_count()));
  h.add(static_cast<std::int32_t>(vocabulary.weighting()));
  h.add(vocabulary.training_images());
  h.add(vocabulary.training_descriptors());
  for (WordId w = 0; w < vocabulary.size(); ++w) {
    h.add(vocabulary.word_node(w));
    h.add(vocabulary.word_weight(w));
  }
  // The node descriptors are not exposed; the words of fixed probe
  // descriptors depend on them.
  if (!vocabulary.empty()) {
    std::uint64_t state = 0x5354494c4c4d4150ULL;
    for (int probe = 0; probe < 256; ++probe) {
      std::array<std::uint8_t, 32> d{};
      for (std::size_t i = 0; i < d.size(); i += 8) {
        const std::uint64_t bits = splitmix64(state);
        std::memcpy(d.data() + i, &bits, 8);
      }
      h.add(vocabulary.word_of(d.data()));
    }
  }
  const std::uint64_t v = h.value();
  return v == 0 ? 1 : v;  // 0 means "no vocabulary" in a map file
}

}  // namespace stillslam
