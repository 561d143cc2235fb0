#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace stillslam {

// The 80 COCO class names in YOLO order (person = 0).
const std::vector<std::string>& coco_class_names();

// Name of a class id; "class<id>" for ids outside the COCO list (models with other heads).
std::string coco_class_name(int class_id);

// "person", "Dining_Table", "dining table" or "0" -> class id. Case-insensitive,
// '_' matches ' '. Throws stillslam::Error naming the value when unknown.
int coco_class_id(std::string_view name_or_id);

// Resolves every entry (see coco_class_id); duplicates are removed, order kept.
std::vector<int> resolve_class_ids(const std::vector<std::string>& names_or_ids);

}  // namespace stillslam
