// Vocabulary and place-recognition costs with the committed vocabulary
// (vocab/orb_vocabulary.bin) on ORB features of rendered images (640x480,
// 1000 features, the walking_xyz room of `stillslam simulate`):
//   - vocabulary load (median of --loads loads)
//   - transform per keyframe: bag of words alone, and with the direct index
//     (depth 2, what relocalization and loop detection use)
//   - keyframe database: add per keyframe, and the relocalization query (best
//     10, common words >= 0.8 of the best) per keyframe at database sizes
//     --sizes (keyframes beyond the rendered ones are rendered keyframes with
//     20% of their features swapped for another view's and bits flipped, so
//     inverted lists grow like a real map's)
//   - relocalization per attempt (describe + candidates + Relocalizer) against
//     a map of rendered keyframes at their true poses: frames between the
//     keyframes (success), and frames of a different room (failure: the cost
//     paid on every lost frame).
// Medians; wall clock and CPU time of the calling thread (the latter is not
// inflated by other processes on the machine).
//
//   build/bench/bench_vocabulary [--vocabulary FILE] [--loads 10] [--images 40]
//       [--sizes 100,1000,5000] [--queries 200]
// Plain main, no Google Benchmark.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "stillslam/core/error.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/core/thread_cpu_stopwatch.h"
#include "stillslam/loop/place_recognizer.h"
#include "stillslam/map/map.h"
#include "stillslam/place/keyframe_database.h"
#include "stillslam/place/vocabulary.h"
#include "stillslam/sim/sensor_frame.h"
#include "stillslam/sim/simulator.h"
#include "stillslam/system/system.h"
#include "stillslam/tracking/frame_builder.h"
#include "stillslam/tracking/relocalizer.h"

namespace fs = std::filesystem;
using namespace stillslam;

namespace {

constexpr int kDirectIndexLevel = 2;

struct Timing {
  std::vector<double> wall, cpu;
};

template <typename F>
void timed(Timing& t, F&& f) {
  Stopwatch w;
  const ThreadCpuStopwatch cpu_watch;
  f();
  t.cpu.push_back(cpu_watch.elapsed_ms());
  t.wall.push_back(w.elapsed_ms());
}

double median(std::vector<double> v) {
  if (v.empty()) return -1;
  std::sort(v.begin(), v.end());
  return v[(v.size() - 1) / 2];
}

void row(const std::string& name, const Timing& t, const std::string& note = "") {
  std::printf("%-52s %6zu %10.3f %10.3f  %s\n", name.c_str(), t.wall.size(), median(t.wall), median(t.cpu),
              note.c_str());
}

struct Args {
  fs::path vocabulary = fs::path(STILLSLAM_SOURCE_DIR) / "vocab" / "orb_vocabulary.bin";
  int loads = 10;
  int images = 40;
  std::vector<std::size_t> sizes{100, 1000, 5000};
  int queries = 200;
};

Args parse(int argc, char** argv) {
  Args a;
  CLI::App app("Vocabulary benchmark (see the comment at the top of bench/bench_vocabulary.cpp)", "bench_vocabulary");
  app.add_option("--vocabulary", a.vocabulary, "ORB vocabulary file")->capture_default_str();
  app.add_option("--loads", a.loads, "vocabulary loads (at least 1)")->capture_default_str();
  app.add_option("--images", a.images, "rendered images (at least 4)")->capture_default_str();
  app.add_option("--queries", a.queries, "queries (at least 1)")->capture_default_str();
  app.add_option("--sizes", a.sizes, "database sizes (comma separated)")->delimiter(',')->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::exit(app.exit(e));  // --help prints and exits 0; bad values print CLI11's message and exit non-zero
  }
  a.loads = std::max(1, a.loads);
  a.images = std::max(4, a.images);
  a.queries = std::max(1, a.queries);
  return a;
}

// Rendered RGB-D views of one room with their true poses.
struct Views {
  std::shared_ptr<const CameraSetup> setup;
  std::vector<Frame> frames;  // posed (ground truth), ORB features, depth
};

Views render_views(int count, int step, int offset, std::uint64_t seed) {
  sim::SimulationOptions opts;
  opts.trajectory = "walking_xyz";
  opts.frames = count * step + offset + 1;
  opts.no_people = true;
  opts.seed = seed;
  opts.supersampling = 1;
  opts.data_dir = fs::path(STILLSLAM_SOURCE_DIR) / "data";
  sim::Simulator simulator(opts);
  Settings settings;
  settings.camera = simulator.camera();
  settings.bf = 40.0 / 535.4 * settings.camera.fx;
  settings.orb.n_features = 1000;
  Views v;
  v.setup = make_camera_setup(settings, SensorType::Rgbd, std::nullopt);
  const FrameBuilder builder(v.setup, SensorType::Rgbd, settings.orb, nullptr);
  const Eigen::Isometry3d T_world0 = simulator.render_frame(0).T_world_cam;
  for (int k = 0; k < count; ++k) {
    const int i = offset + k * step;
    const sim::SimFrame f = simulator.render_frame(i);
    Frame frame = builder.build(sim::to_sensor_frame(f), static_cast<std::uint64_t>(i), nullptr);
    frame.set_pose((T_world0.inverse() * f.T_world_cam).inverse());  // world = first camera
    v.frames.push_back(std::move(frame));
  }
  return v;
}

// A keyframe with one map point per keypoint with depth (no association
// between keyframes: each candidate relocalizes on its own points).
KeyFramePtr add_keyframe(Map& map, const Frame& frame) {
  KeyFramePtr kf = map.create_keyframe(frame);
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const auto p = kf->unproject(i);
    if (!p) continue;
    MapPointPtr mp = map.create_map_point(*p, kf.get());
    mp->add_observation(kf.get(), i);
    kf->set_map_point(i, mp);
    mp->compute_distinctive_descriptor();
    mp->update_normal_and_depth(frame.setup().pyramid);
  }
  return kf;
}

// Another keyframe's worth of descriptors: `base` with a fifth of its rows
// replaced by rows of `other`, and a few bits flipped in a third of them.
cv::Mat perturbed(const cv::Mat& base, const cv::Mat& other, std::mt19937& rng) {
  cv::Mat d = base.clone();
  std::uniform_int_distribution<int> row_of_other(0, other.rows - 1), bit(0, 255);
  std::uniform_real_distribution<double> u(0, 1);
  for (int r = 0; r < d.rows; ++r) {
    const double x = u(rng);
    if (x < 0.2) {
      other.row(row_of_other(rng)).copyTo(d.row(r));
    } else if (x < 0.53) {
      for (int b = 0; b < 3; ++b) {
        const int k = bit(rng);
        d.at<std::uint8_t>(r, k / 8) ^= static_cast<std::uint8_t>(1u << (k % 8));
      }
    }
  }
  return d;
}

double position_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.inverse().translation() - b.inverse().translation()).norm();
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args a = parse(argc, argv);
    std::printf("%-52s %6s %10s %10s\n", "operation", "calls", "wall ms", "cpu ms");

    Timing load;
    std::shared_ptr<const Vocabulary> vocabulary;
    for (int i = 0; i < a.loads; ++i) {
      timed(load, [&] { vocabulary = std::make_shared<const Vocabulary>(Vocabulary::load(a.vocabulary)); });
    }
    row("vocabulary load", load,
        std::to_string(vocabulary->size()) + " words, k=" + std::to_string(vocabulary->k()) + ", depth " +
            std::to_string(vocabulary->depth()) + ", " + std::to_string(fs::file_size(a.vocabulary) / 1024) + " KiB");

    // Keyframes every 6th frame (0.2 s), query frames 3 frames after each.
    const Views keyframes = render_views(a.images, 6, 0, 0);
    const Views queries = render_views(a.images, 6, 3, 0);
    const Views elsewhere = render_views(std::max(4, a.images / 4), 6, 0, 7);  // another room
    double features = 0;
    for (const Frame& f : keyframes.frames) features += static_cast<double>(f.size());
    features /= static_cast<double>(keyframes.frames.size());

    Timing bow_only, with_index;
    std::vector<BowVector> bows;
    for (const Frame& f : keyframes.frames) {
      BowVector bow;
      FeatureVector fv;
      for (int repeat = 0; repeat < 3; ++repeat) {  // interleaved: both see the same cache state
        timed(bow_only, [&] { bow = vocabulary->transform(f.descriptors()); });
        timed(with_index, [&] { vocabulary->transform(f.descriptors(), bow, fv, kDirectIndexLevel); });
      }
      bows.push_back(bow);
    }
    char note[160];
    std::snprintf(note, sizeof(note), "%.0f features per image", features);
    row("transform: bag of words", bow_only, note);
    row("transform: bag of words + direct index (depth 2)", with_index, note);

    // Database sizes: the rendered keyframes, then perturbed copies.
    const std::size_t max_size = a.sizes.empty() ? 0 : *std::max_element(a.sizes.begin(), a.sizes.end());
    std::mt19937 rng(11);
    const std::size_t n = keyframes.frames.size();
    std::uniform_int_distribution<std::size_t> pick(0, n - 1);
    std::vector<BowVector> database_bows;
    for (std::size_t k = 0; k < max_size; ++k) {
      if (k < n) {
        database_bows.push_back(bows[k]);
      } else {
        database_bows.push_back(vocabulary->transform(
            perturbed(keyframes.frames[k % n].descriptors(), keyframes.frames[pick(rng)].descriptors(), rng)));
      }
    }
    std::vector<BowVector> query_bows;
    for (const Frame& f : queries.frames) query_bows.push_back(vocabulary->transform(f.descriptors()));
    PlaceQueryOptions relocalization_query;
    relocalization_query.max_results = 10;
    relocalization_query.min_common_words_ratio = 0.8;
    for (std::size_t size : a.sizes) {
      KeyframeDatabase database;
      Timing add, query;
      for (std::size_t k = 0; k < size; ++k) {
        timed(add, [&] { database.add(static_cast<KeyframeId>(k), database_bows[k]); });
      }
      std::size_t candidates = 0;
      for (int q = 0; q < a.queries; ++q) {
        const BowVector& bow = query_bows[static_cast<std::size_t>(q) % query_bows.size()];
        std::vector<PlaceCandidate> c;
        timed(query, [&] { c = database.query(bow, relocalization_query); });
        candidates += c.size();
      }
      row("database add, " + std::to_string(size) + " keyframes", add);
      std::snprintf(note, sizeof(note), "%.1f candidates per query",
                    static_cast<double>(candidates) / static_cast<double>(a.queries));
      row("database relocalization query, " + std::to_string(size) + " keyframes", query, note);
    }

    // Relocalization against the rendered keyframes at their true poses.
    Map map;
    auto recognizer = std::make_unique<PlaceRecognizer>(vocabulary);
    for (const Frame& f : keyframes.frames) recognizer->add(*add_keyframe(map, f));
    const Relocalizer verified;
    RelocalizerOptions no_check;
    no_check.min_found_ratio = 0;
    const Relocalizer unverified(no_check);
    auto attempt = [&](const Frame& query, Timing& total, Timing& only, const Relocalizer& relocalizer) {
      // Without its pose: the relocalizer must find it.
      Frame frame(query.id(), query.timestamp(), query.setup_ptr(), query.keypoints_raw(), query.keypoints(),
                  query.descriptors(), query.u_right(), query.depth());
      RelocalizationResult r;
      timed(total, [&] {
        const BowDescription d = recognizer->describe(frame.descriptors());
        std::vector<RelocalizationCandidate> candidates;
        for (const PlaceCandidate& c : recognizer->relocalization_candidates(d.bow)) {
          candidates.push_back({map.keyframe(c.id), recognizer->description(c.id)->features});
        }
        timed(only, [&] { r = relocalizer.relocalize(frame, d.features, candidates); });
      });
      return r;
    };
    Timing ok_total, ok_only, fail_total, fail_only;
    int successes = 0, within_1cm = 0, accepted_elsewhere = 0;
    std::vector<double> tried;
    for (const Frame& q : queries.frames) {
      const RelocalizationResult r = attempt(q, ok_total, ok_only, verified);
      tried.push_back(r.candidates_tried);
      if (!r.success) continue;
      ++successes;
      if (position_error(r.T_cam_world, q.T_cam_world()) < 0.01) ++within_1cm;
    }
    int rejected_elsewhere = 0, accepted_unverified = 0;
    for (const Frame& q : elsewhere.frames) {
      const RelocalizationResult r = attempt(q, fail_total, fail_only, verified);
      accepted_elsewhere += r.success ? 1 : 0;
      rejected_elsewhere += r.rejected_by_verification > 0 ? 1 : 0;
      Timing unused;
      accepted_unverified += attempt(q, unused, unused, unverified).success ? 1 : 0;
    }
    std::snprintf(note, sizeof(note), "%d/%zu relocalized, %d within 1 cm, median %.0f candidates tried", successes,
                  queries.frames.size(), within_1cm, median(tried));
    row("relocalization attempt, mapped place (all steps)", ok_total, note);
    row("  of which Relocalizer::relocalize", ok_only);
    std::snprintf(note, sizeof(note), "%d/%zu accepted (should be 0); %d stopped by the verification, %d accepted without it",
                  accepted_elsewhere, elsewhere.frames.size(), rejected_elsewhere, accepted_unverified);
    row("relocalization attempt, unmapped room (all steps)", fail_total, note);
    row("  of which Relocalizer::relocalize", fail_only);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_vocabulary: %s\n", e.what());
    return 1;
  }
}
