// `stillslam segment`: run the YOLO-seg front end on one image or a folder of
// images; print one JSON object per detection on stdout and write binary masks
// (union of the dynamic classes and one per instance) and overlays into --out.
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "opencv_threads.h"
#include "stillslam/core/error.h"
#include "stillslam/core/json_text.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/io/image_files.h"
#include "stillslam/io/image_io.h"
#include "stillslam/settings/settings.h"
#include "stillslam/segmentation/coco_classes.h"
#include "stillslam/segmentation/dynamic_mask.h"
#include "stillslam/segmentation/yolo_segmenter.h"

namespace stillslam::apps {
namespace {

namespace fs = std::filesystem;

struct SegmentArgs {
  std::string config, model, image, input, out;
  std::vector<std::string> classes;
  std::optional<float> score, iou, mask_threshold;
  std::optional<int> dilation;
  int threads = 0;
  bool agnostic_nms = false;
  bool skip_bad_frames = false;
};

// A folder of images, or a dataset folder whose color/left images live in a
// known subfolder (TUM rgb/, EuRoC mav0/cam0/data, KITTI image_2 or image_0).
std::vector<fs::path> sequence_images(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw Error("--input '" + dir.string() + "' is not a folder; use --image for one file");
  for (const fs::path& sub : {fs::path("."), fs::path("rgb"), fs::path("mav0/cam0/data"), fs::path("image_2"),
                             fs::path("image_0"), fs::path("cam0/data")}) {
    if (!fs::is_directory(dir / sub)) continue;
    auto files = image_files_in((dir / sub).lexically_normal());  // no "./" in the names
    if (!files.empty()) return files;
  }
  throw Error("no images (.png, .jpg, ...) in '" + dir.string() +
              "' or its rgb/, mav0/cam0/data, image_2/, image_0/ subfolders");
}

cv::Scalar color_of(std::size_t i) {
  static constexpr int kPalette[][3] = {{56, 56, 255},  {151, 157, 255}, {31, 112, 255}, {29, 178, 255},
                                        {49, 210, 207}, {10, 249, 72},   {23, 204, 146}, {134, 219, 61},
                                        {211, 188, 0},  {209, 99, 0},    {255, 115, 100}, {236, 24, 0}};
  const auto& c = kPalette[i % (sizeof(kPalette) / sizeof(kPalette[0]))];
  return cv::Scalar(c[0], c[1], c[2]);
}

cv::Mat overlay(const cv::Mat& bgr, const std::vector<Detection>& dets) {
  cv::Mat out = bgr.clone();
  for (std::size_t i = 0; i < dets.size(); ++i) {
    if (dets[i].mask.empty()) continue;
    cv::Mat tinted(out.size(), out.type(), color_of(i));
    cv::Mat blended;
    cv::addWeighted(out, 0.5, tinted, 0.5, 0, blended);
    blended.copyTo(out, dets[i].mask);
  }
  const int thickness = std::max(1, static_cast<int>(std::lround(std::max(out.cols, out.rows) / 500.0)));
  for (std::size_t i = 0; i < dets.size(); ++i) {
    const Detection& d = dets[i];
    const cv::Rect box(cv::Point(cvRound(d.box.x), cvRound(d.box.y)), cv::Point(cvRound(d.box.br().x), cvRound(d.box.br().y)));
    cv::rectangle(out, box, color_of(i), thickness);
    char label[96];
    std::snprintf(label, sizeof(label), "%s %.2f", d.class_name.c_str(), d.score);
    int baseline = 0;
    const double font = 0.4 * thickness;
    const cv::Size ts = cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, font, thickness, &baseline);
    const cv::Point org(std::clamp(box.x, 0, std::max(0, out.cols - ts.width - 2)), std::max(ts.height + 2, box.y - 2));
    cv::rectangle(out, cv::Rect(org.x, org.y - ts.height - 2, ts.width + 2, ts.height + baseline + 2), color_of(i),
                  cv::FILLED);
    cv::putText(out, label, cv::Point(org.x + 1, org.y - 1), cv::FONT_HERSHEY_SIMPLEX, font, cv::Scalar(255, 255, 255),
                thickness, cv::LINE_AA);
  }
  return out;
}

// One detection as {"class": "person", "class_id": 0, "score": 0.83, "box": [x0, y0, x1, y1]}.
std::string detection_json(const Detection& d) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), R"({"class": "%s", "class_id": %d, "score": %.3f, "box": [%.1f, %.1f, %.1f, %.1f]})",
                d.class_name.c_str(), d.class_id, d.score, d.box.x, d.box.y, d.box.br().x, d.box.br().y);
  return buf;
}

void write_png(const fs::path& file, const cv::Mat& image) {
  if (!cv::imwrite(file.string(), image)) throw Error("cannot write '" + file.string() + "': check --out is writable");
}

void run_segment(const SegmentArgs& args) {
  SegmentationOptions options;
  if (!args.config.empty()) {
    options = load_settings(args.config).segmentation;
    if (!args.model.empty()) options.model_path = args.model;
  } else {
    options.model_path = args.model;
  }
  // --classes picks what is reported and what the union mask covers; without it every
  // detection is reported and the union covers the configured dynamic classes.
  const std::optional<std::vector<int>> report_ids =
      args.classes.empty() ? std::nullopt : std::optional(resolve_class_ids(args.classes));
  if (!args.classes.empty()) options.classes = args.classes;
  const std::vector<int> dynamic_ids = resolve_class_ids(options.classes);
  if (args.score) options.score_threshold = *args.score;
  if (args.iou) options.nms_iou_threshold = *args.iou;
  if (args.mask_threshold) options.mask_threshold = *args.mask_threshold;
  if (args.dilation) options.mask_dilation = *args.dilation;
  // The limits of Segmentation.maskDilation and Segmentation.threads.
  if (options.mask_dilation < 0 || options.mask_dilation > 256) {
    throw Error("--dilation is " + std::to_string(options.mask_dilation) + ": must be in [0, 256] pixels");
  }
  if (args.threads > max_threads()) {
    throw Error("--threads is " + std::to_string(args.threads) + ": must be in [0, " + std::to_string(max_threads()) +
                "]");
  }
  set_opencv_threads(args.threads);
  options.agnostic_nms = options.agnostic_nms || args.agnostic_nms;
  options.masks_for_classes_only = false;

  const std::vector<fs::path> images =
      args.image.empty() ? sequence_images(args.input) : std::vector<fs::path>{fs::path(args.image)};
  if (!args.image.empty() && !fs::is_regular_file(args.image))
    throw Error("--image '" + args.image + "' does not exist");
  YoloSegmenter segmenter(options);
  const fs::path out(args.out);
  for (const char* sub : {"masks", "instances", "overlays"}) {
    std::error_code ec;
    fs::create_directories(out / sub, ec);
    if (ec) throw Error("cannot create '" + (out / sub).string() + "': " + ec.message());
  }
  // Same objects as stdout plus the image name, for sequences.
  std::ofstream jsonl(out / "detections.jsonl");
  if (!jsonl) throw Error("cannot write '" + (out / "detections.jsonl").string() + "': check --out is writable");
  std::cerr << "segment: " << images.size() << " image(s), model " << options.model_path << " ("
            << segmenter.input_size().width << "x" << segmenter.input_size().height << ")\n";
  std::size_t skipped = 0;
  for (const auto& file : images) {
    cv::Mat bgr;
    try {
      bgr = read_color_image(file);
    } catch (const Error& e) {
      if (!args.skip_bad_frames) throw;
      ++skipped;
      spdlog::warn("skipping bad image ({} skipped so far): {}", skipped, e.what());
      continue;
    }
    Stopwatch watch;
    std::vector<Detection> dets = segmenter.segment(bgr);
    const double ms = watch.elapsed_ms();
    if (report_ids)
      std::erase_if(dets, [&](const Detection& d) {
        return std::find(report_ids->begin(), report_ids->end(), d.class_id) == report_ids->end();
      });
    const std::string stem = file.stem().string();
    write_png(out / "masks" / (stem + ".png"), dynamic_mask(dets, dynamic_ids, bgr.size(), options.mask_dilation));
    for (std::size_t i = 0; i < dets.size(); ++i) {
      std::string cls = dets[i].class_name;
      std::replace(cls.begin(), cls.end(), ' ', '_');
      const std::string index = (i < 10 ? "0" : "") + std::to_string(i);
      write_png(out / "instances" / (stem + "_" + index + "_" + cls + ".png"), dets[i].mask);
    }
    write_png(out / "overlays" / (stem + ".jpg"), overlay(bgr, dets));
    for (const auto& d : dets) {
      const std::string json = detection_json(d);
      std::cout << json << '\n';
      jsonl << R"({"image": )" << json_text(file.filename().string()) << ", " << json.substr(1) << '\n';
    }
    std::cout.flush();
    std::cerr << file.filename().string() << ": " << dets.size() << " detection(s), " << static_cast<int>(ms)
              << " ms\n";
  }
  if (skipped == images.size()) throw Error("no readable image: all " + std::to_string(skipped) + " were skipped");
  if (skipped > 0) std::cerr << "segment: " << skipped << " of " << images.size() << " image(s) skipped\n";
}

}  // namespace

void add_segment_command(CLI::App& app) {
  auto args = std::make_shared<SegmentArgs>();
  CLI::App* cmd = app.add_subcommand(
      "segment",
      "Run YOLO instance segmentation on images: one JSON line per detection on stdout "
      "({\"class\", \"class_id\", \"score\", \"box\": [x0, y0, x1, y1]} in image pixels); writes OUT/masks/<image>.png "
      "(union of the dynamic classes), OUT/instances/<image>_<n>_<class>.png, OUT/overlays/<image>.jpg and "
      "OUT/detections.jsonl (the stdout lines with an \"image\" key)");
  cmd->add_option("--config", args->config, "settings YAML (Segmentation.* keys)")->check(CLI::ExistingFile);
  cmd->add_option("--model", args->model, "YOLOv8/YOLO11-seg ONNX file (overrides Segmentation.model)");
  auto* image = cmd->add_option("--image", args->image, "one image file");
  auto* input = cmd->add_option("--input", args->input, "folder of images (or a TUM/EuRoC/KITTI sequence folder)");
  image->excludes(input);
  cmd->add_option("--out", args->out, "output folder")->required();
  cmd->add_option("--classes", args->classes,
                  "report only these classes (COCO names or ids, comma-separated) and use them for the union mask; "
                  "default: report all, union of Segmentation.classes (person)")
      ->delimiter(',');
  cmd->add_option("--score", args->score, "score threshold (default 0.25 or Segmentation.scoreThreshold)");
  cmd->add_option("--iou", args->iou, "NMS IoU threshold (default 0.45)");
  cmd->add_option("--mask-threshold", args->mask_threshold, "mask probability threshold (default 0.5)");
  cmd->add_option("--dilation", args->dilation, "grow the union mask by this many pixels (default Segmentation.maskDilation)");
  cmd->add_option("--threads", args->threads, "OpenCV threads (0 = all cores)")->check(CLI::NonNegativeNumber);
  cmd->add_flag("--agnostic-nms", args->agnostic_nms, "suppress overlapping boxes across classes");
  cmd->add_flag("--skip-bad-frames", args->skip_bad_frames,
                "go on past a missing or unreadable image (a warning names each) instead of stopping there");
  cmd->callback([args]() {
    if (args->config.empty() && args->model.empty()) throw Error("stillslam segment needs --config YAML or --model FILE");
    if (args->image.empty() && args->input.empty()) throw Error("stillslam segment needs --image FILE or --input FOLDER");
    run_segment(*args);
  });
}

}  // namespace stillslam::apps
