// io benchmark: per-frame cost of the dataset readers on real data.
//   - EuRoC (../shared/data/euroc_V1_01_micro): load() = two PNG decodes +
//     stereo rectification, and the rectification (remap) part alone;
//   - the same clip written as ROS 2 bags (db3, MCAP zstd / lz4 / none, raw
//     and PNG images): open (index + header stamps) and load() per frame,
//     and what the bag adds over the folder reader;
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

#include <unistd.h>

#include <opencv2/imgcodecs.hpp>

#include "stillslam/core/stopwatch.h"
#include "stillslam/io/bag_dataset.h"
#include "stillslam/io/bag_folder_writer.h"
#include "stillslam/io/ros2_message_codec.h"
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

    // The same clip as bags.
    const fs::path tmp = fs::temp_directory_path() / ("stillslam_bench_io_bags_" + std::to_string(::getpid()));
    fs::remove_all(tmp);
    struct Variant {
      const char* name;
      const char* format;
      const char* compression;
      const char* images;
    };
    const double folder_ms = median(load_ms);
    for (const Variant& v : {Variant{"db3 raw", "db3", "none", "raw"}, Variant{"mcap zstd raw", "mcap", "zstd", "raw"},
                             Variant{"mcap lz4 raw", "mcap", "lz4", "raw"}, Variant{"mcap none raw", "mcap", "none", "raw"},
                             Variant{"mcap zstd png", "mcap", "zstd", "png"}, Variant{"db3 png", "db3", "none", "png"}}) {
      BagFolderWriteOptions wo;
      wo.bag.format = v.format;
      wo.bag.compression = v.compression;
      wo.images = v.images;
      const fs::path bag = tmp / (std::string(v.format) + "_" + v.compression + "_" + v.images);
      write_folder_as_bag(clip, bag, wo);
      DatasetOptions o;
      o.topics = {"/cam0/image_raw", "/cam1/image_raw"};
      Stopwatch bag_open;
      const auto bag_dataset = open_dataset(bag, settings, o);
      const double bag_open_ms = bag_open.elapsed_ms();
      std::vector<double> bag_ms;
      for (int r = 0; r < runs; ++r) {
        for (std::size_t i = 0; i < bag_dataset->size(); ++i) {
          Stopwatch sw;
          const SensorFrame f = bag_dataset->load(i);
          bag_ms.push_back(sw.elapsed_ms());
        }
      }
      // The bag reader's own part: fetch both messages and parse their CDR (no image decode).
      const BagReader& reader = dynamic_cast<const BagDataset&>(*bag_dataset).bag();
      std::vector<double> fetch_ms;
      for (int r = 0; r < runs; ++r) {
        Stopwatch sw;
        for (std::size_t i = 0; i < reader.messages().size(); ++i) {
          const std::string& type = reader.topics()[reader.messages()[i].topic].type;
          if (type == ros2::kImageType) (void)ros2::decode_image(reader.read(i), "bench");
          if (type == ros2::kCompressedImageType) (void)ros2::decode_compressed_image(reader.read(i), "bench");
        }
        fetch_ms.push_back(sw.elapsed_ms() / static_cast<double>(bag_dataset->size()));
      }
      std::printf("bag %-14s: open %.1f ms (%zu frames); load() median %.2f ms per stereo frame (%+.2f ms vs the "
                  "folder); read + CDR parse of both messages %.2f ms per frame\n",
                  v.name, bag_open_ms, bag_dataset->size(), median(bag_ms), median(bag_ms) - folder_ms,
                  median(fetch_ms));
    }
    fs::remove_all(tmp);
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
