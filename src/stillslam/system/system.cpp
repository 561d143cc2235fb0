#include "stillslam/system/system.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <unordered_set>

#include "stillslam/core/error.h"
#include "stillslam/core/shipped_files.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/core/thread_cpu_stopwatch.h"
#include "stillslam/core/thread_run_queue_wait.h"
#include "stillslam/publish/map_snapshot.h"
#include "stillslam/segmentation/coco_classes.h"
#include "stillslam/segmentation/yolo_segmenter.h"
#include "stillslam/system/snapshot_instances.h"
#include "stillslam/tracking/sparse_view.h"
#include "stillslam/tracking/keypoint_pixels.h"

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

std::filesystem::path resolve_vocabulary_option(const std::string& option) {
  if (option == "none") return {};
  if (!option.empty()) return option;
  const std::filesystem::path executable = running_executable();
  if (auto found = find_shipped_file(executable, kShippedVocabulary)) return *found;
  spdlog::warn("no {} found above {}: relocalization and loop closing are off (pass --vocabulary FILE)",
               kShippedVocabulary, executable.string());
  return {};
}

System::System(const Settings& settings, SensorType sensor, const std::optional<StereoCalibration>& rectified,
               SystemOptions options)
    : options_(std::move(options)),
      relocalization_options_(settings.relocalization),
      merger_options_(settings.map_merger),
      sensor_(sensor) {
  options_.publish.check();
  merger_options_.check();
  setup_ = make_camera_setup(settings, sensor, rectified);
  if (options_.localization_only && options_.load_map.empty()) {
    throw Error("localization-only mode needs a map to localize in: pass --load-map FILE (written by "
                "`stillslam run --save-map FILE`)");
  }
  atlas_ = std::make_unique<Atlas>();
  if (!options_.vocabulary_path.empty()) {
    if (!std::filesystem::is_regular_file(options_.vocabulary_path)) {
      throw Error("vocabulary " + options_.vocabulary_path.string() + " not found: pass --vocabulary " +
                  "<repo>/vocab/orb_vocabulary.bin (committed in the repository)");
    }
    vocabulary_ = std::make_shared<const Vocabulary>(Vocabulary::load(options_.vocabulary_path));
    recognizer_ = std::make_unique<PlaceRecognizer>(vocabulary_, settings.place_recognition);
    relocalizer_ = Relocalizer(relocalization_options_);
    if (settings.map_merging && !options_.localization_only) {
      merge_detector_ = std::make_unique<MergeDetector>(*recognizer_, merger_options_.detector);
    }
  }
  const int fps_frames = settings.fps > 0 ? static_cast<int>(settings.fps) : 30;
  new_map_after_lost_frames_ = options_.new_map_after_lost_frames >= 0 ? options_.new_map_after_lost_frames
                               : recognizer_                            ? fps_frames
                                                                        : 0;
  if (options_.localization_only) new_map_after_lost_frames_ = 0;
  if (!options_.load_map.empty()) load_maps(options_.load_map);
  build_pipeline(settings);
  if (!options_.load_map.empty()) tracker_->localize_in(atlas_->active_map());
}

// The data flow, numbered in the order a frame goes through it:
//   1 segmentation -> 2 frame building -> 3 tracking -> [queue] 4 local mapping
//   -> [queue] 5 loop closing (and finished keyframes -> merge detection in process()).
// Stages 3-5 are built from the end backwards, so each exists before the
// stage that feeds it.
void System::build_pipeline(const Settings& settings) {
  const WorkerMode mode = options_.deterministic ? WorkerMode::Synchronous : WorkerMode::Threaded;

  // 1. Segmentation (own thread): the colour image in, the dynamic mask out.
  // Sync: each frame waits for its own mask. Async: a stage at its own rate
  // on the newest frame it is given, masks carried to the frames between.
  const bool async = settings.segmentation.mode == SegmentationMode::Async;
  if (options_.use_segmentation && settings.segmentation.enabled) {
    dynamic_class_ids_ = resolve_class_ids(settings.segmentation.classes);
    std::unique_ptr<Segmenter> segmenter = options_.segmenter_factory
                                               ? options_.segmenter_factory()
                                               : std::make_unique<YoloSegmenter>(settings.segmentation);
    const MaskHoldOptions hold{.frames = settings.segmentation.hold_frames};
    if (async) {
      segmentation_stage_ = std::make_unique<SegmentationStage>(
          DynamicMaskMaker(std::move(segmenter), dynamic_class_ids_, settings.segmentation.mask_dilation, hold),
          mode == WorkerMode::Threaded, settings.segmentation.thread_nice);
      const PinholeCamera& camera = setup_->camera;
      MaskPropagator propagator(MaskPropagationCamera{camera.fx(), camera.fy(), camera.cx(), camera.cy(),
                                                     sensor_ == SensorType::Stereo ? camera.bf() : 0.0},
                                settings.mask_propagation);
      async_masks_ = std::make_unique<AsyncMasks>(*segmentation_stage_, AsyncMaskOptions::from(settings.segmentation),
                                                  std::move(propagator), settings.segmentation.mask_dilation);
      urgent_inliers_ = settings.segmentation.urgent_inliers;
      if (settings.segmentation.fresh_mask_cull) fresh_mask_check_ = std::make_unique<FreshMaskCheck>();
      if (settings.segmentation.keyframe_hold && settings.segmentation.provisional_points) {
        provisional_points_ = std::make_unique<ProvisionalPoints>();
      } else if (settings.segmentation.keyframe_hold) {
        keyframe_hold_ = std::make_unique<KeyframeHold>(settings.segmentation.held_evidence);
      }
      keyframe_mask_age_ = settings.segmentation.keyframe_mask_age;
      check_start_ = settings.segmentation.start_check;
      check_keyframes_ = settings.segmentation.keyframe_check;
      if (check_start_ || check_keyframes_) {
        keyframe_check_ = std::make_unique<KeyframeCheck>(settings.segmentation.check_new_points);
      }
    } else {
      segmentation_ = std::make_unique<SegmentationWorker>(std::move(segmenter), dynamic_class_ids_,
                                                           settings.segmentation.mask_dilation, hold);
    }
  }

  // 2. Frame building (tracking thread): ORB outside the mask, stereo / depth association.
  StereoMatchOptions stereo_matching;
  stereo_matching.flow_for_unmatched = settings.stereo_flow_matching;
  if (async_masks_) {
    builder_ = std::make_unique<FrameBuilder>(setup_, sensor_, settings.orb, async_masks_.get(), stereo_matching);
  } else {
    builder_ = std::make_unique<FrameBuilder>(setup_, sensor_, settings.orb, segmentation_.get(), stereo_matching);
  }
  // 2b. Motion-aware masks (issue #19): instances judged by their motion after tracking.
  if (settings.motion.enabled && builder_->segmentation_enabled()) {
    motion_stage_ = std::make_unique<MotionStage>(setup_->camera, settings.orb, dynamic_class_ids_,
                                                  settings.segmentation.mask_dilation, settings.motion);
    builder_->set_motion_stage(motion_stage_.get());
    options_.trajectory_refinement.leave_out_kept_points = settings.motion.kept_points_out_of_pose;
    options_.trajectory_refinement.kept_point_sigma = settings.motion.kept_point_sigma;
  }

  Map& map = atlas_->active_map();
  // 5. Loop closing (own thread, with a vocabulary): keyframes from local
  // mapping in; pauses local mapping while it corrects a loop.
  if (recognizer_) {
    LoopCloserOptions loop = settings.loop_closing;
    loop.threaded = mode == WorkerMode::Threaded;
    loop.detect_loops = loop.detect_loops && options_.loop_closing;
    if (options_.deterministic) loop.global_bundle_adjustment.num_threads = 1;
    loop.pause_local_mapping = [&mapper = mapper_] { mapper->pause(); };
    loop.resume_local_mapping = [&mapper = mapper_] { mapper->resume(); };
    loop_closer_ = std::make_unique<LoopCloser>(map, *recognizer_, std::move(loop));
  }

  // 4. Local mapping (own thread): keyframes from tracking in; each finished
  // keyframe goes on to loop closing and to merge detection.
  LocalMapperOptions mapping = settings.local_mapping;
  mapping.threaded = mode == WorkerMode::Threaded;
  mapping.window.leave_out_kept_points = motion_stage_ && settings.motion.kept_points_out_of_ba;
  if (options_.deterministic) {
    mapping.bundle_adjustment.num_threads = 1;
    mapping.bundle_adjustment.max_seconds_per_pass = 0;  // a wall-clock budget would not repeat
  }
  if (recognizer_) {
    LoopCloser* loop_closer = loop_closer_.get();
    WorkQueue<KeyFramePtr>* finished = merge_detector_ ? &finished_keyframes_ : nullptr;
    mapping.on_keyframe_processed = [loop_closer, finished](KeyFramePtr kf) {
      if (finished) finished->push(kf);
      loop_closer->submit(std::move(kf));
    };
    PlaceRecognizer* recognizer = recognizer_.get();
    mapping.on_keyframe_culled = [recognizer](std::uint64_t id) { recognizer->erase(id); };
  }
  mapper_ = std::make_unique<LocalMapper>(map, std::move(mapping));

  // 3. Tracking (the caller's thread): frames in; keyframes out to local
  // mapping; relocalization in the active map when lost.
  LocalMapper* mapper = mapper_.get();
  LocalMappingLink link;
  link.insert_keyframe = [this](KeyFramePtr kf, const Frame& tracked) { on_new_keyframe(std::move(kf), tracked); };
  link.accepts_keyframes = [mapper](double now) { return mapper->accepts_keyframes(now); };
  link.queued_keyframes = [mapper](double now) { return mapper->queued_keyframes(now); };
  link.interrupt_bundle_adjustment = [mapper] { mapper->interrupt_bundle_adjustment(); };
  if (recognizer_) {
    // Called by the tracker with the active map's lock held.
    link.relocalize = [recognizer = recognizer_.get(), &relocalizer = relocalizer_, &tracker = tracker_](Frame& frame) {
      const Map& active = tracker->map();
      const BowDescription d = recognizer->describe(frame.descriptors());
      std::vector<RelocalizationCandidate> candidates;
      // Keyframes of other maps are not candidates: relocalization stays in the active map.
      for (const PlaceCandidate& c : recognizer->relocalization_candidates(d.bow)) {
        KeyFramePtr kf = active.keyframe(c.id);
        auto words = recognizer->description(c.id);
        if (kf && !kf->is_bad() && words) candidates.push_back({kf, words->features});
      }
      return relocalizer.relocalize(frame, d.features, candidates).success;
    };
  }
  TrackerOptions tracking = settings.tracking;
  tracking.localization_only = options_.localization_only;
  tracking.probe = options_.tracking_probe;
  tracking.sparse_view = settings.motion.sparse_view;
  sparse_view_smooth_frames_ = settings.motion.sparse_view.enabled ? settings.motion.sparse_view.smooth_frames : 0;
  sparse_view_filter_gain_ = settings.motion.sparse_view.enabled ? settings.motion.sparse_view.filter_gain : 0;
  sparse_view_filter_frames_ = settings.motion.sparse_view.filter_frames;
  tracking.static_evidence.leave_out_kept_points = motion_stage_ && settings.motion.kept_points_out_of_pose;
  if (motion_stage_) tracking.static_evidence.kept_point_sigma = settings.motion.kept_point_sigma;
  // Held keyframes are checked later instead of deferred.
  if (async_masks_ && !keyframe_hold_ && !provisional_points_) {
    tracking.max_keyframe_mask_age = settings.segmentation.keyframe_mask_age;
  }
  if (provisional_points_) tracking.provisional_mask_age = settings.segmentation.keyframe_mask_age;
  if (async_masks_) {
    tracking.near_person.px_per_frame = settings.segmentation.near_person_px_per_frame;
    tracking.near_person.max_px = settings.segmentation.near_person_max_px;
    tracking.near_person.depth_band_m = settings.segmentation.near_person_depth_band;
    tracking.near_person.at_start = settings.segmentation.near_person_at_start;
  }
  tracker_ = std::make_unique<Tracker>(map, tracking, std::move(link));
}

MapFileContext System::map_file_context() const {
  MapFileContext context;
  context.sensor = to_string(sensor_);
  context.setup = setup_;
  context.vocabulary_checksum = vocabulary_ ? vocabulary_fingerprint(*vocabulary_) : 0;
  return context;
}

void System::load_maps(const std::filesystem::path& path) {
  if (!recognizer_) {
    throw Error(path.string() + ": starting from a saved map needs the vocabulary it was saved with (tracking "
                "relocalizes in it first); pass --vocabulary FILE");
  }
  Stopwatch time;
  MapFileContents contents = load_map_file(path, map_file_context(), atlas_->id_counters());
  if (contents.maps.empty()) {
    throw Error(path.string() + ": the map file holds no keyframes (the run that saved it never initialized a "
                "map); save a map from a run that tracked");
  }
  std::vector<std::unique_ptr<Map>> maps;
  std::size_t keyframes = 0, points = 0;
  for (LoadedMap& loaded : contents.maps) {
    // Bag of words is not stored: every keyframe is described again.
    for (const KeyFramePtr& kf : loaded.map->keyframes()) recognizer_->add(*kf);
    keyframes += loaded.map->num_keyframes();
    points += loaded.map->num_map_points();
    maps.push_back(std::move(loaded.map));
  }
  atlas_->replace_maps(std::move(maps), contents.active_map_id, contents.next_map_id);
  spdlog::info("loaded {}: {} maps, {} keyframes, {} map points ({:.0f} ms); active map {}", path.string(),
               contents.maps.size(), keyframes, points, time.elapsed_ms(), contents.active_map_id);
}

MapFileStats System::save_map(const std::filesystem::path& path) {
  shutdown();  // no thread changes a map while it is written
  // Maps without keyframes (a new map not initialized yet) are left out; if
  // the active one is among them, the largest map is active in the file.
  std::vector<MapToSave> maps;
  const Map* largest = nullptr;
  bool active_kept = false;
  for (const Map* map : atlas_->maps()) {
    if (map->num_keyframes() == 0) continue;
    maps.push_back({map, {}});
    active_kept = active_kept || map->id() == atlas_->active_map_id();
    if (!largest || map->num_keyframes() > largest->num_keyframes()) largest = map;
  }
  const std::uint64_t active = active_kept || !largest ? atlas_->active_map_id() : largest->id();
  return save_map_file(path, map_file_context(), maps, active, atlas_->maps_created());
}

System::~System() { shutdown(); }

void System::move_stages_to_active_map() {
  // Local mapping first: the keyframes it still finishes reach loop closing.
  mapper_->flush();
  if (loop_closer_) loop_closer_->flush();
  Map& map = atlas_->active_map();
  mapper_->switch_map(map);
  if (loop_closer_) loop_closer_->switch_map(map);
}

void System::on_new_keyframe(KeyFramePtr kf, const Frame& tracked) {
  if (provisional_points_ && kf->frame_id() == tracked.id() && tracker_->makes_provisional_points(tracked)) {
    provisional_points_->add(kf, keypoint_pixels(tracked));
  }
  if (keyframe_check_) {
    // The tracker holds the map lock while it makes a keyframe.
    const bool first = tracker_->map().num_keyframes() == 1;
    const bool this_frame = kf->frame_id() == tracked.id();
    const bool held = keyframe_hold_ && this_frame && tracked.mask_age() > keyframe_mask_age_;
    if (this_frame && !held && tracked.mask_age() > 0 && (check_keyframes_ || (check_start_ && first))) {
      keyframe_check_->add(kf, keypoint_pixels(tracked));  // process() gives it the frame's input index
    } else if (!this_frame && first && check_start_ && start_candidate_ &&
               start_candidate_->frame_id == kf->frame_id()) {
      // The map started from an earlier frame, the candidate whose own mask was requested.
      keyframe_check_->add(kf, std::move(start_candidate_->pixels), start_candidate_->index);
      start_candidate_.reset();
    }
  }
  if (!keyframe_hold_) {
    mapper_->insert_keyframe(std::move(kf));
    return;
  }
  // Only a keyframe of the frame being tracked is checked with that frame's
  // mask (a map started from an earlier frame passes); process() gives it
  // the frame's input index.
  if (kf->frame_id() == tracked.id() && tracked.mask_age() > keyframe_mask_age_) {
    keyframe_hold_->hold(std::move(kf), keypoint_pixels(tracked));
    return;
  }
  for (KeyFramePtr& k : keyframe_hold_->pass(std::move(kf))) mapper_->insert_keyframe(std::move(k));
}

void System::request_start_candidate_mask(const SensorFrame& input, const Frame& frame) {
  if (!keyframe_check_ || !check_start_ || tracker_->state() != TrackingState::NotInitialized) return;
  if (tracker_->start_candidate_id() != frame.id() || frame.mask_age() <= 0) return;
  // One request in flight: a candidate replaced before its mask came keeps it.
  const std::shared_ptr<const SegmentationResult>& fresh = async_masks_->fresh();
  if (start_candidate_ && (!fresh || fresh->frame_index < start_candidate_->index)) return;
  async_masks_->segment_last(input.color, input.index);
  start_candidate_ = StartCandidate{frame.id(), input.index, keypoint_pixels(frame)};
}

int System::release_held_keyframes() {
  int checked_removed = 0;
  if (keyframe_check_ && !keyframe_check_->empty() && async_masks_->fresh()) {
    const SegmentationResult& fresh = *async_masks_->fresh();
    std::lock_guard<std::mutex> lock(tracker_->map().update_mutex());
    // The mask a frame segmented for itself would have had (held-over instances, dilation).
    const KeyframeCheckResult checked = keyframe_check_->check(fresh.frame_index, {fresh.dynamic_mask});
    checked_removed = checked.culled + checked.unlinked;
  }
  return checked_removed + release_held_and_provisional();
}

int System::release_held_and_provisional() {
  if (provisional_points_ && !provisional_points_->empty() && async_masks_->fresh()) {
    const SegmentationResult& fresh = *async_masks_->fresh();
    Map& map = tracker_->map();
    ProvisionalCheck checked;
    {
      std::lock_guard<std::mutex> lock(map.update_mutex());
      checked =
          provisional_points_->check(fresh.frame_index, {fresh.dynamic_mask}, map.id_counters()->next_keyframe.load());
    }
    // Local mapping fuses the confirmed points as it fuses a new keyframe's.
    for (KeyFramePtr& kf : checked.settled) mapper_->fuse_confirmed(std::move(kf));
    return checked.culled + checked.unlinked;
  }
  if (!keyframe_hold_ || keyframe_hold_->empty() || !async_masks_->fresh()) return 0;
  const SegmentationResult& fresh = *async_masks_->fresh();
  KeyframeHoldRelease released;
  {
    std::lock_guard<std::mutex> lock(tracker_->map().update_mutex());
    // The mask a frame segmented for itself would have had (held-over instances, dilation).
    released = keyframe_hold_->release(fresh.frame_index, {fresh.dynamic_mask});
  }
  for (KeyFramePtr& kf : released.keyframes) mapper_->insert_keyframe(std::move(kf));
  return released.culled + released.unlinked;
}

void System::release_all_held_keyframes() {
  if (keyframe_check_) keyframe_check_->drop_all();
  start_candidate_.reset();
  if (provisional_points_ && !provisional_points_->empty()) {
    Map& map = tracker_->map();
    ProvisionalCheck confirmed;
    {
      std::lock_guard<std::mutex> lock(map.update_mutex());
      confirmed = provisional_points_->confirm_all(map.id_counters()->next_keyframe.load());
    }
    for (KeyFramePtr& kf : confirmed.settled) mapper_->fuse_confirmed(std::move(kf));
  }
  if (!keyframe_hold_) return;
  for (KeyFramePtr& kf : keyframe_hold_->release_all().keyframes) mapper_->insert_keyframe(std::move(kf));
}

void System::shutdown() {
  // Held keyframes go unchecked: no more masks come.
  release_all_held_keyframes();
  // Local mapping first: the keyframes it still finishes reach loop closing,
  // which indexes them before it stops.
  mapper_->stop();
  if (loop_closer_) loop_closer_->stop();
  if (segmentation_) segmentation_->stop();
  if (segmentation_stage_) segmentation_stage_->stop();
}

void System::start_new_map() {
  // The old map's held keyframes go to local mapping before it switches maps.
  release_all_held_keyframes();
  const std::uint64_t old_id = atlas_->active_map_id();
  Map& map = atlas_->create_map();
  spdlog::info("atlas: tracking lost for {} frames, map {} kept, new map {} starts", lost_frames_, old_id,
               map.id());
  move_stages_to_active_map();
  finished_keyframes_.take_all();
  if (merge_detector_) merge_detector_->reset();
  tracker_->start_new_map(map);
  if (fresh_mask_check_) fresh_mask_check_->clear();
  lost_frames_ = 0;
  ++new_maps_started_;
}

void System::detect_and_merge() {
  const std::deque<KeyFramePtr> finished = finished_keyframes_.take_all();
  if (!merge_detector_ || atlas_->num_maps() < 2) return;
  Map& active = atlas_->active_map();
  for (const KeyFramePtr& kf : finished) {
    for (Map* other : atlas_->maps()) {
      if (other == &active) continue;
      std::optional<LoopDetection> detection;
      {
        std::scoped_lock lock(active.update_mutex(), other->update_mutex());
        if (kf->is_bad() || !active.keyframe(kf->id())) break;
        detection = merge_detector_->detect(*other, *kf);
      }
      if (detection && merge_into(*other, *detection)) return;
    }
  }
}

bool System::merge_into(Map& target, const LoopDetection& detection) {
  Map& source = atlas_->active_map();
  release_all_held_keyframes();
  // Nothing may change either map while they are merged.
  mapper_->flush();
  if (loop_closer_) loop_closer_->flush();
  std::optional<MapMergeStats> merged;
  {
    std::scoped_lock lock(source.update_mutex(), target.update_mutex());
    // Local mapping may have culled or fused while it was running: check again.
    if (auto checked = merge_detector_->verify(*detection.query, detection.loop)) {
      Stopwatch time;
      merged = merge_maps(target, source, *checked, merger_options_);
      spdlog::info("atlas: map {} merged into map {} (keyframe {} recognized as {}, {} inliers, {} points fused, "
                   "{:.0f} ms)", source.id(), target.id(), merged->query_id, merged->loop_id, merged->inliers,
                   merged->fused_points, time.elapsed_ms());
    }
  }
  if (merged) {
    atlas_->set_active_map(target.id());
    atlas_->remove_map(source.id());
    tracker_->switch_map(target);
    merges_.push_back(*merged);
    merge_detector_->reset();
    finished_keyframes_.take_all();
  }
  // After a merge and after a failed re-check alike, the stages start afresh
  // on the active map.
  move_stages_to_active_map();
  return merged.has_value();
}

FrameStats System::process(const SensorFrame& input) {
  Stopwatch total;
  ThreadCpuStopwatch total_cpu;
  const std::optional<double> core_wait_before = this_thread_run_queue_wait_ms();
  FrameStats stats;
  stats.index = input.index;
  stats.timestamp = input.timestamp;
  FrameDynamics dynamics;
  if (motion_stage_) motion_stage_->set_prediction(tracker_->predicted_pose());
  Frame frame = builder_->build(input, next_frame_id_++, &stats.build, &dynamics);
  if (fresh_mask_check_ && async_masks_->fresh()) {
    // An earlier frame's own mask may have come: what that frame saw on people goes.
    const SegmentationResult& fresh = *async_masks_->fresh();
    if (fresh_mask_check_->remembers(fresh.frame_index)) {
      std::lock_guard<std::mutex> lock(tracker_->map().update_mutex());
      stats.fresh_mask_culled = fresh_mask_check_->apply(fresh.frame_index, fresh.instances);
    } else {
      fresh_mask_check_->apply(fresh.frame_index, {});
    }
  }
  stats.held_points_removed = release_held_keyframes();
  // Deterministic: local mapping fuses confirmed points before this frame is
  // tracked (the threaded mapper, idle, would start at once).
  if (options_.deterministic && provisional_points_) mapper_->process_pending();
  Stopwatch tracking;
  ThreadCpuStopwatch tracking_cpu;
  const std::size_t checks_before = keyframe_check_ ? keyframe_check_->size() : 0;
  const TrackingResult result = tracker_->track(frame);
  stats.tracking_ms = tracking.elapsed_ms();
  stats.tracking_cpu_ms = tracking_cpu.elapsed_ms();
  stats.state = result.state;
  stats.reason = result.reason;
  stats.matches = result.matches;
  stats.inliers = result.inliers;
  stats.keyframe = result.new_keyframe;
  stats.keyframe_deferred = result.keyframe_deferred;
  stats.motion_prior = result.motion_prior;
  stats.build.motion.sparse_view = static_cast<int>(result.sparse_view);
  if (motion_stage_) {
    std::lock_guard<std::mutex> lock(tracker_->map().update_mutex());
    stats.build.motion.map_points_culled = motion_stage_->on_tracked(frame, result.state == TrackingState::Ok);
  }
  // A keyframe candidate or weak tracking gets the next segmentation slot.
  const bool weak = result.state == TrackingState::Ok && result.inliers < urgent_inliers_;
  if (async_masks_ && (result.keyframe_deferred || weak)) async_masks_->request_urgent();
  const int held = keyframe_hold_ ? keyframe_hold_->assign(input.index) : 0;
  const int provisional = provisional_points_ ? provisional_points_->assign(input.index) : 0;
  const int checked = keyframe_check_ ? keyframe_check_->assign(input.index) : 0;
  if (held + provisional + checked > 0) {
    // The held (or checked) keyframe's frame gets its own mask.
    stats.keyframe_held = true;
    if (async_masks_->segment_last(input.color, input.index)) stats.build.segmentation_request = ScheduleReason::Keyframe;
  }
  // The map's first keyframe made from an earlier frame (the start candidate, segmented already).
  if (keyframe_check_ && keyframe_check_->size() > checks_before && checked == 0) stats.keyframe_held = true;
  if (async_masks_) request_start_candidate_mask(input, frame);
  if (async_masks_) {
    std::optional<Eigen::Isometry3d> pose;
    if (result.state == TrackingState::Ok && frame.has_pose()) pose = frame.T_cam_world();
    cv::Mat1f sparse_depth;
    if (sensor_ == SensorType::Stereo && async_masks_->wants_sparse_depth(input.index)) {
      // Mask propagation from this frame, if it was segmented, needs depth.
      sparse_depth = cv::Mat1f::zeros(input.gray.size());
      for (std::size_t i = 0; i < frame.size(); ++i) {
        const cv::Point p = frame.keypoints_raw()[i].pt;
        if (frame.depth(i) > 0 && p.inside(cv::Rect(0, 0, sparse_depth.cols, sparse_depth.rows))) {
          sparse_depth(p) = frame.depth(i);
        }
      }
    }
    async_masks_->on_tracked(input.index, pose, std::move(sparse_depth));
    // Segmented but built with a carried mask: checked when its own mask comes.
    if (fresh_mask_check_ && pose && stats.build.segmentation_request != ScheduleReason::None &&
        stats.build.mask_age > 0) {
      std::lock_guard<std::mutex> lock(tracker_->map().update_mutex());
      fresh_mask_check_->remember(input.index, frame);
    }
  }
  stats.map_id = atlas_->active_map_id();
  // The map started from an earlier frame: the frames its start waited on get
  // their records (and poses) now, before this frame's.
  for (const StartFramePose& s : result.start_frames) {
    const auto input = std::find_if(start_inputs_.begin(), start_inputs_.end(),
                                    [&s](const auto& p) { return p.first == s.frame.id(); });
    records_.push_back({s.frame.timestamp(), s.reference, s.T_cam_reference, s.keyframe, {}});
    if (options_.trajectory_refinement.enabled) {
      std::lock_guard<std::mutex> lock(tracker_->map().update_mutex());
      records_.back().observations = collect_frame_observations(s.frame);
    }
    if (input != start_inputs_.end()) {
      stats.start_frames_posed.push_back({input->second, s.frame.timestamp(), s.frame.T_cam_world().inverse()});
    }
  }
  if (result.state == TrackingState::NotInitialized) {
    // Only the frames from the start candidate on can be posed by a start.
    start_inputs_.emplace_back(frame.id(), input.index);
    const std::optional<std::uint64_t> candidate = tracker_->start_candidate_id();
    std::erase_if(start_inputs_, [&candidate](const auto& p) { return !candidate || p.first < *candidate; });
  } else {
    start_inputs_.clear();
  }
  last_T_world_cam_.reset();
  if (result.state == TrackingState::Ok && frame.has_pose() && result.reference) {
    records_.push_back({frame.timestamp(), result.reference, result.T_cam_reference, result.new_keyframe, {}});
    records_.back().sparse_view = result.sparse_view == SparseView::Tracked ||
                                  result.sparse_view == SparseView::Blended ||
                                  result.sparse_view == SparseView::Predicted;
    records_.back().filter_projection = result.sparse_filter_projection;
    if (options_.trajectory_refinement.enabled) {
      // It reads the matched points' observations, which local mapping changes.
      std::lock_guard<std::mutex> lock(tracker_->map().update_mutex());
      records_.back().observations = collect_frame_observations(frame);
    }
    last_T_world_cam_ = frame.T_cam_world().inverse();
    stats.has_pose = true;
  }
  if (options_.deterministic) {
    Stopwatch mapping;
    mapper_->process_pending();
    if (loop_closer_) loop_closer_->process_pending();
    stats.mapping_ms = mapping.elapsed_ms();
  }
  // Only frames on which relocalization could have worked count towards a new
  // map: black or fully masked frames say nothing about the place.
  if (result.state != TrackingState::Lost) {
    lost_frames_ = 0;
  } else if (stats.build.keypoints_after >= relocalization_options_.min_inliers) {
    ++lost_frames_;
  }
  if (new_map_after_lost_frames_ > 0 && lost_frames_ >= new_map_after_lost_frames_) {
    start_new_map();
    stats.new_map = true;
  } else {
    const std::size_t merges_before = merges_.size();
    detect_and_merge();
    stats.merged = merges_.size() > merges_before;
  }
  if (loop_closer_) {
    stats.loops_closed = loop_closer_->stats().loops_closed;
    stats.global_bundle_adjustment_running = loop_closer_->global_bundle_adjustment_running();
  }
  stats.total_ms = total.elapsed_ms();
  stats.total_cpu_ms = total_cpu.elapsed_ms();
  if (const std::optional<double> core_wait = this_thread_run_queue_wait_ms(); core_wait && core_wait_before) {
    stats.core_wait_ms = *core_wait - *core_wait_before;
  }
  Stopwatch publishing;
  publish(input, frame, stats, std::move(dynamics));
  stats.publish_ms = publishing.elapsed_ms();
  return stats;
}

void System::publish(const SensorFrame& input, const Frame& frame, const FrameStats& stats, FrameDynamics dynamics) {
  auto f = std::make_shared<FrameSnapshot>();
  f->index = stats.index;
  f->frame_id = frame.id();
  f->timestamp = stats.timestamp;
  f->state = to_string(stats.state);
  f->reason = stats.reason;
  f->has_pose = stats.has_pose;
  if (last_T_world_cam_) f->T_world_cam = *last_T_world_cam_;
  f->map_id = atlas_->active_map_id();
  f->start_frames_posed = stats.start_frames_posed;
  f->keyframe = stats.keyframe;
  f->image = input.color.empty() ? input.gray : input.color;
  f->dynamic_mask = frame.dynamic_mask();
  f->keypoints.reserve(frame.size());
  f->tracked.reserve(frame.size());
  for (std::size_t i = 0; i < frame.size(); ++i) {
    f->keypoints.push_back(frame.keypoints_raw()[i].pt);
    f->tracked.push_back(frame.map_point(i) != nullptr && !frame.is_outlier(i));
  }
  f->removed_keypoints = std::move(dynamics.removed_keypoints);
  f->instances = snapshot_instances(dynamics.detections, dynamic_class_ids_);
  f->keypoints_with_depth = stats.build.keypoints_with_depth;
  f->detections = stats.build.detections;
  f->mask_coverage = stats.build.mask_coverage;
  f->held_coverage = stats.build.held_coverage;
  f->matches = stats.matches;
  f->inliers = stats.inliers;
  f->total_ms = stats.total_ms;
  publisher_.publish_frame(std::move(f));

  const bool map_changed = stats.keyframe || stats.new_map || stats.merged;
  ++frames_since_map_snapshot_;
  const int every = options_.publish.map_every_frames;
  if (!map_changed && (every == 0 || frames_since_map_snapshot_ < every)) return;
  frames_since_map_snapshot_ = 0;
  auto atlas = std::make_shared<AtlasSnapshot>();
  atlas->frame_id = frame.id();
  atlas->active_map_id = atlas_->active_map_id();
  atlas->loops_closed = stats.loops_closed;
  atlas->merges = static_cast<int>(merges_.size());
  atlas->new_maps = new_maps_started_;
  for (Map* map : atlas_->maps()) {
    std::lock_guard<std::mutex> lock(map->update_mutex());
    MapSnapshot m = snapshot_map(*map, options_.publish.min_covisibility_weight);
    m.active = map->id() == atlas->active_map_id;
    const std::unordered_set<const KeyFrame*> members = keyframes_of(*map);
    for (const FrameRecord& r : records_) {
      if (!members.count(r.reference.get())) continue;
      m.trajectory.push_back(r.T_cam_world().inverse().translation());
    }
    atlas->maps.push_back(std::move(m));
  }
  publisher_.publish_atlas(std::move(atlas));
}

std::unordered_set<const KeyFrame*> System::keyframes_of(const Map& map) {
  std::unordered_set<const KeyFrame*> out;
  for (const KeyFramePtr& kf : map.all_keyframes()) out.insert(kf.get());
  return out;
}

std::vector<MapPose> System::trajectory_with_maps() const {
  std::vector<MapPose> out(records_.size());
  std::vector<bool> done(records_.size(), false);
  for (Map* map : atlas_->maps()) {
    std::lock_guard<std::mutex> lock(map->update_mutex());
    const std::unordered_set<const KeyFrame*> members = keyframes_of(*map);
    for (std::size_t i = 0; i < records_.size(); ++i) {
      const FrameRecord& r = records_[i];
      if (done[i] || !members.count(r.reference.get())) continue;
      Eigen::Isometry3d T_cam_world = r.T_cam_world();
      // A keyframe's own pose comes from bundle adjustment, with every
      // observation of it since: better than one frame's motion-only BA.
      const bool active_keyframe = r.keyframe && !r.reference->is_bad();
      if (options_.trajectory_refinement.enabled && !active_keyframe) {
        const auto refined = refine_frame_pose(r.reference->setup(), T_cam_world, r.observations,
                                               options_.trajectory_refinement);
        if (refined) T_cam_world = *refined;
      }
      out[i] = {{r.timestamp, T_cam_world.inverse()}, map->id()};
      done[i] = true;
    }
  }
  std::vector<MapPose> kept;
  std::vector<bool> sparse;
  std::vector<Eigen::Matrix3d> projections;
  kept.reserve(out.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (!done[i]) continue;
    kept.push_back(out[i]);
    sparse.push_back(records_[i].sparse_view);
    projections.push_back(records_[i].filter_projection);
  }
  if (sparse_view_filter_gain_ > 0 || sparse_view_smooth_frames_ > 0) {
    // The sparse views' centres, filtered and then smoothed within each map.
    std::vector<Eigen::Vector3d> centres;
    std::vector<std::uint64_t> maps;
    for (const MapPose& p : kept) {
      centres.push_back(p.pose.T_world_cam.translation());
      maps.push_back(p.map_id);
    }
    if (sparse_view_filter_gain_ > 0) {
      filter_sparse_centres(centres, sparse, maps, sparse_view_filter_gain_, sparse_view_filter_frames_, projections);
    }
    if (sparse_view_smooth_frames_ > 0) smooth_sparse_centres(centres, sparse, maps, sparse_view_smooth_frames_);
    for (std::size_t i = 0; i < kept.size(); ++i) kept[i].pose.T_world_cam.translation() = centres[i];
  }
  return kept;
}

Trajectory System::trajectory() const {
  Trajectory out;
  for (const MapPose& p : trajectory_with_maps()) out.push_back(p.pose);
  return out;
}

Trajectory System::keyframe_trajectory() const {
  Trajectory out;
  for (Map* map : atlas_->maps()) {
    std::lock_guard<std::mutex> lock(map->update_mutex());
    for (const KeyFramePtr& kf : map->keyframes()) out.push_back({kf->timestamp(), kf->T_world_cam()});
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const StampedPose& a, const StampedPose& b) { return a.timestamp < b.timestamp; });
  return out;
}

LocalMapperStats System::mapper_stats() const { return mapper_->stats(); }

LoopCloserStats System::loop_closer_stats() const { return loop_closer_ ? loop_closer_->stats() : LoopCloserStats{}; }

std::size_t System::num_keyframes() const {
  std::size_t n = 0;
  for (Map* map : atlas_->maps()) {
    std::lock_guard<std::mutex> lock(map->update_mutex());
    n += map->num_keyframes();
  }
  return n;
}

std::size_t System::num_map_points() const {
  std::size_t n = 0;
  for (Map* map : atlas_->maps()) {
    std::lock_guard<std::mutex> lock(map->update_mutex());
    n += map->num_map_points();
  }
  return n;
}

}  // namespace stillslam
