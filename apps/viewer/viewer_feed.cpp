#include "viewer/viewer_feed.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "stillslam/core/base64.h"
#include "stillslam/core/stopwatch.h"


namespace stillslam::viewer {

namespace {

using Clock = std::chrono::steady_clock;

std::shared_ptr<const std::string> event(const char* name, const nlohmann::json& data) {
  return std::make_shared<const std::string>(std::string("event: ") + name + "\ndata: " + data.dump() + "\n\n");
}

Clock::duration period(double rate_hz) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate_hz));
}

}  // namespace

ViewerFeed::ViewerFeed(const ViewerOptions& options, const PauseGate* pause)
    : options_(options), pause_(pause), thread_([this] { run(); }) {}

ViewerFeed::~ViewerFeed() {
  stop_ = true;
  thread_.join();
}

void ViewerFeed::attach(const Publisher* publisher) {
  std::lock_guard lock(source_mutex_);
  publisher_ = publisher;
}

void ViewerFeed::set_groundtruth(const Trajectory& groundtruth) {
  std::lock_guard lock(source_mutex_);
  groundtruth_.emplace(groundtruth);
}

ViewerFeed::Newest ViewerFeed::read_newest(std::chrono::milliseconds wait) {
  std::unique_lock lock(source_mutex_);
  if (publisher_ != nullptr) {
    // The wait holds the lock: attach(nullptr) returns within `wait` and the
    // publisher is not read after that.
    const Publisher::FrameRead f = publisher_->wait_frame(newest_.frame_version, wait);
    const Publisher::AtlasRead a = publisher_->atlas();
    if (f.value && f.version != newest_.frame_version && groundtruth_ && f.value->has_pose) {
      groundtruth_->add(f.value->timestamp, f.value->T_world_cam.translation(), f.value->map_id);
    }
    if (f.value) newest_.frame = f.value, newest_.frame_version = f.version;
    if (a.value) newest_.atlas = a.value, newest_.atlas_version = a.version;
  } else {
    lock.unlock();
    std::this_thread::sleep_for(wait);
    lock.lock();
  }
  if (newest_.frame) measure_rate(newest_.frame->frame_id);
  return newest_;
}

void ViewerFeed::measure_rate(std::uint64_t frame_id) {
  const Clock::time_point now = Clock::now();
  rate_samples_.emplace_back(now, frame_id);
  while (rate_samples_.size() > 2 && now - rate_samples_.front().first > std::chrono::seconds(2)) {
    rate_samples_.pop_front();
  }
  const double seconds = std::chrono::duration<double>(now - rate_samples_.front().first).count();
  if (seconds > 0.2) {
    fps_ = static_cast<double>(frame_id - rate_samples_.front().second) / seconds;
  }
}

RunStatus ViewerFeed::status() const {
  RunStatus s;
  s.fps = fps_;
  s.encode_ms = frames_encoded_ > 0 ? encode_ms_total_ / static_cast<double>(frames_encoded_) : 0;
  s.paused = pause_ != nullptr && pause_->paused();
  s.running = publisher_ != nullptr;
  return s;
}

nlohmann::json ViewerFeed::state() const {
  std::lock_guard lock(source_mutex_);
  Newest n = newest_;
  if (publisher_ != nullptr) {
    // Newer than what the thread read last, when no page is connected.
    const Publisher::FrameRead f = publisher_->frame();
    const Publisher::AtlasRead a = publisher_->atlas();
    if (f.value) n.frame = f.value;
    if (a.value) n.atlas = a.value;
  }
  return state_json(n.frame.get(), n.atlas.get(), status());
}

std::vector<std::uint8_t> ViewerFeed::jpeg() const {
  std::shared_ptr<const FrameSnapshot> frame;
  {
    std::lock_guard lock(source_mutex_);
    frame = publisher_ != nullptr ? publisher_->frame().value : newest_.frame;
  }
  std::vector<std::uint8_t> bytes;
  if (frame && !frame->image.empty()) {
    cv::imencode(".jpg", frame->image, bytes, {cv::IMWRITE_JPEG_QUALITY, options_.jpeg_quality});
  }
  return bytes;
}

nlohmann::json ViewerFeed::atlas() const {
  std::shared_ptr<const AtlasSnapshot> atlas;
  {
    std::lock_guard lock(source_mutex_);
    atlas = publisher_ != nullptr ? publisher_->atlas().value : newest_.atlas;
  }
  return atlas ? atlas_json(*atlas) : nlohmann::json();
}

std::string ViewerFeed::encode_frame(const FrameSnapshot& frame) const {
  nlohmann::json data = overlay_json(frame);
  if (!frame.image.empty()) {
    std::vector<std::uint8_t> bytes;
    cv::imencode(".jpg", frame.image, bytes, {cv::IMWRITE_JPEG_QUALITY, options_.jpeg_quality});
    data["image"] = "data:image/jpeg;base64," + base64_encode(bytes);
  }
  return *event("frame", data);
}

nlohmann::json ViewerFeed::encode_atlas(const AtlasSnapshot& atlas) const {
  nlohmann::json data = atlas_json(atlas);
  std::lock_guard lock(source_mutex_);
  if (groundtruth_) {
    nlohmann::json points = nlohmann::json::array();
    for (const Eigen::Vector3d& c : groundtruth_->aligned(atlas.active_map_id, 3000)) {
      for (int i = 0; i < 3; ++i) points.push_back(std::round(c[i] * 1000.0) / 1000.0);
    }
    data["groundtruth"] = {{"map", atlas.active_map_id}, {"points", std::move(points)}};
  }
  return data;
}

void ViewerFeed::run() {
  // This thread's work waits for tracking's on a busy machine: ten nice
  // levels below the process (a per-thread setting on Linux, not process-wide).
  const int nice_now = ::getpriority(PRIO_PROCESS, 0);
  ::setpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()), std::min(19, nice_now + 10));
  const Clock::duration frame_period = period(options_.image_rate);
  const Clock::duration map_period = period(options_.map_rate);
  Clock::time_point next_frame{}, next_map{};
  std::uint64_t sent_frame_version = 0, sent_atlas_version = 0;
  RunStatus sent_status;
  ViewerUpdate update;
  while (!stop_) {
    const Newest n = read_newest(std::chrono::milliseconds(50));
    if (clients_ <= 0) continue;
    RunStatus s;
    {
      std::lock_guard lock(source_mutex_);
      s = status();
    }
    const Clock::time_point now = Clock::now();
    const Stopwatch encoding;
    bool encoded = false;
    bool changed = false;
    if (n.frame && n.frame_version != sent_frame_version && now >= next_frame) {
      update.frame = std::make_shared<const std::string>(encode_frame(*n.frame));
      ++update.frame_seq;
      sent_frame_version = n.frame_version;
      next_frame = now + frame_period;
      changed = encoded = true;
    }
    if (n.atlas && n.atlas_version != sent_atlas_version && now >= next_map) {
      update.map = event("map", encode_atlas(*n.atlas));
      ++update.map_seq;
      sent_atlas_version = n.atlas_version;
      next_map = now + map_period;
      changed = encoded = true;
    }
    if (encoded) {
      std::lock_guard lock(source_mutex_);
      encode_ms_total_ += encoding.elapsed_ms();
      ++frames_encoded_;
      s.encode_ms = encode_ms_total_ / static_cast<double>(frames_encoded_);
    }
    // The counters follow the frame shown and the pause / end of the run.
    if (changed || s.paused != sent_status.paused || s.running != sent_status.running || !update.state) {
      update.state = event("state", state_json(n.frame.get(), n.atlas.get(), s));
      ++update.state_seq;
      sent_status = s;
      changed = true;
    }
    if (changed) updates_.publish(std::make_shared<const ViewerUpdate>(update));
  }
}

}  // namespace stillslam::viewer
