#pragma once
// The ground-truth instances of a `stillslam simulate` folder (instances/<t>.png,
// 16-bit ids, and instances.txt: id kind class moves) as a Segmenter: one
// detection per instance in the frame, with its own mask and class (COCO id
// when the class is a COCO name, else -1), so instances keep apart and carry
// their class (bench_slam --oracle-instances, for the motion stage of #19).
// The simulator writes a moved object's id only in the frames where it moves:
// a detector that sees it only then, which favours finding it moving.
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "stillslam/core/error.h"
#include "stillslam/io/tum_dataset.h"
#include "stillslam/segmentation/coco_classes.h"
#include "stillslam/segmentation/segmenter.h"

namespace stillslam::oracle {

class OracleInstanceSegmenter : public Segmenter {
 public:
  explicit OracleInstanceSegmenter(const std::filesystem::path& sequence) {
    for (const TumPair& p : read_tum_associations(sequence / "associations.txt")) {
      files_.push_back(sequence / "instances" / std::filesystem::path(p.rgb_file).filename());
    }
    const std::filesystem::path list = sequence / "instances.txt";
    std::ifstream in(list);
    if (!in) throw Error(list.string() + " not found: --oracle-instances needs a sequence rendered with instances/");
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream row(line);
      int id = 0, moves = 0;
      std::string kind, category;
      if (!(row >> id >> kind >> category >> moves)) throw Error(list.string() + ": expected `id kind class moves`");
      categories_[id] = category;
    }
  }
  std::vector<Detection> segment(const cv::Mat& bgr) override { return segment_frame(bgr, next_++); }
  std::vector<Detection> segment_frame(const cv::Mat& bgr, std::size_t k) override {
    if (k >= files_.size()) throw Error("--oracle-instances: more frames than instance images");
    const cv::Mat ids = cv::imread(files_[k].string(), cv::IMREAD_UNCHANGED);
    if (ids.type() != CV_16UC1 || ids.size() != bgr.size()) {
      throw Error(files_[k].string() + ": missing, not 16-bit or not the frame's size");
    }
    std::vector<Detection> out;
    for (const auto& [id, category] : categories_) {
      const cv::Mat1b mask = ids == id;
      if (cv::countNonZero(mask) == 0) continue;
      Detection d;
      d.class_id = class_id(category);
      d.class_name = category;
      d.score = 1.f;
      d.box = cv::boundingRect(mask);
      d.mask = mask;
      out.push_back(std::move(d));
    }
    return out;
  }

 private:
  static int class_id(const std::string& category) {
    try {
      return coco_class_id(category);
    } catch (const Error&) {
      return -1;
    }
  }
  std::vector<std::filesystem::path> files_;
  std::map<int, std::string> categories_;
  std::size_t next_ = 0;
};

}  // namespace stillslam::oracle
