#pragma once
// The SLAM system facade: builds the pipeline from Settings (camera setup,
// segmentation worker, frame builder, map, tracker, local mapper thread and,
// with a vocabulary, place recognition, relocalization and loop closing),
// processes frames one at a time, and exports trajectories. Poses of frames
// are stored relative to their reference keyframe and resolved on export,
// so map corrections after a frame was tracked still apply to it.
#include <Eigen/Geometry>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "stillslam/io/dataset.h"
#include "stillslam/io/settings.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/loop/loop_closer.h"
#include "stillslam/loop/place_recognizer.h"
#include "stillslam/map/map.h"
#include "stillslam/mapping/local_mapper.h"
#include "stillslam/segmentation/segmentation_worker.h"
#include "stillslam/system/frame_stats.h"
#include "stillslam/tracking/frame_builder.h"
#include "stillslam/tracking/relocalizer.h"
#include "stillslam/tracking/tracker.h"

namespace stillslam {

struct SystemOptions {
  bool use_segmentation = true;  // also needs Segmentation.enabled in the settings
  // Synchronous local mapping (each keyframe processed inline, single-threaded
  // BA, no aborts): same input gives the same trajectory bit for bit.
  bool deterministic = false;
  // ORB vocabulary (the committed vocab/orb_vocabulary.bin, see
  // default_vocabulary_path()) for relocalization and loop closing. Empty:
  // both disabled (unit tests); a path that cannot be read: Error.
  std::filesystem::path vocabulary_path;
  // With a vocabulary: detect and correct loops. false: keyframes are still
  // indexed, for relocalization only.
  bool loop_closing = true;
  TrackerOptions tracker;
  LocalMapperOptions mapper;
  PlaceRecognizerOptions place_recognition;
  RelocalizerOptions relocalization;
  LoopCloserOptions loop_closer;  // threaded / pause callbacks are set by System
};

// vocab/orb_vocabulary.bin of the repository the executable was built in:
// looked for next to `executable` and in its parent folders (build/stillslam
// -> <repo>/vocab/). nullopt when not found.
std::optional<std::filesystem::path> default_vocabulary_path(const std::filesystem::path& executable);
// The running executable (/proc/self/exe).
std::filesystem::path current_executable();
// The apps' --vocabulary option: "none" -> empty (disabled), a path -> that
// path, empty -> default_vocabulary_path(current_executable()) (empty with a
// warning when not found).
std::filesystem::path resolve_vocabulary_option(const std::string& option);

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

  // Stops loop closing, then local mapping (finishing queued keyframes). Idempotent.
  void shutdown();

  Trajectory trajectory() const;           // every tracked frame
  Trajectory keyframe_trajectory() const;  // active keyframes
  LocalMapperStats mapper_stats() const { return mapper_->stats(); }
  // Zero when there is no vocabulary.
  LoopCloserStats loop_closer_stats() const { return loop_closer_ ? loop_closer_->stats() : LoopCloserStats{}; }
  bool relocalization_enabled() const { return recognizer_ != nullptr; }
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
  std::shared_ptr<const Vocabulary> vocabulary_;
  std::unique_ptr<PlaceRecognizer> recognizer_;
  Relocalizer relocalizer_;
  // Declared after the mapper so that it is destroyed first (shutdown() also
  // stops it first): it pauses the mapper during corrections.
  std::unique_ptr<LocalMapper> mapper_;
  std::unique_ptr<LoopCloser> loop_closer_;
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
