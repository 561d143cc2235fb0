#include "stillslam/settings/section_binders.h"
#include "stillslam/settings/section_keys.h"

namespace stillslam {

void bind_loop_closing(const YamlReader& yaml, Settings& settings) {
  SectionKeys keys(yaml, "LoopClosing", true);
  LoopCloserOptions& loop = settings.loop_closing;
  keys.flag("detectLoops", loop.detect_loops);
  // Candidates from the bag-of-words index (shared with relocalization).
  PlaceRecognizerOptions& place = settings.place_recognition;
  keys.count("maxCandidates", place.max_loop_candidates, "PlaceRecognizerOptions.max_loop_candidates", {1, 1000});
  keys.number("minCommonWordsRatio", place.min_common_words_ratio,
              "PlaceRecognizerOptions.min_common_words_ratio", {0, 1});
  keys.check([&] { place.check(); });
  // Detection and geometric verification of a loop.
  LoopDetectorOptions& detector = loop.detector;
  keys.integer("minKeyframesBetweenLoops", detector.min_keyframes_between_loops,
               "LoopDetectorOptions.min_keyframes_between_loops", {0, 100000});
  keys.integer("consistencyThreshold", detector.consistency_threshold,
               "LoopDetectorOptions.consistency_threshold", {1, 100});
  keys.integer("minBowMatches", detector.min_bow_matches, "LoopDetectorOptions.min_bow_matches", {1, 50000});
  keys.number("projectionWindow", detector.projection_window, "LoopDetectorOptions.projection_window", {0, 1000, true});
  keys.integer("minInliers", detector.min_inliers, "LoopDetectorOptions.min_inliers", {1, 50000});
  keys.count("confirmationNeighbours", detector.confirmation_neighbours, "", {0, 1000});
  keys.integer("minConfirmationMatches", detector.min_confirmation_matches,
               "LoopDetectorOptions.min_confirmation_matches", {0, 50000});
  // Correction and global bundle adjustment.
  keys.number("fuseWindow", loop.correction.fuse_window, "LoopCorrectionOptions.fuse_window", {0, 1000, true});
  keys.integer("poseGraphIterations", loop.correction.pose_graph_iterations,
               "LoopCorrectionOptions.pose_graph_iterations", {1, 10000});
  keys.flag("globalBundleAdjustment", loop.run_global_bundle_adjustment);
  BundleAdjustmentOptions& ba = loop.global_bundle_adjustment;
  keys.integer("baThreads", ba.num_threads, "BundleAdjustmentOptions.num_threads", thread_limits(1));
  keys.integer("baIterations", ba.iterations, "BundleAdjustmentOptions.iterations", {1, 1000});
  keys.check([&] { loop.check(); });
  // Map merging (a place recognized in another map of the atlas).
  keys.flag("mapMerging", settings.map_merging);
  MapMergerOptions& merger = settings.map_merger;
  keys.integer("mergeMinInliers", merger.detector.min_inliers, "LoopDetectorOptions.min_inliers", {1, 50000});
  keys.flag("mergeGlobalBundleAdjustment", merger.global_bundle_adjustment);
  keys.reject_unknown_keys();
  keys.check([&] { merger.check(); });
}

}  // namespace stillslam
