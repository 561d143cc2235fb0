// Vocabulary files whose payload is damaged but whose checksum is put back
// the way the writer computes it: every field class of a small trained
// vocabulary is damaged with a fixed seed, and each file either gives an
// Error that names the file and says it is damaged, or loads a vocabulary of
// identical structure (k, L, weighting, tree, words).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <sstream>

#include "io/temp_dir.h"
#include "stillslam/core/error.h"
#include "stillslam/core/fnv1a.h"
#include "stillslam/place/vocabulary.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}
void write_bytes(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
}

// The tree and its words. k and L are bounds the tree must keep: a larger
// one in the header leaves a tree that works the same (it only changes the
// fingerprint, so maps saved with the original then refuse to load).
std::string structure_of(const Vocabulary& v) {
  std::ostringstream s;
  s << "weighting " << static_cast<int>(v.weighting()) << " nodes "
    << v.node_count() << " words " << v.size() << "\n";
  for (std::size_t n = 0; n < v.node_count(); ++n) s << v.node_depth(static_cast<NodeId>(n)) << " ";
  s << "\n";
  for (WordId w = 0; w < v.size(); ++w) s << v.word_node(w) << " ";
  return s.str();
}

// Offsets of the file's fields (format in src/stillslam/place/vocabulary_io.cpp).
enum class Part { K, L, Weighting, Images, NodeCount, WordCount, FirstChild, ChildCount, Descriptor, WordNode, Weight };
constexpr std::size_t kHeader = 8 + 4 + 4 * 3 + 8 * 2 + 4 * 2;

class VocabularyDamageTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // k = 3, L = 3 over 240 random descriptors of 6 images: a tree with
    // inner nodes, leaves at several depths and idf weights.
    std::mt19937 rng(4);
    std::uniform_int_distribution<int> byte(0, 255);
    std::vector<cv::Mat> images;
    for (int i = 0; i < 6; ++i) {
      cv::Mat d(40, 32, CV_8U);
      for (int r = 0; r < d.rows; ++r)
        for (int c = 0; c < 32; ++c) d.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(byte(rng));
      images.push_back(d);
    }
    VocabularyOptions options;
    options.branching = 3;
    options.levels = 3;
    vocabulary_ = Vocabulary::train(images, options);
    vocabulary_.save(path());
    original_ = read_bytes(path());
    nodes_ = vocabulary_.node_count();
    words_ = vocabulary_.size();
  }
  fs::path path() const { return dir_.path() / "vocabulary.bin"; }

  // Byte offset of element `i` of `part`.
  std::size_t offset(Part part, std::size_t i = 0) const {
    switch (part) {
      case Part::K: return 12;
      case Part::L: return 16;
      case Part::Weighting: return 20;
      case Part::Images: return 24;
      case Part::NodeCount: return 40;
      case Part::WordCount: return 44;
      case Part::FirstChild: return kHeader + 4 * i;
      case Part::ChildCount: return kHeader + 4 * nodes_ + i;
      case Part::Descriptor: return kHeader + 5 * nodes_ + i;  // byte i of all node descriptors
      case Part::WordNode: return kHeader + 37 * nodes_ + 4 * i;
      case Part::Weight: return kHeader + 37 * nodes_ + 4 * words_ + 8 * i;
    }
    return 0;
  }

  // Loads `bytes` with the checksum recomputed: the Error's message, or ""
  // after checking that the vocabulary loaded has the original structure.
  std::string load_damaged(std::string bytes) {
    const std::uint64_t sum = fnv1a(bytes.data(), bytes.size() - 8);
    std::memcpy(bytes.data() + bytes.size() - 8, &sum, 8);
    write_bytes(path(), bytes);
    try {
      const Vocabulary loaded = Vocabulary::load(path());
      EXPECT_EQ(structure_of(loaded), structure_of(vocabulary_)) << "a damaged file loaded another tree";
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }

  test::TempDir dir_;
  Vocabulary vocabulary_;
  std::string original_;
  std::size_t nodes_ = 0, words_ = 0;
};

template <typename T>
void put(std::string& bytes, std::size_t offset, T value) {
  std::memcpy(bytes.data() + offset, &value, sizeof(T));
}
template <typename T>
T get(const std::string& bytes, std::size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof(T));
  return value;
}

TEST_F(VocabularyDamageTest, DamagedFieldsGiveAnErrorOrTheSameTree) {
  ASSERT_GT(nodes_, 20u);
  ASSERT_GT(words_, 10u);
  std::mt19937 rng(15);
  const auto uniform = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  const Part parts[] = {Part::K,          Part::L,          Part::Weighting, Part::Images,
                        Part::NodeCount,  Part::WordCount,  Part::FirstChild, Part::ChildCount,
                        Part::Descriptor, Part::WordNode,   Part::Weight};
  int damaged = 0, refused = 0;
  std::map<Part, int> refused_of;
  for (int trial = 0; trial < 220; ++trial) {
    const Part part = parts[trial % std::size(parts)];
    const int pick = static_cast<int>(uniform(4));
    std::string bytes = original_;
    std::size_t at = 0;
    switch (part) {
      case Part::K:
      case Part::L:
      case Part::Weighting:
      case Part::NodeCount:
      case Part::WordCount: {
        at = offset(part);
        const auto v = get<std::uint32_t>(bytes, at);
        const std::uint32_t values[] = {v + 1, v - 1, 0, 0xFFFFFFFFu};
        put(bytes, at, values[pick]);
        break;
      }
      case Part::Images: {
        at = offset(part);
        const auto v = get<std::uint64_t>(bytes, at);
        const std::uint64_t values[] = {0, 1, v / 2, v + 1};
        put(bytes, at, values[pick]);
        break;
      }
      case Part::FirstChild: {
        at = offset(part, uniform(nodes_));
        const auto v = get<std::uint32_t>(bytes, at);
        const std::uint32_t values[] = {v + 1, v - 1, static_cast<std::uint32_t>(nodes_), v == 0 ? 1u : 0u};
        put(bytes, at, values[pick]);
        break;
      }
      case Part::ChildCount: {
        at = offset(part, uniform(nodes_));
        const auto v = get<std::uint8_t>(bytes, at);
        const std::uint8_t values[] = {static_cast<std::uint8_t>(v + 1), static_cast<std::uint8_t>(v - 1), 0, 255};
        put(bytes, at, values[pick]);
        break;
      }
      case Part::Descriptor: {
        // The root's (first 32 bytes) or any other node's: a centre moves.
        at = offset(part, pick == 0 ? uniform(32) : uniform(32 * nodes_));
        bytes[at] = static_cast<char>(bytes[at] ^ (1 << uniform(8)));
        break;
      }
      case Part::WordNode: {
        const std::size_t w = uniform(words_);
        at = offset(part, w);
        const auto v = get<std::uint32_t>(bytes, at);
        const std::uint32_t values[] = {v + 1, v - 1, static_cast<std::uint32_t>(nodes_),
                                        get<std::uint32_t>(bytes, offset(part, (w + 1) % words_))};
        put(bytes, at, values[pick]);
        break;
      }
      case Part::Weight: {
        at = offset(part, uniform(words_));
        const double values[] = {std::numeric_limits<double>::quiet_NaN(), -0.5, 1e300,
                                 std::numeric_limits<double>::infinity()};
        put(bytes, at, values[pick]);
        break;
      }
    }
    if (bytes == original_) continue;
    ++damaged;
    SCOPED_TRACE("part " + std::to_string(static_cast<int>(part)) + " byte " + std::to_string(at));
    const std::string e = load_damaged(bytes);
    if (e.empty()) continue;
    ++refused;
    ++refused_of[part];
    EXPECT_NE(e.find("vocabulary file '" + path().string() + "' is damaged ("), std::string::npos) << e;
    EXPECT_NE(e.find("re-copy it or rebuild it with scripts/train_vocabulary"), std::string::npos) << e;
  }
  EXPECT_GE(damaged, 200);
  // A moved non-root node centre (a descriptor bit), a larger k, L or image
  // count can leave a valid tree.
  EXPECT_GE(refused, damaged - 40) << "of " << damaged;
  // Of about 20 damages per part: only root descriptors (1 in 4) and image
  // counts that shrink below what the weights need (0, 1, some halvings) are
  // sure to be refused there; every other part is structure.
  for (const Part part : parts) {
    const int least = part == Part::Descriptor ? 1 : part == Part::Images ? 5 : 12;
    EXPECT_GE(refused_of[part], least) << "part " << static_cast<int>(part);
  }
}

// The error names the node or word that is wrong.
TEST_F(VocabularyDamageTest, ErrorsNameTheNodeOrWord) {
  const auto damaged_with = [&](const std::function<void(std::string&)>& damage) {
    std::string bytes = original_;
    damage(bytes);
    return load_damaged(bytes);
  };
  EXPECT_NE(damaged_with([&](std::string& b) { b[offset(Part::Descriptor, 5)] = 1; })
                .find("is damaged (node 0: the root's descriptor is not zeros)"),
            std::string::npos);
  const NodeId leaf = vocabulary_.word_node(2);
  EXPECT_NE(damaged_with([&](std::string& b) { put<std::uint32_t>(b, offset(Part::FirstChild, leaf), 7); })
                .find("is damaged (node " + std::to_string(leaf) + ": a leaf with first child 7)"),
            std::string::npos);
  EXPECT_NE(damaged_with([&](std::string& b) { put<std::uint8_t>(b, offset(Part::ChildCount, 0), 9); })
                .find("is damaged (node 0: 9 children, k is 3)"),
            std::string::npos);
  EXPECT_NE(damaged_with([&](std::string& b) { put<double>(b, offset(Part::Weight, 4), 2.0); })
                .find("is damaged (word 4: weight 2.000000 outside [0, ln(training images)])"),
            std::string::npos);
  EXPECT_NE(damaged_with([&](std::string& b) { put<std::uint32_t>(b, offset(Part::WordNode, 3), 0); })
                .find("is damaged (word 3: node 0 is not the next leaf)"),
            std::string::npos);
  EXPECT_NE(damaged_with([&](std::string& b) { put<std::uint32_t>(b, offset(Part::L), 1); })
                .find("is damaged (node 4: depth 2, L is 1)"),
            std::string::npos);
}

}  // namespace
}  // namespace stillslam
