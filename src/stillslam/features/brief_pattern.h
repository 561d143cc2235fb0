#pragma once
// The 256 point-pair sampling pattern of the BRIEF descriptor.
//
// Generated, not copied: following Calonder et al.'s BRIEF "G II" strategy,
// both points of each pair are drawn i.i.d. from an isotropic Gaussian with
// sigma = S/5 (S = 31, the patch size), here with a fixed-seed Mersenne
// twister and our own Box-Muller transform so the pattern is identical on
// every platform and standard library. Points are rounded to integers and
// redrawn if they fall outside the radius-15 disc (so any rotation of the
// pattern stays inside the orientation patch) or if both points coincide.
// Descriptors are therefore NOT compatible with ORB-SLAM's / OpenCV's learned
// table: vocabularies must be trained on our own descriptors.
#include <array>
#include <cstdint>

namespace stillslam {

struct BriefPair {
  std::int8_t x1, y1, x2, y2;
};

struct BriefPattern {
  static constexpr int kNumPairs = 256;
  static constexpr int kRadius = 15;
  std::array<BriefPair, kNumPairs> pairs{};

  // Default seed gives the project's pattern; other seeds for experiments.
  static BriefPattern generate(std::uint64_t seed = kDefaultSeed);
  static constexpr std::uint64_t kDefaultSeed = 0x5eed0b1efULL;
};

}  // namespace stillslam
