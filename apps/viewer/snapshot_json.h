#pragma once
// The publish layer's snapshots as the JSON the page reads (viewer.js):
// counters, the frame overlay and the atlas. Coordinates are rounded (0.1 px,
// 1 mm) to keep the event stream small.
#include <nlohmann/json.hpp>

#include "stillslam/publish/snapshots.h"

namespace stillslam::viewer {

struct RunStatus {
  double fps = 0;       // frames processed per second of wall time, recently
  double encode_ms = 0;  // the viewer's own work (JPEG + JSON) per update it encoded, mean so far
  bool paused = false;  // the run loop waits at the pause gate
  bool running = true;  // false once the run has ended
};

// The counters shown on the page and returned by /api/state; either snapshot
// may be null (nothing published yet).
nlohmann::json state_json(const FrameSnapshot* frame, const AtlasSnapshot* atlas, const RunStatus& status);

// Kept / tracked / removed features and the instances of one frame, without the image.
nlohmann::json overlay_json(const FrameSnapshot& frame);

// Per map: points, keyframe poses, covisibility edges, trajectory.
nlohmann::json atlas_json(const AtlasSnapshot& atlas);

}  // namespace stillslam::viewer
