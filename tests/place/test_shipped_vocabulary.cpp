// The committed vocab/orb_vocabulary.bin on real images: the EuRoC clip (one
// place, nearly static camera) against coco128 photos (other places).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "place_fixtures.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/place/keyframe_database.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

const fs::path kVocabulary = fs::path(STILLSLAM_SOURCE_DIR) / "vocab" / "orb_vocabulary.bin";
const fs::path kShared = STILLSLAM_SHARED_DIR;

std::vector<fs::path> images_in(const fs::path& dir, std::size_t step, std::size_t count) {
  std::vector<fs::path> all;
  for (const auto& e : fs::directory_iterator(dir)) all.push_back(e.path());
  std::sort(all.begin(), all.end());
  std::vector<fs::path> out;
  for (std::size_t i = 0; i < all.size() && out.size() < count; i += step) out.push_back(all[i]);
  return out;
}

BowVector bow_of(const Vocabulary& voc, const fs::path& image) {
  const cv::Mat gray = cv::imread(image.string(), cv::IMREAD_GRAYSCALE);
  EXPECT_FALSE(gray.empty()) << image;
  return voc.transform(test::orb_of(gray, 1000).descriptors);
}

TEST(ShippedVocabulary, LoadsWithDocumentedShape) {
  Stopwatch clock;
  const Vocabulary voc = Vocabulary::load(kVocabulary);
  std::printf("loaded %s in %.1f ms\n", kVocabulary.c_str(), clock.elapsed_ms());
  EXPECT_EQ(voc.k(), 10);
  EXPECT_EQ(voc.depth(), 5);
  EXPECT_EQ(voc.size(), 81160u);
  EXPECT_EQ(voc.node_count(), 91394u);
  EXPECT_EQ(voc.weighting(), WordWeighting::kTfIdf);
  EXPECT_EQ(voc.training_images(), 509u);
  EXPECT_LT(fs::file_size(kVocabulary), 20'000'000u);
}

TEST(ShippedVocabulary, EurocFramesScoreAboveUnrelatedPhotosAndAreRetrieved) {
  const fs::path euroc = kShared / "data" / "euroc_V1_01_micro" / "mav0";
  const fs::path coco = kShared / "images" / "coco128" / "images" / "train2017";
  if (!fs::is_directory(euroc) || !fs::is_directory(coco))
    GTEST_SKIP() << "needs " << euroc << " and " << coco << " (the ../shared data folder)";
  const Vocabulary voc = Vocabulary::load(kVocabulary);
  const auto cam0 = images_in(euroc / "cam0" / "data", 10, 10);  // 0.5 s apart
  const auto cam1 = images_in(euroc / "cam1" / "data", 20, 5);
  const auto photos = images_in(coco, 5, 20);
  std::vector<BowVector> b0, b1, bp;
  for (const auto& f : cam0) b0.push_back(bow_of(voc, f));
  for (const auto& f : cam1) b1.push_back(bow_of(voc, f));
  for (const auto& f : photos) bp.push_back(bow_of(voc, f));

  double same_min = 1, unrelated_max = 0;
  for (std::size_t i = 0; i < b0.size(); ++i) {
    for (std::size_t j = i + 1; j < b0.size(); ++j) same_min = std::min(same_min, voc.score(b0[i], b0[j]));
    for (const auto& p : bp) unrelated_max = std::max(unrelated_max, voc.score(b0[i], p));
  }
  std::printf("EuRoC cam0 pairs 0.5-4.5 s apart: min %.3f; EuRoC vs coco: max %.3f\n", same_min, unrelated_max);
  EXPECT_GT(same_min, 0.07);
  EXPECT_LT(unrelated_max, 0.05);
  EXPECT_GT(same_min, 1.5 * unrelated_max);

  // cam1 frames (other camera of the rig) retrieve a cam0 frame first.
  KeyframeDatabase db;
  for (std::size_t i = 0; i < b0.size(); ++i) db.add(i, b0[i]);
  for (std::size_t i = 0; i < bp.size(); ++i) db.add(1000 + i, bp[i]);
  for (const auto& q : b1) {
    const auto r = db.query(q);
    ASSERT_FALSE(r.empty());
    EXPECT_LT(r[0].id, b0.size());
  }
}

}  // namespace
}  // namespace stillslam
