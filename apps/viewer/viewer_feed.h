#pragma once
// The viewer's one encoding thread: it reads the publish layer's newest
// snapshots (never the map), and while a page is connected turns them into
// server-sent events at most Viewer.image_rate times a second (state + frame
// with its JPEG) and Viewer.map_rate times a second (atlas). Stale snapshots
// are skipped, so neither the thread nor a slow page can hold tracking up;
// each page connection sends the newest update it has not sent yet.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include "stillslam/core/latest_value.h"
#include "stillslam/publish/publisher.h"
#include "stillslam/settings/viewer_options.h"
#include "stillslam/system/pause_gate.h"
#include "viewer/groundtruth_overlay.h"
#include "viewer/snapshot_json.h"

namespace stillslam::viewer {

// One SSE message per part ("event: NAME\ndata: JSON\n\n"); a part's
// sequence number changes when it does.
struct ViewerUpdate {
  std::uint64_t state_seq = 0, frame_seq = 0, map_seq = 0;
  std::shared_ptr<const std::string> state, frame, map;
};

class ViewerFeed {
 public:
  // `pause` may be null (no pause buttons); it must outlive the feed.
  ViewerFeed(const ViewerOptions& options, const PauseGate* pause);
  ~ViewerFeed();
  ViewerFeed(const ViewerFeed&) = delete;
  ViewerFeed& operator=(const ViewerFeed&) = delete;

  // Starts reading `publisher` (null: stops reading it; returns once the
  // thread has let go of it). The last snapshots read stay available.
  void attach(const Publisher* publisher);
  // Ground truth to draw, aligned with the active map's trajectory.
  void set_groundtruth(const Trajectory& groundtruth);

  const LatestValue<ViewerUpdate>& updates() const { return updates_; }
  // Page connections: the thread encodes only while there is one.
  void client_connected() { ++clients_; }
  void client_disconnected() { --clients_; }

  // The counters from the newest snapshots (/api/state), JPEG-free and cheap.
  nlohmann::json state() const;
  // The newest frame's image as JPEG (empty before the first frame).
  std::vector<std::uint8_t> jpeg() const;
  // The newest atlas snapshot as JSON (null before the first one).
  nlohmann::json atlas() const;

 private:
  struct Newest {
    std::shared_ptr<const FrameSnapshot> frame;
    std::uint64_t frame_version = 0;
    std::shared_ptr<const AtlasSnapshot> atlas;
    std::uint64_t atlas_version = 0;
  };
  void run();
  Newest read_newest(std::chrono::milliseconds wait);
  RunStatus status() const;
  void measure_rate(std::uint64_t frame_id);
  std::string encode_frame(const FrameSnapshot& frame) const;
  nlohmann::json encode_atlas(const AtlasSnapshot& atlas) const;

  ViewerOptions options_;
  const PauseGate* pause_;
  std::atomic<int> clients_{0};
  std::atomic<bool> stop_{false};
  LatestValue<ViewerUpdate> updates_;

  mutable std::mutex source_mutex_;  // publisher_ and newest_
  const Publisher* publisher_ = nullptr;
  Newest newest_;
  std::optional<GroundTruthOverlay> groundtruth_;
  std::deque<std::pair<std::chrono::steady_clock::time_point, std::uint64_t>> rate_samples_;  // (time, frame id)
  double fps_ = 0;
  double encode_ms_total_ = 0;  // frame and map events encoded so far
  std::uint64_t frames_encoded_ = 0;

  std::thread thread_;  // last: starts after the members above exist
};

}  // namespace stillslam::viewer
