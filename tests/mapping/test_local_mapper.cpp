// LocalMapper's hooks for loop closing: pause()/resume() of the worker thread
// and the keyframe-processed / keyframe-culled callbacks.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>

#include "map/map_builder.h"
#include "stillslam/core/option_check.h"
#include "stillslam/core/thread_priority.h"
#include "stillslam/mapping/local_mapper.h"

namespace stillslam {
namespace {

struct Recorded {
  std::mutex mutex;
  std::vector<std::uint64_t> processed, culled;
};

LocalMapperOptions options_recording(Recorded& rec, bool threaded) {
  LocalMapperOptions o;
  o.threaded = threaded;
  o.enable_bundle_adjustment = false;  // the hooks are under test, not BA
  o.on_keyframe_processed = [&rec](KeyFramePtr kf) {
    std::lock_guard<std::mutex> lock(rec.mutex);
    rec.processed.push_back(kf->id());
  };
  o.on_keyframe_culled = [&rec](std::uint64_t id) {
    std::lock_guard<std::mutex> lock(rec.mutex);
    rec.culled.push_back(id);
  };
  return o;
}

TEST(LocalMapper, PausedWorkerLeavesKeyframesQueuedUntilResumed) {
  test::SyntheticScene scene;
  test::MapBuilder builder(scene);
  std::vector<KeyFramePtr> kfs;
  for (int k = 0; k < 5; ++k) kfs.push_back(builder.add_keyframe(test::pose_at(0.01 * k)));
  Recorded rec;
  LocalMapper mapper(builder.map(), options_recording(rec, true));
  mapper.pause();
  mapper.insert_keyframe(kfs[4]);
  EXPECT_EQ(mapper.queued_keyframes(0.0), 1u);  // the paused worker does not take it
  EXPECT_EQ(mapper.stats().keyframes, 0);
  mapper.resume();
  mapper.flush();
  EXPECT_EQ(mapper.queued_keyframes(0.0), 0u);
  const LocalMapperStats stats = mapper.stats();
  EXPECT_EQ(stats.keyframes, 1);
  mapper.stop();
  ASSERT_EQ(rec.processed.size(), 1u);
  EXPECT_EQ(rec.processed[0], kfs[4]->id());
  // Every culled keyframe is reported once, and is gone from the map.
  EXPECT_EQ(static_cast<int>(rec.culled.size()), stats.keyframes_culled);
  EXPECT_GT(stats.keyframes_culled, 0);
  for (std::uint64_t id : rec.culled) EXPECT_TRUE(builder.map().keyframe(id) == nullptr) << id;
}

#if defined(__linux__)
TEST(LocalMapper, ThreadNiceLowersTheMappingThreadOnly) {
  test::SyntheticScene scene;
  test::MapBuilder builder(scene);
  std::vector<KeyFramePtr> kfs;
  for (int k = 0; k < 3; ++k) kfs.push_back(builder.add_keyframe(test::pose_at(0.01 * k)));
  const int main_nice = this_thread_nice().value();
  std::optional<int> seen;
  LocalMapperOptions o;
  o.enable_bundle_adjustment = false;
  o.thread_nice = 6;
  o.on_keyframe_processed = [&seen](KeyFramePtr) { seen = this_thread_nice(); };
  {
    LocalMapper mapper(builder.map(), o);
    mapper.insert_keyframe(kfs[2]);
    mapper.flush();
  }
  EXPECT_EQ(seen, std::min(main_nice + 6, kMaxNice));
  EXPECT_EQ(this_thread_nice(), main_nice);
  o.thread_nice = 20;
  EXPECT_THROW(LocalMapper(builder.map(), o), OptionError);
}
#endif

TEST(LocalMapper, PauseIsANoOpInSynchronousMode) {
  test::SyntheticScene scene;
  test::MapBuilder builder(scene);
  std::vector<KeyFramePtr> kfs;
  for (int k = 0; k < 3; ++k) kfs.push_back(builder.add_keyframe(test::pose_at(0.01 * k)));
  Recorded rec;
  LocalMapper mapper(builder.map(), options_recording(rec, false));
  mapper.pause();  // must not block: the owner's thread is the worker
  mapper.insert_keyframe(kfs[2]);
  mapper.process_pending();
  mapper.resume();
  EXPECT_EQ(mapper.stats().keyframes, 1);
  ASSERT_EQ(rec.processed.size(), 1u);
  EXPECT_EQ(rec.processed[0], kfs[2]->id());
}

// A keyframe queued behind another does not cost the first its BA; a
// backlog of two does (the mapper hurries to catch up).
TEST(LocalMapper, OneWaitingKeyframeKeepsTheBundleAdjustmentABacklogSkipsIt) {
  test::SyntheticScene scene;
  test::MapBuilder builder(scene);
  std::vector<KeyFramePtr> kfs;
  for (int k = 0; k < 6; ++k) kfs.push_back(builder.add_keyframe(test::pose_at(0.05 * k)));
  for (int backlog : {2, 3}) {
    Recorded rec;
    LocalMapperOptions o = options_recording(rec, true);
    o.enable_bundle_adjustment = true;
    o.enable_keyframe_culling = false;
    LocalMapper mapper(builder.map(), o);
    mapper.pause();
    for (int k = 0; k < backlog; ++k) mapper.insert_keyframe(kfs[static_cast<std::size_t>(3 + k)]);
    mapper.resume();
    mapper.flush();
    const LocalMapperStats stats = mapper.stats();
    EXPECT_EQ(stats.keyframes, backlog);
    EXPECT_EQ(stats.bundle_adjustments_aborted, 0);
    EXPECT_EQ(stats.bundle_adjustments_skipped, backlog - 2);
    EXPECT_EQ(stats.bundle_adjustments, 2);
    ASSERT_EQ(stats.bundle_adjustment_runs.size(), 2u);
    EXPECT_GE(stats.bundle_adjustment_runs[0].keyframes, 1);
    EXPECT_GT(stats.bundle_adjustment_runs[0].observations, 0);
    EXPECT_GT(stats.cpu_ms, 0);
  }
}

// LocalMapping.bundleAdjustmentsPerSecond: keyframes 0.1 s apart with at most
// 4 BAs per second get a BA 0.3 s apart (the first, then the fourth); without
// it every keyframe gets one.
TEST(LocalMapper, BundleAdjustmentsPerSecondSkipsTheKeyframesBetween) {
  test::SyntheticScene scene;
  test::MapBuilder builder(scene);
  std::vector<KeyFramePtr> kfs;
  for (int k = 0; k < 8; ++k) kfs.push_back(builder.add_keyframe(test::pose_at(0.05 * k)));
  ASSERT_DOUBLE_EQ(kfs[2]->timestamp(), 0.2);
  for (double rate : {0.0, 4.0}) {
    Recorded rec;
    LocalMapperOptions o = options_recording(rec, false);
    o.enable_bundle_adjustment = true;
    o.enable_keyframe_culling = false;
    o.bundle_adjustments_per_second = rate;
    LocalMapper mapper(builder.map(), o);
    std::vector<int> bundle_adjustments;  // after each keyframe
    for (std::size_t k = 2; k < 8; ++k) {
      mapper.insert_keyframe(kfs[k]);
      mapper.process_pending();
      bundle_adjustments.push_back(mapper.stats().bundle_adjustments);
    }
    const LocalMapperStats stats = mapper.stats();
    EXPECT_EQ(stats.keyframes, 6);
    if (rate == 0) {
      EXPECT_EQ(bundle_adjustments, (std::vector<int>{1, 2, 3, 4, 5, 6}));
      EXPECT_EQ(stats.bundle_adjustments_skipped, 0);
    } else {
      // BAs at 0.2 s and 0.5 s (0.3 >= 1 / 4), none at 0.3, 0.4 (< 0.25 s after 0.2), 0.6, 0.7.
      EXPECT_EQ(bundle_adjustments, (std::vector<int>{1, 1, 1, 2, 2, 2}));
      EXPECT_EQ(stats.bundle_adjustments_skipped, 4);
    }
    EXPECT_EQ(static_cast<int>(stats.bundle_adjustment_runs.size()), stats.bundle_adjustments);
  }
  // Out of range: the error names the field.
  LocalMapperOptions bad;
  bad.bundle_adjustments_per_second = -1;
  try {
    bad.check();
    FAIL() << "no error";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "LocalMapperOptions.bundle_adjustments_per_second");
  }
}

// Synchronous mapping is never busy when tracking asks; the busy model makes
// it look busy for each keyframe's modelled cost from the keyframe's
// timestamp on, and a keyframe arriving meanwhile waits behind it.
TEST(LocalMapper, SynchronousMapperLooksBusyForTheModelledTime) {
  test::SyntheticScene scene;
  test::MapBuilder builder(scene);
  std::vector<KeyFramePtr> kfs;
  for (int k = 0; k < 6; ++k) kfs.push_back(builder.add_keyframe(test::pose_at(0.05 * k)));
  for (bool model : {false, true}) {
    Recorded rec;
    LocalMapperOptions o = options_recording(rec, false);
    o.enable_bundle_adjustment = true;
    o.enable_keyframe_culling = false;
    o.busy_model = model;
    o.busy.keyframe_ms = 250;  // longer than the 0.1 s between the keyframes
    LocalMapper mapper(builder.map(), o);
    const double t4 = kfs[4]->timestamp(), t5 = kfs[5]->timestamp();
    ASSERT_NEAR(t5 - t4, 0.1, 1e-9);
    mapper.insert_keyframe(kfs[4]);
    mapper.process_pending();
    const LocalMapperStats stats = mapper.stats();
    ASSERT_EQ(stats.bundle_adjustment_runs.size(), 1u);
    const LocalBundleAdjustmentRecord& run = stats.bundle_adjustment_runs[0];
    ASSERT_GT(run.observations, 0);
    const double busy_ms = MapperBusyModel(o.busy).busy_ms(run.observations, run.iterations);
    EXPECT_GT(busy_ms, 250.0);
    if (!model) {
      EXPECT_TRUE(mapper.accepts_keyframes(t4 + 0.001));
      EXPECT_EQ(stats.modelled_busy_ms, 0.0);
      continue;
    }
    EXPECT_DOUBLE_EQ(stats.modelled_busy_ms, busy_ms);
    EXPECT_FALSE(mapper.accepts_keyframes(t4 + 0.5 * busy_ms / 1000));
    EXPECT_TRUE(mapper.accepts_keyframes(t4 + busy_ms / 1000));
    EXPECT_EQ(mapper.queued_keyframes(t5), 0u);
    mapper.insert_keyframe(kfs[5]);  // arrives while kfs[4] is modelled busy
    mapper.process_pending();
    EXPECT_EQ(mapper.queued_keyframes(t5), 1u);
    EXPECT_EQ(mapper.queued_keyframes(t4 + busy_ms / 1000), 0u);
    EXPECT_FALSE(mapper.accepts_keyframes(t4 + busy_ms / 1000));
    EXPECT_TRUE(mapper.accepts_keyframes(t4 + mapper.stats().modelled_busy_ms / 1000 + 1e-9));
  }
}

// Loop closing pauses the mapper while its BA runs (the hook pauses from
// another thread and returns once the pause is requested, before the solve):
// by default the BA finishes and the pause waits for it; with
// pause_aborts_bundle_adjustment the BA is aborted and counted as the pause's.
TEST(LocalMapper, PauseWaitsForTheRunningBundleAdjustmentUnlessSetToAbortIt) {
  test::SyntheticScene scene;
  test::MapBuilder builder(scene);
  std::vector<KeyFramePtr> kfs;
  for (int k = 0; k < 5; ++k) kfs.push_back(builder.add_keyframe(test::pose_at(0.05 * k)));
  for (bool aborts : {false, true}) {
    Recorded rec;
    LocalMapperOptions o = options_recording(rec, true);
    o.enable_bundle_adjustment = true;
    o.enable_keyframe_culling = false;
    o.pause_aborts_bundle_adjustment = aborts;
    LocalMapper* mapper_ptr = nullptr;
    std::thread pauser;
    std::atomic<bool> hooked{false};
    o.on_bundle_adjustment_start = [&] {
      if (hooked) return;
      pauser = std::thread([&] { mapper_ptr->pause(); });
      while (!mapper_ptr->paused()) std::this_thread::yield();
      hooked = true;
    };
    LocalMapper mapper(builder.map(), o);
    mapper_ptr = &mapper;
    mapper.insert_keyframe(kfs[4]);
    while (!hooked) std::this_thread::yield();
    pauser.join();  // pause() returns once the keyframe is done
    const LocalMapperStats stats = mapper.stats();
    EXPECT_EQ(stats.keyframes, 1) << aborts;
    ASSERT_EQ(stats.bundle_adjustments, 1) << aborts;
    EXPECT_EQ(stats.bundle_adjustments_aborted, aborts ? 1 : 0);
    EXPECT_EQ(stats.bundle_adjustments_aborted_by_pause, aborts ? 1 : 0);
    EXPECT_EQ(stats.bundle_adjustments_aborted_by_tracking, 0);
    ASSERT_EQ(stats.bundle_adjustment_runs.size(), 1u);
    EXPECT_EQ(stats.bundle_adjustment_runs[0].abort_cause,
              aborts ? BundleAdjustmentAbort::Pause : BundleAdjustmentAbort::None);
    if (aborts) {
      // The exact map is at its optimum: the robust pass ends at its start and
      // the abort stops the outlier-free pass before it takes a step.
      EXPECT_EQ(stats.bundle_adjustment_runs[0].iterations, 0);
      EXPECT_EQ(stats.bundle_adjustments_discarded, 1);
    } else {
      EXPECT_GT(stats.bundle_adjustment_runs[0].iterations, 0);
    }
    mapper.resume();
    mapper.stop();
  }
}

// Tracking's interrupt aborts the running BA and is counted as its cause; a
// pause that comes after it does not change the cause.
TEST(LocalMapper, TrackingInterruptIsCountedAsTheAbortCause) {
  test::SyntheticScene scene;
  test::MapBuilder builder(scene);
  std::vector<KeyFramePtr> kfs;
  for (int k = 0; k < 5; ++k) kfs.push_back(builder.add_keyframe(test::pose_at(0.05 * k)));
  Recorded rec;
  LocalMapperOptions o = options_recording(rec, true);
  o.enable_bundle_adjustment = true;
  o.enable_keyframe_culling = false;
  o.pause_aborts_bundle_adjustment = true;
  LocalMapper* mapper_ptr = nullptr;
  std::thread pauser;
  std::atomic<bool> hooked{false};
  o.on_bundle_adjustment_start = [&] {
    mapper_ptr->interrupt_bundle_adjustment();
    pauser = std::thread([&] { mapper_ptr->pause(); });
    while (!mapper_ptr->paused()) std::this_thread::yield();
    hooked = true;
  };
  LocalMapper mapper(builder.map(), o);
  mapper_ptr = &mapper;
  mapper.insert_keyframe(kfs[4]);
  while (!hooked) std::this_thread::yield();
  pauser.join();
  const LocalMapperStats stats = mapper.stats();
  ASSERT_EQ(stats.bundle_adjustments, 1);
  EXPECT_EQ(stats.bundle_adjustments_aborted, 1);
  EXPECT_EQ(stats.bundle_adjustments_aborted_by_tracking, 1);
  EXPECT_EQ(stats.bundle_adjustments_aborted_by_pause, 0);
  ASSERT_EQ(stats.bundle_adjustment_runs.size(), 1u);
  EXPECT_EQ(stats.bundle_adjustment_runs[0].abort_cause, BundleAdjustmentAbort::Tracking);
  mapper.resume();
  mapper.stop();
}

// Five keyframes of the synthetic scene with exact points; the newest one's
// pose is moved 3 cm off, so a BA step shows in its error.
struct DisplacedKeyframeMap {
  test::SyntheticScene scene;
  test::MapBuilder builder{scene};
  std::vector<KeyFramePtr> kfs;
  Eigen::Isometry3d truth;
  double start_error = 0;
  DisplacedKeyframeMap() {
    for (int k = 0; k < 5; ++k) kfs.push_back(builder.add_keyframe(test::pose_at(0.05 * k)));
    truth = kfs[4]->T_cam_world();
    Eigen::Isometry3d start = truth;
    start.translation() += Eigen::Vector3d(0.03, -0.01, 0.02);
    kfs[4]->set_pose(start);
    start_error = (start.translation() - truth.translation()).norm();
  }
  double error() const { return (kfs[4]->T_cam_world().translation() - truth.translation()).norm(); }
};

// Tracking interrupts the BA after its first Ceres step (the new keyframe's
// pose was moved 3 cm off). By default that step is applied to the map and
// the BA counts as cut short; with keep_progress_on_abort false the keyframe
// keeps its start pose and the BA counts as discarded.
TEST(LocalMapper, InterruptedBundleAdjustmentAppliesItsProgress) {
  for (const bool keep : {true, false}) {
    DisplacedKeyframeMap m;
    Recorded rec;
    LocalMapperOptions o = options_recording(rec, true);
    o.enable_bundle_adjustment = true;
    o.enable_keyframe_culling = false;
    o.bundle_adjustment.keep_progress_on_abort = keep;
    LocalMapper* mapper_ptr = nullptr;
    int calls = 0;
    o.bundle_adjustment.on_iteration = [&] {
      if (++calls == 2) mapper_ptr->interrupt_bundle_adjustment();  // after iteration 1
    };
    LocalMapper mapper(m.builder.map(), o);
    mapper_ptr = &mapper;
    mapper.insert_keyframe(m.kfs[4]);
    mapper.flush();
    const LocalMapperStats stats = mapper.stats();
    mapper.stop();
    ASSERT_EQ(stats.bundle_adjustments, 1) << keep;
    EXPECT_EQ(stats.bundle_adjustments_aborted, 1) << keep;
    EXPECT_EQ(stats.bundle_adjustments_aborted_by_tracking, 1) << keep;
    EXPECT_EQ(stats.bundle_adjustments_cut_short, keep ? 1 : 0);
    EXPECT_EQ(stats.bundle_adjustments_discarded, keep ? 0 : 1);
    ASSERT_EQ(stats.bundle_adjustment_runs.size(), 1u);
    EXPECT_EQ(stats.bundle_adjustment_runs[0].cut_short, keep);
    EXPECT_EQ(stats.bundle_adjustment_runs[0].iterations, 1) << keep;
    const double error = m.error();
    if (keep) {
      EXPECT_LT(error, 0.2 * m.start_error);  // one Gauss-Newton-like step from exact points
    } else {
      EXPECT_NEAR(error, m.start_error, 1e-9);
    }
  }
}

// Tracking interrupts just before the solve: with iterations_before_interrupt
// 1 (the default) the BA does one iteration and applies it (cut short); with
// 0 it stops before any and nothing is kept (discarded).
TEST(LocalMapper, InterruptTakesEffectAfterTheFirstIteration) {
  for (const int gate : {1, 0}) {
    DisplacedKeyframeMap m;
    Recorded rec;
    LocalMapperOptions o = options_recording(rec, true);
    o.enable_bundle_adjustment = true;
    o.enable_keyframe_culling = false;
    o.iterations_before_interrupt = gate;
    LocalMapper* mapper_ptr = nullptr;
    o.on_bundle_adjustment_start = [&] { mapper_ptr->interrupt_bundle_adjustment(); };
    LocalMapper mapper(m.builder.map(), o);
    mapper_ptr = &mapper;
    mapper.insert_keyframe(m.kfs[4]);
    mapper.flush();
    const LocalMapperStats stats = mapper.stats();
    mapper.stop();
    ASSERT_EQ(stats.bundle_adjustment_runs.size(), 1u) << gate;
    EXPECT_EQ(stats.bundle_adjustments_aborted_by_tracking, 1) << gate;
    EXPECT_EQ(stats.bundle_adjustment_runs[0].iterations, gate);
    EXPECT_EQ(stats.bundle_adjustments_cut_short, gate);
    EXPECT_EQ(stats.bundle_adjustments_discarded, 1 - gate);
    const double error = m.error();
    if (gate == 1) {
      EXPECT_LT(error, 0.2 * m.start_error);
    } else {
      EXPECT_NEAR(error, m.start_error, 1e-9);
    }
  }
}

}  // namespace
}  // namespace stillslam
