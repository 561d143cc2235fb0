// Feature front-end timings: ORB extraction (ours vs cv::ORB on the same
// images, two threads and one), stereo matching on real rectified EuRoC
// pairs, descriptor distance. Plain main (prints a table), so it runs with or
// without Google Benchmark installed.
//
//   build/bench/bench_features [--repeats N]
//
// Real data is read from ../shared when present (coco128 photo, EuRoC micro
// clip); the procedural texture is always available.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "../tests/features/euroc_stereo.h"    // same data loading as the tests
#include "../tests/features/textured_image.h"  // same procedural texture as the tests
#include "stillslam/core/stopwatch.h"
#include "stillslam/core/thread_cpu_stopwatch.h"
#include "stillslam/features/descriptor.h"
#include "stillslam/features/orb_extractor.h"
#include "stillslam/features/stereo_matcher.h"

namespace fs = std::filesystem;
using namespace stillslam;

namespace {

#ifdef STILLSLAM_BENCH_SHARED_DIR
const fs::path kShared = STILLSLAM_BENCH_SHARED_DIR;
#else
const fs::path kShared = fs::path(STILLSLAM_SOURCE_DIR).parent_path() / "shared";
#endif

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

struct Timing {
  double median_ms = 0;      // wall clock
  double median_cpu_ms = 0;  // calling thread's CPU time
  double mean_features = 0;
};

template <typename Extract>
Timing time_extraction(const std::vector<cv::Mat>& images, int repeats, Extract&& extract) {
  std::vector<double> ms, cpu;
  double features = 0;
  for (int r = 0; r < repeats; ++r) {
    for (const cv::Mat& image : images) {
      const ThreadCpuStopwatch cpu_watch;
      Stopwatch sw;
      const std::size_t n = extract(image);
      ms.push_back(sw.elapsed_ms());
      cpu.push_back(cpu_watch.elapsed_ms());
      features += static_cast<double>(n);
    }
  }
  return {median(ms), median(cpu), features / static_cast<double>(ms.size())};
}

void compare(const char* name, const std::vector<cv::Mat>& images, int n_features, int repeats) {
  if (images.empty()) return;
  OrbOptions options;
  options.n_features = n_features;
  const OrbExtractor ours(options);
  const cv::Ptr<cv::ORB> opencv = cv::ORB::create(n_features, 1.2f, 8);
  auto run_ours = [&](const cv::Mat& im) { return ours.extract(im).size(); };
  auto run_opencv = [&](const cv::Mat& im) {
    std::vector<cv::KeyPoint> kps;
    cv::Mat desc;
    opencv->detectAndCompute(im, cv::noArray(), kps, desc);
    return kps.size();
  };
  const int threads = cv::getNumThreads();
  const Timing ours_mt = time_extraction(images, repeats, run_ours);
  const Timing cv_mt = time_extraction(images, repeats, run_opencv);
  cv::setNumThreads(1);
  const Timing ours_1 = time_extraction(images, repeats, run_ours);
  const Timing cv_1 = time_extraction(images, repeats, run_opencv);
  cv::setNumThreads(threads);
  std::printf("%-36s %dx%d n=%d\n", name, images[0].cols, images[0].rows, n_features);
  std::printf("  stillslam: %6.2f ms wall (%d threads) | %6.2f ms wall, %6.2f ms cpu (1 thread) | %5.0f keypoints\n",
              ours_mt.median_ms, threads, ours_1.median_ms, ours_1.median_cpu_ms, ours_mt.mean_features);
  std::printf("  cv::ORB:   %6.2f ms wall (%d threads) | %6.2f ms wall, %6.2f ms cpu (1 thread) | %5.0f keypoints\n",
              cv_mt.median_ms, threads, cv_1.median_ms, cv_1.median_cpu_ms, cv_mt.mean_features);
}

void bench_stereo(const test::EurocStereo& data, bool flow) {
  OrbOptions options;
  options.n_features = 1200;  // EuRoC.yaml
  const OrbExtractor extractor(options);
  StereoMatchOptions matching;
  matching.flow_for_unmatched = flow;
  std::vector<double> ms, matches, depths;
  for (std::size_t i = 0; i < data.left.size(); ++i) {
    std::vector<cv::Mat> pl, pr;
    const OrbFeatures fl = extractor.extract(data.left[i], &pl);
    const OrbFeatures fr = extractor.extract(data.right[i], &pr);
    const ThreadCpuStopwatch cpu_watch;
    const StereoMatches m = match_stereo(fl, pl, fr, pr, extractor.pyramid(), data.fx, data.bf, matching);
    ms.push_back(cpu_watch.elapsed_ms());
    matches.push_back(m.num_matches);
    for (float d : m.depth) {
      if (d > 0) depths.push_back(d);
    }
  }
  double mean_matches = 0;
  for (double m : matches) mean_matches += m;
  mean_matches /= static_cast<double>(std::max<std::size_t>(1, matches.size()));
  std::sort(depths.begin(), depths.end());
  auto pct = [&](double p) { return depths.empty() ? 0.0 : depths[static_cast<std::size_t>(p * (depths.size() - 1))]; };
  std::printf("stereo matching EuRoC V1_01 micro, %s (%zu rectified pairs, fx %.1f, bf %.2f): median %.2f ms cpu, "
              "%.0f matches of 1200 per pair, depth p10/p50/p90 %.2f/%.2f/%.2f m\n",
              flow ? "descriptors + optical flow" : "descriptors only", data.left.size(), data.fx, data.bf,
              median(ms), mean_matches, pct(0.1), pct(0.5), pct(0.9));
}

void bench_descriptor_distance() {
  cv::RNG rng(1);
  cv::Mat a(2000, 32, CV_8UC1), b(2000, 32, CV_8UC1);
  rng.fill(a, cv::RNG::UNIFORM, 0, 256);
  rng.fill(b, cv::RNG::UNIFORM, 0, 256);
  long sum = 0;
  ThreadCpuStopwatch cpu_watch;
  for (int i = 0; i < a.rows; ++i) {
    const std::uint8_t* pa = a.ptr<std::uint8_t>(i);
    for (int j = 0; j < b.rows; ++j) sum += descriptor_distance(pa, b.ptr<std::uint8_t>(j));
  }
  const double ours_ns = cpu_watch.elapsed_ms() * 1e6 / (a.rows * b.rows);
  long sum_cv = 0;
  cpu_watch = ThreadCpuStopwatch();
  for (int i = 0; i < a.rows; ++i) {
    for (int j = 0; j < b.rows; ++j) {
      sum_cv += static_cast<long>(cv::norm(a.row(i), b.row(j), cv::NORM_HAMMING));
    }
  }
  const double cv_ns = cpu_watch.elapsed_ms() * 1e6 / (a.rows * b.rows);
  std::printf("descriptor_distance: %.1f ns cpu per pair (cv::norm NORM_HAMMING %.1f ns), checksums %s\n", ours_ns, cv_ns,
              sum == sum_cv ? "equal" : "DIFFER");
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 30;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], "--repeats") == 0) repeats = std::max(1, std::atoi(argv[i + 1]));
  }
  std::printf("OpenCV %s, %d threads; medians over %d runs. Wall times depend on machine load, cpu times\n"
              "(1 thread) do not.\n",
              CV_VERSION, cv::getNumThreads(), repeats);
  compare("procedural texture", {test::textured_image()}, 1000, repeats);

  const fs::path photo = kShared / "images" / "coco128" / "images" / "train2017" / "000000000110.jpg";
  cv::Mat coco = cv::imread(photo.string(), cv::IMREAD_GRAYSCALE);
  if (!coco.empty()) {
    cv::resize(coco, coco, cv::Size(640, 480), 0, 0, cv::INTER_AREA);
    compare("coco128 photo 000000000110", {coco}, 1000, repeats);
  } else {
    std::printf("(skipped coco128 photo: %s not found)\n", photo.c_str());
  }

  const fs::path mav0 = kShared / "data" / "euroc_V1_01_micro" / "mav0";
  if (fs::exists(mav0 / "cam1" / "sensor.yaml")) {
    const test::EurocStereo euroc = test::load_euroc_stereo(mav0);
    compare("EuRoC V1_01 micro cam0 (rectified)", euroc.left, 1200, std::max(1, repeats / 10));
    bench_stereo(euroc, false);
    bench_stereo(euroc, true);
  } else {
    std::printf("(skipped EuRoC: %s not found)\n", mav0.c_str());
  }
  bench_descriptor_distance();
  return 0;
}
