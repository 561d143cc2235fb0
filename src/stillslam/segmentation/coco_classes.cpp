#include "stillslam/segmentation/coco_classes.h"

#include <algorithm>
#include <cctype>
#include <charconv>

#include "stillslam/core/error.h"
#include "stillslam/core/text.h"

namespace stillslam {

const std::vector<std::string>& coco_class_names() {
  static const std::vector<std::string> names{
      "person",        "bicycle",      "car",          "motorcycle",    "airplane",     "bus",
      "train",         "truck",        "boat",         "traffic light", "fire hydrant", "stop sign",
      "parking meter", "bench",        "bird",         "cat",           "dog",          "horse",
      "sheep",         "cow",          "elephant",     "bear",          "zebra",        "giraffe",
      "backpack",      "umbrella",     "handbag",      "tie",           "suitcase",     "frisbee",
      "skis",          "snowboard",    "sports ball",  "kite",          "baseball bat", "baseball glove",
      "skateboard",    "surfboard",    "tennis racket", "bottle",       "wine glass",   "cup",
      "fork",          "knife",        "spoon",        "bowl",          "banana",       "apple",
      "sandwich",      "orange",       "broccoli",     "carrot",        "hot dog",      "pizza",
      "donut",         "cake",         "chair",        "couch",         "potted plant", "bed",
      "dining table",  "toilet",       "tv",           "laptop",        "mouse",        "remote",
      "keyboard",      "cell phone",   "microwave",    "oven",          "toaster",      "sink",
      "refrigerator",  "book",         "clock",        "vase",          "scissors",     "teddy bear",
      "hair drier",    "toothbrush"};
  return names;
}

std::string coco_class_name(int class_id) {
  const auto& names = coco_class_names();
  if (class_id >= 0 && class_id < static_cast<int>(names.size())) return names[static_cast<std::size_t>(class_id)];
  return "class" + std::to_string(class_id);
}

namespace {

// "Traffic_Light " -> "traffic light".
std::string normalized(std::string_view s) {
  std::string out = lower(trim(s));
  std::replace(out.begin(), out.end(), '_', ' ');
  return out;
}

}  // namespace

int coco_class_id(std::string_view name_or_id) {
  const std::string key = normalized(name_or_id);
  const auto& names = coco_class_names();
  int id = -1;
  const auto [end, ec] = std::from_chars(key.data(), key.data() + key.size(), id);
  if (!key.empty() && ec == std::errc() && end == key.data() + key.size()) {
    if (id >= 0 && id < static_cast<int>(names.size())) return id;
  } else {
    const auto it = std::find(names.begin(), names.end(), key);
    if (it != names.end()) return static_cast<int>(it - names.begin());
  }
  throw Error("unknown segmentation class '" + std::string(name_or_id) +
              "': use a COCO class name (person, chair, dining_table, ...) or an id 0..79 "
              "(Segmentation.classes / --classes)");
}

std::vector<int> resolve_class_ids(const std::vector<std::string>& names_or_ids) {
  std::vector<int> ids;
  for (const auto& n : names_or_ids) {
    const int id = coco_class_id(n);
    if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
  }
  return ids;
}

}  // namespace stillslam
