// io benchmark: per-frame cost of the dataset readers on real data.
//   - EuRoC (../shared/data/euroc_V1_01_micro): load() = two PNG decodes +
//     stereo rectification, and the rectification (remap) part alone;
//   - TUM association (associate.py rule) of the real fr3 frame lists;
//   - settings loading of every preset.
//
//   build/bench/bench_io [--runs N] [--source REPO_DIR]
//
// Wall-clock numbers on a shared machine: compare them within one run.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "stillslam/core/stopwatch.h"
#include "stillslam/io/dataset.h"
#include "stillslam/io/euroc_dataset.h"
#include "stillslam/settings/settings.h"
#include "stillslam/io/timestamp_association.h"
#include "stillslam/io/tum_dataset.h"

namespace fs = std::filesystem;
using namespace stillslam;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 3;
  fs::path source = fs::path(STILLSLAM_SOURCE_DIR);  // this checkout
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string arg = argv[i];
    if (arg == "--runs") runs = std::max(1, std::atoi(argv[i + 1]));
    if (arg == "--source") source = argv[i + 1];
  }
  const fs::path shared = source / ".." / "shared";

  // Settings.
  {
    std::vector<double> ms;
    int files = 0;
    for (int r = 0; r < runs; ++r) {
      for (const auto& entry : fs::directory_iterator(source / "config")) {
        if (entry.path().extension() != ".yaml") continue;
        Stopwatch sw;
        (void)load_settings(entry.path());
        ms.push_back(sw.elapsed_ms());
        ++files;
      }
    }
    std::printf("settings: %d loads, median %.3f ms per file\n", files, median(ms));
  }

  // EuRoC read + rectify.
  const fs::path clip = shared / "data" / "euroc_V1_01_micro";
  if (fs::exists(clip / "mav0")) {
    const Settings settings = load_settings(source / "config" / "euroc.yaml");
    Stopwatch open_sw;
    const auto dataset = open_dataset(clip, settings);
    const double open_ms = open_sw.elapsed_ms();
    const auto& euroc = dynamic_cast<const EurocDataset&>(*dataset);
    std::vector<double> load_ms, remap_ms;
    for (int r = 0; r < runs; ++r) {
      for (std::size_t i = 0; i < dataset->size(); ++i) {
        Stopwatch sw;
        const SensorFrame f = dataset->load(i);
        load_ms.push_back(sw.elapsed_ms());
      }
    }
    const cv::Mat raw = cv::imread((clip / "mav0/cam0/data" / dataset->load(0).name).string(), cv::IMREAD_GRAYSCALE);
    for (int k = 0; k < 50 * runs; ++k) {
      Stopwatch sw;
      const cv::Mat l = euroc.rectifier().rectify_left(raw);
      const cv::Mat rr = euroc.rectifier().rectify_right(raw);
      remap_ms.push_back(sw.elapsed_ms());
    }
    std::printf("euroc: open (lists, %zu IMU samples, rectification maps) %.1f ms; load() median %.2f ms per "
                "stereo frame (%zu loads); rectify both images %.2f ms\n",
                euroc.imu().size(), open_ms, median(load_ms), load_ms.size(), median(remap_ms));
  } else {
    std::printf("euroc: skipped (%s not found)\n", clip.string().c_str());
  }

  // TUM association of the real frame lists (rgb.txt/depth.txt rebuilt from them).
  const fs::path lists = shared / "data" / "frame_lists" / "tum";
  if (fs::exists(lists)) {
    std::vector<double> ms;
    std::size_t pairs = 0;
    for (const auto& entry : fs::directory_iterator(lists)) {
      const auto reference = read_tum_associations(entry.path());
      std::vector<double> rgb, depth;
      for (const auto& p : reference) {
        rgb.push_back(p.rgb_time);
        depth.push_back(p.depth_time);
      }
      for (int r = 0; r < runs; ++r) {
        Stopwatch sw;
        pairs += associate_timestamps(rgb, depth, 0.02).size();
        ms.push_back(sw.elapsed_ms());
      }
    }
    std::printf("tum association: %zu pairs over %zu runs, median %.3f ms per sequence\n", pairs, ms.size(),
                median(ms));
  }
  return 0;
}
