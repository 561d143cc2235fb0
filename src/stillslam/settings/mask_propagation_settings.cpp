#include "stillslam/settings/section_binders.h"
#include "stillslam/settings/section_keys.h"

namespace stillslam {

void bind_mask_propagation(const YamlReader& yaml, MaskPropagationOptions& options) {
  SectionKeys keys(yaml, "MaskPropagation", true);
  keys.integer("mode", options.mode, "MaskPropagationOptions.mode", {0, 2});
  keys.integer("marginPx", options.margin_px, "MaskPropagationOptions.margin_px", {0, 256});
  keys.number("marginPxPerFrame", options.margin_px_per_frame, "MaskPropagationOptions.margin_px_per_frame", {0, 100});
  keys.integer("maxMarginPx", options.max_margin_px, "MaskPropagationOptions.max_margin_px", {0, 256});
  keys.integer("pointsPerInstance", options.points_per_instance, "MaskPropagationOptions.points_per_instance",
               {1, 10000});
  keys.integer("minPointDistancePx", options.min_point_distance_px, "MaskPropagationOptions.min_point_distance_px",
               {1, 100});
  keys.integer("erodePx", options.erode_px, "MaskPropagationOptions.erode_px", {0, 100});
  keys.integer("lkWindowPx", options.lk_window_px, "MaskPropagationOptions.lk_window_px", {5, 101});
  keys.integer("lkLevels", options.lk_levels, "MaskPropagationOptions.lk_levels", {0, 8});
  keys.number("fbMaxErrorPx", options.fb_max_error_px, "MaskPropagationOptions.fb_max_error_px", {0, 100});
  keys.integer("minTrackedPoints", options.min_tracked_points, "MaskPropagationOptions.min_tracked_points", {1, 10000});
  keys.integer("minPointsSimilarity", options.min_points_similarity, "MaskPropagationOptions.min_points_similarity",
               {2, 10000});
  keys.number("ransacThresholdPx", options.ransac_threshold_px, "MaskPropagationOptions.ransac_threshold_px",
              {0, 100, true});
  keys.number("minDepth", options.min_depth_m, "MaskPropagationOptions.min_depth_m", {0, 1000, true});
  keys.number("maxDepth", options.max_depth_m, "MaskPropagationOptions.max_depth_m", {0, 10000, true});
  keys.integer("splitMinPx", options.split_min_px, "MaskPropagationOptions.split_min_px", {0, 1000000});
  keys.flag("stereoBlockDepth", options.stereo_block_depth, "MaskPropagationOptions.stereo_block_depth");
  keys.reject_unknown_keys();
  keys.check([&] { options.check(); });
}

}  // namespace stillslam
