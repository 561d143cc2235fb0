// Segmentation benchmark: latency per model input size, accuracy of the smaller
// inputs against the 480x640 model, and ORB extraction overlapped with
// segmentation (SegmentationWorker) versus run one after the other.
//
//   build/bench/bench_segmentation [--runs N] [--threads T] [--frames F] [--coco C] [--source REPO_DIR]
//
// Reads the models in models/ and, when present, ../shared/models/yolo-seg
// (REPO_DIR defaults to the checkout this file was compiled from).
// Wall-clock numbers on a shared machine: compare them within one run.
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>


#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <memory>
#include <string>
#include <vector>

#include "load_average.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/segmentation/dynamic_mask.h"
#include "stillslam/segmentation/segmentation_worker.h"
#include "stillslam/segmentation/yolo_segmenter.h"
#include "stillslam/system/process_cpu_time.h"

namespace fs = std::filesystem;
using namespace stillslam;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// CPU time of the whole process: unlike wall-clock time it barely depends on what
// other processes on a shared machine are doing.
double process_cpu_ms() { return 1e3 * process_cpu_seconds(); }

SegmentationOptions options_for(const std::string& model, int threads) {
  SegmentationOptions o;
  o.model_path = model;
  o.threads = threads;
  return o;
}

// Person masks of a and b matched greedily by IoU; returns the mean IoU over the persons of b
// (a person of b without a match counts 0).
double person_mask_iou(const std::vector<Detection>& a, const std::vector<Detection>& b) {
  std::vector<bool> used(a.size(), false);
  double sum = 0;
  int n = 0;
  for (const auto& db : b) {
    if (db.class_id != 0) continue;
    ++n;
    double best = 0;
    std::size_t best_i = a.size();
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (used[i] || a[i].class_id != 0) continue;
      const double inter = cv::countNonZero(a[i].mask & db.mask);
      const double uni = cv::countNonZero(a[i].mask | db.mask);
      if (uni > 0 && inter / uni > best) best = inter / uni, best_i = i;
    }
    if (best_i < a.size()) used[best_i] = true;
    sum += best;
  }
  return n ? sum / n : 0.0;
}

int count_class(const std::vector<Detection>& d, int id) {
  return static_cast<int>(std::count_if(d.begin(), d.end(), [&](const Detection& x) { return x.class_id == id; }));
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 20;
  int threads = 2;
  int frames = 20;
  int coco = 30;
  std::string src = fs::path(STILLSLAM_SOURCE_DIR).string();
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--runs") runs = std::stoi(argv[i + 1]);
    if (a == "--threads") threads = std::stoi(argv[i + 1]);
    if (a == "--frames") frames = std::stoi(argv[i + 1]);
    if (a == "--coco") coco = std::stoi(argv[i + 1]);
    if (a == "--source") src = argv[i + 1];
  }
  const std::string shared = src + "/../shared";
  const std::string bus_path = src + "/tests/segmentation/data/bus.jpg";
  const cv::Mat bus = cv::imread(bus_path);
  const cv::Mat busstop = cv::imread(shared + "/images/busstop.jpg");
  if (bus.empty()) {
    std::fprintf(stderr, "cannot read %s\n", bus_path.c_str());
    return 1;
  }
  std::printf("load average at start: %.2f, OpenCV threads: %d\n", load_average(), threads);

  // 1. Latency and accuracy per model.
  const std::string reference_model = shared + "/models/yolo-seg/yolo11n-seg_480x640.onnx";
  std::vector<std::string> models{src + "/models/yolo11n-seg_384x512.onnx"};
  for (const char* f : {"yolo11n-seg_480x640.onnx", "yolo11n-seg_384x512.onnx", "yolo11n-seg_288x384.onnx",
                        "yolov8n-seg_480x640.onnx"})
    if (fs::exists(shared + "/models/yolo-seg/" + f)) models.push_back(shared + "/models/yolo-seg/" + f);
  std::vector<Detection> ref_bus, ref_busstop;
  if (fs::exists(reference_model)) {
    YoloSegmenter ref(options_for(reference_model, threads));
    ref_bus = ref.segment(bus);
    if (!busstop.empty()) ref_busstop = ref.segment(busstop);
  }
  const cv::Mat frame640 = [&] {
    cv::Mat f;
    cv::resize(busstop.empty() ? bus : busstop, f, cv::Size(640, 480), 0, 0, cv::INTER_AREA);
    return f;
  }();
  // Models are timed round-robin (one run of each per round) so that load from other
  // processes on a shared machine hits them all alike.
  std::vector<std::unique_ptr<YoloSegmenter>> segs;
  for (const auto& model : models) segs.push_back(std::make_unique<YoloSegmenter>(options_for(model, threads)));
  std::vector<std::vector<double>> t_bus(models.size()), t_640(models.size()), cpu_640(models.size());
  for (int r = 0; r < runs + 2; ++r) {  // 2 warm-up rounds
    for (std::size_t m = 0; m < segs.size(); ++m) {
      Stopwatch w;
      segs[m]->segment(bus);
      if (r >= 2) t_bus[m].push_back(w.elapsed_ms());
      w.restart();
      const double cpu0 = process_cpu_ms();
      segs[m]->segment(frame640);
      if (r >= 2) t_640[m].push_back(w.elapsed_ms()), cpu_640[m].push_back(process_cpu_ms() - cpu0);
    }
  }
  std::printf("\n%-28s %7s %9s %9s %9s %9s %8s %8s\n", "model", "input", "bus ms", "640x480", "cpu ms", "persons",
              "IoU bus", "IoU stop");
  for (std::size_t m = 0; m < segs.size(); ++m) {
    const auto d_bus = segs[m]->segment(bus);
    const auto d_stop = busstop.empty() ? std::vector<Detection>{} : segs[m]->segment(busstop);
    const cv::Size in = segs[m]->input_size();
    std::printf("%-28s %3dx%-3d %9.1f %9.1f %9.1f %4d/%-4d %8.3f %8.3f\n", fs::path(models[m]).filename().c_str(),
                in.height, in.width, median(t_bus[m]), median(t_640[m]), median(cpu_640[m]), count_class(d_bus, 0),
                count_class(d_stop, 0), ref_bus.empty() ? 0.0 : person_mask_iou(d_bus, ref_bus),
                ref_busstop.empty() ? 0.0 : person_mask_iou(d_stop, ref_busstop));
  }
  std::printf("(median of %d runs: wall-clock ms on bus.jpg 810x1080 and a 640x480 frame, process CPU ms on the\n"
              " 640x480 frame; persons found in bus/busstop; IoU = mean person-mask IoU against yolo11n-seg 480x640)\n",
              runs);

  // Person-pixel accuracy against COCO ground-truth polygons (coco128 photos with people):
  // what the dynamic mask should cover. Summed over the images.
  const fs::path coco_dir = shared + "/images/coco128";
  std::vector<std::pair<fs::path, std::vector<std::vector<cv::Point2f>>>> coco_images;  // image, person polygons
  if (coco > 0 && fs::exists(coco_dir / "labels")) {
    std::vector<fs::path> labels;
    for (const auto& e : fs::recursive_directory_iterator(coco_dir / "labels"))
      if (e.path().extension() == ".txt") labels.push_back(e.path());
    std::sort(labels.begin(), labels.end());
    for (const auto& label : labels) {
      std::ifstream in(label);
      std::vector<std::vector<cv::Point2f>> polys;
      for (std::string line; std::getline(in, line);) {
        std::istringstream ls(line);
        int cls = -1;
        ls >> cls;
        if (cls != 1) continue;  // coco128 labels use COCO category ids: 1 = person
        std::vector<cv::Point2f> poly;
        for (float x, y; ls >> x >> y;) poly.emplace_back(x, y);
        polys.push_back(poly);
      }
      const fs::path image = coco_dir / "images" / label.parent_path().filename() / (label.stem().string() + ".jpg");
      if (!polys.empty() && fs::exists(image)) coco_images.emplace_back(image, polys);
      if (static_cast<int>(coco_images.size()) == coco) break;
    }
  }
  if (!coco_images.empty()) {
    std::vector<double> inter(segs.size()), uni(segs.size()), pred(segs.size());
    double gt_total = 0;
    for (const auto& [path, polys] : coco_images) {
      const cv::Mat img = cv::imread(path.string());
      cv::Mat1b gt(img.size(), uchar{0});
      std::vector<std::vector<cv::Point>> pix;
      for (const auto& poly : polys) {
        std::vector<cv::Point> p;
        for (const auto& q : poly) p.emplace_back(cvRound(q.x * img.cols), cvRound(q.y * img.rows));
        pix.push_back(p);
      }
      cv::fillPoly(gt, pix, cv::Scalar(255));
      gt_total += cv::countNonZero(gt);
      for (std::size_t m = 0; m < segs.size(); ++m) {
        const cv::Mat1b mask = dynamic_mask(segs[m]->segment(img), {0}, img.size(), 0);
        inter[m] += cv::countNonZero(mask & gt);
        uni[m] += cv::countNonZero(mask | gt);
        pred[m] += cv::countNonZero(mask);
      }
    }
    std::printf("\nperson pixels vs COCO ground truth, %zu coco128 photos with people:\n", coco_images.size());
    std::printf("%-28s %8s %8s %10s\n", "model", "IoU", "recall", "precision");
    for (std::size_t m = 0; m < segs.size(); ++m)
      std::printf("%-28s %8.3f %8.3f %10.3f\n", fs::path(models[m]).filename().c_str(), inter[m] / uni[m],
                  inter[m] / gt_total, pred[m] > 0 ? inter[m] / pred[m] : 0.0);
  }
  segs.clear();

  // 2. ORB extraction of frame k overlapped with segmentation of frame k.
  std::vector<cv::Mat> seq;
  for (int i = 0; i < frames; ++i) {
    // A moving 640x480 window over the street photo so every frame differs.
    const cv::Mat& src_img = busstop.empty() ? bus : busstop;
    const int max_dx = std::max(0, src_img.cols - 960), max_dy = std::max(0, src_img.rows - 720);
    const cv::Rect roi(max_dx * i / std::max(1, frames - 1), max_dy * i / std::max(1, frames - 1),
                       std::min(960, src_img.cols), std::min(720, src_img.rows));
    cv::Mat f;
    cv::resize(src_img(roi), f, cv::Size(640, 480), 0, 0, cv::INTER_AREA);
    seq.push_back(f);
  }
  const std::string model = src + "/models/yolo11n-seg_384x512.onnx";
  const cv::Ptr<cv::ORB> orb = cv::ORB::create(1000);
  auto extract = [&](const cv::Mat& bgr, std::vector<cv::KeyPoint>& kps, cv::Mat& desc) {
    cv::Mat gray;
    cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
    orb->detectAndCompute(gray, cv::noArray(), kps, desc);
  };
  for (int net_threads : threads == 1 ? std::vector<int>{1} : std::vector<int>{1, threads}) {
    YoloSegmenter direct(options_for(model, net_threads));
    SegmentationWorker worker(std::make_unique<YoloSegmenter>(options_for(model, net_threads)), {0}, 3);
    std::vector<double> seq_total, seq_orb, seq_seg, par_total, par_orb, par_wait;
    std::size_t kept_seq = 0, kept_par = 0;
    std::size_t index = 0;  // the worker's MaskHold ages held people by frame index
    for (int pass = 0; pass < 2; ++pass) {  // pass 0 warms up
      for (const auto& f : seq) {
        // Sequential: ORB, then segmentation and the mask, on this thread.
        Stopwatch total;
        std::vector<cv::KeyPoint> kps;
        cv::Mat desc;
        Stopwatch w;
        extract(f, kps, desc);
        const double orb_ms = w.elapsed_ms();
        w.restart();
        const cv::Mat1b mask = dynamic_mask(direct.segment(f), {0}, f.size(), 3);
        const double seg_ms = w.elapsed_ms();
        const std::size_t kept = keypoints_outside_mask(kps, mask).size();
        const double seq_ms = total.elapsed_ms();
        // Overlapped: submit, ORB on this thread, then wait for the mask.
        total.restart();
        auto future = worker.submit(f, index++);
        std::vector<cv::KeyPoint> kps2;
        cv::Mat desc2;
        w.restart();
        extract(f, kps2, desc2);
        const double orb2_ms = w.elapsed_ms();
        w.restart();
        const SegmentationResult r = future.get();
        const double wait_ms = w.elapsed_ms();
        const std::size_t kept2 = keypoints_outside_mask(kps2, r.dynamic_mask).size();
        const double par_ms = total.elapsed_ms();
        if (pass == 0) continue;
        seq_total.push_back(seq_ms), seq_orb.push_back(orb_ms), seq_seg.push_back(seg_ms);
        par_total.push_back(par_ms), par_orb.push_back(orb2_ms), par_wait.push_back(wait_ms);
        kept_seq += kept, kept_par += kept2;
      }
    }
    std::printf("\noverlap demo, %d frames 640x480, ORB 1000 features, yolo11n-seg 384x512, OpenCV threads %d:\n",
                frames, net_threads);
    std::printf("  sequential: per-frame total median %.1f ms (ORB %.1f + segmentation %.1f)\n", median(seq_total),
                median(seq_orb), median(seq_seg));
    std::printf("  overlapped: per-frame total median %.1f ms (ORB %.1f on caller, then waited %.1f for the mask)\n",
                median(par_total), median(par_orb), median(par_wait));
    std::printf("  static keypoints kept: %zu sequential, %zu overlapped (must be equal)\n", kept_seq, kept_par);
  }
  std::printf("\nload average at end: %.2f\n", load_average());
  return 0;
}
