#pragma once
// The SLAM system facade: builds the pipeline from Settings (camera setup,
// segmentation worker, frame builder, map, tracker, local mapper thread),
// processes frames one at a time, and exports trajectories. Poses of frames
// are stored relative to their reference keyframe and resolved on export,
// so map corrections after a frame was tracked still apply to it.
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <vector>

#include "stillslam/io/dataset.h"
#include "stillslam/io/settings.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/map/map.h"
#include "stillslam/mapping/local_mapper.h"
#include "stillslam/segmentation/segmentation_worker.h"
#include "stillslam/system/frame_stats.h"
#include "stillslam/tracking/frame_builder.h"
#include "stillslam/tracking/tracker.h"

namespace stillslam {

struct SystemOptions {
  bool use_segmentation = true;  // also needs Segmentation.enabled in the settings
  // Synchronous local mapping (each keyframe processed inline, single-threaded
  // BA, no aborts): same input gives the same trajectory bit for bit.
  bool deterministic = false;
  TrackerOptions tracker;
  LocalMapperOptions mapper;
};

class System {
 public:
  // sensor: RGB-D or stereo (monocular is not supported yet: Error).
  // rectified: for stereo, the dataset's rectified calibration (required).
  System(const Settings& settings, SensorType sensor, const std::optional<StereoCalibration>& rectified,
         SystemOptions options);
  ~System();
  System(const System&) = delete;
  System& operator=(const System&) = delete;

  FrameStats process(const SensorFrame& input);
  // Pose of the last processed frame if it was tracked.
  std::optional<Eigen::Isometry3d> last_T_world_cam() const { return last_T_world_cam_; }

  // Stops local mapping (finishing queued keyframes). Idempotent.
  void shutdown();

  Trajectory trajectory() const;           // every tracked frame
  Trajectory keyframe_trajectory() const;  // active keyframes
  LocalMapperStats mapper_stats() const { return mapper_->stats(); }
  std::size_t num_keyframes() const;
  std::size_t num_map_points() const;
  const CameraSetup& camera_setup() const { return *setup_; }
  bool segmentation_enabled() const { return segmentation_ != nullptr; }

 private:
  struct FrameRecord {
    double timestamp;
    KeyFramePtr reference;
    Eigen::Isometry3d T_cam_ref;
  };

  SystemOptions options_;
  std::shared_ptr<const CameraSetup> setup_;
  std::unique_ptr<SegmentationWorker> segmentation_;
  std::unique_ptr<FrameBuilder> builder_;
  std::unique_ptr<Map> map_;
  std::unique_ptr<LocalMapper> mapper_;
  std::unique_ptr<Tracker> tracker_;
  std::vector<FrameRecord> records_;
  std::uint64_t next_frame_id_ = 0;
  std::optional<Eigen::Isometry3d> last_T_world_cam_;
};

// The camera model the system uses for a sensor: RGB-D from the settings
// (with Camera.bf), stereo from the dataset's rectified calibration.
std::shared_ptr<const CameraSetup> make_camera_setup(const Settings& settings, SensorType sensor,
                                                     const std::optional<StereoCalibration>& rectified);

}  // namespace stillslam
