#include "stillslam/eval/pose_pairs.h"

#include <cmath>

#include "stillslam/core/error.h"

namespace stillslam {
namespace {

std::vector<PosePair> consecutive(const std::vector<std::size_t>& ids) {
  std::vector<PosePair> pairs;
  for (std::size_t k = 0; k + 1 < ids.size(); ++k) pairs.emplace_back(ids[k], ids[k + 1]);
  return pairs;
}

std::vector<PosePair> by_frames(std::size_t n, std::size_t delta, bool all_pairs) {
  std::vector<PosePair> pairs;
  if (all_pairs) {
    for (std::size_t i = 0; i + delta < n; ++i) pairs.emplace_back(i, i + delta);
    return pairs;
  }
  std::vector<std::size_t> ids;
  for (std::size_t i = 0; i < n; i += delta) ids.push_back(i);
  return consecutive(ids);
}

// For each start i, the j > i whose accumulated value (path or time) from i is
// closest to delta, kept when within the tolerance.
std::vector<PosePair> all_pairs_by_accumulated(const std::vector<double>& accumulated, double delta, double tolerance) {
  std::vector<PosePair> pairs;
  const std::size_t n = accumulated.size();
  std::size_t j = 0;
  for (std::size_t i = 0; i < n; ++i) {
    j = std::max(j, i + 1);
    while (j + 1 < n && accumulated[j] - accumulated[i] < delta) ++j;
    if (j >= n) break;
    std::size_t best = j;
    if (j > i + 1 && std::abs(accumulated[j - 1] - accumulated[i] - delta) <= std::abs(accumulated[j] - accumulated[i] - delta)) {
      best = j - 1;
    }
    if (std::abs(accumulated[best] - accumulated[i] - delta) <= tolerance) pairs.emplace_back(i, best);
  }
  return pairs;
}

std::vector<double> path_lengths(const Trajectory& poses) {
  std::vector<double> path(poses.size(), 0.0);
  for (std::size_t i = 1; i < poses.size(); ++i) {
    path[i] = path[i - 1] + (poses[i].T_world_cam.translation() - poses[i - 1].T_world_cam.translation()).norm();
  }
  return path;
}

}  // namespace

DeltaUnit parse_delta_unit(const std::string& name) {
  if (name == "frames" || name == "f") return DeltaUnit::Frames;
  if (name == "s" || name == "seconds") return DeltaUnit::Seconds;
  if (name == "m" || name == "meters" || name == "metres") return DeltaUnit::Meters;
  throw Error("unknown RPE delta unit '" + name + "'; use frames, s or m");
}

std::string to_string(DeltaUnit unit) {
  switch (unit) {
    case DeltaUnit::Frames: return "frames";
    case DeltaUnit::Seconds: return "s";
    case DeltaUnit::Meters: return "m";
  }
  return "frames";
}

std::vector<PosePair> select_pose_pairs(const Trajectory& poses, const PosePairOptions& options) {
  if (!(options.delta > 0) || !std::isfinite(options.delta)) {
    throw Error("the RPE delta must be a positive finite number (--rpe-delta)");
  }
  const std::size_t n = poses.size();
  if (n < 2) return {};
  switch (options.unit) {
    case DeltaUnit::Frames: {
      const double rounded = std::round(options.delta);
      if (rounded < 1 || std::abs(rounded - options.delta) > 1e-9) {
        throw Error("an RPE delta in frames must be a whole number >= 1 (--rpe-delta)");
      }
      return by_frames(n, static_cast<std::size_t>(rounded), options.all_pairs);
    }
    case DeltaUnit::Meters: {
      if (options.all_pairs) {
        return all_pairs_by_accumulated(path_lengths(poses), options.delta, options.delta * options.relative_tolerance);
      }
      // evo's consecutive mode: a new id each time the path since the last id reaches delta.
      std::vector<std::size_t> ids;
      double current = 0;
      for (std::size_t i = 0; i < n; ++i) {
        if (i > 0) current += (poses[i].T_world_cam.translation() - poses[i - 1].T_world_cam.translation()).norm();
        if (current >= options.delta) {
          ids.push_back(i);
          current = 0;
        }
      }
      return consecutive(ids);
    }
    case DeltaUnit::Seconds: {
      if (options.all_pairs) {
        std::vector<double> times(n);
        for (std::size_t i = 0; i < n; ++i) times[i] = poses[i].timestamp;
        return all_pairs_by_accumulated(times, options.delta, options.delta * options.relative_tolerance);
      }
      // Time analogue of evo's index steps: start at the first pose, next id once delta has elapsed.
      std::vector<std::size_t> ids{0};
      for (std::size_t i = 1; i < n; ++i) {
        if (poses[i].timestamp - poses[ids.back()].timestamp >= options.delta) ids.push_back(i);
      }
      return consecutive(ids);
    }
  }
  return {};
}

}  // namespace stillslam
