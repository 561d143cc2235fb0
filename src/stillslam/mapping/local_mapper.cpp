#include "stillslam/mapping/local_mapper.h"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "stillslam/core/stopwatch.h"
#include "stillslam/core/thread_priority.h"
#include "stillslam/core/thread_cpu_stopwatch.h"
#include "stillslam/mapping/keyframe_insertion.h"
#include "stillslam/mapping/local_bundle_adjustment.h"

namespace stillslam {

LocalMapper::LocalMapper(Map& map, LocalMapperOptions options)
    : map_(&map),
      options_(std::move(options)),
      busy_model_(options_.busy),
      worker_(options_.threaded ? WorkerMode::Threaded : WorkerMode::Synchronous, [this](Job& job) {
        if (job.fuse_only) {
          fuse(job.kf);
          return;
        }
        abort_ba_ = false;
        abort_cause_ = BundleAdjustmentAbort::None;
        process(job.kf);
      },
      0, [nice = options_.thread_nice] {
        if (const std::string failed = lower_this_thread_priority(nice); !failed.empty()) {
          spdlog::warn("LocalMapping.threadNice {}: the mapping thread keeps its priority ({})", nice, failed);
        }
      }) {
  options_.check();
}

LocalMapper::~LocalMapper() { stop(); }

// A new keyframe does not interrupt the BA in progress: tracking asks for
// that (interrupt_bundle_adjustment) only when it needs the keyframe at once.
void LocalMapper::insert_keyframe(KeyFramePtr kf) { worker_.submit({std::move(kf), false}); }

void LocalMapper::fuse_confirmed(KeyFramePtr kf) { worker_.submit({std::move(kf), true}); }

void LocalMapper::fuse(const KeyFramePtr& kf) {
  ThreadCpuStopwatch cpu;
  {
    std::lock_guard<std::mutex> lock(map_->update_mutex());
    if (!kf->is_bad()) fuse_with_neighbours(*kf, options_.fusion);
  }
  LocalMapperStats delta;
  delta.cpu_ms = cpu.elapsed_ms();
  delta.cpu_by_step.fusion = delta.cpu_ms;
  std::lock_guard<std::mutex> lock(stats_mutex_);
  stats_ += delta;
}

bool LocalMapper::accepts_keyframes(double now) const {
  const bool idle = !worker_.threaded() || worker_.idle();
  if (!idle || !uses_busy_model()) return idle;
  std::lock_guard<std::mutex> lock(busy_mutex_);
  return busy_model_.idle(now);
}

std::size_t LocalMapper::queued_keyframes(double now) const {
  const std::size_t queued = worker_.queued();
  if (!uses_busy_model()) return queued;
  std::lock_guard<std::mutex> lock(busy_mutex_);
  return std::max(queued, busy_model_.queued(now));
}

void LocalMapper::abort(BundleAdjustmentAbort cause) {
  BundleAdjustmentAbort none = BundleAdjustmentAbort::None;
  abort_cause_.compare_exchange_strong(none, cause);
  abort_ba_ = true;
}

void LocalMapper::pause() {
  if (!worker_.threaded()) return;
  if (options_.pause_aborts_bundle_adjustment) abort(BundleAdjustmentAbort::Pause);
  worker_.pause();
}

void LocalMapper::switch_map(Map& map) {
  worker_.wait_idle();
  map_ = &map;
  recent_points_.clear();
}

LocalMapperStats LocalMapper::stats() const {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

bool LocalMapper::bundle_adjustment_due(const KeyFrame& kf) const {
  const double rate = options_.bundle_adjustments_per_second;
  if (rate <= 0 || !last_bundle_adjustment_timestamp_) return true;
  const double since = kf.timestamp() - *last_bundle_adjustment_timestamp_;
  return since < 0 || since * rate >= 1;  // time going backwards: another input
}

void LocalMapper::process(const KeyFramePtr& kf) {
  Stopwatch total;
  ThreadCpuStopwatch cpu;
  LocalMapperStats delta;
  delta.keyframes = 1;
  LocalMapperCpu& step = delta.cpu_by_step;
  ThreadCpuStopwatch step_cpu;
  auto next_step = [&step_cpu](double& total) {
    total += step_cpu.elapsed_ms();
    step_cpu = ThreadCpuStopwatch();
  };
  {
    std::lock_guard<std::mutex> lock(map_->update_mutex());
    kf->set_not_erase(true);
    register_keyframe(*kf, recent_points_);
    delta.points_culled = cull_recent_points(recent_points_, kf->id(), options_.point_culling);
  }
  next_step(step.registration);
  // Hurry (first triangulation neighbour only, no fusion, no BA) when tracking
  // interrupted us or a backlog builds up; one keyframe waiting is normal
  // (tracking queues one while we are busy). Never in synchronous mode
  // (determinism).
  const bool threaded = options_.threaded;
  auto hurry = [this, threaded] { return threaded && (abort_ba_.load() || worker_.queued() >= 2); };
  delta.points_created = create_new_points(*map_, *kf, recent_points_, options_.triangulation, hurry);
  next_step(step.triangulation);

  if (!hurry()) {
    std::lock_guard<std::mutex> lock(map_->update_mutex());
    fuse_with_neighbours(*kf, options_.fusion);
  }
  next_step(step.fusion);
  int ba_observations = 0, ba_iterations = 0;  // for the busy model
  const bool run_bundle_adjustment = options_.enable_bundle_adjustment && !hurry() && bundle_adjustment_due(*kf);
  if (options_.enable_bundle_adjustment && !run_bundle_adjustment) delta.bundle_adjustments_skipped = 1;
  if (run_bundle_adjustment) {
    LocalBundleAdjustmentProblem problem;
    {
      std::lock_guard<std::mutex> lock(map_->update_mutex());
      if (map_->num_keyframes() > 2) problem = gather_local_window(*kf, options_.window);
    }
    if (!problem.keyframes.empty()) {
      last_bundle_adjustment_timestamp_ = kf->timestamp();
      if (options_.on_bundle_adjustment_start) options_.on_bundle_adjustment_start();
      Stopwatch ba;
      ThreadCpuStopwatch ba_cpu;
      BundleAdjustmentOptions ba_options = options_.bundle_adjustment;
      // The solver sees the interrupt only after iterations_before_interrupt
      // iterations (counted over the passes, each pass's start included).
      std::atomic<bool> ba_abort{false};
      int calls = 0;
      if (threaded) {
        ba_options.abort = &ba_abort;
        const int gate = options_.iterations_before_interrupt;
        ba_options.on_iteration = [this, &ba_abort, &calls, gate, hook = options_.bundle_adjustment.on_iteration] {
          if (hook) hook();
          if (calls++ >= gate && abort_ba_.load()) ba_abort = true;
        };
        if (gate == 0 && abort_ba_.load()) ba_abort = true;
      }
      const BundleAdjustmentResult result = solve_local_window(kf->setup().camera, problem, ba_options);
      LocalBundleAdjustmentStats window;
      {
        std::lock_guard<std::mutex> lock(map_->update_mutex());
        window = apply_local_window(problem, result);
      }
      delta.bundle_adjustments = 1;
      delta.bundle_adjustments_aborted = result.aborted ? 1 : 0;
      const BundleAdjustmentAbort cause = result.aborted ? abort_cause_.load() : BundleAdjustmentAbort::None;
      delta.bundle_adjustments_aborted_by_tracking = cause == BundleAdjustmentAbort::Tracking ? 1 : 0;
      delta.bundle_adjustments_aborted_by_pause = cause == BundleAdjustmentAbort::Pause ? 1 : 0;
      const bool cut_short = result.aborted && result.applied_steps > 0;
      delta.bundle_adjustments_cut_short = cut_short ? 1 : 0;
      delta.bundle_adjustments_discarded = result.aborted && !cut_short ? 1 : 0;
      delta.bundle_adjustment_ms = ba.elapsed_ms();
      LocalBundleAdjustmentRecord record;
      record.keyframes = window.keyframes;
      record.fixed_keyframes = window.fixed_keyframes;
      record.points = window.points;
      record.observations = window.observations;
      record.iterations = result.iterations;
      record.ms = delta.bundle_adjustment_ms;
      record.cpu_ms = ba_cpu.elapsed_ms();
      record.aborted = result.aborted;
      record.cut_short = cut_short;
      record.abort_cause = cause;
      delta.bundle_adjustment_runs.push_back(record);
      ba_observations = window.observations;
      ba_iterations = result.iterations;
    }
  }
  next_step(step.bundle_adjustment);
  std::vector<std::uint64_t> culled;
  bool keyframe_alive = false;
  {
    std::lock_guard<std::mutex> lock(map_->update_mutex());
    kf->set_not_erase(false);
    if (options_.enable_keyframe_culling) {
      delta.keyframes_culled = cull_redundant_keyframes(*map_, *kf, options_.keyframe_culling, &culled);
    }
    map_->remove_bad_points();
    keyframe_alive = !kf->is_bad();
  }
  next_step(step.keyframe_culling);
  if (options_.on_keyframe_culled) {
    for (std::uint64_t id : culled) options_.on_keyframe_culled(id);
  }
  if (options_.on_keyframe_processed && keyframe_alive) options_.on_keyframe_processed(kf);
  delta.total_ms = total.elapsed_ms();
  delta.cpu_ms = cpu.elapsed_ms();
  if (uses_busy_model()) {
    std::lock_guard<std::mutex> lock(busy_mutex_);
    delta.modelled_busy_ms = busy_model_.busy_ms(ba_observations, ba_iterations);
    busy_model_.add(kf->timestamp(), delta.modelled_busy_ms);
  }
  std::lock_guard<std::mutex> lock(stats_mutex_);
  stats_ += delta;
}

}  // namespace stillslam
