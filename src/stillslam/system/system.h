#pragma once
// The SLAM system facade. build_pipeline() (system.cpp) builds the stages
// from the settings and shows the whole data flow in one place:
//   segmentation -> frame building -> tracking -> [queue] local mapping
//   -> [queue] loop closing, plus relocalization and map merging with a
// vocabulary. process() runs one frame through it and, at the end, posts
// snapshots of the frame and the map to the publish layer
// (publish/publisher.h), which readers (progress, viewers) take without
// touching the map lock. Poses of frames are stored relative to their
// reference keyframe and resolved on export, so map corrections after a
// frame was tracked still apply to it.
//
// Atlas: when tracking stays lost for new_map_after_lost_frames frames
// (relocalization keeps failing), a new map starts from the next frame with
// enough depth; the old map is kept unchanged. Local mapping and loop closing
// work on the active map only: they are flushed and moved to the new (or,
// after a merge, the merged) map, so no thread ever touches an inactive map.
// With a vocabulary, every keyframe local mapping finishes is also looked for
// in the other maps (loop/merge_detector.h); a recognized place merges the
// active map into the old one (loop/map_merger.h) and tracking continues in
// the merged map. Frames keep the map of their reference keyframe: until a
// merge their poses are in their own map's frame.
#include <Eigen/Geometry>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <unordered_set>
#include <vector>

#include "stillslam/core/work_queue.h"
#include "stillslam/io/dataset.h"
#include "stillslam/settings/settings.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/loop/loop_closer.h"
#include "stillslam/loop/map_merger.h"
#include "stillslam/loop/merge_detector.h"
#include "stillslam/loop/place_recognizer.h"
#include "stillslam/map/atlas.h"
#include "stillslam/map/map.h"
#include "stillslam/map/map_file.h"
#include "stillslam/mapping/local_mapper.h"
#include "stillslam/publish/publisher.h"
#include "stillslam/segmentation/async_masks.h"
#include "stillslam/segmentation/segmentation_stage.h"
#include "stillslam/segmentation/segmentation_worker.h"
#include "stillslam/system/frame_stats.h"
#include "stillslam/system/trajectory_refinement.h"
#include "stillslam/tracking/frame_builder.h"
#include "stillslam/tracking/fresh_mask_check.h"
#include "stillslam/tracking/keyframe_check.h"
#include "stillslam/tracking/keyframe_hold.h"
#include "stillslam/tracking/provisional_points.h"
#include "stillslam/tracking/motion_stage.h"
#include "stillslam/tracking/relocalizer.h"
#include "stillslam/tracking/tracker.h"

namespace stillslam {

struct SystemOptions {
  bool use_segmentation = true;  // also needs Segmentation.enabled in the settings
  // Replaces the settings' YOLO model (bench_slam --oracle-masks runs on
  // ground-truth masks); the classes, dilation and hold settings still apply.
  std::function<std::unique_ptr<Segmenter>()> segmenter_factory;
  // Synchronous local mapping (each keyframe processed inline, single-threaded
  // BA, no aborts): same input gives the same trajectory bit for bit.
  bool deterministic = false;
  // ORB vocabulary (the committed vocab/orb_vocabulary.bin, see
  // resolve_vocabulary_option()) for relocalization and loop closing. Empty:
  // both disabled (unit tests); a path that cannot be read: Error.
  std::filesystem::path vocabulary_path;
  // With a vocabulary: detect and correct loops. false: keyframes are still
  // indexed, for relocalization only.
  bool loop_closing = true;
  // The stages' own options (tracking, relocalization, local mapping, loop
  // closing, place recognition, map merging) come from the Settings
  // (Tracking.*, LocalMapping.*, LoopClosing.*), not from here.
  // Atlas: consecutive frames without a pose (lost, relocalization failing)
  // after which a new map starts. -1: one second of frames (Camera.fps, else
  // 30) when a vocabulary is loaded, never without one; 0: never.
  int new_map_after_lost_frames = -1;
  // A map file (map/map_file.h, System::save_map) to start from: its maps
  // replace the empty atlas, their keyframes are indexed for place
  // recognition, and tracking starts lost, relocalizing in the active map
  // (the first frame need not be at the map's origin). Needs the vocabulary,
  // sensor and calibration the map was saved with (else Error).
  std::filesystem::path load_map;
  // Track against the loaded map without changing it: no keyframes, map
  // points, local mapping, loop closing, new maps or merges. Needs load_map.
  bool localization_only = false;
  // Re-estimate every tracked frame against the final map when the
  // trajectory is read (system/trajectory_refinement.h).
  TrajectoryRefinementOptions trajectory_refinement;
  // What is published after each frame, and how often the map is.
  PublishOptions publish;
  // Diagnostics (bench/bench_dynamic_points.cpp): sees each tracking stage.
  TrackingProbe tracking_probe;
};

// A frame's pose with the id of the map it is expressed in.
struct MapPose {
  StampedPose pose;
  std::uint64_t map_id = 0;
};

// The apps' --vocabulary option: "none" -> empty (disabled), a path -> that
// path, empty -> the committed vocab/orb_vocabulary.bin found from the
// running executable (core/shipped_files.h; empty with a warning when not
// found).
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

  // Every tracked frame, each in the frame of the map holding its reference
  // keyframe (maps merged into another are in that map's frame). With
  // trajectory refinement each pose is re-estimated against the map as it is
  // now, so read it after shutdown() for the final answer.
  Trajectory trajectory() const;
  std::vector<MapPose> trajectory_with_maps() const;
  Trajectory keyframe_trajectory() const;  // active keyframes of all maps
  // Local mapping / loop closing totals over every map.
  LocalMapperStats mapper_stats() const;
  // Zero when there is no vocabulary.
  LoopCloserStats loop_closer_stats() const;
  bool relocalization_enabled() const { return recognizer_ != nullptr; }
  std::size_t num_keyframes() const;  // all maps
  std::size_t num_map_points() const;

  // The maps (e.g. to save them all). Read map contents under each map's
  // update_mutex(); the list of maps changes only inside process().
  const Atlas& atlas() const { return *atlas_; }
  std::size_t num_maps() const { return atlas_->num_maps(); }
  std::uint64_t active_map_id() const { return atlas_->active_map_id(); }
  // Maps started because tracking stayed lost, and merges done.
  int new_maps_started() const { return new_maps_started_; }
  const std::vector<MapMergeStats>& merges() const { return merges_; }
  const CameraSetup& camera_setup() const { return *setup_; }
  // What a map file of this system records and must match on load.
  MapFileContext map_file_context() const;
  // Saves every map of the atlas (map/map_file.h). Stops the threads first
  // (shutdown()): call it at the end of a run. Throws Error when the file
  // can't be written.
  MapFileStats save_map(const std::filesystem::path& path);
  bool segmentation_enabled() const { return segmentation_ != nullptr || async_masks_ != nullptr; }
  // The snapshots posted after each frame, for readers on other threads.
  const Publisher& publisher() const { return publisher_; }

 private:
  struct FrameRecord {
    double timestamp;
    KeyFramePtr reference;
    Eigen::Isometry3d T_cam_ref;
    bool keyframe;                   // the frame became `reference`
    FrameObservations observations;  // empty without trajectory refinement
    bool sparse_view = false;        // the crowd fallback acted on it (Motion.sparseViewSmoothFrames)
    // The directions the centre filter acts on (Motion.sparseViewFilterAxes).
    Eigen::Matrix3d filter_projection = Eigen::Matrix3d::Identity();
    // As tracked, moved with its reference keyframe since. Caller holds the
    // lock of the map that holds the reference keyframe.
    Eigen::Isometry3d T_cam_world() const { return T_cam_ref * reference->T_cam_world_resolved(); }
  };
  // Every keyframe `map` has held (culled ones too): the records whose
  // reference is among them are expressed in `map`. Caller holds its lock.
  static std::unordered_set<const KeyFrame*> keyframes_of(const Map& map);

  // Creates the stages and connects them (the data flow in one place).
  void build_pipeline(const Settings& settings);
  // Local mapping, then loop closing, finish what they have (so every
  // keyframe local mapping finishes still reaches loop closing), then both
  // move to the active map.
  void move_stages_to_active_map();
  void start_new_map();
  // SystemOptions::load_map: the file's maps into the (empty) atlas.
  void load_maps(const std::filesystem::path& path);
  // Looks for the keyframes local mapping finished in the other maps; merges
  // on a recognized place.
  void detect_and_merge();
  bool merge_into(Map& target, const LoopDetection& detection);
  // Posts the frame snapshot and, when due, the atlas snapshot.
  void publish(const SensorFrame& input, const Frame& frame, const FrameStats& stats, FrameDynamics dynamics);

  SystemOptions options_;
  // The stage options of the settings this system was built from.
  RelocalizerOptions relocalization_options_;
  MapMergerOptions merger_options_;
  SensorType sensor_;
  std::shared_ptr<const CameraSetup> setup_;
  std::unique_ptr<SegmentationWorker> segmentation_;  // Segmentation.mode sync
  // Segmentation.mode async: the stage and what the frame builder reads from it.
  std::unique_ptr<SegmentationStage> segmentation_stage_;
  std::unique_ptr<AsyncMasks> async_masks_;
  std::unique_ptr<FreshMaskCheck> fresh_mask_check_;  // Segmentation.freshMaskCull
  // Segmentation.keyframeHold: keyframes from frames with masks older than
  // keyframe_mask_age_ wait here for their own masks before local mapping.
  std::unique_ptr<KeyframeHold> keyframe_hold_;
  // Segmentation.provisionalPoints (instead of keyframe_hold_): such keyframes
  // go to local mapping at once, their new points wait here for the mask.
  std::unique_ptr<ProvisionalPoints> provisional_points_;
  int keyframe_mask_age_ = 0;
  // Segmentation.startCheck / keyframeCheck: keyframes made under carried
  // masks, in local mapping already, checked here when their own masks come.
  std::unique_ptr<KeyframeCheck> keyframe_check_;
  bool check_start_ = false;      // Segmentation.startCheck: the map's first keyframe
  bool check_keyframes_ = false;  // Segmentation.keyframeCheck: every keyframe not held
  // startCheck: the start candidate under a carried mask sent to the
  // segmenter, whose own mask checks the first keyframe if the map starts from it.
  struct StartCandidate {
    std::uint64_t frame_id = 0;
    std::size_t index = 0;  // its input index
    std::vector<cv::Point2f> pixels;  // its keypoints in the image
  };
  std::optional<StartCandidate> start_candidate_;
  // startCheck: after tracking a frame that became the start candidate.
  void request_start_candidate_mask(const SensorFrame& input, const Frame& frame);
  // Local mapping gets `kf` now or, with keyframe_hold_, when its turn comes
  // (`tracked`: the frame being tracked, LocalMappingLink::insert_keyframe).
  void on_new_keyframe(KeyFramePtr kf, const Frame& tracked);
  // Releases the held keyframes (or checks the provisional points) and checks
  // the keyframes of keyframe_check_ the newest segmentation result allows;
  // returns the points removed.
  int release_held_keyframes();
  int release_held_and_provisional();  // the keyframe hold's and provisional points' part
  // Every held keyframe, unchecked, every provisional point confirmed and
  // every keyframe check dropped (a new map, a merge, shutdown).
  void release_all_held_keyframes();
  int urgent_inliers_ = 0;  // Segmentation.urgentInliers
  std::vector<int> dynamic_class_ids_;  // the classes the segmentation masks
  std::unique_ptr<FrameBuilder> builder_;
  std::unique_ptr<MotionStage> motion_stage_;  // Motion.enabled with segmentation on
  std::unique_ptr<Atlas> atlas_;
  std::shared_ptr<const Vocabulary> vocabulary_;
  std::unique_ptr<PlaceRecognizer> recognizer_;
  Relocalizer relocalizer_;
  std::unique_ptr<MergeDetector> merge_detector_;
  // The stages live as long as the system (moved between maps, never
  // replaced), so the connections between them never dangle. The mapper is
  // declared first so it is destroyed last: loop closing pauses it.
  std::unique_ptr<LocalMapper> mapper_;
  std::unique_ptr<LoopCloser> loop_closer_;
  std::unique_ptr<Tracker> tracker_;
  // Keyframes local mapping has finished, for merge detection: filled by the
  // local-mapping stage, drained by process().
  WorkQueue<KeyFramePtr> finished_keyframes_;
  Publisher publisher_;
  int frames_since_map_snapshot_ = 0;
  std::vector<FrameRecord> records_;
  // The frames processed since the tracker's start candidate (frame id, input
  // index): those a start from an earlier frame poses.
  std::vector<std::pair<std::uint64_t, std::size_t>> start_inputs_;
  int sparse_view_smooth_frames_ = 0;  // Motion.sparseViewSmoothFrames (with Motion.sparseView)
  double sparse_view_filter_gain_ = 0;  // Motion.sparseViewFilterGain (with Motion.sparseView)
  int sparse_view_filter_frames_ = 5;   // Motion.sparseViewFilterFrames
  std::uint64_t next_frame_id_ = 0;
  std::optional<Eigen::Isometry3d> last_T_world_cam_;
  int new_map_after_lost_frames_ = 0;  // 0: never
  int lost_frames_ = 0;
  int new_maps_started_ = 0;
  std::vector<MapMergeStats> merges_;
};

// The camera model the system uses for a sensor: RGB-D from the settings
// (with Camera.bf), stereo from the dataset's rectified calibration.
std::shared_ptr<const CameraSetup> make_camera_setup(const Settings& settings, SensorType sensor,
                                                     const std::optional<StereoCalibration>& rectified);

}  // namespace stillslam
