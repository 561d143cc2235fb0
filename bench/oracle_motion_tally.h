#pragma once
// bench_slam --oracle-instances: how the motion stage (Motion.enabled) treated
// the simulator's instances, per kind (instances.txt), frame by frame from the
// run's stats: a still person counts as kept in a frame where an instance was
// kept static (walking people never are on these renders: bench/README.md,
// issue #19), past its evidence window (span + personFrames frames after it is
// first seen); a moved object counts as removed in a frame where an instance
// was masked for its motion (only moved objects are of a non-masked class).
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "stillslam/core/error.h"
#include "stillslam/io/tum_dataset.h"
#include "stillslam/system/frame_stats.h"

namespace stillslam::oracle {

struct MotionTally {
  int still_frames = 0, still_kept = 0;  // frames with the still person past the window / kept static
  int moved_frames = 0, moved_removed = 0;  // frames in which a moved object moves / masked for it
  int frames_without_pose = 0;
};

inline MotionTally tally_motion(const std::filesystem::path& sequence, const std::vector<FrameStats>& frames,
                                int window_frames, int min_pixels = 400) {
  std::map<int, std::string> kinds;
  std::ifstream in(sequence / "instances.txt");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream row(line);
    int id = 0;
    std::string kind;
    if (row >> id >> kind) kinds[id] = kind;
  }
  const std::vector<TumPair> pairs = read_tum_associations(sequence / "associations.txt");
  MotionTally t;
  int still_seen = 0;
  for (const FrameStats& f : frames) {
    if (!f.has_pose) ++t.frames_without_pose;
    if (f.index >= pairs.size()) continue;
    const cv::Mat ids = cv::imread((sequence / "instances" / std::filesystem::path(pairs[f.index].rgb_file).filename()).string(),
                                   cv::IMREAD_UNCHANGED);
    if (ids.type() != CV_16UC1) throw Error(sequence.string() + ": cannot read instances/ of frame " + std::to_string(f.index));
    bool still = false, moved = false;
    for (const auto& [id, kind] : kinds) {
      const int n = cv::countNonZero(ids == id);
      if (n < min_pixels) continue;
      still = still || kind == "still_person";
      moved = moved || kind == "moved_box" || kind == "moved_chair";
    }
    if (still && ++still_seen > window_frames) {
      ++t.still_frames;
      t.still_kept += f.build.motion.static_instances > 0;
    }
    if (moved) {
      ++t.moved_frames;
      t.moved_removed += f.build.motion.moving_instances > 0;
    }
  }
  return t;
}

}  // namespace stillslam::oracle
