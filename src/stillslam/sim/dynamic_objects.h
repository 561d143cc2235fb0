#pragma once
// Everything that moves: people (RGBA billboards at human height, walking
// ones always facing the camera, walking back and forth across the camera's line of sight
// with a little bob and sway, see walking_paths.h), people who stay still
// (seated on the chairs behind the desk, swaying slightly, facing where the
// camera starts: a seated person does not turn with a camera carried around
// them), a box carried
// across the desk, a chair pushed aside, a crowd walking through close to the
// camera, and an optional occluder: a person passing right in front of the
// lens who hides (nearly) the whole view for a while. Each gets its own
// Quad::dynamic_id so masks can be told apart; the box and the chair are
// marked dynamic only while they move (before and after they are part of the
// static scene).
#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "stillslam/sim/camera_motion.h"
#include "stillslam/sim/quad.h"
#include "stillslam/sim/scene_layout.h"
#include "stillslam/sim/walking_paths.h"

namespace stillslam::sim {

struct PersonTrack {
  int texture = 0;               // renderer texture index of the cut-out
  double height = 1.7;           // metres
  double aspect = 0.4;           // cut-out width / height
  Eigen::Vector2d a, b;          // walking between these floor points (scene frame)
  double speed = 1.0;            // m/s
  double pause = 2.0;            // seconds out of view at each end
  double stop_at = 0.5;          // fraction of the path where the person stands a while
  double stop_time = 0.0;        // seconds standing there (0 = walks straight through)
  // While "standing" the person shifts slowly out to this floor offset and back
  // (half a sine over stop_time, 0.1-0.3 m/s): people who talk or look around
  // are never still, and slow motion is what a geometric outlier test misses.
  Eigen::Vector2d dawdle = Eigen::Vector2d::Zero();
  double offset = 0.0;           // seconds into the back-and-forth cycle at t = 0
  bool still = false;            // stands at `a`, only sways
  // A still person faces this floor point (scene frame; the camera's start)
  // whatever the camera does later.
  Eigen::Vector2d faces = Eigen::Vector2d(0, -1);
  std::uint16_t id = 1;
};

// A person of a crowd: walks straight from a to b (scene frame floor points,
// both out of view) starting at t_start; not in the scene before or after.
struct CrowdMember {
  int texture = 0;
  double height = 1.7, aspect = 0.4;
  Eigen::Vector2d a, b;
  double t_start = 0, speed = 1.0;
  std::uint16_t id = 1;
};

// What each dynamic id stands for (ground truth for motion checks).
struct InstanceInfo {
  std::uint16_t id = 0;
  std::string kind;       // walking_person, still_person, moved_box, moved_chair, crowd_person, occluder
  std::string category;   // person, box, chair
  bool moves = true;      // false: stays (nearly) still for the whole sequence
};

struct DynamicObjectsOptions {
  int walking = 2;
  int still = 0;
  bool moved_box = false;
  double duration = 10.0;        // seconds; the box moves at 40% of it, the chair at 65%
  double half_view_tan = 0.6;    // tan of the camera's horizontal half field of view
  // The occluder covers the view from occlude_at for occlude_seconds (it walks
  // in during the kOccluderWalk seconds before and out during those after).
  std::optional<double> occlude_at;
  double occlude_seconds = 1.0;
  // A crowd walks across the view, close to the camera, so that it covers
  // most of it from crowd_at for crowd_seconds (it walks in during the
  // seconds before and out during those after).
  std::optional<double> crowd_at;
  double crowd_seconds = 3.0;
};

// Renderer texture indices and pixel sizes of the people.
struct PeopleTextures {
  std::vector<int> walking;
  std::vector<cv::Size> walking_sizes;
  std::vector<int> sitting;  // seated people (may be empty: still people then stand)
  std::vector<cv::Size> sitting_sizes;
  // The occluder's cut-out and the texture point (normalized) put on the
  // optical axis: the middle of its most opaque part (the torso).
  int occluder = -1;
  cv::Size occluder_size;
  Eigen::Vector2d occluder_centre{0.5, 0.35};
};

class DynamicObjects {
 public:
  // Seconds the occluder takes to walk into (and out of) the view.
  static constexpr double kOccluderWalk = 0.5;
  // Its distance in front of the lens (metres along the optical axis).
  static constexpr double kOccluderDistance = 0.2;

  // camera_path: world-frame camera poses over the sequence (t = seconds since
  // the start, every ~0.1 s); walking paths are laid across its lines of sight.
  // texture_sizes: the room's photo textures (for the box). chair: the quads
  // of a chair of the room (scene frame, build_static_scene's movable_chair)
  // to push aside during the sequence; empty: no moved chair.
  DynamicObjects(const DynamicObjectsOptions& options, const Eigen::Isometry3d& T_world_scene,
                 const std::vector<TimedPose>& camera_path, const PeopleTextures& textures,
                 const std::vector<cv::Size>& texture_sizes, std::uint64_t seed,
                 std::vector<Quad> chair = {});

  // Quads at time t (seconds since the start) in the world frame; walking
  // people's billboards face the camera, still people's where it started, the
  // occluder stands in front of it.
  std::vector<Quad> quads_at(double t, const Eigen::Isometry3d& T_world_cam) const;
  const std::vector<PersonTrack>& people() const { return people_; }
  const std::vector<WalkingPath>& walking_paths() const { return paths_; }  // one per walking person
  std::uint16_t occluder_id() const { return occluder_id_; }                // 0: none
  const std::vector<CrowdMember>& crowd() const { return crowd_; }
  Eigen::Vector3d person_foot(const PersonTrack& p, double t) const;        // scene frame
  std::optional<Eigen::Vector3d> crowd_foot(const CrowdMember& m, double t) const;  // scene frame; none when gone
  // Every dynamic id of the sequence, ascending.
  std::vector<InstanceInfo> instances() const;
  // Seconds during which the chair moves ([start, end]; both 0 without a chair).
  std::pair<double, double> chair_motion() const;

 private:
  std::optional<Quad> occluder_at(double t, const Eigen::Isometry3d& T_world_cam) const;
  void place_crowd(const std::vector<TimedPose>& camera_path, std::uint16_t& next_id, PanelPainter& rng);

  DynamicObjectsOptions options_;
  Eigen::Isometry3d T_world_scene_;
  PeopleTextures textures_;
  std::vector<PersonTrack> people_;
  std::vector<WalkingPath> paths_;
  std::vector<Quad> box_;        // the movable box in scene frame at its start, resting
  std::uint16_t box_id_ = 0;
  std::vector<Quad> chair_;      // the pushed chair in scene frame at its start
  std::uint16_t chair_id_ = 0;
  std::vector<CrowdMember> crowd_;
  std::uint16_t occluder_id_ = 0;
};

}  // namespace stillslam::sim
