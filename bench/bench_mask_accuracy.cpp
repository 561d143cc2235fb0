// Accuracy of the dynamic masks on a generated sequence: every k-th frame of a
// `stillslam simulate` folder (rgb/ + ground-truth masks/) is segmented by each
// model, and the union of its person masks is compared with the exact mask.
//   recall    = |predicted ∩ true| / |true|      (dynamic pixels caught)
//   precision = |predicted ∩ true| / |predicted| (predicted pixels truly dynamic)
// pooled over all pixels of the sampled frames, plus CPU time per frame.
//
//   build/bench/bench_mask_accuracy --sequence DIR [--step 10] [--model FILE ...] [--gray]
//
// --gray segments what a monochrome camera (EuRoC, most stereo rigs) would
// give: the same frames turned to gray and back to three equal channels.
// Without --model: models/*.onnx and ../shared/models/yolo-seg/yolo11n-seg_*.onnx.
// --propagate A: accuracy of propagated masks by age 0..A (mask_propagation_accuracy.h).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "stillslam/core/error.h"
#include "stillslam/system/process_cpu_time.h"
#include "stillslam/io/tum_dataset.h"
#include "stillslam/segmentation/coco_classes.h"
#include "stillslam/segmentation/dynamic_mask.h"
#include "stillslam/segmentation/yolo_segmenter.h"
#include "mask_propagation_accuracy.h"

namespace fs = std::filesystem;
using namespace stillslam;

namespace {

// rgb/<name>.png of associations.txt, every `step`-th frame.
std::vector<std::string> sampled_frames(const fs::path& seq, int step) {
  const std::vector<TumPair> pairs = read_tum_associations(seq / "associations.txt");
  std::vector<std::string> names;
  for (std::size_t i = 0; i < pairs.size(); i += static_cast<std::size_t>(step)) {
    names.push_back(fs::path(pairs[i].rgb_file).filename().string());
  }
  return names;
}

}  // namespace

int main(int argc, char** argv) {
  fs::path seq;
  int step = 10;
  std::vector<std::string> models;
  bool gray = false, per_frame = false;
  std::size_t max_frames = 0;
  CLI::App app("Dynamic-mask accuracy against a generated sequence's masks/", "bench_mask_accuracy");
  app.add_option("--sequence", seq, "`stillslam simulate` folder")->required();
  app.add_option("--step", step, "every k-th frame")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--model", models, "ONNX model(s) (default: models/ and ../shared/models/yolo-seg/yolo11n-seg_*)");
  app.add_flag("--gray", gray, "segment the frames as a monochrome camera gives them");
  app.add_flag("--per-frame", per_frame, "print each frame's figures too");
  app.add_option("--max-frames", max_frames, "only the first N sampled frames (0: all)");
  bench::PropagationBenchOptions prop;
  app.add_option("--propagate", prop.max_age, "propagation mode: carry each sampled frame's mask to ages 1..A")
      ->check(CLI::Range(1, 100));
  app.add_option("--depth", prop.depth, "propagation mode: dense, sparse (FAST corners only, like stereo) or none")
      ->capture_default_str();
  app.add_option("--margin-px", prop.propagation.margin_px, "propagation mode: margin at age 0")->capture_default_str();
  app.add_option("--margin-per-frame", prop.propagation.margin_px_per_frame, "propagation mode: margin growth per frame")
      ->capture_default_str();
  app.add_option("--max-margin", prop.propagation.max_margin_px, "propagation mode: margin cap")->capture_default_str();
  app.add_option("--frame-stride", prop.frame_stride, "propagation mode: every S-th frame only (S times faster motion)")
      ->capture_default_str()
      ->check(CLI::Range(1, 30));
  app.add_option("--points", prop.propagation.points_per_instance, "propagation mode: flow points per instance")
      ->capture_default_str();
  app.add_option("--lk-window", prop.propagation.lk_window_px, "propagation mode: LK window (odd)")->capture_default_str();
  app.add_option("--lk-levels", prop.propagation.lk_levels, "propagation mode: LK pyramid levels")->capture_default_str();
  app.add_option("--fb-max-error", prop.propagation.fb_max_error_px, "propagation mode: forward-backward check (0: off)")
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (app.count("--propagate") > 0) {
    prop.sequence = seq;
    prop.step = step;
    prop.max_starts = max_frames;
    if (models.size() > 1) {
      std::fprintf(stderr, "--propagate takes one --model at most\n");
      return 1;
    }
    if (!models.empty()) prop.model = models.front();
    try {
      prop.propagation.check();
      return bench::run_propagation_bench(prop);
    } catch (const Error& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return 1;
    }
  }
  if (models.empty()) {
    const fs::path repo = fs::path(STILLSLAM_SOURCE_DIR);
    for (const fs::path& dir : {repo / "models", repo / ".." / "shared" / "models" / "yolo-seg"}) {
      if (!fs::is_directory(dir)) continue;
      for (const auto& e : fs::directory_iterator(dir)) {
        const std::string n = e.path().filename().string();
        const bool listed = std::any_of(models.begin(), models.end(),
                                        [&](const std::string& m) { return fs::path(m).filename() == n; });
        if (e.path().extension() == ".onnx" && n.rfind("yolo11n-seg_", 0) == 0 &&
            n.find("uint8") == std::string::npos && !listed)
          models.push_back(e.path().string());
      }
    }
    std::sort(models.begin(), models.end());
  }
  try {
    std::vector<std::string> frames = sampled_frames(seq, step);
    if (max_frames > 0 && frames.size() > max_frames) frames.resize(max_frames);
    std::printf("%zu frames of %s (every %d-th)%s\n", frames.size(), seq.string().c_str(), step,
                gray ? ", segmented in gray" : "");
    std::printf("%-40s %8s %9s %8s %12s\n", "model", "recall", "precision", "IoU", "cpu ms/frame");
    for (const std::string& model : models) {
      SegmentationOptions o;
      o.model_path = model;
      o.threads = 1;
      YoloSegmenter segmenter(o);
      const std::vector<int> person = resolve_class_ids({"person"});
      double inter = 0, truth = 0, predicted = 0, cpu = 0;
      for (const std::string& name : frames) {
        cv::Mat bgr = cv::imread((seq / "rgb" / name).string(), cv::IMREAD_COLOR);
        const cv::Mat gt = cv::imread((seq / "masks" / name).string(), cv::IMREAD_GRAYSCALE);
        if (bgr.empty() || gt.empty()) throw Error("cannot read rgb/ or masks/ " + name + " in " + seq.string());
        if (gray) {
          cv::cvtColor(bgr, bgr, cv::COLOR_BGR2GRAY);
          cv::cvtColor(bgr, bgr, cv::COLOR_GRAY2BGR);
        }
        const double t0 = process_cpu_seconds();
        const cv::Mat1b pred = dynamic_mask(segmenter.segment(bgr), person, bgr.size(), 0);
        cpu += (process_cpu_seconds() - t0) * 1e3;
        const cv::Mat1b g = gt > 0;
        const double i = cv::countNonZero(pred & g), t = cv::countNonZero(g), p = cv::countNonZero(pred);
        inter += i;
        truth += t;
        predicted += p;
        if (per_frame) {
          std::printf("  %-20s truth %5.1f %%  recall %6.3f  precision %6.3f\n", name.c_str(),
                      100.0 * t / static_cast<double>(g.total()), t > 0 ? i / t : 1.0, p > 0 ? i / p : 1.0);
        }
      }
      std::printf("%-40s %8.3f %9.3f %8.3f %12.1f\n", fs::path(model).filename().string().c_str(),
                  truth > 0 ? inter / truth : 0.0, predicted > 0 ? inter / predicted : 0.0,
                  inter / std::max(1.0, truth + predicted - inter), cpu / std::max<std::size_t>(1, frames.size()));
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
