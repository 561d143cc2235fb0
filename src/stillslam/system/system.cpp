#include "stillslam/system/system.h"

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
  LocalMapperOptions mapper_options = options_.mapper;
  mapper_options.threaded = !options_.deterministic;
  if (options_.deterministic) mapper_options.bundle_adjustment.num_threads = 1;
  mapper_ = std::make_unique<LocalMapper>(*map_, mapper_options);
  LocalMappingLink link;
  LocalMapper* mapper = mapper_.get();
  link.insert_keyframe = [mapper](KeyFramePtr kf) { mapper->insert_keyframe(std::move(kf)); };
  link.accepts_keyframes = [mapper] { return mapper->accepts_keyframes(); };
  link.queued_keyframes = [mapper] { return mapper->queued_keyframes(); };
  link.interrupt_bundle_adjustment = [mapper] { mapper->interrupt_bundle_adjustment(); };
  TrackerOptions tracker_options = options_.tracker;
  if (settings.fps > 0) tracker_options.max_frames_between_keyframes = static_cast<int>(settings.fps);
  tracker_ = std::make_unique<Tracker>(*map_, tracker_options, std::move(link));
}

System::~System() { shutdown(); }

void System::shutdown() {
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
