#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>

#include "place_fixtures.h"
#include "stillslam/core/error.h"
#include "stillslam/features/descriptor_matcher.h"
#include "stillslam/place/direct_index_matcher.h"
#include "stillslam/place/vocabulary.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

// Trained once: 12 unrelated procedural scenes, k = 8, L = 4. The scenes share
// one texture model, so a coarser tree (k = 6, L = 3) leaves unrelated images
// scoring ~0.4 against each other; this one brings that below 0.1.
class VocabularyTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    images_ = std::make_unique<std::vector<cv::Mat>>(test::scene_images(12));
    descriptors_ = std::make_unique<std::vector<cv::Mat>>(test::descriptors_of(*images_));
    vocabulary_ = std::make_unique<Vocabulary>(Vocabulary::train(*descriptors_, test::small_options()));
  }
  static void TearDownTestSuite() {
    images_.reset();
    descriptors_.reset();
    vocabulary_.reset();
  }
  static const Vocabulary& voc() { return *vocabulary_; }
  static const std::vector<cv::Mat>& images() { return *images_; }
  static const std::vector<cv::Mat>& descriptors() { return *descriptors_; }

  static fs::path temp_file(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / "stillslam_test_place";
    fs::create_directories(dir);
    return dir / name;
  }

 private:
  // gtest suite-level fixture: trained once in SetUpTestSuite, released in TearDownTestSuite.
  static inline std::unique_ptr<std::vector<cv::Mat>> images_;
  static inline std::unique_ptr<std::vector<cv::Mat>> descriptors_;
  static inline std::unique_ptr<Vocabulary> vocabulary_;
};

TEST_F(VocabularyTest, TreeShape) {
  EXPECT_EQ(voc().k(), 8);
  EXPECT_EQ(voc().depth(), 4);
  EXPECT_EQ(voc().training_images(), 12u);
  std::uint64_t total = 0;
  for (const auto& d : descriptors()) total += static_cast<std::uint64_t>(d.rows);
  EXPECT_EQ(voc().training_descriptors(), total);
  // 12 x ~500 descriptors fill most of the 8^4 = 4096 leaves' parents but
  // leave many deep nodes with fewer than k distinct descriptors.
  EXPECT_GT(voc().size(), 2000u);
  EXPECT_LE(voc().size(), 4096u);
  for (WordId w = 0; w < voc().size(); ++w) {
    ASSERT_LE(voc().node_depth(voc().word_node(w)), 4);
    EXPECT_GE(voc().word_weight(w), 0.0);
    EXPECT_LE(voc().word_weight(w), std::log(12.0) + 1e-12);
  }
}

TEST_F(VocabularyTest, IdenticalImagesScoreOne) {
  const BowVector a = voc().transform(descriptors()[0]);
  const BowVector b = voc().transform(test::orb_of(images()[0]).descriptors);
  EXPECT_NEAR(a.l1_norm(), 1.0, 1e-12);
  EXPECT_GT(a.size(), 300u);
  EXPECT_DOUBLE_EQ(voc().score(a, b), 1.0);
}

TEST_F(VocabularyTest, SmallMotionScoresFarAboveUnrelatedImages) {
  for (int i = 0; i < 3; ++i) {
    const BowVector original = voc().transform(descriptors()[i]);
    const BowVector shifted = voc().transform(test::orb_of(test::moved(images()[i], 12, -8, 0)).descriptors);
    const BowVector rotated = voc().transform(test::orb_of(test::moved(images()[i], 0, 0, 4)).descriptors);
    double unrelated = 0;
    for (int j = 0; j < 12; ++j)
      if (j != i) unrelated = std::max(unrelated, voc().score(original, voc().transform(descriptors()[j])));
    const double s_shift = voc().score(original, shifted), s_rot = voc().score(original, rotated);
    std::printf("image %d: shifted %.3f rotated %.3f best unrelated %.3f\n", i, s_shift, s_rot, unrelated);
    EXPECT_GT(s_shift, 0.35);
    EXPECT_GT(s_rot, 0.35);
    EXPECT_LT(unrelated, 0.12);
    EXPECT_GT(std::min(s_shift, s_rot), 3.0 * unrelated);
  }
}

TEST_F(VocabularyTest, TrainingIsDeterministicForASeed) {
  const Vocabulary again = Vocabulary::train(descriptors(), test::small_options(0));
  EXPECT_TRUE(again == voc());
  const Vocabulary other = Vocabulary::train(descriptors(), test::small_options(1));
  EXPECT_FALSE(other == voc());
}

TEST_F(VocabularyTest, WordWeightsAreIdf) {
  // A word's weight is ln(N / images containing it): recount from the training images.
  std::vector<int> images_with(voc().size(), 0);
  for (const auto& d : descriptors()) {
    std::vector<bool> seen(voc().size(), false);
    for (int r = 0; r < d.rows; ++r) seen[voc().word_of(d.ptr<std::uint8_t>(r))] = true;
    for (std::size_t w = 0; w < seen.size(); ++w) images_with[w] += seen[w] ? 1 : 0;
  }
  for (WordId w = 0; w < voc().size(); ++w) {
    ASSERT_GT(images_with[w], 0);
    EXPECT_NEAR(voc().word_weight(w), std::log(12.0 / images_with[w]), 1e-12);
  }
}

TEST_F(VocabularyTest, DirectIndexGroupsFeaturesByNode) {
  BowVector bow;
  FeatureVector groups;
  voc().transform(descriptors()[0], bow, groups, 1);
  std::size_t total = 0;
  for (const auto& g : groups) {
    EXPECT_EQ(voc().node_depth(g.node), 1);
    total += g.features.size();
    for (auto f : g.features) {
      NodeId node = 0;
      voc().word_of(descriptors()[0].ptr<std::uint8_t>(static_cast<int>(f)), &node, 1);
      EXPECT_EQ(node, g.node);
    }
  }
  EXPECT_EQ(total, static_cast<std::size_t>(descriptors()[0].rows));
  EXPECT_LE(groups.size(), 8u);
  FeatureVector none;
  voc().transform(descriptors()[0], bow, none, 0);
  EXPECT_TRUE(none.empty());
}

TEST_F(VocabularyTest, DirectIndexMatchingAgreesWithBruteForce) {
  const cv::Mat query = descriptors()[1];
  const cv::Mat train = test::orb_of(test::moved(images()[1], 10, 6, 2)).descriptors;
  const auto brute = match_descriptors(query, train);
  // Level 1 splits the features into 8 groups, level 2 into up to 64; more
  // groups means fewer comparisons but more true matches split apart.
  for (const auto& [level, agreement] : {std::pair{1, 0.85}, std::pair{2, 0.7}}) {
    BowVector bq, bt;
    FeatureVector fq, ft;
    voc().transform(query, bq, fq, level);
    voc().transform(train, bt, ft, level);
    const auto fast = match_by_direct_index(query, fq, train, ft);
    std::size_t same = 0;
    for (const auto& m : brute)
      same += std::any_of(fast.begin(), fast.end(), [&](const cv::DMatch& f) {
        return f.queryIdx == m.queryIdx && f.trainIdx == m.trainIdx;
      });
    std::printf("level %d: brute force %zu matches, direct index %zu, shared %zu\n", level, brute.size(),
                fast.size(), same);
    EXPECT_GT(brute.size(), 150u);
    EXPECT_GT(static_cast<double>(same), agreement * static_cast<double>(brute.size()));
  }
}

TEST_F(VocabularyTest, SaveLoadRoundTrip) {
  const fs::path file = temp_file("round_trip.bin");
  voc().save(file);
  const Vocabulary loaded = Vocabulary::load(file);
  EXPECT_TRUE(loaded == voc());
  EXPECT_EQ(fs::file_size(file), 48 + voc().node_count() * 37 + voc().size() * 12 + 8);
  for (int i = 0; i < 3; ++i) {
    BowVector b1, b2;
    FeatureVector f1, f2;
    voc().transform(descriptors()[i], b1, f1, 2);
    loaded.transform(descriptors()[i], b2, f2, 2);
    EXPECT_EQ(b1.entries, b2.entries);
    ASSERT_EQ(f1.size(), f2.size());
    for (std::size_t g = 0; g < f1.size(); ++g) {
      EXPECT_EQ(f1.groups[g].node, f2.groups[g].node);
      EXPECT_EQ(f1.groups[g].features, f2.groups[g].features);
    }
  }
}

void expect_load_error(const fs::path& file, const std::string& fragment) {
  try {
    Vocabulary::load(file);
    ADD_FAILURE() << "loading " << file << " did not throw";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(file.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
  }
}

void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

TEST_F(VocabularyTest, OtherFormatsAndDamagedFilesAreRejected) {
  expect_load_error(temp_file("does_not_exist.bin"), "cannot open");
  expect_load_error(fs::temp_directory_path(), "not a file");
  const fs::path dbow = temp_file("ORBvoc.txt");
  write_bytes(dbow, "10 6  0 0\n0 0 252 188 188 242 169 109 85 143 187 171 0.0\n");
  expect_load_error(dbow, "DBoW2");
  const fs::path random = temp_file("random.bin");
  std::string noise(4096, '\0');
  cv::RNG rng(3);
  for (auto& c : noise) c = static_cast<char>(rng.uniform(0, 256));
  write_bytes(random, noise);
  expect_load_error(random, "not a stillslam vocabulary");
  write_bytes(temp_file("empty.bin"), "");
  expect_load_error(temp_file("empty.bin"), "not a stillslam vocabulary");

  const fs::path good = temp_file("good.bin");
  voc().save(good);
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const fs::path truncated = temp_file("truncated.bin");
  write_bytes(truncated, bytes.substr(0, bytes.size() / 2));
  expect_load_error(truncated, "is damaged (size");
  std::string flipped = bytes;
  flipped[bytes.size() / 2] = static_cast<char>(flipped[bytes.size() / 2] ^ 0x10);
  const fs::path damaged = temp_file("damaged.bin");
  write_bytes(damaged, flipped);
  expect_load_error(damaged, "checksum");
  std::string future = bytes;
  future[8] = 9;  // version
  const fs::path newer = temp_file("newer.bin");
  write_bytes(newer, future);
  expect_load_error(newer, "version 9");
}

TEST(Vocabulary, BadTrainingInput) {
  EXPECT_THROW(Vocabulary::train({}, VocabularyOptions{}), Error);
  EXPECT_THROW(Vocabulary::train({cv::Mat()}, VocabularyOptions{}), Error);
  EXPECT_THROW(Vocabulary::train({cv::Mat(5, 16, CV_8UC1, cv::Scalar(1))}, VocabularyOptions{}), Error);
  VocabularyOptions bad;
  bad.branching = 1;
  EXPECT_THROW(Vocabulary::train({cv::Mat(5, 32, CV_8UC1, cv::Scalar(1))}, bad), Error);
  EXPECT_THROW(Vocabulary().transform(cv::Mat(5, 32, CV_8UC1, cv::Scalar(1))), Error);
}

TEST(Vocabulary, IdenticalDescriptorsMakeASingleWord) {
  const Vocabulary v = Vocabulary::train({cv::Mat(20, 32, CV_8UC1, cv::Scalar(7))}, VocabularyOptions{});
  EXPECT_EQ(v.size(), 1u);
  EXPECT_EQ(v.node_count(), 1u);
  // Seen in every (the only) training image: idf 0, so the BoW vector is empty.
  EXPECT_TRUE(v.transform(cv::Mat(3, 32, CV_8UC1, cv::Scalar(7))).empty());
}

}  // namespace
}  // namespace stillslam
