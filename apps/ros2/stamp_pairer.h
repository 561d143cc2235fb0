#pragma once
// Pairs the messages of two image topics (left/right, or colour/depth) by
// header stamp: a message pairs with the waiting message of the other topic
// closest in stamp, within the tolerance. Each topic's stamps are taken to
// grow (a camera driver's do), so a waiting message older than a pair just
// made, or older than the other topic's newest message by more than the
// tolerance, can never pair: it is dropped and counted. At most `max_waiting`
// messages wait per topic (the oldest goes first), so memory stays bounded
// when one topic stops.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>

#include <opencv2/core.hpp>

namespace stillslam::ros2 {

struct PairingOptions {
  double tolerance_s = 0.01;   // --pair-tolerance; 0..1 s
  std::size_t max_waiting = 10;
  void check() const;
};

struct StampedImage {
  std::int64_t stamp_ns = 0;
  cv::Mat image;
};

struct ImagePair {
  StampedImage first, second;  // left and right, or colour and depth
};

class StampPairer {
 public:
  explicit StampPairer(const PairingOptions& options);
  std::optional<ImagePair> add_first(StampedImage image) { return add(std::move(image), 0); }
  std::optional<ImagePair> add_second(StampedImage image) { return add(std::move(image), 1); }
  // Messages dropped without a partner, per topic.
  std::size_t unpaired_first() const { return unpaired_[0]; }
  std::size_t unpaired_second() const { return unpaired_[1]; }
  std::size_t pairs() const { return pairs_; }

 private:
  std::optional<ImagePair> add(StampedImage image, int side);
  // Drops the messages of `side` older than `stamp_ns`.
  void drop_older(int side, std::int64_t stamp_ns);

  std::int64_t tolerance_ns_;
  std::size_t max_waiting_;
  std::deque<StampedImage> waiting_[2];
  std::size_t unpaired_[2] = {0, 0};
  std::size_t pairs_ = 0;
};

}  // namespace stillslam::ros2
