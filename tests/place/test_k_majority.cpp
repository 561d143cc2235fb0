#include <gtest/gtest.h>

#include "stillslam/place/k_majority.h"

namespace stillslam::place_detail {
namespace {

Descriptor256 random_descriptor(std::mt19937_64& rng) { return {rng(), rng(), rng(), rng()}; }

Descriptor256 flip_bits(Descriptor256 d, int bits, std::mt19937_64& rng) {
  for (int i = 0; i < bits; ++i) {
    const auto b = rng() % 256;
    d[b / 64] ^= std::uint64_t{1} << (b % 64);
  }
  return d;
}

TEST(KMajority, MajorityCentreVotesPerBit) {
  BitMajority m;
  m.add({0b0111, 0, 0, 1});
  m.add({0b0011, 0, 0, 0});
  m.add({0b0001, 0, 0, 0});
  const Descriptor256 c = m.centre();
  EXPECT_EQ(c[0], 0b0011u);  // bit 0: 3/3, bit 1: 2/3, bit 2: 1/3
  EXPECT_EQ(c[3], 0u);
  EXPECT_EQ(m.size(), 3);
}

TEST(KMajority, HammingDistance) {
  EXPECT_EQ(hamming({0, 0, 0, 0}, {~0ULL, 0, 1, 3}), 64 + 1 + 2);
}

TEST(KMajority, RecoversSeparatedGroups) {
  std::mt19937_64 gen(7);
  std::vector<Descriptor256> centres, data;
  for (int c = 0; c < 4; ++c) centres.push_back(random_descriptor(gen));
  std::vector<int> truth;
  for (int i = 0; i < 400; ++i) {
    truth.push_back(i % 4);
    data.push_back(flip_bits(centres[i % 4], 12, gen));
  }
  std::vector<std::uint32_t> members(data.size());
  for (std::uint32_t i = 0; i < members.size(); ++i) members[i] = i;
  std::mt19937_64 rng(1);
  const auto clusters = cluster_k_majority(data, members, 4, 10, rng);
  ASSERT_EQ(clusters.size(), 4u);
  for (const auto& c : clusters) {
    ASSERT_EQ(c.members.size(), 100u);
    const int label = truth[c.members.front()];
    for (auto m : c.members) EXPECT_EQ(truth[m], label);
    // The majority of 100 noisy copies is the true centre.
    EXPECT_EQ(hamming(c.centre, centres[label]), 0);
  }
}

TEST(KMajority, FewerDistinctDescriptorsThanK) {
  std::mt19937_64 gen(3);
  const Descriptor256 a = random_descriptor(gen), b = random_descriptor(gen);
  const std::vector<Descriptor256> data{a, b, a, a, b};
  const std::vector<std::uint32_t> members{0, 1, 2, 3, 4};
  std::mt19937_64 rng(0);
  const auto clusters = cluster_k_majority(data, members, 10, 10, rng);
  ASSERT_EQ(clusters.size(), 2u);
  EXPECT_EQ(clusters[0].members.size() + clusters[1].members.size(), 5u);
}

TEST(KMajority, DeterministicForSeed) {
  std::mt19937_64 gen(11);
  std::vector<Descriptor256> data;
  for (int i = 0; i < 300; ++i) data.push_back(random_descriptor(gen));
  std::vector<std::uint32_t> members(data.size());
  for (std::uint32_t i = 0; i < members.size(); ++i) members[i] = i;
  std::mt19937_64 r1(5), r2(5);
  const auto c1 = cluster_k_majority(data, members, 8, 10, r1);
  const auto c2 = cluster_k_majority(data, members, 8, 10, r2);
  ASSERT_EQ(c1.size(), c2.size());
  for (std::size_t i = 0; i < c1.size(); ++i) {
    EXPECT_EQ(c1[i].centre, c2[i].centre);
    EXPECT_EQ(c1[i].members, c2[i].members);
  }
}

}  // namespace
}  // namespace stillslam::place_detail
