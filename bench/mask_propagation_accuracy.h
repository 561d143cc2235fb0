#pragma once
// bench_mask_accuracy --propagate A: accuracy of propagated masks as a function
// of their age. From every --step-th frame k of a `stillslam simulate` folder,
// the fresh instances of frame k (connected components of the exact masks/, or
// the person instances of --model) are carried to frames k+1..k+A by
// MaskPropagator, and each frame's union mask (dilated by the margin for its
// age) is compared with that frame's exact mask. Age 0 is the fresh mask with
// the age-0 margin: the reference. Variants, on the same frames:
//   hold         mode 0: the old mask with the same margin (no propagation)
//   flow-only    mode 2 without poses
//   camera       mode 1: camera motion with depth
//   camera+flow  mode 2 (the default)
// The pose given for frame j is the constant-velocity prediction from the
// ground truth of j-1 and j-2, as the tracker's motion model predicts it before
// tracking; after each frame the ground-truth pose is set (the tracked pose).
// --depth sparse keeps depth only at FAST corners (what stereo keypoints give).
// --frame-stride S uses every S-th frame only (S times faster motion per frame;
// ages count those frames).
#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>
#include <vector>

#include "stillslam/core/error.h"
#include "stillslam/core/thread_cpu_stopwatch.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/io/tum_dataset.h"
#include "stillslam/segmentation/coco_classes.h"
#include "stillslam/segmentation/dynamic_mask.h"
#include "stillslam/segmentation/mask_propagation.h"
#include "stillslam/segmentation/yolo_segmenter.h"

namespace stillslam::bench {

struct PropagationBenchOptions {
  std::filesystem::path sequence;
  int max_age = 10;
  int frame_stride = 1;        // every S-th frame only: S times faster motion per frame
  int step = 10;
  std::size_t max_starts = 0;  // 0: all
  std::string model;           // empty: exact instances
  std::string depth = "dense"; // dense, sparse, none
  MaskPropagationOptions propagation;
};

// Connected components of a binary mask, one frame-size mask each (components
// under 50 pixels dropped: single stray pixels are no person).
inline std::vector<cv::Mat1b> mask_components(const cv::Mat1b& mask) {
  cv::Mat1i labels;
  cv::Mat stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  std::vector<cv::Mat1b> out;
  for (int i = 1; i < n; ++i) {
    if (stats.at<int>(i, cv::CC_STAT_AREA) < 50) continue;
    cv::Mat1b m;
    cv::compare(labels, i, m, cv::CMP_EQ);
    out.push_back(m);
  }
  return out;
}

inline Eigen::Isometry3d T_cam_world_of(const StampedPose& p) { return p.T_world_cam.inverse(); }

struct PixelCounts {
  double inter = 0, truth = 0, predicted = 0;
  void add(const cv::Mat1b& pred, const cv::Mat1b& truth_mask) {
    inter += cv::countNonZero(pred & truth_mask);
    truth += cv::countNonZero(truth_mask);
    predicted += cv::countNonZero(pred);
  }
  double recall() const { return truth > 0 ? inter / truth : 0.0; }
  double precision() const { return predicted > 0 ? inter / predicted : 0.0; }
};

inline int run_propagation_bench(const PropagationBenchOptions& b) {
  namespace fs = std::filesystem;
  const fs::path& seq = b.sequence;
  const std::vector<TumPair> pairs = read_tum_associations(seq / "associations.txt");
  const Trajectory gt = read_trajectory(seq / "groundtruth.txt");
  if (gt.size() < pairs.size())
    throw Error("groundtruth.txt of " + seq.string() + " has fewer poses than associations.txt has frames");
  const cv::FileStorage settings((seq / "settings.yaml").string(), cv::FileStorage::READ);
  if (!settings.isOpened()) throw Error("cannot read " + (seq / "settings.yaml").string());
  const MaskPropagationCamera camera{static_cast<double>(settings["Camera1.fx"]), static_cast<double>(settings["Camera1.fy"]),
                                     static_cast<double>(settings["Camera1.cx"]), static_cast<double>(settings["Camera1.cy"])};
  double depth_factor = static_cast<double>(settings["RGBD.DepthMapFactor"]);
  if (!(depth_factor > 0)) depth_factor = 5000.0;
  if (b.depth != "dense" && b.depth != "sparse" && b.depth != "none")
    throw Error("--depth must be dense, sparse or none (got " + b.depth + ")");

  struct Frame {
    cv::Mat1b gray, truth;
    cv::Mat1f depth;
    cv::Mat bgr;
  };
  std::map<std::size_t, Frame> cache;
  const auto frame = [&](std::size_t i) -> const Frame& {
    auto it = cache.find(i);
    if (it != cache.end()) return it->second;
    while (!cache.empty() && cache.begin()->first + static_cast<std::size_t>(b.max_age * b.frame_stride) + 2 < i) cache.erase(cache.begin());
    Frame f;
    f.bgr = cv::imread((seq / pairs[i].rgb_file).string(), cv::IMREAD_COLOR);
    const fs::path name = fs::path(pairs[i].rgb_file).filename();
    const cv::Mat truth = cv::imread((seq / "masks" / name).string(), cv::IMREAD_GRAYSCALE);
    const cv::Mat depth16 = cv::imread((seq / pairs[i].depth_file).string(), cv::IMREAD_UNCHANGED);
    if (f.bgr.empty() || truth.empty() || depth16.empty())
      throw Error("cannot read the rgb, depth or masks/ image of " + pairs[i].rgb_file + " in " + seq.string());
    cv::cvtColor(f.bgr, f.gray, cv::COLOR_BGR2GRAY);
    f.truth = truth > 0;
    if (b.depth != "none") {
      depth16.convertTo(f.depth, CV_32F, 1.0 / depth_factor);
      if (b.depth == "sparse") {
        std::vector<cv::KeyPoint> corners;
        cv::FAST(f.gray, corners, 20);
        cv::Mat1f sparse(f.depth.size(), 0.f);
        for (const cv::KeyPoint& k : corners) {
          const cv::Point p(cvRound(k.pt.x), cvRound(k.pt.y));
          sparse(p) = f.depth(p);
        }
        f.depth = sparse;
      }
    }
    return cache.emplace(i, std::move(f)).first->second;
  };

  std::optional<YoloSegmenter> segmenter;
  if (!b.model.empty()) {
    SegmentationOptions so;
    so.model_path = b.model;
    so.threads = 1;
    segmenter.emplace(so);
  }
  const std::vector<int> person = resolve_class_ids({"person"});

  struct Variant {
    const char* name;
    int mode;
    bool poses;
  };
  const std::vector<Variant> variants{{"hold", 0, false}, {"flow-only", 2, false}, {"camera", 1, true}, {"camera+flow", 2, true}};
  std::vector<std::vector<PixelCounts>> counts(variants.size(), std::vector<PixelCounts>(b.max_age + 1));
  std::vector<double> cpu_ms(variants.size(), 0.0), reset_ms(variants.size(), 0.0);
  std::vector<int> calls(variants.size(), 0);
  std::vector<std::map<InstanceMotion, int>> motions(variants.size());

  std::size_t starts = 0;
  const auto S = static_cast<std::size_t>(b.frame_stride);
  for (std::size_t k = 2 * S; k + static_cast<std::size_t>(b.max_age) * S < pairs.size(); k += static_cast<std::size_t>(b.step)) {
    if (b.max_starts > 0 && starts >= b.max_starts) break;
    ++starts;
    const Frame& f0 = frame(k);
    const std::vector<cv::Mat1b> fresh =
        segmenter ? dynamic_instances(segmenter->segment(f0.bgr), person, f0.gray.size()) : mask_components(f0.truth);
    for (std::size_t v = 0; v < variants.size(); ++v) {
      MaskPropagationOptions o = b.propagation;
      o.mode = variants[v].mode;
      MaskPropagator propagator(camera, o);
      const ThreadCpuStopwatch reset_cpu;
      propagator.reset({.frame_id = k, .gray = f0.gray, .depth = f0.depth, .right = {}, .instances = fresh,
                        .T_cam_world = T_cam_world_of(gt[k])});
      reset_ms[v] += reset_cpu.elapsed_ms();
      counts[v][0].add(dynamic_mask(fresh, f0.gray.size(), propagator.margin_px(0)), f0.truth);
      for (int a = 1; a <= b.max_age; ++a) {
        const std::size_t j = k + static_cast<std::size_t>(a) * S;
        const Frame& f = frame(j);
        std::optional<Eigen::Isometry3d> predicted;
        if (variants[v].poses) {
          const Eigen::Isometry3d T1 = T_cam_world_of(gt[j - S]), T2 = T_cam_world_of(gt[j - 2 * S]);
          predicted = (T1 * T2.inverse()) * T1;
        }
        const ThreadCpuStopwatch propagate_cpu;
        const PropagatedMasks p = propagator.propagate(k + static_cast<std::size_t>(a), f.gray, f.depth, predicted);  // virtual frame ids: age a
        cpu_ms[v] += propagate_cpu.elapsed_ms();
        ++calls[v];
        if (variants[v].poses) propagator.set_last_pose(T_cam_world_of(gt[j]));
        for (const PropagatedInstance& i : p.instances) ++motions[v][i.motion];
        counts[v][a].add(p.union_mask, f.truth);
      }
    }
  }

  const MaskPropagationOptions& o = b.propagation;
  std::printf("%s: %zu start frames (every %d-th), ages 1..%d, frame stride %d, fresh masks: %s, depth: %s, margin %d px + %.2f px/frame (max %d)\n",
              seq.string().c_str(), starts, b.step, b.max_age, b.frame_stride, b.model.empty() ? "exact" : b.model.c_str(),
              b.depth.c_str(), o.margin_px, o.margin_px_per_frame, o.max_margin_px);
  std::printf("%4s", "age");
  for (const Variant& v : variants) std::printf(" | %-11s rec  prec  rec/fresh", v.name);
  std::printf("\n");
  for (int a = 0; a <= b.max_age; ++a) {
    std::printf("%4d", a);
    for (std::size_t v = 0; v < variants.size(); ++v) {
      const double fresh_recall = counts[v][0].recall();
      std::printf(" | %11s %5.3f %5.3f %6.3f   ", "", counts[v][a].recall(), counts[v][a].precision(),
                  fresh_recall > 0 ? counts[v][a].recall() / fresh_recall : 0.0);
    }
    std::printf("\n");
  }
  std::printf("cpu ms per propagate():");
  for (std::size_t v = 0; v < variants.size(); ++v)
    std::printf("  %s %.2f", variants[v].name, calls[v] ? cpu_ms[v] / calls[v] : 0.0);
  std::printf("\ncpu ms per reset():");
  for (std::size_t v = 0; v < variants.size(); ++v)
    std::printf("  %s %.2f", variants[v].name, starts ? reset_ms[v] / static_cast<double>(starts) : 0.0);
  std::printf("\ninstance motions (flow/camera/none):");
  for (std::size_t v = 0; v < variants.size(); ++v)
    std::printf("  %s %d/%d/%d", variants[v].name, motions[v][InstanceMotion::flow], motions[v][InstanceMotion::camera],
                motions[v][InstanceMotion::none]);
  std::printf("\n");
  // The bar: ages 1..5 keep >= 90 % of the fresh recall (camera+flow).
  double worst = 1e9;
  for (int a = 1; a <= std::min(5, b.max_age); ++a)
    worst = std::min(worst, counts.back()[a].recall() / std::max(1e-9, counts.back()[0].recall()));
  std::printf("camera+flow: worst recall / fresh recall at ages 1..5: %.3f (bar >= 0.90: %s)\n", worst,
              worst >= 0.9 ? "met" : "not met");
  return 0;
}

}  // namespace stillslam::bench
