#include "stamp_pairer.h"

#include <cmath>
#include <cstdlib>

#include <spdlog/fmt/fmt.h>

#include "stillslam/core/error.h"

namespace stillslam::ros2 {

void PairingOptions::check() const {
  if (!(tolerance_s >= 0 && tolerance_s <= 1)) {
    throw Error(fmt::format("--pair-tolerance {} is out of range 0..1 s", tolerance_s));
  }
  if (max_waiting < 1) throw Error("pairing needs room for at least one waiting message per topic");
}

StampPairer::StampPairer(const PairingOptions& options)
    : tolerance_ns_(std::llround(options.tolerance_s * 1e9)), max_waiting_(options.max_waiting) {
  options.check();
}

void StampPairer::drop_older(int side, std::int64_t stamp_ns) {
  auto& q = waiting_[side];
  while (!q.empty() && q.front().stamp_ns < stamp_ns) {
    q.pop_front();
    ++unpaired_[side];
  }
}

std::optional<ImagePair> StampPairer::add(StampedImage image, int side) {
  const int other = 1 - side;
  auto& candidates = waiting_[other];
  auto best = candidates.end();
  for (auto it = candidates.begin(); it != candidates.end(); ++it) {
    const std::int64_t dt = std::llabs(it->stamp_ns - image.stamp_ns);
    if (dt <= tolerance_ns_ && (best == candidates.end() || dt < std::llabs(best->stamp_ns - image.stamp_ns))) best = it;
  }
  if (best != candidates.end()) {
    StampedImage partner = std::move(*best);
    candidates.erase(best);
    drop_older(other, partner.stamp_ns);
    drop_older(side, image.stamp_ns);
    ++pairs_;
    if (side == 0) return ImagePair{std::move(image), std::move(partner)};
    return ImagePair{std::move(partner), std::move(image)};
  }
  drop_older(other, image.stamp_ns - tolerance_ns_);
  auto& own = waiting_[side];
  own.push_back(std::move(image));
  while (own.size() > max_waiting_) {
    own.pop_front();
    ++unpaired_[side];
  }
  return std::nullopt;
}

}  // namespace stillslam::ros2
