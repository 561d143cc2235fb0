// Place recognition figures for the committed vocabulary (or --vocab FILE):
// load time, transform time per keyframe, KeyframeDatabase query time with
// 1000 keyframes, direct-index vs brute-force matching, and the BoW score
// distribution on the real EuRoC clip by time gap between frames, against
// unrelated photos (coco128). Plain main
// (prints tables); times are medians, wall clock and the thread's CPU time
// (the machine is shared, CPU time is the work itself).
//
//   build/bench/bench_place [--vocab FILE] [--repeats N]
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "stillslam/core/stopwatch.h"
#include "stillslam/core/thread_cpu_stopwatch.h"
#include "stillslam/features/descriptor_matcher.h"
#include "stillslam/features/orb_extractor.h"
#include "stillslam/place/direct_index_matcher.h"
#include "stillslam/place/keyframe_database.h"
#include "stillslam/place/vocabulary.h"

namespace fs = std::filesystem;
using namespace stillslam;

namespace {

const fs::path kSource = fs::path(STILLSLAM_SOURCE_DIR);
const fs::path kShared = kSource.parent_path() / "shared";

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5)];
}

struct Timed {
  double wall_ms = 0, cpu_ms = 0;
};

template <typename F>
Timed time_median(int repeats, F&& f) {
  std::vector<double> wall, cpu;
  for (int r = 0; r < repeats; ++r) {
    Stopwatch w;
    const ThreadCpuStopwatch cpu_watch;
    f();
    cpu.push_back(cpu_watch.elapsed_ms());
    wall.push_back(w.elapsed_ms());
  }
  return {percentile(wall, 0.5), percentile(cpu, 0.5)};
}

std::vector<fs::path> images_in(const fs::path& dir) {
  std::vector<fs::path> files;
  if (!fs::is_directory(dir)) return files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".png" || e.path().extension() == ".jpg") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

cv::Mat moved(const cv::Mat& image, double dx, double dy, double degrees) {
  cv::Mat m = cv::getRotationMatrix2D(cv::Point2f(image.cols / 2.f, image.rows / 2.f), degrees, 1.0);
  m.at<double>(0, 2) += dx;
  m.at<double>(1, 2) += dy;
  cv::Mat out;
  cv::warpAffine(image, out, m, image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  fs::path vocab_file = kSource / "vocab" / "orb_vocabulary.bin";
  int repeats = 5;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], "--vocab") == 0) vocab_file = argv[++i];
    else if (std::strcmp(argv[i], "--repeats") == 0) repeats = std::max(1, std::atoi(argv[++i]));
  }
  cv::setNumThreads(1);
  std::printf("vocabulary: %s\n", vocab_file.string().c_str());

  Vocabulary voc;
  const Timed load = time_median(repeats, [&] { voc = Vocabulary::load(vocab_file); });
  std::printf("load: %.1f ms wall, %.1f ms cpu (%zu words, %zu nodes, k=%d L=%d, %.1f MB)\n", load.wall_ms,
              load.cpu_ms, voc.size(), voc.node_count(), voc.k(), voc.depth(),
              static_cast<double>(fs::file_size(vocab_file)) / 1e6);

  const fs::path euroc = kShared / "data" / "euroc_V1_01_micro" / "mav0";
  const auto cam0 = images_in(euroc / "cam0" / "data");
  const auto cam1 = images_in(euroc / "cam1" / "data");
  auto coco = images_in(kShared / "images" / "coco128" / "images" / "train2017");
  const auto coco_val = images_in(kShared / "images" / "coco128" / "images" / "val2017");
  coco.insert(coco.end(), coco_val.begin(), coco_val.end());
  if (cam0.empty() || coco.empty()) {
    std::printf("../shared data missing (EuRoC clip, coco128): only the load time is measured\n");
    return 0;
  }

  OrbOptions orb;
  orb.n_features = 1000;
  const OrbExtractor extractor(orb);
  std::vector<cv::Mat> gray0, desc0, desc1;
  for (const auto& f : cam0) gray0.push_back(cv::imread(f.string(), cv::IMREAD_GRAYSCALE));
  for (const auto& g : gray0) desc0.push_back(extractor.extract(g).descriptors);
  for (const auto& f : cam1) desc1.push_back(extractor.extract(cv::imread(f.string(), cv::IMREAD_GRAYSCALE)).descriptors);

  // Transform: one EuRoC keyframe (~1000 features) at a time.
  std::size_t features = 0;
  for (const auto& d : desc0) features += static_cast<std::size_t>(d.rows);
  BowVector bow;
  FeatureVector fv;
  std::size_t next = 0;
  const Timed transform = time_median(std::max(repeats, 20), [&] {
    voc.transform(desc0[next++ % desc0.size()], bow, fv, 2);
  });
  std::printf("transform (BoW + direct index at depth 2): %.2f ms wall, %.2f ms cpu per keyframe (%.0f features)\n",
              transform.wall_ms, transform.cpu_ms, static_cast<double>(features) / static_cast<double>(desc0.size()));

  // Database of 1000 keyframes: EuRoC cam0/cam1, coco128 photos, and moved
  // copies of the photos (shifted and rotated) to fill up to 1000.
  std::vector<BowVector> bows;
  for (const auto& d : desc0) bows.push_back(voc.transform(d));
  for (const auto& d : desc1) bows.push_back(voc.transform(d));
  std::vector<cv::Mat> coco_gray;
  for (const auto& f : coco) coco_gray.push_back(cv::imread(f.string(), cv::IMREAD_GRAYSCALE));
  for (const auto& g : coco_gray) bows.push_back(voc.transform(extractor.extract(g).descriptors));
  for (std::size_t i = 0; bows.size() < 1000; ++i) {
    const double a = static_cast<double>(i / coco_gray.size() + 1);
    bows.push_back(voc.transform(extractor.extract(moved(coco_gray[i % coco_gray.size()], 15 * a, -10 * a, 4 * a)).descriptors));
  }
  KeyframeDatabase db;
  const Timed add = time_median(1, [&] {
    for (std::size_t i = 0; i < bows.size(); ++i) db.add(i, bows[i]);
  });
  std::vector<double> query_wall, query_cpu;
  std::size_t candidates = 0;
  for (std::size_t q = 0; q < desc0.size(); ++q) {
    PlaceQueryOptions o;
    o.max_results = 10;
    std::size_t n = 0;
    const Timed t = time_median(1, [&] { n = db.query(bows[q], o).size(); });
    query_wall.push_back(t.wall_ms);
    query_cpu.push_back(t.cpu_ms);
    candidates += n;
  }
  std::printf("database: %zu keyframes added in %.1f ms; query (top 10): median %.3f ms wall, %.3f ms cpu, p90 %.3f ms cpu\n",
              db.size(), add.wall_ms, percentile(query_wall, 0.5), percentile(query_cpu, 0.5),
              percentile(query_cpu, 0.9));
  std::vector<double> brute;
  for (std::size_t q = 0; q < 10; ++q) {
    const ThreadCpuStopwatch cpu_watch;
    double best = 0;
    for (const auto& b : bows) best = std::max(best, l1_score(bows[q], b));
    brute.push_back(cpu_watch.elapsed_ms() + best * 0);
  }
  std::printf("  (scoring all 1000 with l1_score instead: %.3f ms cpu)\n", percentile(brute, 0.5));

  // Direct index matching vs brute force on frames 5 apart, by the depth of
  // the nodes that group the features (deeper: fewer comparisons, more true
  // matches split into different groups).
  for (int level = 1; level <= std::min(voc.depth(), 4); ++level) {
    std::vector<double> brute_ms, direct_ms, agreement;
    for (std::size_t i = 0; i + 5 < desc0.size(); i += 10) {
      BowVector b1, b2;
      FeatureVector f1, f2;
      voc.transform(desc0[i], b1, f1, level);
      voc.transform(desc0[i + 5], b2, f2, level);
      std::vector<cv::DMatch> m_brute, m_direct;
      brute_ms.push_back(time_median(1, [&] { m_brute = match_descriptors(desc0[i], desc0[i + 5]); }).cpu_ms);
      direct_ms.push_back(time_median(1, [&] { m_direct = match_by_direct_index(desc0[i], f1, desc0[i + 5], f2); }).cpu_ms);
      std::size_t same = 0;
      for (const auto& m : m_brute)
        same += std::any_of(m_direct.begin(), m_direct.end(),
                            [&](const cv::DMatch& d) { return d.queryIdx == m.queryIdx && d.trainIdx == m.trainIdx; });
      agreement.push_back(m_brute.empty() ? 1.0 : static_cast<double>(same) / static_cast<double>(m_brute.size()));
    }
    std::printf("matching EuRoC frames 5 apart: brute force %.2f ms cpu, direct index at depth %d %.2f ms cpu, "
                "%.0f%% of brute-force matches found (median)\n",
                percentile(brute_ms, 0.5), level, percentile(direct_ms, 0.5), 100 * percentile(agreement, 0.5));
  }

  // Score distribution on EuRoC cam0 by time gap (20 Hz: 1 frame = 50 ms).
  std::printf("\nEuRoC V1_01 micro (95 frames, 4.7 s), cam0 vs cam0, L1 score by frame gap:\n");
  std::printf("%-18s %6s %7s %7s %7s %7s %7s\n", "gap (frames)", "pairs", "p10", "median", "mean", "p90", "max");
  const std::vector<std::pair<int, int>> bands = {{1, 1}, {2, 3}, {4, 10}, {11, 30}, {31, 60}, {61, 94}};
  std::vector<std::vector<double>> scores(bands.size());
  for (std::size_t i = 0; i < desc0.size(); ++i)
    for (std::size_t j = i + 1; j < desc0.size(); ++j) {
      const int gap = static_cast<int>(j - i);
      for (std::size_t b = 0; b < bands.size(); ++b)
        if (gap >= bands[b].first && gap <= bands[b].second) scores[b].push_back(l1_score(bows[i], bows[j]));
    }
  for (std::size_t b = 0; b < bands.size(); ++b) {
    double mean = 0;
    for (double s : scores[b]) mean += s;
    mean /= static_cast<double>(std::max<std::size_t>(scores[b].size(), 1));
    char label[32];
    std::snprintf(label, sizeof(label), "%d-%d", bands[b].first, bands[b].second);
    std::printf("%-18s %6zu %7.3f %7.3f %7.3f %7.3f %7.3f\n", label, scores[b].size(), percentile(scores[b], 0.1),
                percentile(scores[b], 0.5), mean, percentile(scores[b], 0.9), percentile(scores[b], 1.0));
  }
  std::vector<double> stereo, unrelated;
  for (std::size_t i = 0; i < desc0.size() && i < desc1.size(); ++i)
    stereo.push_back(l1_score(bows[i], bows[desc0.size() + i]));
  for (std::size_t i = 0; i < desc0.size(); ++i)
    for (std::size_t c = 0; c < coco.size(); c += 7) unrelated.push_back(l1_score(bows[i], bows[2 * desc0.size() + c]));
  {
    // How similar the raw features are: mutual-best brute-force matches.
    std::vector<double> stereo_matches, temporal_matches;
    for (std::size_t i = 0; i + 1 < desc0.size() && i < desc1.size(); i += 10) {
      stereo_matches.push_back(static_cast<double>(match_descriptors(desc0[i], desc1[i]).size()));
      temporal_matches.push_back(static_cast<double>(match_descriptors(desc0[i], desc0[i + 1]).size()));
    }
    std::printf("brute-force matches (median): cam0 t vs cam1 t %.0f, cam0 t vs cam0 t+1 %.0f\n",
                percentile(stereo_matches, 0.5), percentile(temporal_matches, 0.5));
  }
  std::printf("%-18s %6zu %7.3f %7.3f %7s %7.3f %7.3f\n", "cam0 vs cam1 same t", stereo.size(),
              percentile(stereo, 0.1), percentile(stereo, 0.5), "", percentile(stereo, 0.9), percentile(stereo, 1.0));
  std::printf("%-18s %6zu %7.3f %7.3f %7s %7.3f %7.3f\n", "EuRoC vs coco", unrelated.size(),
              percentile(unrelated, 0.1), percentile(unrelated, 0.5), "", percentile(unrelated, 0.9),
              percentile(unrelated, 1.0));
  // Same place vs different place: the camera hardly moves during the clip
  // (the MAV sits on the ground, ground truth moves < 1 cm), so every EuRoC
  // pair is the same place and coco photos are other places. AUC = fraction
  // of (EuRoC pair >= 61 frames apart, EuRoC-coco pair) orderings that are right.
  {
    std::vector<double> far = scores.back();
    std::sort(unrelated.begin(), unrelated.end());
    double right = 0;
    for (double f : far)
      right += static_cast<double>(std::lower_bound(unrelated.begin(), unrelated.end(), f) - unrelated.begin());
    std::printf("AUC (EuRoC frames 3-4.7 s apart vs EuRoC-coco): %.4f\n",
                right / static_cast<double>(far.size() * unrelated.size()));
  }
  // Retrieval among the 1000 keyframes for each cam1 frame (other cam1
  // frames excluded): is the best keyframe a cam0 frame of the same clip?
  std::size_t hits = 0;
  for (std::size_t i = 0; i < desc1.size(); ++i) {
    PlaceQueryOptions o;
    o.max_results = 1;
    o.exclude = [&](KeyframeId id) { return id >= desc0.size() && id < 2 * desc0.size(); };
    const auto r = db.query(bows[desc0.size() + i], o);
    if (!r.empty() && r[0].id < desc0.size()) ++hits;
  }
  std::printf("cam1 frame as query -> best of the other keyframes is a cam0 frame: %zu / %zu\n", hits, desc1.size());
  return 0;
}
