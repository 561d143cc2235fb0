#include "stillslam/features/brief_pattern.h"

#include <cmath>
#include <numbers>
#include <random>

namespace stillslam {
namespace {

// Box-Muller on std::mt19937_64, whose output sequence is fixed by the
// standard (std::normal_distribution is not), so the pattern is portable.
class PortableGaussian {
 public:
  explicit PortableGaussian(std::uint64_t seed) : rng_(seed) {}
  double operator()(double sigma) {
    // Uniform in (0, 1]: 53 random bits.
    const double u1 = (static_cast<double>(rng_() >> 11) + 1.0) / 9007199254740992.0;
    const double u2 = static_cast<double>(rng_() >> 11) / 9007199254740992.0;
    return sigma * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  std::mt19937_64 rng_;
};

struct Point {
  int x, y;
};

Point sample_point(PortableGaussian& gauss) {
  constexpr double kSigma = 31.0 / 5.0;  // BRIEF G II: sigma^2 = S^2 / 25
  constexpr int r2 = BriefPattern::kRadius * BriefPattern::kRadius;
  while (true) {
    const int x = static_cast<int>(std::lround(gauss(kSigma)));
    const int y = static_cast<int>(std::lround(gauss(kSigma)));
    if (x * x + y * y <= r2) return {x, y};
  }
}

}  // namespace

BriefPattern BriefPattern::generate(std::uint64_t seed) {
  PortableGaussian gauss(seed);
  BriefPattern pattern;
  for (auto& pair : pattern.pairs) {
    Point a{}, b{};
    do {
      a = sample_point(gauss);
      b = sample_point(gauss);
    } while (a.x == b.x && a.y == b.y);
    pair = {static_cast<std::int8_t>(a.x), static_cast<std::int8_t>(a.y),
            static_cast<std::int8_t>(b.x), static_cast<std::int8_t>(b.y)};
  }
  return pattern;
}

}  // namespace stillslam
