#pragma once
// splitmix64: a tiny generator that gives the same numbers on every platform
// and standard library (std:: distributions do not), so a seed means the same
// scene everywhere.
#include <cstdint>
#include <numbers>

namespace stillslam::sim {

// A full turn: random phases and angles, and the periodic camera and people
// motions (one name for the whole module, so its files share unity batches).
inline constexpr double kTwoPi = 2 * std::numbers::pi;

class SplitMix {
 public:
  explicit SplitMix(std::uint64_t seed) : state_(seed * 0x9E3779B97F4A7C15ULL + 0x632BE59BD9B4E019ULL) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  // Uniform in [a, b).
  double uniform(double a, double b) {
    return a + (b - a) * (static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0));
  }

 private:
  std::uint64_t state_;
};

}  // namespace stillslam::sim
