#include "viewer/snapshot_json.h"

#include <algorithm>
#include <cmath>

namespace stillslam::viewer {

namespace {

// To `decimals` places; dividing by a power of ten gives the double nearest
// the decimal, which the JSON writer prints short.
double rounded(double v, int decimals) {
  const double scale = std::pow(10.0, decimals);
  return std::round(v * scale) / scale;
}

nlohmann::json points_2d(const std::vector<cv::Point2f>& points) {
  nlohmann::json out = nlohmann::json::array();
  for (const cv::Point2f& p : points) {
    out.push_back(rounded(p.x, 1));
    out.push_back(rounded(p.y, 1));
  }
  return out;
}

// Position and orientation quaternion (x, y, z, qx, qy, qz, qw).
nlohmann::json pose_json(const Eigen::Isometry3d& T_world_cam) {
  const Eigen::Vector3d t = T_world_cam.translation();
  const Eigen::Quaterniond q(T_world_cam.rotation());
  return {rounded(t.x(), 3), rounded(t.y(), 3), rounded(t.z(), 3), rounded(q.x(), 4),
          rounded(q.y(), 4), rounded(q.z(), 4), rounded(q.w(), 4)};
}

nlohmann::json map_json(const MapSnapshot& map) {
  nlohmann::json points = nlohmann::json::array();
  for (const Eigen::Vector3f& p : map.points) {
    for (int i = 0; i < 3; ++i) points.push_back(rounded(p[i], 3));
  }
  nlohmann::json keyframes = nlohmann::json::array();
  for (const MapSnapshot::KeyFrame& kf : map.keyframes) {
    for (const nlohmann::json& v : pose_json(kf.T_world_cam)) keyframes.push_back(v);
  }
  nlohmann::json edges = nlohmann::json::array();
  for (const auto& [a, b] : map.covisibility) {
    edges.push_back(a);
    edges.push_back(b);
  }
  nlohmann::json trajectory = nlohmann::json::array();
  for (const Eigen::Vector3d& c : map.trajectory) {
    for (int i = 0; i < 3; ++i) trajectory.push_back(rounded(c[i], 3));
  }
  return {{"id", map.map_id},       {"active", map.active},          {"points", std::move(points)},
          {"keyframes", std::move(keyframes)}, {"covisibility", std::move(edges)},
          {"trajectory", std::move(trajectory)}};
}

}  // namespace

nlohmann::json state_json(const FrameSnapshot* frame, const AtlasSnapshot* atlas, const RunStatus& status) {
  nlohmann::json s;
  s["fps"] = rounded(status.fps, 1);
  s["viewer_encode_ms"] = rounded(status.encode_ms, 2);
  s["paused"] = status.paused;
  s["running"] = status.running;
  if (frame) {
    const auto tracked = std::count(frame->tracked.begin(), frame->tracked.end(), true);
    const auto dynamic = std::count_if(frame->instances.begin(), frame->instances.end(),
                                       [](const FrameSnapshot::Instance& i) { return i.dynamic; });
    s["frame"] = frame->index;
    s["frame_id"] = frame->frame_id;
    s["timestamp"] = frame->timestamp;
    s["state"] = frame->state;
    s["reason"] = frame->reason;
    s["keyframe"] = frame->keyframe;
    s["features_kept"] = frame->keypoints.size();
    s["features_tracked"] = tracked;
    s["features_removed"] = frame->removed_keypoints.size();
    s["detections"] = frame->detections;
    s["dynamic_instances"] = dynamic;
    s["mask_coverage"] = frame->mask_coverage;
    s["held_coverage"] = frame->held_coverage;
    s["frame_ms"] = rounded(frame->total_ms, 2);
    s["map_id"] = frame->map_id;
    s["pose"] = frame->has_pose ? pose_json(frame->T_world_cam) : nlohmann::json();
  }
  if (atlas) {
    s["map_points"] = atlas->num_points();
    s["keyframes"] = atlas->num_keyframes();
    s["maps"] = atlas->maps.size();
    s["active_map"] = atlas->active_map_id;
    s["loops_closed"] = atlas->loops_closed;
    s["merges"] = atlas->merges;
    s["new_maps"] = atlas->new_maps;
    s["map_frame_id"] = atlas->frame_id;
  }
  return s;
}

nlohmann::json overlay_json(const FrameSnapshot& frame) {
  nlohmann::json tracked = nlohmann::json::array();
  for (bool t : frame.tracked) tracked.push_back(t ? 1 : 0);
  nlohmann::json instances = nlohmann::json::array();
  for (const FrameSnapshot::Instance& i : frame.instances) {
    nlohmann::json outline = nlohmann::json::array();
    for (const cv::Point& p : i.outline) {
      outline.push_back(p.x);
      outline.push_back(p.y);
    }
    instances.push_back({{"class", i.class_name},
                         {"class_id", i.class_id},
                         {"score", rounded(i.score, 3)},
                         {"box", {i.box.x, i.box.y, i.box.width, i.box.height}},
                         {"outline", std::move(outline)},
                         {"dynamic", i.dynamic}});
  }
  return {{"frame", frame.index},
          {"width", frame.image.cols},
          {"height", frame.image.rows},
          {"kept", points_2d(frame.keypoints)},
          {"tracked", std::move(tracked)},
          {"removed", points_2d(frame.removed_keypoints)},
          {"instances", std::move(instances)}};
}

nlohmann::json atlas_json(const AtlasSnapshot& atlas) {
  nlohmann::json maps = nlohmann::json::array();
  for (const MapSnapshot& m : atlas.maps) maps.push_back(map_json(m));
  return {{"frame_id", atlas.frame_id}, {"active_map", atlas.active_map_id}, {"maps", std::move(maps)}};
}

}  // namespace stillslam::viewer
