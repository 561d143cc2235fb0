#include <gtest/gtest.h>

#include <thread>

#include "place_fixtures.h"
#include "stillslam/place/keyframe_database.h"

namespace stillslam {
namespace {

PlaceQueryOptions top(std::size_t n) {
  PlaceQueryOptions o;
  o.max_results = n;
  return o;
}

BowVector bow(std::vector<std::pair<WordId, double>> pairs) {
  BowVector v = make_bow_vector(std::move(pairs));
  v.normalize_l1();
  return v;
}

TEST(KeyframeDatabase, QueryReturnsIdsBestFirstWithL1Scores) {
  KeyframeDatabase db;
  const BowVector query = bow({{1, 1}, {2, 1}, {3, 1}, {4, 1}});
  const BowVector kf10 = bow({{1, 1}, {2, 1}, {3, 1}, {5, 1}});  // 3 of 4 words
  const BowVector kf11 = bow({{1, 1}, {6, 1}, {7, 1}, {8, 1}});  // 1 of 4
  const BowVector kf12 = bow({{1, 1}, {2, 1}, {3, 1}, {4, 1}});  // identical
  const BowVector kf13 = bow({{9, 1}});                          // nothing shared
  const BowVector kf14 = bow({{1, 1}, {2, 1}, {7, 1}, {8, 1}});  // 2 of 4
  db.add(10, kf10);
  db.add(11, kf11);
  db.add(12, kf12);
  db.add(13, kf13);
  db.add(14, kf14);
  EXPECT_EQ(db.size(), 5u);

  const auto r = db.query(query);
  ASSERT_EQ(r.size(), 4u);  // 13 shares no word
  EXPECT_EQ(r[0].id, 12u);
  EXPECT_EQ(r[1].id, 10u);
  EXPECT_EQ(r[2].id, 14u);
  EXPECT_EQ(r[3].id, 11u);
  EXPECT_NEAR(r[0].score, 1.0, 1e-12);
  EXPECT_NEAR(r[1].score, 0.75, 1e-12);
  EXPECT_NEAR(r[2].score, 0.5, 1e-12);
  EXPECT_NEAR(r[3].score, 0.25, 1e-12);
  EXPECT_EQ(r[1].common_words, 3);
  for (const auto& c : r) {
    const BowVector& v = c.id == 10 ? kf10 : c.id == 11 ? kf11 : c.id == 12 ? kf12 : kf14;
    EXPECT_NEAR(c.score, l1_score(query, v), 1e-12);
  }

  PlaceQueryOptions o;
  o.max_results = 2;
  o.exclude = [](KeyframeId id) { return id == 12; };
  const auto top = db.query(query, o);
  ASSERT_EQ(top.size(), 2u);
  EXPECT_EQ(top[0].id, 10u);
  EXPECT_EQ(top[1].id, 14u);

  PlaceQueryOptions strict;
  strict.min_score = 0.6;
  EXPECT_EQ(db.query(query, strict).size(), 2u);
  PlaceQueryOptions common;
  common.min_common_words = 2;
  EXPECT_EQ(db.query(query, common).size(), 3u);
  // Most shared words: 4 (keyframe 12); 0.6 * 4 = 2.4 keeps 12 and 10 (3 words).
  PlaceQueryOptions ratio;
  ratio.min_common_words_ratio = 0.6;
  const auto r_ratio = db.query(query, ratio);
  ASSERT_EQ(r_ratio.size(), 2u);
  EXPECT_EQ(r_ratio[1].id, 10u);
  // The ratio is relative to the best non-excluded candidate: without 12 the
  // best shares 3 words, and 0.6 * 3 = 1.8 keeps 10 and 14 (2 words).
  ratio.exclude = [](KeyframeId id) { return id == 12; };
  const auto r_excl = db.query(query, ratio);
  ASSERT_EQ(r_excl.size(), 2u);
  EXPECT_EQ(r_excl[0].id, 10u);
  EXPECT_EQ(r_excl[1].id, 14u);
}

TEST(KeyframeDatabase, EraseReplaceAndTies) {
  KeyframeDatabase db;
  db.add(5, bow({{1, 1}, {2, 1}}));
  db.add(3, bow({{1, 1}, {2, 1}}));
  db.add(4, bow({{1, 1}, {9, 1}}));
  auto r = db.query(bow({{1, 1}, {2, 1}}));
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r[0].id, 3u);  // equal scores: lower id first
  EXPECT_EQ(r[1].id, 5u);
  db.erase(3);
  db.erase(99);  // unknown: no-op
  EXPECT_FALSE(db.contains(3));
  r = db.query(bow({{1, 1}, {2, 1}}));
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].id, 5u);
  // Replacing keyframe 5 removes its old words from the index.
  db.add(5, bow({{7, 1}}));
  r = db.query(bow({{1, 1}, {2, 1}}));
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].id, 4u);
  EXPECT_EQ(db.query(bow({{7, 1}}))[0].id, 5u);
  db.clear();
  EXPECT_EQ(db.size(), 0u);
  EXPECT_TRUE(db.query(bow({{1, 1}})).empty());
  EXPECT_TRUE(db.query(BowVector{}).empty());
}

TEST(KeyframeDatabase, FindsTheMovedImageAmongScenes) {
  const auto images = test::scene_images(10);
  const auto descriptors = test::descriptors_of(images);
  const Vocabulary voc = Vocabulary::train(descriptors, test::small_options());
  KeyframeDatabase db;
  for (std::size_t i = 0; i < images.size(); ++i) db.add(100 + i, voc.transform(descriptors[i]));
  for (std::size_t i = 0; i < images.size(); i += 3) {
    const BowVector q = voc.transform(test::orb_of(test::moved(images[i], -9, 5, 3)).descriptors);
    const auto r = db.query(q, top(3));
    ASSERT_EQ(r.size(), 3u);
    EXPECT_EQ(r[0].id, 100 + i);
    EXPECT_GT(r[0].score, 2.5 * r[1].score);
  }
}

TEST(KeyframeDatabase, ConcurrentAddAndQuery) {
  KeyframeDatabase db;
  std::thread writer([&] {
    for (KeyframeId id = 0; id < 500; ++id) db.add(id, bow({{static_cast<WordId>(id % 50), 1}, {1000, 1}}));
  });
  std::size_t seen = 0;
  for (int i = 0; i < 200; ++i) seen = std::max(seen, db.query(bow({{1000, 1}}), top(0)).size());
  writer.join();
  EXPECT_EQ(db.query(bow({{1000, 1}}), top(0)).size(), 500u);
  EXPECT_LE(seen, 500u);
}

}  // namespace
}  // namespace stillslam
