#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <tuple>

#include "stillslam/features/brief_pattern.h"

namespace stillslam {

TEST(BriefPattern, IsDeterministicAndSeedDependent) {
  const BriefPattern a = BriefPattern::generate();
  const BriefPattern b = BriefPattern::generate();
  const BriefPattern c = BriefPattern::generate(7);
  int differ = 0;
  for (int i = 0; i < BriefPattern::kNumPairs; ++i) {
    EXPECT_EQ(a.pairs[i].x1, b.pairs[i].x1);
    EXPECT_EQ(a.pairs[i].y2, b.pairs[i].y2);
    differ += a.pairs[i].x1 != c.pairs[i].x1 || a.pairs[i].y1 != c.pairs[i].y1;
  }
  EXPECT_GT(differ, 200);
}

TEST(BriefPattern, PinnedChecksumKeepsVocabulariesCompatible) {
  // Any change of the generator changes every descriptor: vocabularies and
  // saved maps would silently stop matching. Change this number only on purpose.
  const BriefPattern p = BriefPattern::generate();
  long checksum = 0;
  for (int i = 0; i < BriefPattern::kNumPairs; ++i) {
    checksum = (checksum * 31 + p.pairs[i].x1 * 7 + p.pairs[i].y1 * 11 + p.pairs[i].x2 * 13 +
                p.pairs[i].y2 * 17) % 1000000007L;
  }
  EXPECT_EQ(checksum, -302161599L);
}

TEST(BriefPattern, InsideDiscGaussianAndNoDegeneratePairs) {
  const BriefPattern p = BriefPattern::generate();
  double sum = 0, sum2 = 0;
  std::set<std::tuple<int, int, int, int>> unique;
  for (const BriefPair& q : p.pairs) {
    for (auto [x, y] : {std::pair{q.x1, q.y1}, std::pair{q.x2, q.y2}}) {
      EXPECT_LE(x * x + y * y, BriefPattern::kRadius * BriefPattern::kRadius);
      sum += x + y;
      sum2 += x * x + y * y;
    }
    EXPECT_FALSE(q.x1 == q.x2 && q.y1 == q.y2);
    unique.insert({q.x1, q.y1, q.x2, q.y2});
  }
  const double n = 4.0 * BriefPattern::kNumPairs;
  const double mean = sum / n, sigma = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 0.6);
  // sigma = 31/5 = 6.2 before truncation; cutting the 2-D Gaussian at radius
  // 15 (2.42 sigma) leaves sigma * sqrt(0.835) = 5.66 per coordinate.
  EXPECT_NEAR(sigma, 5.66, 0.3);
  EXPECT_GE(unique.size(), 250u);
}

}  // namespace stillslam
