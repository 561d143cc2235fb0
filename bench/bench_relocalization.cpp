// Forced tracking loss (issue #6 bar): the System runs over a rendered
// sequence in which the frames [a, a + gap) are replaced by black frames (the
// camera keeps moving), optionally with `skip` more seconds of camera motion
// left out after them (a jump the wide-window search of the last local map
// cannot bridge). Per gap position and seed it prints:
//   frames from the first frame after the gap to the first tracked frame (bar: <= 10)
//   how tracking came back (relocalized / wide-window search of the last map)
//   translation error of the first pose after the loss: the poses as the
//     tracker gave them (before later loop/merge corrections), SE3-aligned to
//     the ground truth all together (a map's small drift does not count, a
//     pose in the wrong place does; a pose in a new map that is not merged
//     shows as its offset)
//   err_prior: the largest such error before the loss (the map's own drift)
//   ATE rmse of the final trajectory (SE3-aligned)
//   false relocalizations: relocalized frames whose pose is > 5 cm off
//   maps started (atlas: after --new-map-after lost frames, default the
//     system's one second) and merges
// and the time of the tracker on lost frames with an image (one relocalization
// attempt each). Deterministic mode (synchronous local mapping and loop closing).
//
//   build/bench/bench_relocalization [--trajectory walking_xyz] [--frames 330]
//       [--seeds 0,1] [--gaps 60,120,180,240] [--gap 1.0] [--skip 0,2]
//       [--width 320 --height 240] [--noise 0] [--vocabulary FILE]
//       [--new-map-after N (-1: system default, 0: never)] [--no-verification] [--verbose]
//   build/bench/bench_relocalization --sequence DIR [--gaps ...] [--gap S|0] ...
//       [--keep-images]
//       DIR: a TUM-layout folder written by `stillslam simulate` (settings.yaml,
//       groundtruth.txt), e.g. with an occluder (--occlude T:D of the sim);
//       --keep-images leaves the frames of [a, a + gap) as they are (the
//       occluder forces the loss): --gaps a --gap D then only say where the
//       view is blocked. --segmentation runs with the settings' segmentation.
// Plain main, no Google Benchmark.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "stillslam/core/error.h"
#include "stillslam/eval/evaluate.h"
#include "stillslam/io/dataset.h"
#include "stillslam/settings/settings.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/sim/sensor_frame.h"
#include "stillslam/sim/simulator.h"
#include "stillslam/system/system.h"

namespace fs = std::filesystem;
using namespace stillslam;

namespace {

struct Args {
  std::string trajectory = "walking_xyz";
  int frames = 330;
  std::vector<int> seeds{0, 1};
  std::vector<int> gaps{60, 120, 180, 240};
  double gap_s = 1.0;
  std::vector<double> skips{0.0, 2.0};
  int width = 320, height = 240;
  int noise = 0;
  fs::path vocabulary = fs::path(STILLSLAM_SOURCE_DIR) / "vocab" / "orb_vocabulary.bin";
  fs::path sequence;        // TUM folder instead of rendering
  bool segmentation = false;  // --sequence only: run with the settings' segmentation
  int new_map_after = -1;     // SystemOptions::new_map_after_lost_frames (-1: the system's default)
  bool no_verification = false;  // relocalization without its verification (for comparison)
  bool keep_images = false;      // the gap's frames are not blanked (an occluder in the sequence)
  bool verbose = false;
};

Args parse(int argc, char** argv) {
  Args a;
  CLI::App app("Relocalization benchmark (see the comment at the top of bench/bench_relocalization.cpp)",
               "bench_relocalization");
  app.add_option("--trajectory", a.trajectory, "simulated trajectory")->capture_default_str();
  app.add_option("--frames", a.frames, "rendered frames")->capture_default_str();
  app.add_option("--seeds", a.seeds, "render seeds (comma separated)")->delimiter(',')->capture_default_str();
  app.add_option("--gaps", a.gaps, "frames where a gap starts (comma separated)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--gap", a.gap_s, "gap length in seconds")->capture_default_str();
  app.add_option("--skip", a.skips, "seconds skipped in the gap (comma separated)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--width", a.width, "rendered width")->capture_default_str();
  app.add_option("--height", a.height, "rendered height")->capture_default_str();
  app.add_option("--noise", a.noise, "sensor noise level")->capture_default_str();
  app.add_option("--vocabulary", a.vocabulary, "ORB vocabulary file")->capture_default_str();
  app.add_option("--sequence", a.sequence, "TUM folder instead of rendering");
  app.add_flag("--segmentation", a.segmentation, "--sequence only: run with the settings' segmentation");
  app.add_option("--new-map-after", a.new_map_after, "SystemOptions::new_map_after_lost_frames (-1: default)")
      ->capture_default_str();
  app.add_flag("--no-verification", a.no_verification, "relocalization without its verification");
  app.add_flag("--keep-images", a.keep_images, "the gap's frames are not blanked");
  app.add_flag("--verbose", a.verbose, "print every frame");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::exit(app.exit(e));  // --help prints and exits 0; bad values print CLI11's message and exit non-zero
  }
  return a;
}

struct Sequence {
  std::string name;
  Settings settings;
  std::vector<SensorFrame> frames;
  Trajectory groundtruth;  // one pose per frame, same order
  double fps = 30;
};

Sequence render(const Args& a, int seed) {
  sim::SimulationOptions opts;
  opts.trajectory = a.trajectory;
  opts.frames = a.frames;
  opts.width = a.width;
  opts.height = a.height;
  opts.no_people = true;
  opts.seed = static_cast<std::uint64_t>(seed);
  opts.noise = a.noise;
  opts.supersampling = 1;
  opts.data_dir = fs::path(STILLSLAM_SOURCE_DIR) / "data";
  sim::Simulator simulator(opts);
  Sequence seq;
  seq.name = a.trajectory + " seed " + std::to_string(seed);
  seq.fps = opts.fps;
  seq.settings.camera = simulator.camera();
  seq.settings.fps = opts.fps;
  seq.settings.th_depth = 40;
  seq.settings.segmentation.enabled = false;
  seq.settings.orb.n_features = 1000;
  seq.settings.bf = 40.0 / 535.4 * seq.settings.camera.fx;
  for (int i = 0; i < simulator.frame_count(); ++i) {
    const sim::SimFrame f = simulator.render_frame(i);
    seq.frames.push_back(sim::to_sensor_frame(f));
    seq.groundtruth.push_back({f.timestamp, f.T_world_cam});
  }
  return seq;
}

Sequence load(const Args& a) {
  Sequence seq;
  seq.name = a.sequence.filename().string();
  seq.settings = load_settings(a.sequence / "settings.yaml");
  if (!a.segmentation) seq.settings.segmentation.enabled = false;
  if (seq.settings.fps > 0) seq.fps = seq.settings.fps;
  const Trajectory gt = read_trajectory(a.sequence / "groundtruth.txt");
  const auto dataset = open_dataset(a.sequence, seq.settings);
  for (std::size_t i = 0; i < dataset->size(); ++i) {
    const double t = dataset->timestamp(i);
    auto g = std::min_element(gt.begin(), gt.end(), [t](const StampedPose& x, const StampedPose& y) {
      return std::abs(x.timestamp - t) < std::abs(y.timestamp - t);
    });
    if (g == gt.end() || std::abs(g->timestamp - t) > 1e-3) {
      throw Error((a.sequence / "groundtruth.txt").string() + ": no pose at frame time " + std::to_string(t));
    }
    seq.frames.push_back(dataset->load(i));
    seq.groundtruth.push_back({t, g->T_world_cam});
  }
  return seq;
}

// The run's input: black frames over [begin, end), then `skip` frames left out.
struct Variant {
  std::vector<const SensorFrame*> frames;
  std::vector<StampedPose> groundtruth;
  std::vector<bool> blank;
  std::size_t gap_end = 0;  // index (in the variant) of the first frame after the gap
};

Variant make_variant(const Sequence& seq, std::size_t begin, std::size_t end, std::size_t skip, bool keep_images) {
  Variant v;
  for (std::size_t i = 0; i < seq.frames.size(); ++i) {
    if (i >= end && i < end + skip) continue;
    if (i >= end && v.gap_end == 0) v.gap_end = v.frames.size();
    v.frames.push_back(&seq.frames[i]);
    v.groundtruth.push_back(seq.groundtruth[i]);
    v.blank.push_back(!keep_images && i >= begin && i < end);
  }
  if (v.gap_end == 0) v.gap_end = v.frames.size();
  return v;
}

// New buffers: assigning cv::Mat::zeros to a copied header would write the
// zeros into the shared original image.
SensorFrame black_copy(const SensorFrame& f) {
  auto black = [](const cv::Mat& m) { return m.empty() ? cv::Mat() : cv::Mat(m.size(), m.type(), cv::Scalar::all(0)); };
  SensorFrame b = f;
  b.gray = black(f.gray);
  b.color = black(f.color);
  b.depth = black(f.depth);
  b.right = black(f.right);
  return b;
}

struct Outcome {
  int first_lost = -1;       // variant index of the first lost frame at/after the gap start
  int frames_to_track = -1;  // from the first frame after the gap to the first tracked frame
  std::string how;           // "relocalized" or the tracker's reason
  double error_after = -1;   // error of that first pose (m), see below
  double max_error_after = 0;  // over the rest of the run
  double max_error_before = 0;  // before the loss (the map's own drift, same alignment)
  double ate = -1;           // final trajectory (after loop/merge corrections), SE3-aligned
  int relocalizations = 0, false_relocalizations = 0;
  int new_maps = 0, merges = 0;
  int tracked = 0, frames = 0;
  std::vector<double> attempt_ms;  // tracker time on lost frames with an image
};

// Errors of the poses as the tracker gave them (before later corrections),
// after one SE3 alignment of all of them to the ground truth: a map that
// drifted a little does not count against the relocalization, a pose in the
// wrong place does. Keyed by variant frame index.
std::map<std::size_t, double> online_errors(const Variant& v, const std::map<std::size_t, Eigen::Isometry3d>& poses) {
  Trajectory gt(v.groundtruth.begin(), v.groundtruth.end()), est;
  for (const auto& [i, T] : poses) est.push_back({v.groundtruth[i].timestamp, T});
  std::map<std::size_t, double> out;
  if (est.size() < 3) return out;
  const EvaluationResult ev = evaluate(gt, est, EvaluationOptions{});
  for (const auto& [i, T] : poses) {
    const Eigen::Vector3d p = ev.alignment.apply(T).translation();
    out[i] = (p - v.groundtruth[i].T_world_cam.translation()).norm();
  }
  return out;
}

Outcome run(const Sequence& seq, const Variant& v, std::size_t gap_begin, const Args& a) {
  SystemOptions options;
  options.deterministic = true;
  options.use_segmentation = a.segmentation;
  options.vocabulary_path = a.vocabulary;
  options.new_map_after_lost_frames = a.new_map_after;
  Settings settings = seq.settings;
  if (a.no_verification) {
    settings.relocalization.min_found_ratio = 0;
    settings.relocalization.min_supported_cells = 0;
  }
  System system(settings, SensorType::Rgbd, std::nullopt, options);
  Outcome out;
  out.frames = static_cast<int>(v.frames.size());
  std::vector<FrameStats> stats;
  std::map<std::size_t, Eigen::Isometry3d> poses;
  for (std::size_t i = 0; i < v.frames.size(); ++i) {
    SensorFrame input = v.blank[i] ? black_copy(*v.frames[i]) : *v.frames[i];
    input.index = i;
    FrameStats latest = system.process(input);
    mark_start_frames_posed(stats, latest);  // the frames the map's start waited on
    for (const FrameStats::EarlierPose& p : latest.start_frames_posed) poses[p.index] = p.T_world_cam;
    stats.push_back(std::move(latest));
    const FrameStats& s = stats.back();
    if (s.has_pose) poses[i] = *system.last_T_world_cam();
    out.new_maps += s.new_map ? 1 : 0;
    out.merges += s.merged ? 1 : 0;
  }
  system.shutdown();
  const std::map<std::size_t, double> errors = online_errors(v, poses);
  for (std::size_t i = 0; i < stats.size(); ++i) {
    const FrameStats& s = stats[i];
    if (s.has_pose) ++out.tracked;
    const bool lost = s.state == TrackingState::Lost;
    if (lost && !v.blank[i] && s.build.keypoints_after > 0) out.attempt_ms.push_back(s.tracking_ms);
    if (lost && i >= gap_begin && out.first_lost < 0) out.first_lost = static_cast<int>(i);
    const double err = errors.count(i) ? errors.at(i) : -1;
    if (s.reason == "relocalized") {
      ++out.relocalizations;
      if (err > 0.05) ++out.false_relocalizations;
    }
    const std::size_t back_from = std::max<std::size_t>(v.gap_end, static_cast<std::size_t>(std::max(out.first_lost, 0)));
    const bool after_loss = out.first_lost >= 0 && i >= back_from;
    if (s.has_pose && out.first_lost < 0) out.max_error_before = std::max(out.max_error_before, err);
    if (s.has_pose && after_loss) {
      if (out.frames_to_track < 0) {
        out.frames_to_track = static_cast<int>(i - back_from);
        out.how = s.reason + " (map " + std::to_string(s.map_id) + ")";
        out.error_after = err;
      }
      out.max_error_after = std::max(out.max_error_after, err);
    }
    if (a.verbose && (lost || s.reason == "relocalized" || s.new_map || s.merged) && !v.blank[i]) {
      std::printf("    frame %zu: %s (%s) map %lu%s%s err %.3f, %d keypoints, %d matches, %d inliers, %.1f ms\n", i,
                  lost ? "lost" : "tracked", s.reason.c_str(), static_cast<unsigned long>(s.map_id),
                  s.new_map ? " NEW MAP" : "", s.merged ? " MERGED" : "", err, s.build.keypoints_after, s.matches,
                  s.inliers, s.tracking_ms);
    }
  }
  try {
    Trajectory gt(v.groundtruth.begin(), v.groundtruth.end());
    out.ate = evaluate(gt, system.trajectory(), EvaluationOptions{}).ape_stats.rmse;
  } catch (const Error&) {
    out.ate = -1;
  }
  return out;
}

double median(std::vector<double> v) {
  if (v.empty()) return -1;
  std::sort(v.begin(), v.end());
  return v[(v.size() - 1) / 2];
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args a = parse(argc, argv);
    if (!fs::is_regular_file(a.vocabulary)) throw Error("vocabulary " + a.vocabulary.string() + " not found");
    std::vector<Sequence> sequences;
    if (!a.sequence.empty()) {
      sequences.push_back(load(a));
    } else {
      for (int seed : a.seeds) sequences.push_back(render(a, seed));
    }
    std::printf("%-20s %4s %4s %5s | %6s %-24s %9s %9s %9s %8s %6s %5s %4s %5s\n", "sequence", "gap", "skip",
                "lost@", "frames", "how", "err_first", "err_max", "err_prior", "ATE", "relocs", "false", "maps",
                "merge");
    std::vector<double> all_attempts, frames_to_track, first_errors;
    int runs = 0, within_bar = 0, false_total = 0, reloc_total = 0, never = 0;
    for (const Sequence& seq : sequences) {
      const auto gap = static_cast<std::size_t>(std::lround(a.gap_s * seq.fps));
      for (double skip_s : (a.sequence.empty() ? a.skips : std::vector<double>{0.0})) {
        const auto skip = static_cast<std::size_t>(std::lround(skip_s * seq.fps));
        for (int g : a.gaps) {
          const auto begin = static_cast<std::size_t>(g);
          if (begin + gap + skip + 10 > seq.frames.size()) continue;
          const Variant v = make_variant(seq, begin, begin + gap, skip, a.keep_images);
          const Outcome o = run(seq, v, begin, a);
          ++runs;
          all_attempts.insert(all_attempts.end(), o.attempt_ms.begin(), o.attempt_ms.end());
          false_total += o.false_relocalizations;
          reloc_total += o.relocalizations;
          if (o.frames_to_track >= 0) {
            frames_to_track.push_back(o.frames_to_track);
            first_errors.push_back(o.error_after);
            if (o.frames_to_track <= 10) ++within_bar;
          } else {
            ++never;
          }
          std::printf("%-20s %4zu %4zu %5d | %6d %-24s %9.4f %9.4f %9.4f %8.4f %6d %5d %4d %5d\n", seq.name.c_str(),
                      begin, skip, o.first_lost, o.frames_to_track, o.how.substr(0, 24).c_str(), o.error_after,
                      o.max_error_after, o.max_error_before, o.ate, o.relocalizations, o.false_relocalizations,
                      o.new_maps, o.merges);
          std::fflush(stdout);
        }
      }
    }
    std::printf("\nruns %d: tracking back within 10 frames of the gap in %d, never in %d; "
                "frames to track median %.0f max %.0f\n",
                runs, within_bar, never, median(frames_to_track),
                frames_to_track.empty() ? -1.0 : *std::max_element(frames_to_track.begin(), frames_to_track.end()));
    std::printf("first pose after the loss: median error %.4f m, max %.4f m\n", median(first_errors),
                first_errors.empty() ? -1.0 : *std::max_element(first_errors.begin(), first_errors.end()));
    std::printf("relocalizations %d, false (> 5 cm) %d\n", reloc_total, false_total);
    std::printf("tracker time on lost frames with an image (one relocalization attempt): median %.2f ms over %zu\n",
                median(all_attempts), all_attempts.size());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_relocalization: %s\n", e.what());
    return 1;
  }
}
