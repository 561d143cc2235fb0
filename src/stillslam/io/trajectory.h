#pragma once
// Stamped camera trajectories and their three common text formats.
//
//   TUM    `t x y z qx qy qz qw` per line (blanks or commas), '#' comments.
//          Timestamps above 1e12 are taken as nanoseconds and converted to
//          seconds. A header comment that names the columns with qw before qx
//          (e.g. `# t x y z qw qx qy qz`) switches the reader to w-first
//          quaternions. 8 columns, or 9 (pyslam's ground truth, the last ignored).
//   KITTI  12 numbers per line, the row-major 3x4 [R|t] of T_world_cam. No
//          stamps: the line index is the time, or a separate times file.
//   EuRoC  csv `timestamp [ns], p_x, p_y, p_z, q_w, q_x, q_y, q_z, ...`
//          (extra columns ignored, the same count on every line), e.g.
//          state_groundtruth_estimate0/data.csv and ORB-SLAM3's EuRoC
//          left-camera ground truth files (V101_GT_leftcam_from_ORB_SLAM3_eval.txt
//          is one of these: ns stamps written as "1403715274312143104.0000000000",
//          header q_RS_w first). A header naming qx before qw switches to
//          x-first; a stamp with a real fraction below 1e12 is taken as seconds.
//
// Every malformed line raises stillslam::Error naming the file and line number:
// a wrong column count, a non-finite number, a position beyond 1e8 m, a stamp
// beyond 1e10 s, a quaternion whose length is not 1 (within 1e-2), a KITTI 3x3
// part that is not a rotation. A stamp repeated with a different pose keeps
// the later line with a warning naming both lines, or is an Error (see
// DuplicateStamps); repeated with the same pose, a warning, one kept.
// A leading UTF-8 BOM is skipped; a folder or unreadable path is an Error.
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

// Decides the format from the first data line and the header before it:
// 12 blank-separated numbers -> KITTI, 8 or 9 -> TUM; a csv line (8 or more
// fields) -> EuRoC when the header names q_w before q_x, TUM when after.
// Error when the file is missing, empty, has another column count, or is a csv
// without a header naming the quaternion order (ambiguous: pass the format).
TrajectoryFormat detect_trajectory_format(const std::filesystem::path& path);

// What to do with a stamp that repeats with a different pose. KeepLast (the
// default) keeps the later line as TUM's associate.py does, with a warning
// naming the lines: the TUM fr2/desk ground truth has one such pair and must
// evaluate as the TUM tools do. Error refuses the file.
enum class DuplicateStamps { Error, KeepLast };

// Reads any of the three formats (detected when `format` is empty). KITTI
// poses get their line index as timestamp.
Trajectory read_trajectory(const std::filesystem::path& path,
                           std::optional<TrajectoryFormat> format = {},
                           DuplicateStamps duplicates = DuplicateStamps::KeepLast);

// KITTI poses with one timestamp per line from `times_path` (same line count).
Trajectory read_kitti_trajectory(const std::filesystem::path& path,
                                 const std::filesystem::path& times_path,
                                 DuplicateStamps duplicates = DuplicateStamps::KeepLast);

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
