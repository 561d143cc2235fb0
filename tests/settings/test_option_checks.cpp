// check() of every Options struct the settings bind: defaults pass, and a bad
// value of each kind is an OptionError naming the field, its value and the
// valid range. Components that take the options check them on construction.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "stillslam/core/option_check.h"
#include "stillslam/features/orb_extractor.h"
#include "stillslam/features/stereo_matcher.h"
#include "stillslam/segmentation/mask_hold.h"
#include "stillslam/settings/settings.h"
#include "stillslam/tracking/tracker.h"

namespace stillslam {
namespace {

struct Case {
  std::string field, message;
  std::function<void()> check;  // runs check() on options with one bad value
};

// `mutate` spoils one field of default options; check() must name it.
template <class Options>
Case bad(const std::string& field, const std::string& message, std::function<void(Options&)> mutate) {
  return {field, message, [mutate] {
            Options o;
            mutate(o);
            o.check();
          }};
}

void expect_rejected(const std::vector<Case>& cases) {
  for (const Case& c : cases) {
    SCOPED_TRACE(c.field);
    try {
      c.check();
      ADD_FAILURE() << "no error";
    } catch (const OptionError& e) {
      EXPECT_EQ(e.field(), c.field);
      EXPECT_EQ(std::string(e.what()), c.field + " is " + c.message) << e.what();
    }
  }
}

TEST(OptionChecks, DefaultsPass) {
  EXPECT_NO_THROW(OrbOptions{}.check());
  EXPECT_NO_THROW(StereoMatchOptions{}.check());
  EXPECT_NO_THROW(SegmentationOptions{}.check());
  EXPECT_NO_THROW(MaskHoldOptions{}.check());
  EXPECT_NO_THROW(TrackerOptions{}.check());
  EXPECT_NO_THROW(InitialViewCheckOptions{}.check());
  EXPECT_NO_THROW(PoseOptimizerOptions{}.check());
  EXPECT_NO_THROW(LocalMapperOptions{}.check());
  EXPECT_NO_THROW(BundleAdjustmentOptions{}.check());
  EXPECT_NO_THROW(LoopCloserOptions{}.check());
  EXPECT_NO_THROW(PlaceRecognizerOptions{}.check());
  EXPECT_NO_THROW(RelocalizerOptions{}.check());
  EXPECT_NO_THROW(MapMergerOptions{}.check());
  EXPECT_NO_THROW(ViewerOptions{}.check());
}

TEST(OptionChecks, FeaturesAndSegmentation) {
  expect_rejected({
      bad<OrbOptions>("OrbOptions.n_features", "0: must be >= 1", [](auto& o) { o.n_features = 0; }),
      bad<OrbOptions>("OrbOptions.scale_factor", "0.9: must be > 1", [](auto& o) { o.scale_factor = 0.9f; }),
      bad<OrbOptions>("OrbOptions.n_levels", "0: must be >= 1", [](auto& o) { o.n_levels = 0; }),
      bad<OrbOptions>("OrbOptions.ini_th_fast", "255: must be in [1, 254]", [](auto& o) { o.ini_th_fast = 255; }),
      bad<OrbOptions>("OrbOptions.min_th_fast", "21: must be in [1, 20]", [](auto& o) { o.min_th_fast = 21; }),
      bad<OrbOptions>("OrbOptions.fast_cell_size", "4: must be >= 8", [](auto& o) { o.fast_cell_size = 4; }),
      bad<StereoMatchOptions>("StereoMatchOptions.max_descriptor_distance", "300: must be in [0, 256]",
                              [](auto& o) { o.max_descriptor_distance = 300; }),
      bad<StereoMatchOptions>("StereoMatchOptions.patch_half_size", "0: must be >= 1",
                              [](auto& o) { o.patch_half_size = 0; }),
      bad<StereoMatchOptions>("StereoMatchOptions.row_band", "0: must be > 0", [](auto& o) { o.row_band = 0; }),
      bad<StereoMatchOptions>("StereoMatchOptions.max_disparity", "4: must be > 5", [](auto& o) {
        o.min_disparity = 5;
        o.max_disparity = 4;
      }),
      bad<SegmentationOptions>("SegmentationOptions.classes", "empty: must name at least one class",
                               [](auto& o) { o.classes.clear(); }),
      bad<SegmentationOptions>("SegmentationOptions.score_threshold", "1.5: must be in [0, 1]",
                               [](auto& o) { o.score_threshold = 1.5f; }),
      bad<SegmentationOptions>("SegmentationOptions.nms_iou_threshold", "0: must be in (0, 1]",
                               [](auto& o) { o.nms_iou_threshold = 0; }),
      bad<SegmentationOptions>("SegmentationOptions.mask_threshold", "1: must be in (0, 1)",
                               [](auto& o) { o.mask_threshold = 1; }),
      bad<SegmentationOptions>("SegmentationOptions.mask_dilation", "-1: must be >= 0",
                               [](auto& o) { o.mask_dilation = -1; }),
      bad<SegmentationOptions>("SegmentationOptions.threads", "-2: must be >= 0", [](auto& o) { o.threads = -2; }),
      bad<MaskHoldOptions>("MaskHoldOptions.frames", "-1: must be >= 0", [](auto& o) { o.frames = -1; }),
      bad<MaskHoldOptions>("MaskHoldOptions.min_overlap", "0: must be in (0, 1]", [](auto& o) { o.min_overlap = 0; }),
      bad<MaskHoldOptions>("MaskHoldOptions.grow_px_per_frame", "-4: must be >= 0",
                           [](auto& o) { o.grow_px_per_frame = -4; }),
  });
  // One pyramid level needs no scale factor.
  OrbOptions one_level;
  one_level.n_levels = 1;
  one_level.scale_factor = 1.0f;
  EXPECT_NO_THROW(one_level.check());
}

TEST(OptionChecks, Tracking) {
  expect_rejected({
      bad<TrackerOptions>("TrackerOptions.init_min_keypoints", "0: must be >= 1",
                          [](auto& o) { o.init_min_keypoints = 0; }),
      bad<TrackerOptions>("InitialViewCheckOptions.max_masked_fraction", "-0.1: must be in [0, 1]",
                          [](auto& o) { o.initial_view.max_masked_fraction = -0.1; }),
      bad<TrackerOptions>("TrackerOptions.min_frames_between_keyframes", "31: must be in [0, 30]",
                          [](auto& o) { o.min_frames_between_keyframes = 31; }),
      bad<TrackerOptions>("TrackerOptions.motion_search_radius", "0: must be > 0",
                          [](auto& o) { o.motion_search_radius = 0; }),
      bad<TrackerOptions>("TrackerOptions.max_local_keyframes", "0: must be >= 1",
                          [](auto& o) { o.max_local_keyframes = 0; }),
      bad<TrackerOptions>("PoseOptimizerOptions.rounds", "0: must be >= 1", [](auto& o) { o.pose.rounds = 0; }),
      bad<InitialViewCheckOptions>("InitialViewCheckOptions.min_matches", "0: must be >= 1",
                                   [](auto& o) { o.min_matches = 0; }),
      bad<InitialViewCheckOptions>("InitialViewCheckOptions.max_reprojection_error_px", "0: must be > 0",
                                   [](auto& o) { o.max_reprojection_error_px = 0; }),
      bad<PoseOptimizerOptions>("PoseOptimizerOptions.chi2_stereo", "-1: must be > 0",
                                [](auto& o) { o.chi2_stereo = -1; }),
      bad<PoseOptimizerOptions>("PoseOptimizerOptions.chi2_mono", "nan: must be > 0",  // NaN fails every range
                                [](auto& o) { o.chi2_mono = std::nan(""); }),
      bad<RelocalizerOptions>("RelocalizerOptions.min_inliers", "0: must be >= 1", [](auto& o) { o.min_inliers = 0; }),
      bad<RelocalizerOptions>("RelocalizerOptions.min_supported_cells", "1.2: must be in [0, 1]",
                              [](auto& o) { o.min_supported_cells = 1.2; }),
      bad<RelocalizerOptions>("RelocalizerOptions.check_radius", "0: must be > 0", [](auto& o) { o.check_radius = 0; }),
  });
}

TEST(OptionChecks, LocalMapping) {
  expect_rejected({
      bad<LocalMapperOptions>("PointCullingOptions.min_found_ratio", "2: must be in [0, 1]",
                              [](auto& o) { o.point_culling.min_found_ratio = 2; }),
      bad<LocalMapperOptions>("PointTriangulationOptions.neighbours", "0: must be >= 1",
                              [](auto& o) { o.triangulation.neighbours = 0; }),
      bad<LocalMapperOptions>("FusionOptions.neighbours", "0: must be >= 1", [](auto& o) { o.fusion.neighbours = 0; }),
      bad<LocalMapperOptions>("KeyFrameCullingOptions.min_observers", "0: must be >= 1",
                              [](auto& o) { o.keyframe_culling.min_observers = 0; }),
      bad<LocalMapperOptions>("BundleAdjustmentOptions.num_threads", "0: must be >= 1",
                              [](auto& o) { o.bundle_adjustment.num_threads = 0; }),
      bad<BundleAdjustmentOptions>("BundleAdjustmentOptions.iterations", "0: must be >= 1",
                                   [](auto& o) { o.iterations = 0; }),
      bad<BundleAdjustmentOptions>("BundleAdjustmentOptions.outlier_rounds", "-1: must be >= 0",
                                   [](auto& o) { o.outlier_rounds = -1; }),
      bad<BundleAdjustmentOptions>("BundleAdjustmentOptions.chi2_mono", "0: must be > 0",
                                   [](auto& o) { o.chi2_mono = 0; }),
  });
}

TEST(OptionChecks, LoopClosingAndViewer) {
  expect_rejected({
      bad<LoopCloserOptions>("LoopDetectorOptions.consistency_threshold", "0: must be >= 1",
                             [](auto& o) { o.detector.consistency_threshold = 0; }),
      bad<LoopCloserOptions>("LoopDetectorOptions.group_score_ratio", "1.5: must be in [0, 1]",
                             [](auto& o) { o.detector.group_score_ratio = 1.5; }),
      bad<LoopCloserOptions>("LoopCorrectionOptions.pose_graph_iterations", "0: must be >= 1",
                             [](auto& o) { o.correction.pose_graph_iterations = 0; }),
      bad<LoopCloserOptions>("BundleAdjustmentOptions.num_threads", "0: must be >= 1",
                             [](auto& o) { o.global_bundle_adjustment.num_threads = 0; }),
      bad<LoopCorrectionOptions>("LoopCorrectionOptions.fuse_window", "0: must be > 0",
                                 [](auto& o) { o.fuse_window = 0; }),
      bad<PlaceRecognizerOptions>("PlaceRecognizerOptions.max_loop_candidates", "0: must be >= 1",
                                  [](auto& o) { o.max_loop_candidates = 0; }),
      bad<PlaceRecognizerOptions>("PlaceRecognizerOptions.direct_index_level", "-1: must be >= 0",
                                  [](auto& o) { o.direct_index_level = -1; }),
      bad<MapMergerOptions>("LoopDetectorOptions.min_inliers", "0: must be >= 1",
                            [](auto& o) { o.detector.min_inliers = 0; }),
      bad<MapMergerOptions>("MapMergerOptions.fuse_window", "-1: must be > 0", [](auto& o) { o.fuse_window = -1; }),
      bad<MapMergerOptions>("BundleAdjustmentOptions.iterations", "0: must be >= 1",
                            [](auto& o) { o.welding_bundle_adjustment.iterations = 0; }),
      bad<ViewerOptions>("ViewerOptions.port", "70000: must be in [0, 65535]", [](auto& o) { o.port = 70000; }),
      bad<ViewerOptions>("ViewerOptions.image_rate", "0: must be in [0.1, 60]", [](auto& o) { o.image_rate = 0; }),
      bad<ViewerOptions>("ViewerOptions.jpeg_quality", "101: must be in [10, 100]",
                         [](auto& o) { o.jpeg_quality = 101; }),
      bad<ViewerOptions>("ViewerOptions.host", "empty: must be a host name or address", [](auto& o) { o.host = " "; }),
  });
}

// Components check their options when they are made.
TEST(OptionChecks, ComponentsCheckOnConstruction) {
  OrbOptions orb;
  orb.min_th_fast = 30;
  EXPECT_THROW(OrbExtractor{orb}, OptionError);
  MaskHoldOptions hold;
  hold.frames = -1;
  EXPECT_THROW(MaskHold{hold}, OptionError);
  RelocalizerOptions reloc;
  reloc.fine_window = 0;
  EXPECT_THROW(Relocalizer{reloc}, OptionError);
  Map map;
  TrackerOptions tracker;
  tracker.min_local_map_inliers = 0;
  EXPECT_THROW(Tracker(map, tracker, LocalMappingLink{}), OptionError);
}

}  // namespace
}  // namespace stillslam
