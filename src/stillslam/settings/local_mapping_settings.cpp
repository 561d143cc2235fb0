#include <string>

#include "stillslam/settings/section_binders.h"
#include "stillslam/settings/section_keys.h"

namespace stillslam {
namespace {

BaSolver read_ba_solver(SectionKeys& keys, BaSolver current) {
  const cv::FileNode n = keys.node("baSolver");
  if (n.isNone()) return current;
  const std::string value = n.isString() ? static_cast<std::string>(n) : std::string();
  if (value == "schur") return BaSolver::Schur;
  if (value == "ceres") return BaSolver::Ceres;
  keys.fail("baSolver", "must be schur (the hand-written Schur-complement solver) or ceres");
}

}  // namespace

void bind_local_mapping(const YamlReader& yaml, LocalMapperOptions& options) {
  SectionKeys keys(yaml, "LocalMapping", true);
  // Local bundle adjustment.
  keys.flag("bundleAdjustment", options.enable_bundle_adjustment);
  BundleAdjustmentOptions& ba = options.bundle_adjustment;
  keys.integer("baThreads", ba.num_threads, "BundleAdjustmentOptions.num_threads", thread_limits(1));
  keys.integer("threadNice", options.thread_nice, "LocalMapperOptions.thread_nice", {0, 19});
  keys.integer("baIterations", ba.iterations, "BundleAdjustmentOptions.iterations", {1, 1000});
  keys.integer("baIterationsAfterOutliers", ba.iterations_after_outliers,
               "BundleAdjustmentOptions.iterations_after_outliers", {0, 1000});
  ba.solver = read_ba_solver(keys, ba.solver);
  keys.flag("baSplitStereo", ba.split_stereo);
  keys.number("baFunctionTolerance", ba.function_tolerance, "BundleAdjustmentOptions.function_tolerance", {0, 1});
  keys.number("baMaxSeconds", ba.max_seconds_per_pass, "BundleAdjustmentOptions.max_seconds_per_pass", {0, 60});
  keys.number("bundleAdjustmentsPerSecond", options.bundle_adjustments_per_second,
              "LocalMapperOptions.bundle_adjustments_per_second", {0, 1000});
  keys.flag("pauseAbortsBundleAdjustment", options.pause_aborts_bundle_adjustment);
  keys.flag("baKeepInterrupted", ba.keep_progress_on_abort);
  keys.integer("baIterationsBeforeInterrupt", options.iterations_before_interrupt,
               "LocalMapperOptions.iterations_before_interrupt", {0, 100});
  // Busy model of keyframe admission (mapping/mapper_busy_model.h).
  keys.flag("busyModel", options.busy_model);
  keys.flag("busyModelThreaded", options.busy_model_threaded);
  MapperBusyModelOptions& busy = options.busy;
  keys.number("busyModelKeyframeMs", busy.keyframe_ms, "MapperBusyModelOptions.keyframe_ms", {0, 10000});
  keys.number("busyModelObservationUs", busy.observation_us, "MapperBusyModelOptions.observation_us", {0, 1000});
  keys.number("busyModelObservationIterationUs", busy.observation_iteration_us,
              "MapperBusyModelOptions.observation_iteration_us", {0, 1000});
  // Window budget (0: no limit).
  LocalWindowOptions& window = options.window;
  keys.integer("windowKeyframes", window.max_keyframes, "LocalWindowOptions.max_keyframes", {0, 1000});
  keys.integer("windowFixedKeyframes", window.max_fixed_keyframes, "LocalWindowOptions.max_fixed_keyframes",
               {0, 1000});
  keys.integer("windowPoints", window.max_points, "LocalWindowOptions.max_points", {0, 1000000});
  keys.integer("windowObservations", window.max_observations, "LocalWindowOptions.max_observations",
               {0, 5000000});
  // New points, fusion, culling.
  keys.count("triangulationNeighbours", options.triangulation.neighbours,
             "PointTriangulationOptions.neighbours", {1, 1000});
  keys.count("fusionNeighbours", options.fusion.neighbours, "FusionOptions.neighbours", {1, 1000});
  keys.count("fusionSecondNeighbours", options.fusion.second_neighbours, "FusionOptions.second_neighbours", {0, 1000});
  keys.number("pointMinFoundRatio", options.point_culling.min_found_ratio,
              "PointCullingOptions.min_found_ratio", {0, 1});
  keys.integer("pointMinObservations", options.point_culling.min_observations,
               "PointCullingOptions.min_observations", {0, 1000});
  keys.flag("keyframeCulling", options.enable_keyframe_culling);
  keys.number("keyframeRedundancy", options.keyframe_culling.redundancy,
              "KeyFrameCullingOptions.redundancy", {0, 1, true});
  keys.integer("keyframeMinObservers", options.keyframe_culling.min_observers,
               "KeyFrameCullingOptions.min_observers", {1, 1000});
  keys.reject_unknown_keys();
  keys.check([&] { options.check(); });
}

}  // namespace stillslam
