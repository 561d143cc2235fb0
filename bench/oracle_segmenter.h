#pragma once
// The ground-truth masks of a `stillslam simulate` folder as a Segmenter
// (bench_slam --oracle-masks, bench_mask_misses, bench_dynamic_points), with
// chosen frames "missed" to stand for a detector that loses the people.
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "stillslam/core/error.h"
#include "stillslam/core/thread_cpu_stopwatch.h"
#include "stillslam/io/tum_dataset.h"
#include "stillslam/segmentation/segmenter.h"

namespace stillslam::oracle {

// The ground-truth mask files in associations.txt order (the dataset's frame order).
inline std::vector<std::filesystem::path> oracle_mask_files(const std::filesystem::path& sequence) {
  std::vector<std::filesystem::path> files;
  for (const TumPair& p : read_tum_associations(sequence / "associations.txt")) {
    files.push_back(sequence / "masks" / std::filesystem::path(p.rgb_file).filename());
  }
  return files;
}

struct MaskMissOptions {
  double rate = 0;           // share of the frames whose mask is missed, [0, 1]
  double burst_seconds = 0;  // > 0: missed in whole bursts of this length instead of single frames
  double fps = 30;
  std::uint64_t seed = 1;
};

// Exactly round(rate * frames) missed frames (or round(rate * bursts) bursts),
// chosen with a fixed-seed shuffle: the same options miss the same frames.
inline std::vector<bool> choose_missed_frames(std::size_t frames, const MaskMissOptions& o) {
  std::vector<bool> missed(frames, false);
  if (o.rate <= 0 || frames == 0) return missed;
  const std::size_t block =
      o.burst_seconds > 0 ? std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(o.burst_seconds * o.fps))) : 1;
  const std::size_t blocks = (frames + block - 1) / block;
  std::vector<std::size_t> order(blocks);
  for (std::size_t b = 0; b < blocks; ++b) order[b] = b;
  std::mt19937_64 rng(o.seed);
  std::shuffle(order.begin(), order.end(), rng);
  const auto take = static_cast<std::size_t>(std::lround(std::min(o.rate, 1.0) * static_cast<double>(blocks)));
  for (std::size_t k = 0; k < take; ++k) {
    for (std::size_t f = order[k] * block; f < std::min(frames, (order[k] + 1) * block); ++f) missed[f] = true;
  }
  return missed;
}

// Frame k's ground-truth mask as one "person" (segment_frame; segment()
// counts calls for callers without frame indices); a missed frame returns no
// detection. cost_ms > 0: each call first burns that much CPU time of its
// thread, so asynchronous timing is realistic without the model (the
// measured YOLO CPU time per frame).
class OracleSegmenter : public Segmenter {
 public:
  explicit OracleSegmenter(const std::filesystem::path& sequence, std::vector<bool> missed = {}, double cost_ms = 0)
      : files_(oracle_mask_files(sequence)), missed_(std::move(missed)), cost_ms_(cost_ms) {}
  std::vector<Detection> segment(const cv::Mat& bgr) override { return segment_frame(bgr, next_++); }
  std::vector<Detection> segment_frame(const cv::Mat& bgr, std::size_t k) override {
    if (k >= files_.size()) throw Error("--oracle-masks: more frames than masks");
    const ThreadCpuStopwatch cost;
    while (cost.elapsed_ms() < cost_ms_) {
    }
    if (k < missed_.size() && missed_[k]) return {};
    const std::filesystem::path& file = files_[k];
    const cv::Mat1b mask = cv::imread(file.string(), cv::IMREAD_GRAYSCALE) > 0;
    if (mask.size() != bgr.size()) throw Error(file.string() + ": missing or not the frame's size");
    if (cv::countNonZero(mask) == 0) return {};
    Detection d;
    d.class_id = 0;
    d.class_name = "person";
    d.score = 1.f;
    d.box = cv::boundingRect(mask);
    d.mask = mask;
    return {d};
  }

 private:
  std::vector<std::filesystem::path> files_;
  std::vector<bool> missed_;
  double cost_ms_ = 0;
  std::size_t next_ = 0;
};

}  // namespace stillslam::oracle
