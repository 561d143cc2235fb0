#include <array>
#include <sstream>
#include <string>

#include "stillslam/core/text.h"
#include "stillslam/io/settings_parts.h"

namespace stillslam {
namespace {

constexpr std::array<const char*, 11> kKnownKeys = {
    "enabled",      "model",   "classes",             "scoreThreshold", "nmsIouThreshold",
    "maskThreshold", "maskDilation", "holdFrames", "threads", "masksForClassesOnly", "agnosticNms"};
constexpr const char* kPrefix = "Segmentation.";

std::string known_keys_list() {
  std::string out;
  for (const char* k : kKnownKeys) out += (out.empty() ? "" : ", ") + std::string(kPrefix) + k;
  return out;
}

// Reports errors under the full dotted key, whichever YAML layout was used.
class SegmentationKeys {
 public:
  SegmentationKeys(const YamlReader& yaml, cv::FileNode nested) : yaml_(yaml), nested_(nested) {}

  cv::FileNode get(const std::string& name) const {
    const cv::FileNode flat = yaml_.node(kPrefix + name);
    if (!flat.isNone()) return flat;
    return nested_.isMap() ? nested_[name] : cv::FileNode();
  }
  std::optional<double> number(const std::string& name) const {
    const cv::FileNode n = get(name);
    if (n.isNone()) return std::nullopt;
    const auto v = node_number(n);
    if (!v) fail(name, "must be a number");
    return v;
  }
  [[noreturn]] void fail(const std::string& name, const std::string& message) const {
    yaml_.fail(kPrefix + name, message);
  }
  const YamlReader& yaml() const { return yaml_; }

 private:
  const YamlReader& yaml_;
  cv::FileNode nested_;
};

void check_known(const SegmentationKeys& keys, const std::string& name) {
  for (const char* k : kKnownKeys) {
    if (name == k) return;
  }
  keys.fail(name, "is not a known segmentation setting (known keys: " + known_keys_list() + ")");
}

std::vector<std::string> read_classes(const SegmentationKeys& keys) {
  const cv::FileNode n = keys.get("classes");
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

float unit_interval(const SegmentationKeys& keys, const std::string& name, float fallback) {
  const auto v = keys.number(name);
  if (!v) return fallback;
  if (*v < 0.0 || *v > 1.0) keys.fail(name, "must be between 0 and 1");
  return static_cast<float>(*v);
}

bool flag(const SegmentationKeys& keys, const std::string& name, bool fallback) {
  const auto v = keys.number(name);
  if (!v) return fallback;
  if (*v != 0 && *v != 1) keys.fail(name, "must be 0 or 1");
  return *v == 1;
}

int integer(const SegmentationKeys& keys, const std::string& name, int fallback, int min_value) {
  const auto v = keys.number(name);
  if (!v) return fallback;
  if (static_cast<double>(static_cast<int>(*v)) != *v || *v < min_value) {
    keys.fail(name, "must be an integer >= " + std::to_string(min_value));
  }
  return static_cast<int>(*v);
}

}  // namespace

void read_segmentation_section(const YamlReader& yaml, SegmentationOptions& options) {
  const cv::FileNode nested = yaml.node("Segmentation");
  const SegmentationKeys keys(yaml, nested);
  for (const std::string& key : yaml.keys()) {
    if (key.rfind(kPrefix, 0) == 0) check_known(keys, key.substr(std::string(kPrefix).size()));
  }
  if (nested.isMap()) {
    for (auto it = nested.begin(); it != nested.end(); ++it) check_known(keys, (*it).name());
  } else if (!nested.isNone()) {
    yaml.fail("Segmentation", "must be a map of Segmentation settings or absent");
  }

  options.enabled = flag(keys, "enabled", options.enabled);
  const cv::FileNode model = keys.get("model");
  if (!model.isNone()) {
    if (!model.isString() || trim(static_cast<std::string>(model)).empty()) {
      keys.fail("model", "must be a non-empty path to an ONNX model");
    }
    std::filesystem::path path = trim(static_cast<std::string>(model));
    if (path.is_relative()) {
      path = std::filesystem::absolute(yaml.file()).parent_path() / path;
    }
    options.model_path = path.lexically_normal().string();
  }
  if (!keys.get("classes").isNone()) options.classes = read_classes(keys);
  options.score_threshold = unit_interval(keys, "scoreThreshold", options.score_threshold);
  options.nms_iou_threshold = unit_interval(keys, "nmsIouThreshold", options.nms_iou_threshold);
  options.mask_threshold = unit_interval(keys, "maskThreshold", options.mask_threshold);
  options.mask_dilation = integer(keys, "maskDilation", options.mask_dilation, 0);
  options.hold_frames = integer(keys, "holdFrames", options.hold_frames, 0);
  options.threads = integer(keys, "threads", options.threads, 1);
  options.masks_for_classes_only = flag(keys, "masksForClassesOnly", options.masks_for_classes_only);
  options.agnostic_nms = flag(keys, "agnosticNms", options.agnostic_nms);
}

}  // namespace stillslam
