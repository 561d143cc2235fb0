#pragma once
// The HTTP viewer of `stillslam run --viewer`: serves the page (embedded,
// web_files.h), the counters (/api/state), the event stream (/api/events,
// server-sent events from ViewerFeed), the newest frame (/api/frame.jpg), the
// atlas (/api/map) and the pause / step / resume buttons (POST /api/pause,
// /api/step, /api/resume), on its own threads. It reads the publish layer
// only: never the map, never waiting for tracking.
#include <memory>
#include <string>

#include "stillslam/core/trajectory.h"
#include "stillslam/publish/publisher.h"
#include "stillslam/settings/viewer_options.h"
#include "stillslam/system/pause_gate.h"

namespace stillslam::viewer {

class ViewerServer {
 public:
  // Listens at once (options.port 0: any free port); throws stillslam::Error
  // when it cannot. `pause` may be null (no pause buttons) and must outlive
  // the server.
  ViewerServer(const ViewerOptions& options, PauseGate* pause);
  ~ViewerServer();  // closes every connection and joins the threads
  ViewerServer(const ViewerServer&) = delete;
  ViewerServer& operator=(const ViewerServer&) = delete;

  int port() const;
  std::string url() const;  // http://HOST:PORT/

  // Starts showing what `publisher` publishes (null: stops reading it; the
  // page keeps the last state).
  void attach(const Publisher* publisher);
  // Ground truth to draw in the active map (aligned with its trajectory).
  void set_groundtruth(const Trajectory& groundtruth);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// True for addresses only this machine can reach (127.x, ::1, localhost).
bool is_loopback_host(const std::string& host);

}  // namespace stillslam::viewer
