#include "stillslam/system/system.h"

#include <unistd.h>

#include <spdlog/spdlog.h>

#include <array>
#include "stillslam/core/error.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/segmentation/coco_classes.h"
#include "stillslam/segmentation/yolo_segmenter.h"
#include "stillslam/tracking/thread_cpu_stopwatch.h"

namespace stillslam {

std::shared_ptr<const CameraSetup> make_camera_setup(const Settings& settings, SensorType sensor,
                                                     const std::optional<StereoCalibration>& rectified) {
  ScalePyramid pyramid(settings.orb);
  if (sensor == SensorType::Rgbd) {
    if (settings.bf <= 0) {
      throw Error(settings.file.string() + ": RGB-D needs Camera.bf (baseline x fx) > 0 for the virtual "
                  "stereo coordinate; add e.g. 'Camera.bf: 40.0'");
    }
    return std::make_shared<CameraSetup>(PinholeCamera(settings.camera, settings.bf), pyramid,
                                         settings.close_depth());
  }
  if (sensor == SensorType::Stereo) {
    if (!rectified || rectified->baseline <= 0) {
      throw Error(settings.file.string() + ": stereo input without a rectified calibration with a positive "
                  "baseline (check Stereo.T_c1_c2 / Camera.bf or the dataset's sensor.yaml)");
    }
    const double bf = rectified->left.fx * rectified->baseline;
    return std::make_shared<CameraSetup>(PinholeCamera(rectified->left, bf), pyramid,
                                         settings.th_depth * rectified->baseline);
  }
  throw Error(settings.file.string() + ": monocular input is not supported yet; use an RGB-D or stereo "
              "sequence and settings");
}

std::optional<std::filesystem::path> default_vocabulary_path(const std::filesystem::path& executable) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (fs::path dir = executable.parent_path(); !dir.empty(); dir = dir.parent_path()) {
    const fs::path candidate = dir / "vocab" / "orb_vocabulary.bin";
    if (fs::is_regular_file(candidate, ec)) return candidate;
    if (dir == dir.root_path()) break;
  }
  return std::nullopt;
}

std::filesystem::path current_executable() {
  std::array<char, 4096> buffer{};
  const ssize_t n = readlink("/proc/self/exe", buffer.data(), buffer.size() - 1);
  return n > 0 ? std::filesystem::path(std::string(buffer.data(), static_cast<std::size_t>(n)))
               : std::filesystem::path();
}

std::filesystem::path resolve_vocabulary_option(const std::string& option) {
  if (option == "none") return {};
  if (!option.empty()) return option;
  if (auto found = default_vocabulary_path(current_executable())) return *found;
  spdlog::warn("no vocab/orb_vocabulary.bin found above {}: relocalization and loop closing are off "
               "(pass --vocabulary FILE)", current_executable().string());
  return {};
}

System::System(const Settings& settings, SensorType sensor, const std::optional<StereoCalibration>& rectified,
               SystemOptions options)
    : options_(std::move(options)) {
  setup_ = make_camera_setup(settings, sensor, rectified);
  if (options_.use_segmentation && settings.segmentation.enabled) {
    auto segmenter = std::make_unique<YoloSegmenter>(settings.segmentation);
    segmentation_ = std::make_unique<SegmentationWorker>(std::move(segmenter),
                                                         resolve_class_ids(settings.segmentation.classes),
                                                         settings.segmentation.mask_dilation);
  }
  builder_ = std::make_unique<FrameBuilder>(setup_, sensor, settings.orb, segmentation_.get());
  map_ = std::make_unique<Map>();
  if (!options_.vocabulary_path.empty()) {
    if (!std::filesystem::is_regular_file(options_.vocabulary_path)) {
      throw Error("vocabulary " + options_.vocabulary_path.string() + " not found: pass --vocabulary " +
                  "<repo>/vocab/orb_vocabulary.bin (committed in the repository)");
    }
    vocabulary_ = std::make_shared<const Vocabulary>(Vocabulary::load(options_.vocabulary_path));
    recognizer_ = std::make_unique<PlaceRecognizer>(vocabulary_, options_.place_recognition);
    relocalizer_ = Relocalizer(options_.relocalization);
  }
  LocalMapperOptions mapper_options = options_.mapper;
  mapper_options.threaded = !options_.deterministic;
  if (options_.deterministic) mapper_options.bundle_adjustment.num_threads = 1;
  if (recognizer_) {
    // The loop closer exists before the mapper hands it keyframes; it reaches
    // the mapper (pause/resume) only through mapper_, set right below.
    LoopCloserOptions loop_options = options_.loop_closer;
    loop_options.threaded = !options_.deterministic;
    loop_options.detect_loops = loop_options.detect_loops && options_.loop_closing;
    if (options_.deterministic) loop_options.global_bundle_adjustment.num_threads = 1;
    loop_options.pause_local_mapping = [this] { mapper_->pause(); };
    loop_options.resume_local_mapping = [this] { mapper_->resume(); };
    loop_closer_ = std::make_unique<LoopCloser>(*map_, *recognizer_, loop_options);
    LoopCloser* loop_closer = loop_closer_.get();
    PlaceRecognizer* recognizer = recognizer_.get();
    mapper_options.on_keyframe_processed = [loop_closer](KeyFramePtr kf) { loop_closer->submit(std::move(kf)); };
    mapper_options.on_keyframe_culled = [recognizer](std::uint64_t id) { recognizer->erase(id); };
  }
  mapper_ = std::make_unique<LocalMapper>(*map_, mapper_options);
  LocalMappingLink link;
  LocalMapper* mapper = mapper_.get();
  link.insert_keyframe = [mapper](KeyFramePtr kf) { mapper->insert_keyframe(std::move(kf)); };
  link.accepts_keyframes = [mapper] { return mapper->accepts_keyframes(); };
  link.queued_keyframes = [mapper] { return mapper->queued_keyframes(); };
  link.interrupt_bundle_adjustment = [mapper] { mapper->interrupt_bundle_adjustment(); };
  if (recognizer_) {
    link.relocalize = [this](Frame& frame) {  // called with the map lock held by the tracker
      const BowDescription d = recognizer_->describe(frame.descriptors());
      std::vector<RelocalizationCandidate> candidates;
      for (const PlaceCandidate& c : recognizer_->relocalization_candidates(d.bow)) {
        KeyFramePtr kf = map_->keyframe(c.id);
        auto words = recognizer_->description(c.id);
        if (kf && !kf->is_bad() && words) candidates.push_back({kf, words->features});
      }
      return relocalizer_.relocalize(frame, d.features, candidates).success;
    };
  }
  TrackerOptions tracker_options = options_.tracker;
  if (settings.fps > 0) tracker_options.max_frames_between_keyframes = static_cast<int>(settings.fps);
  tracker_ = std::make_unique<Tracker>(*map_, tracker_options, std::move(link));
}

System::~System() { shutdown(); }

void System::shutdown() {
  // Loop closing first: a correction in progress pauses and resumes the mapper.
  if (loop_closer_) loop_closer_->stop();
  if (mapper_) mapper_->stop();
  if (segmentation_) segmentation_->stop();
}

FrameStats System::process(const SensorFrame& input) {
  Stopwatch total;
  ThreadCpuStopwatch total_cpu;
  FrameStats stats;
  stats.index = input.index;
  stats.timestamp = input.timestamp;
  Frame frame = builder_->build(input, next_frame_id_++, &stats.build);
  Stopwatch tracking;
  ThreadCpuStopwatch tracking_cpu;
  const TrackingResult result = tracker_->track(frame);
  stats.tracking_ms = tracking.elapsed_ms();
  stats.tracking_cpu_ms = tracking_cpu.elapsed_ms();
  stats.state = result.state;
  stats.reason = result.reason;
  stats.matches = result.matches;
  stats.inliers = result.inliers;
  stats.keyframe = result.new_keyframe;
  last_T_world_cam_.reset();
  if (result.state == TrackingState::Ok && frame.has_pose() && result.reference) {
    records_.push_back({frame.timestamp(), result.reference, result.T_cam_reference});
    last_T_world_cam_ = frame.T_cam_world().inverse();
    stats.has_pose = true;
  }
  if (options_.deterministic) {
    Stopwatch mapping;
    mapper_->process_pending();
    if (loop_closer_) loop_closer_->process_pending();
    stats.mapping_ms = mapping.elapsed_ms();
  }
  stats.total_ms = total.elapsed_ms();
  stats.total_cpu_ms = total_cpu.elapsed_ms();
  return stats;
}

Trajectory System::trajectory() const {
  std::lock_guard<std::mutex> lock(map_->update_mutex());
  Trajectory out;
  out.reserve(records_.size());
  for (const FrameRecord& r : records_) {
    const Eigen::Isometry3d T_cam_world = r.T_cam_ref * r.reference->T_cam_world_resolved();
    out.push_back({r.timestamp, T_cam_world.inverse()});
  }
  return out;
}

Trajectory System::keyframe_trajectory() const {
  std::lock_guard<std::mutex> lock(map_->update_mutex());
  Trajectory out;
  for (const KeyFramePtr& kf : map_->keyframes()) out.push_back({kf->timestamp(), kf->T_world_cam()});
  return out;
}

std::size_t System::num_keyframes() const {
  std::lock_guard<std::mutex> lock(map_->update_mutex());
  return map_->num_keyframes();
}

std::size_t System::num_map_points() const {
  std::lock_guard<std::mutex> lock(map_->update_mutex());
  return map_->num_map_points();
}

}  // namespace stillslam
