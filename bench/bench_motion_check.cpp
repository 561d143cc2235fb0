// How well the motion check (tracking/instance_motion_check.h) tells still
// instances from moving ones on a generated sequence, with the
// simulator's exact instance ids (instances/, instances.txt) standing for a
// perfect segmenter and tracker: ORB features of frame k are matched to those
// of frame k - span, each match's residual against the camera motion between
// the two frames is computed (depth of frame k - span; epipolar without),
// and the matches on each instance are judged against the background's.
//
//   build/bench/bench_motion_check --sequence DIR [--span 6] [--poses FILE]
//       [--pose-noise-deg 0.1 --pose-noise-m 0.005] [--max-frames N]
//
// Camera motion from groundtruth.txt, or from --poses (a TUM trajectory of a
// run: only relative motion is used, so no alignment is needed), optionally
// perturbed (--pose-noise-*: per frame, Gaussian, seeded). Reports per
// kind of instance (walking_person, still_person, moved_box, ...): frames in
// which it had enough matches, the share of those in which the verdict was
// "agrees" / "disagrees", and the share of frames it was kept as static once
// past its evidence window; plus the share of background features whose own
// residual is above the moving threshold (false alarms per feature) and of
// each moving kind's features (hits per feature).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "stillslam/core/error.h"
#include "stillslam/features/orb_extractor.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/io/tum_dataset.h"
#include "stillslam/settings/settings.h"
#include "stillslam/tracking/instance_motion_check.h"

namespace fs = std::filesystem;
using namespace stillslam;

namespace {

struct Kind {
  std::string kind, category;
  bool moves = true;
};

std::map<int, Kind> read_instances(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw Error(file.string() + " not found: render the sequence with a `stillslam simulate` that writes instances/");
  std::map<int, Kind> out;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream row(line);
    int id = 0, moves = 0;
    Kind k;
    if (!(row >> id >> k.kind >> k.category >> moves)) {
      throw Error(file.string() + ":" + std::to_string(line_no) + ": expected `id kind class moves`");
    }
    k.moves = moves != 0;
    out[id] = k;
  }
  return out;
}

struct KindTally {
  int frames = 0, agrees = 0, disagrees = 0;
  int past_window = 0, kept_static = 0;
  long features = 0, flagged = 0;
};

Eigen::Isometry3d pose_at(const Trajectory& poses, double t, const fs::path& file) {
  const StampedPose* best = nullptr;
  for (const StampedPose& p : poses) {
    if (!best || std::abs(p.timestamp - t) < std::abs(best->timestamp - t)) best = &p;
  }
  if (!best || std::abs(best->timestamp - t) > 0.005) {
    throw Error(file.string() + ": no pose within 5 ms of frame stamp " + std::to_string(t));
  }
  return best->T_world_cam;
}

}  // namespace

int main(int argc, char** argv) {
  fs::path seq, poses_file;
  int span = 6, max_frames = 0;
  double noise_deg = 0, noise_m = 0;
  MotionEvidenceOptions evidence_options;
  CLI::App app("Motion check on a generated sequence's exact instances", "bench_motion_check");
  app.add_option("--sequence", seq, "`stillslam simulate` folder (with instances/)")->required();
  app.add_option("--span", span, "frames between the two views compared")->capture_default_str()->check(
      CLI::PositiveNumber);
  app.add_option("--poses", poses_file, "TUM trajectory to take the camera motion from (default: groundtruth.txt)");
  app.add_option("--pose-noise-deg", noise_deg, "rotation noise per frame (degrees, std)");
  app.add_option("--pose-noise-m", noise_m, "translation noise per frame (metres, std)");
  app.add_option("--evidence-frames", evidence_options.default_frames, "evidence window (agreeing frames)")->capture_default_str();
  app.add_option("--max-frames", max_frames, "only the first N frames (0: all)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    const Settings settings = load_settings(seq / "settings.yaml");
    const PinholeCamera camera(settings.camera, settings.bf);
    const OrbExtractor extractor(settings.orb);
    const std::map<int, Kind> kinds = read_instances(seq / "instances.txt");
    const std::vector<TumPair> pairs = read_tum_associations(seq / "associations.txt");
    const fs::path pose_path = poses_file.empty() ? seq / "groundtruth.txt" : poses_file;
    const Trajectory poses = read_trajectory(pose_path);
    InstanceMotionCheckOptions check_options;
    check_options.span = span;
    check_options.evidence = evidence_options;
    InstanceMotionCheck check(camera, check_options);
    std::mt19937 rng(7);
    std::normal_distribution<double> gauss(0, 1);
    std::map<std::string, KindTally> tally;
    long bg_features = 0, bg_flagged = 0;
    std::vector<double> bg_medians;
    std::map<int, int> observed_frames;  // per instance: frames with enough matches so far
    std::map<std::uint32_t, std::string> categories;
    for (const auto& [id, kind] : kinds) categories[static_cast<std::uint32_t>(id)] = kind.category;
    const int n = max_frames > 0 ? std::min<int>(max_frames, static_cast<int>(pairs.size()))
                                 : static_cast<int>(pairs.size());
    for (int k = 0; k < n; ++k) {
      const TumPair& p = pairs[static_cast<std::size_t>(k)];
      const cv::Mat gray = cv::imread((seq / p.rgb_file).string(), cv::IMREAD_GRAYSCALE);
      const cv::Mat depth16 = cv::imread((seq / p.depth_file).string(), cv::IMREAD_UNCHANGED);
      const cv::Mat ids = cv::imread((seq / "instances" / fs::path(p.rgb_file).filename()).string(),
                                     cv::IMREAD_UNCHANGED);
      if (gray.empty() || depth16.empty() || ids.type() != CV_16UC1) {
        throw Error("frame " + p.rgb_file + " of " + seq.string() + ": cannot read rgb/, depth/ or instances/");
      }
      const OrbFeatures features = extractor.extract(gray);
      MotionCheckFrame f;
      // Pose noise stands for tracking error: a random perturbation of each frame's pose.
      Eigen::Isometry3d T_world_cam = pose_at(poses, p.rgb_time, pose_path);
      if (noise_deg > 0 || noise_m > 0) {
        const Eigen::Vector3d axis(gauss(rng), gauss(rng), gauss(rng));
        T_world_cam = T_world_cam *
                      Eigen::Translation3d(noise_m * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng))) *
                      Eigen::AngleAxisd(noise_deg * M_PI / 180 * axis.norm() / std::sqrt(3.0), axis.normalized());
      }
      f.T_cam_world = T_world_cam.inverse();
      f.descriptors = features.descriptors;
      f.categories = categories;
      for (const cv::KeyPoint& kp : features.keypoints) {
        const int u = std::clamp(static_cast<int>(std::lround(kp.pt.x)), 0, gray.cols - 1);
        const int v = std::clamp(static_cast<int>(std::lround(kp.pt.y)), 0, gray.rows - 1);
        f.pixels.emplace_back(kp.pt.x, kp.pt.y);
        f.instance.push_back(ids.at<std::uint16_t>(v, u));
        f.depth.push_back(static_cast<float>(depth16.at<std::uint16_t>(v, u) / settings.depth_map_factor));
      }
      const MotionCheckResult r = check.add(std::move(f));
      if (!r.compared) continue;
      bg_medians.push_back(r.background_median_px);
      const double move_px = std::max(evidence_options.moving_factor * r.background_median_px,
                                      evidence_options.moving_floor_px);
      bg_features += static_cast<long>(r.background_residuals.size());
      for (double x : r.background_residuals) bg_flagged += x > move_px;
      for (const InstanceMotionState& s : r.instances) {
        const auto kind = kinds.find(s.id);
        KindTally& t = tally[kind != kinds.end() ? kind->second.kind : "unknown"];
        const std::vector<double>& residuals = r.residuals.at(static_cast<std::uint32_t>(s.id));
        t.features += static_cast<long>(residuals.size());
        for (double x : residuals) t.flagged += x > move_px;
        if (s.matches < evidence_options.min_matches) continue;
        ++t.frames;
        t.agrees += s.verdict == MotionVerdict::Agrees;
        t.disagrees += s.verdict == MotionVerdict::Disagrees;
        const int seen = ++observed_frames[s.id];
        if (seen > evidence_options.frames_for(kind != kinds.end() ? kind->second.category : "")) {
          ++t.past_window;
          t.kept_static += s.is_static;
        }
      }
    }
    std::vector<double> m = bg_medians;
    std::printf("%s: %d frames, span %d, poses %s%s, background median residual %.2f px\n", seq.string().c_str(), n,
                span, pose_path.filename().string().c_str(),
                noise_deg > 0 || noise_m > 0 ? cv::format(" + noise %.2f deg %.3f m", noise_deg, noise_m).c_str() : "",
                median_of(m));
    std::printf("  background features above the moving threshold: %.2f %% of %ld\n",
                bg_features > 0 ? 100.0 * bg_flagged / bg_features : 0.0, bg_features);
    std::printf("  %-16s %7s %8s %10s %12s %14s\n", "kind", "frames", "agrees", "disagrees", "kept static",
                "features flagged");
    for (const auto& [kind, t] : tally) {
      std::printf("  %-16s %7d %7.1f%% %9.1f%% %11.1f%% %13.1f%%\n", kind.c_str(), t.frames,
                  t.frames ? 100.0 * t.agrees / t.frames : 0.0, t.frames ? 100.0 * t.disagrees / t.frames : 0.0,
                  t.past_window ? 100.0 * t.kept_static / t.past_window : 0.0,
                  t.features ? 100.0 * t.flagged / t.features : 0.0);
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
