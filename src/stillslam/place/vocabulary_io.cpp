// Vocabulary file format, version 1 (all integers little-endian):
//   8 bytes  magic "STILLVOC"
//   u32      version (1)
//   u32 k, u32 L, u32 weighting (WordWeighting)
//   u64 training images, u64 training descriptors
//   u32 node count N, u32 word count W
//   N x u32  first child id of each node (0 for leaves)
//   N x u8   child count of each node (0 for leaves; k <= 255)
//   N x 32   node descriptors (root: zeros)
//   W x u32  node id of each word (ascending)
//   W x f64  word weight (idf or 1)
//   u64      FNV-1a 64 checksum of every byte before it
// Nodes are in breadth-first order, so a node's children are the ids
// [first_child, first_child + child_count). With k = 10, L = 5 a file is a few
// MB and loads in a few milliseconds (one read, no parsing of text).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "stillslam/core/byte_io.h"
#include "stillslam/core/error.h"
#include "stillslam/core/fnv1a.h"
#include "stillslam/place/vocabulary.h"

namespace stillslam {

namespace {

constexpr char kMagic[8] = {'S', 'T', 'I', 'L', 'L', 'V', 'O', 'C'};
constexpr std::uint32_t kVersion = 1;
constexpr std::size_t kHeaderBytes = 8 + 4 * 4 + 8 * 2 + 4 * 2;

// A DBoW2 text vocabulary starts with "k L scoring weighting" on one line.
bool looks_like_dbow2_text(const std::vector<char>& bytes) {
  std::string first_line;
  for (char c : bytes) {
    if (c == '\n' || first_line.size() > 64) break;
    first_line.push_back(c);
  }
  std::istringstream in(first_line);
  int k = 0, l = 0, s = -1, w = -1;
  return static_cast<bool>(in >> k >> l >> s >> w) && k > 1 && l > 0;
}

std::vector<char> read_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw Error("vocabulary path '" + path.string() + "' is not a file; pass the path of vocab/orb_vocabulary.bin "
                "or one made with `stillslam vocab train`");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open vocabulary file '" + path.string() + "' (missing or unreadable); pass the path of "
                       "vocab/orb_vocabulary.bin or one made with `stillslam vocab train`");
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::size_t>(in.tellg());
  in.seekg(0);
  std::vector<char> bytes(size);
  if (size > 0 && !in.read(bytes.data(), static_cast<std::streamsize>(size)))
    throw Error("cannot read vocabulary file '" + path.string() + "'");
  return bytes;
}

}  // namespace

void Vocabulary::save(const std::filesystem::path& path) const {
  if (empty()) throw Error("cannot save an empty vocabulary to '" + path.string() + "'");
  ByteWriter w;
  w.put_bytes(kMagic, 8);
  w.put(kVersion);
  w.put(static_cast<std::uint32_t>(branching_));
  w.put(static_cast<std::uint32_t>(levels_));
  w.put(static_cast<std::uint32_t>(weighting_));
  w.put(training_images_);
  w.put(training_descriptors_);
  w.put(static_cast<std::uint32_t>(node_count()));
  w.put(static_cast<std::uint32_t>(size()));
  w.put_all(first_child_);
  std::vector<std::uint8_t> counts(child_count_.begin(), child_count_.end());
  w.put_all(counts);
  w.put_all(descriptors_);
  w.put_all(word_node_);
  w.put_all(word_weight_);
  w.put(fnv1a(w.bytes().data(), w.bytes().size()));

  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw Error("cannot write vocabulary file '" + path.string() + "' (check the folder exists and is writable)");
  out.write(w.bytes().data(), static_cast<std::streamsize>(w.bytes().size()));
  if (!out) throw Error("failed writing vocabulary file '" + path.string() + "' (disk full?)");
}

class VocabularyReader {
 public:
  static Vocabulary read(const std::filesystem::path& path) {
    const std::string file = path.string();
    const std::vector<char> bytes = read_file(path);
    const auto corrupt = [&](const std::string& why) {
      return Error("vocabulary file '" + file + "' is damaged (" + why + ")" +
                   "; re-copy it or rebuild it with scripts/train_vocabulary");
    };
    if (bytes.size() < 8 || std::memcmp(bytes.data(), kMagic, 8) != 0) {
      if (looks_like_dbow2_text(bytes))
        throw Error("'" + file + "' looks like a DBoW2 text vocabulary (e.g. ORB-SLAM's ORBvoc.txt); stillslam "
                    "reads only its own binary format: use vocab/orb_vocabulary.bin or train one with "
                    "`stillslam vocab train`");
      throw Error("'" + file + "' is not a stillslam vocabulary (no STILLVOC header); use "
                  "vocab/orb_vocabulary.bin or train one with `stillslam vocab train`");
    }
    // Any read past the end means the file was cut short.
    ByteReader r(bytes.data(), bytes.size(), [&](const std::string&) {
      return Error("vocabulary file '" + file + "' is truncated (" + std::to_string(bytes.size()) +
                   " bytes); re-copy it or rebuild it with scripts/train_vocabulary");
    });
    r.get<std::uint64_t>();  // magic
    const auto version = r.get<std::uint32_t>();
    if (version != kVersion)
      throw Error("vocabulary file '" + file + "' has format version " + std::to_string(version) +
                  ", this build reads version " + std::to_string(kVersion) + "; rebuild it with scripts/train_vocabulary");
    Vocabulary v;
    v.branching_ = static_cast<int>(r.get<std::uint32_t>());
    v.levels_ = static_cast<int>(r.get<std::uint32_t>());
    const auto weighting = r.get<std::uint32_t>();
    v.training_images_ = r.get<std::uint64_t>();
    v.training_descriptors_ = r.get<std::uint64_t>();
    const auto nodes = r.get<std::uint32_t>();
    const auto words = r.get<std::uint32_t>();
    if (v.branching_ < 2 || v.branching_ > 255 || v.levels_ < 1 || v.levels_ > 16 || weighting > 3)
      throw corrupt("header: k " + std::to_string(v.branching_) + ", L " + std::to_string(v.levels_) + ", weighting " +
                    std::to_string(weighting));
    v.weighting_ = static_cast<WordWeighting>(weighting);
    if (nodes < 1 || words < 1 || words > nodes)
      throw corrupt("header: " + std::to_string(nodes) + " nodes, " + std::to_string(words) + " words");
    const std::size_t expected = kHeaderBytes + std::size_t{nodes} * (4 + 1 + 32) + std::size_t{words} * (4 + 8) + 8;
    if (bytes.size() != expected)
      throw corrupt("size " + std::to_string(bytes.size()) + " bytes, header says " + std::to_string(expected));
    std::uint64_t stored_checksum;
    std::memcpy(&stored_checksum, bytes.data() + bytes.size() - 8, 8);
    if (fnv1a(bytes.data(), bytes.size() - 8) != stored_checksum) throw corrupt("checksum mismatch");

    r.get_all(v.first_child_, nodes);
    std::vector<std::uint8_t> counts;
    r.get_all(counts, nodes);
    v.child_count_.assign(counts.begin(), counts.end());
    r.get_all(v.descriptors_, nodes);
    r.get_all(v.word_node_, words);
    r.get_all(v.word_weight_, words);
    validate(v, corrupt);
    v.index_tree();
    return v;
  }

 private:
  // Rejects anything transform could trip over and anything training cannot
  // have written: children must be the next unused ids (breadth-first
  // layout), leaves have no first child, the root's descriptor is zeros,
  // words are exactly the leaves in node order, and weights are what the
  // weighting gives (1, or an idf ln(N / N_w) between 0 and ln N).
  template <typename Corrupt>
  static void validate(const Vocabulary& v, const Corrupt& corrupt) {
    const std::size_t n = v.descriptors_.size();
    std::size_t next = 1;
    std::size_t leaves = 0;
    const auto node = [](std::size_t p) { return "node " + std::to_string(p) + ": "; };
    if (std::any_of(v.descriptors_[0].begin(), v.descriptors_[0].end(), [](auto b) { return b != 0; }))
      throw corrupt(node(0) + "the root's descriptor is not zeros");
    std::vector<int> depth(n, 0);  // index_tree's are 8 bits: a deep damaged chain would wrap
    for (std::size_t p = 0; p < n; ++p) {
      // Breadth-first: every node but the root is a child of an earlier one.
      if (p >= next) throw corrupt(node(p) + "unreachable from the root");
      if (depth[p] > v.levels_)
        throw corrupt(node(p) + "depth " + std::to_string(depth[p]) + ", L is " + std::to_string(v.levels_));
      const std::uint32_t c = v.child_count_[p];
      if (c == 0) {
        if (v.first_child_[p] != 0)
          throw corrupt(node(p) + "a leaf with first child " + std::to_string(v.first_child_[p]));
        ++leaves;
        continue;
      }
      if (c > static_cast<std::uint32_t>(v.branching_))
        throw corrupt(node(p) + std::to_string(c) + " children, k is " + std::to_string(v.branching_));
      if (v.first_child_[p] != next || next + c > n)
        throw corrupt(node(p) + "children from " + std::to_string(v.first_child_[p]) + ", breadth-first order says " +
                      std::to_string(next));
      for (std::size_t i = next; i < next + c; ++i) depth[i] = depth[p] + 1;
      next += c;
    }
    if (leaves != v.word_node_.size())
      throw corrupt(std::to_string(v.word_node_.size()) + " words for " + std::to_string(leaves) + " leaves");
    const bool idf = v.weighting_ == WordWeighting::kTfIdf || v.weighting_ == WordWeighting::kIdf;
    if (idf && v.training_images_ == 0) throw corrupt("idf weights from 0 training images");
    const double max_idf = idf ? std::log(static_cast<double>(v.training_images_)) * (1 + 1e-12) : 1.0;
    for (std::size_t w = 0; w < v.word_node_.size(); ++w) {
      const std::string word = "word " + std::to_string(w) + ": ";
      const NodeId at = v.word_node_[w];
      if (at >= n || v.child_count_[at] != 0 || (w > 0 && at <= v.word_node_[w - 1]))
        throw corrupt(word + "node " + std::to_string(at) + " is not the next leaf");
      const double weight = v.word_weight_[w];
      if (idf ? !(weight >= 0 && weight <= max_idf) : weight != 1.0)
        throw corrupt(word + "weight " + std::to_string(weight) + (idf ? " outside [0, ln(training images)]" : ", not 1"));
    }
  }
};

Vocabulary Vocabulary::load(const std::filesystem::path& path) { return VocabularyReader::read(path); }

}  // namespace stillslam
