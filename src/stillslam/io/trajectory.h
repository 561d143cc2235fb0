#pragma once
// Stamped camera trajectories and their three common text formats.
//
//   TUM    `t x y z qx qy qz qw` per line, '#' comments. Timestamps above 1e12
//          are taken as nanoseconds and converted to seconds. A header comment
//          that names the columns with qw before qx (e.g. `# t x y z qw qx qy qz`)
//          switches the reader to w-first quaternions. Extra trailing columns
//          are ignored (pyslam's 9-column ground truth).
//   KITTI  12 numbers per line, the row-major 3x4 [R|t] of T_world_cam. No
//          stamps: the line index is the time, or a separate times file.
//   EuRoC  csv `timestamp [ns], p_x, p_y, p_z, q_w, q_x, q_y, q_z, ...`
//          (extra columns ignored), e.g. state_groundtruth_estimate0/data.csv
//          and ORB-SLAM3's EuRoC left-camera ground truth files
//          (V101_GT_leftcam_from_ORB_SLAM3_eval.txt is one of these: ns stamps
//          written as "1403715274312143104.0000000000", header q_RS_w first).
//          A header naming qx before qw switches to x-first; a stamp with a real
//          fraction below 1e12 is taken as seconds.
//
// Every malformed line raises stillslam::Error naming the file and line number.
#include <Eigen/Geometry>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stillslam/core/trajectory.h"

namespace stillslam {

enum class TrajectoryFormat { Tum, Kitti, Euroc };

// "tum", "kitti", "euroc" (case-insensitive) -> format; Error otherwise.
TrajectoryFormat parse_trajectory_format(const std::string& name);
std::string to_string(TrajectoryFormat format);

// Decides the format from the first data line: commas -> EuRoC, 12 numbers ->
// KITTI, 8 or more numbers -> TUM. Error when the file is missing, empty or
// matches none of them.
TrajectoryFormat detect_trajectory_format(const std::filesystem::path& path);

// Reads any of the three formats (detected when `format` is empty). KITTI
// poses get their line index as timestamp.
Trajectory read_trajectory(const std::filesystem::path& path,
                           std::optional<TrajectoryFormat> format = {});

// KITTI poses with one timestamp per line from `times_path` (same line count).
Trajectory read_kitti_trajectory(const std::filesystem::path& path,
                                 const std::filesystem::path& times_path);

// Writes the whole trajectory (full double precision; EuRoC stamps in integer ns).
void write_trajectory(const std::filesystem::path& path, const Trajectory& trajectory,
                      TrajectoryFormat format = TrajectoryFormat::Tum);

// Formats one pose as a line (no newline) in the given format.
std::string format_trajectory_line(const StampedPose& pose, TrajectoryFormat format);

// Appends one pose per call, each line with a single write(), so a process
// killed at any moment leaves only whole lines (the file always reads back
// with read_trajectory once it has a pose). The file is created (truncated)
// on construction; EuRoC files get their header. When a write fails (disk
// full) the partial line is cut off, one warning names the file and the cause,
// and later poses are dropped: the file stays a valid prefix of the run.
class TrajectoryWriter {
 public:
  TrajectoryWriter(const std::filesystem::path& path, TrajectoryFormat format = TrajectoryFormat::Tum);
  ~TrajectoryWriter();
  TrajectoryWriter(const TrajectoryWriter&) = delete;
  TrajectoryWriter& operator=(const TrajectoryWriter&) = delete;
  void write(const StampedPose& pose);
  const std::filesystem::path& path() const { return path_; }
  std::size_t count() const { return count_; }  // poses written
  bool failed() const { return failed_; }        // a write failed; nothing is written after it

 private:
  bool append(const std::string& line);

  std::filesystem::path path_;
  TrajectoryFormat format_;
  int fd_ = -1;
  std::size_t size_ = 0;  // bytes of whole lines in the file
  std::size_t count_ = 0;
  bool failed_ = false;
};

}  // namespace stillslam
