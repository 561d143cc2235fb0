#pragma once
// Ground truth drawn in a map's frame: the feed hands over the camera centres
// it reads from the frame snapshots (per map, as tracked); they are
// associated with the ground truth by timestamp (eval/association.h, as the
// ATE is) and aligned with it (Umeyama, no scale).
#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <vector>

#include "stillslam/core/trajectory.h"

namespace stillslam::viewer {

class GroundTruthOverlay {
 public:
  explicit GroundTruthOverlay(const Trajectory& groundtruth);

  void add(double timestamp, const Eigen::Vector3d& centre, std::uint64_t map_id);

  // The ground-truth camera centres in map_id's frame, thinned to at most
  // max_points; empty while fewer than 3 of the map's centres have a ground-truth pose.
  std::vector<Eigen::Vector3d> aligned(std::uint64_t map_id, std::size_t max_points) const;

 private:
  struct Samples {
    std::vector<double> stamps;
    std::vector<Eigen::Vector3d> centres;
  };
  std::vector<double> gt_stamps_;
  std::vector<Eigen::Vector3d> gt_centres_;
  std::map<std::uint64_t, Samples> estimates_;  // by map id
};

}  // namespace stillslam::viewer
