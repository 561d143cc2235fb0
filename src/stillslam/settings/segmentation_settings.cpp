#include <sstream>
#include <string>

#include "stillslam/core/shipped_files.h"
#include "stillslam/core/text.h"
#include "stillslam/settings/section_binders.h"
#include "stillslam/settings/section_keys.h"

namespace stillslam {
namespace {

std::vector<std::string> read_classes(SectionKeys& keys) {
  const cv::FileNode n = keys.node("classes");
  std::vector<std::string> classes;
  if (n.isString()) {
    std::stringstream ss(static_cast<std::string>(n));
    std::string item;
    while (std::getline(ss, item, ',')) {
      if (!trim(item).empty()) classes.push_back(trim(item));
    }
  } else if (n.isSeq()) {
    for (auto it = n.begin(); it != n.end(); ++it) {
      const cv::FileNode c = *it;
      if (c.isString()) {
        if (!trim(static_cast<std::string>(c)).empty()) classes.push_back(trim(static_cast<std::string>(c)));
      } else if (c.isInt()) {
        classes.push_back(std::to_string(static_cast<int>(c)));  // a COCO class id
      } else {
        keys.fail("classes", "must contain class names or integer class ids");
      }
    }
  } else if (n.isInt()) {
    classes.push_back(std::to_string(static_cast<int>(n)));
  } else {
    keys.fail("classes", "must be a string like \"person,chair\" or a sequence like [person, chair]");
  }
  if (classes.empty()) keys.fail("classes", "is empty (name at least one class, e.g. \"person\")");
  return classes;
}

// Segmentation.model, made absolute relative to the settings file's folder.
// Without the key: the shipped model; with segmentation on, not finding it
// is an error (the run would stop at the segmenter otherwise).
std::string read_model(SectionKeys& keys, bool enabled, const std::filesystem::path& executable) {
  const cv::FileNode model = keys.node("model");
  if (model.isNone()) {
    if (const auto shipped = find_shipped_file(executable, kShippedSegmentationModel)) {
      return std::filesystem::absolute(*shipped).lexically_normal().string();
    }
    if (!enabled) return {};
    keys.fail("model", std::string("is not given and the shipped model ") + kShippedSegmentationModel +
                           " is not in " + executable.parent_path().string() +
                           " or a parent folder: set Segmentation.model to a YOLO-seg .onnx file (relative to "
                           "this settings file), or turn segmentation off with Segmentation.enabled: 0");
  }
  if (!model.isString() || trim(static_cast<std::string>(model)).empty()) {
    keys.fail("model", "must be a non-empty path to an ONNX model");
  }
  std::filesystem::path path = trim(static_cast<std::string>(model));
  if (path.is_relative()) path = std::filesystem::absolute(keys.yaml().file()).parent_path() / path;
  return path.lexically_normal().string();
}

SegmentationMode read_mode(SectionKeys& keys, SegmentationMode current) {
  const cv::FileNode n = keys.node("mode");
  if (n.isNone()) return current;
  const std::string value = n.isString() ? trim(static_cast<std::string>(n)) : std::string();
  if (value == "sync") return SegmentationMode::Sync;
  if (value == "async") return SegmentationMode::Async;
  keys.fail("mode", "must be sync (every frame waits for its mask) or async (own rate, masks carried between)");
}

}  // namespace

void bind_segmentation(const YamlReader& yaml, SegmentationOptions& options,
                       const std::filesystem::path& executable) {
  SectionKeys keys(yaml, "Segmentation", true);
  keys.flag("enabled", options.enabled);
  options.model_path = read_model(keys, options.enabled, executable);
  if (!keys.node("classes").isNone()) options.classes = read_classes(keys);
  keys.number("scoreThreshold", options.score_threshold, "SegmentationOptions.score_threshold", {0, 1});
  keys.number("nmsIouThreshold", options.nms_iou_threshold, "SegmentationOptions.nms_iou_threshold", {0, 1, true});
  keys.number("maskThreshold", options.mask_threshold, "SegmentationOptions.mask_threshold", {0, 1, true});
  keys.integer("maskDilation", options.mask_dilation, "SegmentationOptions.mask_dilation", {0, 256});
  keys.integer("holdFrames", options.hold_frames, "SegmentationOptions.hold_frames", {0, 1000});
  keys.integer("threads", options.threads, "SegmentationOptions.threads", thread_limits(0));
  keys.flag("masksForClassesOnly", options.masks_for_classes_only);
  keys.flag("agnosticNms", options.agnostic_nms);
  options.mode = read_mode(keys, options.mode);
  keys.integer("interval", options.interval, "SegmentationOptions.interval", {1, 1000});
  keys.integer("maxMaskAge", options.max_mask_age, "SegmentationOptions.max_mask_age", {0, 1000});
  keys.integer("keyframeMaskAge", options.keyframe_mask_age, "SegmentationOptions.keyframe_mask_age", {0, 1000});
  keys.integer("modelledLatency", options.modelled_latency, "SegmentationOptions.modelled_latency", {0, 1000});
  keys.integer("maxGrowPx", options.max_grow_px, "SegmentationOptions.max_grow_px", {0, 1000});
  keys.integer("urgentInliers", options.urgent_inliers, "SegmentationOptions.urgent_inliers", {0, 100000});
  keys.integer("threadNice", options.thread_nice, "SegmentationOptions.thread_nice", {0, 19});
  keys.flag("freshMaskCull", options.fresh_mask_cull);
  keys.flag("keyframeHold", options.keyframe_hold);
  keys.flag("heldEvidence", options.held_evidence, "SegmentationOptions.held_evidence");
  keys.flag("provisionalPoints", options.provisional_points, "SegmentationOptions.provisional_points");
  keys.flag("startCheck", options.start_check, "SegmentationOptions.start_check");
  keys.flag("keyframeCheck", options.keyframe_check, "SegmentationOptions.keyframe_check");
  keys.flag("checkNewPoints", options.check_new_points, "SegmentationOptions.check_new_points");
  keys.number("nearPersonPxPerFrame", options.near_person_px_per_frame,
              "SegmentationOptions.near_person_px_per_frame", {0, 100});
  keys.integer("nearPersonMaxPx", options.near_person_max_px, "SegmentationOptions.near_person_max_px", {0, 1000});
  keys.number("nearPersonDepthBand", options.near_person_depth_band, "SegmentationOptions.near_person_depth_band",
              {0, 100, true});
  keys.flag("nearPersonAtStart", options.near_person_at_start);
  keys.reject_unknown_keys();
  keys.check([&] { options.check(); });
}

}  // namespace stillslam
