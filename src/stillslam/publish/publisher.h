#pragma once
// The publish layer: latest-value slots (core/latest_value.h) for the frame
// and the atlas snapshots. The tracking thread publishes; any number of
// readers take the newest snapshot, or wait for a newer one, without touching
// the map lock and without slowing the writer (a publish swaps a pointer).
#include <chrono>
#include <cstdint>
#include <memory>

#include "stillslam/core/latest_value.h"
#include "stillslam/publish/snapshots.h"

namespace stillslam {

struct PublishOptions {
  // The atlas snapshot is taken after a keyframe, a new map or a merge, and
  // at least every this many frames (local mapping and loop closing move
  // points in between). 0: only on those events.
  int map_every_frames = 10;
  // Covisibility edges in the snapshot: weight (shared points) at least this.
  int min_covisibility_weight = 100;
  void check() const;
};

class Publisher {
 public:
  using FrameRead = LatestValue<FrameSnapshot>::Read;
  using AtlasRead = LatestValue<AtlasSnapshot>::Read;

  void publish_frame(std::shared_ptr<const FrameSnapshot> frame) { frame_.publish(std::move(frame)); }
  void publish_atlas(std::shared_ptr<const AtlasSnapshot> atlas) { atlas_.publish(std::move(atlas)); }

  FrameRead frame() const { return frame_.read(); }
  AtlasRead atlas() const { return atlas_.read(); }
  // Waits until a frame newer than version `seen` is published or `timeout` passes.
  FrameRead wait_frame(std::uint64_t seen, std::chrono::milliseconds timeout) const {
    return frame_.wait_newer(seen, timeout);
  }

 private:
  LatestValue<FrameSnapshot> frame_;
  LatestValue<AtlasSnapshot> atlas_;
};

}  // namespace stillslam
