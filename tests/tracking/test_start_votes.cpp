// Which first-keyframe keypoints the start checks keep (tracking/start_votes.h).
#include <gtest/gtest.h>

#include "stillslam/tracking/start_votes.h"

namespace stillslam {
namespace {

// One check over 4 keypoints: 'i' matched as an inlier, 'o' matched off the
// camera motion (left out), '-' not matched.
InitialViewCheck check(const char* votes) {
  InitialViewCheck c;
  c.accepted = true;
  for (const char* v = votes; *v != 0; ++v) {
    c.confirmed.push_back(*v == 'i');
    c.keep.push_back(*v != 'o');
  }
  return c;
}

TEST(StartVotes, UnmaskedKeepsWhatMoreChecksConfirmedThanRejected) {
  StartVotes votes;
  votes.reset(5);
  // keypoint: 0 static, inlier every time; 1 static, one miss of the bound;
  // 2 a walker, off the motion from the second frame; 3 never matched;
  // 4 one inlier, one miss.
  votes.add(check("iii-i"));
  votes.add(check("ioo-o"));
  votes.add(check("iio--"));
  const std::vector<bool> keep = votes.keep(true);
  EXPECT_EQ(keep, (std::vector<bool>{true, true, false, false, false}));
}

TEST(StartVotes, MaskedDropsWhatAnyCheckRejected) {
  StartVotes votes;
  votes.reset(4);
  votes.add(check("ii-i"));
  votes.add(check("io-i"));
  votes.add(check("ii--"));
  // With masks an unmatched keypoint stays (its mask was checked), one miss drops it.
  EXPECT_EQ(votes.keep(false), (std::vector<bool>{true, false, true, true}));
}

TEST(StartVotes, ResetForgetsTheLastCandidate) {
  StartVotes votes;
  votes.reset(2);
  votes.add(check("oo"));
  votes.reset(2);
  votes.add(check("ii"));
  EXPECT_EQ(votes.keep(true), (std::vector<bool>{true, true}));
  EXPECT_EQ(votes.keep(false), (std::vector<bool>{true, true}));
}

}  // namespace
}  // namespace stillslam
