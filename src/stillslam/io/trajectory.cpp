#include "stillslam/io/trajectory.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <sstream>

#include <fcntl.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include "stillslam/core/atomic_file.h"
#include "stillslam/core/error.h"
#include "stillslam/core/text.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

// Above this a stamp can only be nanoseconds (1e12 s is 31,000 years).
constexpr double kNanosecondStampThreshold = 1e12;

struct Line {
  std::size_t number = 0;  // 1-based, for messages
  std::string text;
};

std::optional<double> parse_finite_number(const std::string& token) {
  double value = 0;
  const char* begin = token.data();
  const char* end = begin + token.size();
  if (begin != end && *begin == '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

// Nanosecond stamps ("1403715274312143104" or "1403715274312143104.000") are
// split into whole seconds and the remainder so no digits are lost in a double.
std::optional<double> parse_nanoseconds_as_seconds(const std::string& token) {
  const auto dot = token.find('.');
  const std::string integral = token.substr(0, dot);
  bool fraction_is_zero = true;
  if (dot != std::string::npos) {
    for (std::size_t i = dot + 1; i < token.size(); ++i) {
      if (token[i] != '0') fraction_is_zero = false;
    }
  }
  std::int64_t ns = 0;
  const auto [ptr, ec] = std::from_chars(integral.data(), integral.data() + integral.size(), ns);
  if (ec == std::errc() && ptr == integral.data() + integral.size() && fraction_is_zero) {
    return static_cast<double>(ns / 1'000'000'000) + static_cast<double>(ns % 1'000'000'000) * 1e-9;
  }
  const auto value = parse_finite_number(token);
  if (!value) return std::nullopt;
  return *value * 1e-9;
}

[[noreturn]] void fail(const fs::path& path, std::size_t line, const std::string& what) {
  throw Error("trajectory file " + path.string() + ", line " + std::to_string(line) + ": " + what);
}

std::vector<double> parse_numbers(const fs::path& path, const Line& line, const std::vector<std::string>& tokens,
                                  std::size_t count, const std::string& layout) {
  if (tokens.size() < count) {
    fail(path, line.number,
         "expected " + std::to_string(count) + " numbers (" + layout + "), found " + std::to_string(tokens.size()) +
             "; fix the line or pass the right format explicitly");
  }
  std::vector<double> values(count);
  for (std::size_t i = 0; i < count; ++i) {
    const auto value = parse_finite_number(tokens[i]);
    if (!value) fail(path, line.number, "'" + tokens[i] + "' is not a finite number (" + layout + ")");
    values[i] = *value;
  }
  return values;
}

std::vector<Line> read_lines(const fs::path& path) {
  if (!fs::exists(path)) {
    throw Error("trajectory file " + path.string() + " does not exist; check the path");
  }
  std::ifstream in(path);
  if (!in) throw Error("trajectory file " + path.string() + " cannot be opened; check its permissions");
  std::vector<Line> lines;
  std::string text;
  std::size_t number = 0;
  while (std::getline(in, text)) {
    ++number;
    lines.push_back({number, std::move(text)});
  }
  return lines;
}

bool is_comment_or_blank(const std::string& text) {
  const std::string t = trim(text);
  return t.empty() || t.front() == '#' || t.front() == '%';
}

bool starts_with_number(const std::string& text, bool commas) {
  const auto tokens = split_tokens(trim(text), commas);
  return !tokens.empty() && parse_finite_number(tokens.front()).has_value();
}

double parse_stamp(const fs::path& path, const Line& line, const std::string& token) {
  const auto value = parse_finite_number(token);
  if (!value) fail(path, line.number, "timestamp '" + token + "' is not a finite number");
  if (std::abs(*value) > kNanosecondStampThreshold) return *parse_nanoseconds_as_seconds(token);
  return *value;
}

Eigen::Quaterniond make_quaternion(const fs::path& path, const Line& line, double w, double x, double y, double z) {
  Eigen::Quaterniond q(w, x, y, z);
  const double norm = q.norm();
  if (!(norm > 1e-6)) fail(path, line.number, "quaternion has zero length");
  q.coeffs() /= norm;  // files store rounded quaternions; the pose must be a rotation
  return q;
}

// A column header ("# timestamp x y z qw qx qy qz", EuRoC's "q_RS_w [], q_RS_x []")
// that names both qw and qx tells the quaternion order: true when w comes first.
std::optional<bool> header_says_w_first(const std::string& header) {
  const auto begin = header.find_first_not_of(" \t#%");
  if (begin == std::string::npos) return std::nullopt;
  const auto tokens = split_tokens(lower(header.substr(begin)), true);
  std::optional<std::size_t> w_index, x_index;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const std::string& t = tokens[i];
    if (t == "qw" || t == "q_w" || t.rfind("q_rs_w", 0) == 0) w_index = i;
    if (t == "qx" || t == "q_x" || t.rfind("q_rs_x", 0) == 0) x_index = i;
  }
  if (!w_index || !x_index) return std::nullopt;
  return *w_index < *x_index;
}

// Rotation from the 4 quaternion numbers starting at v[first].
Eigen::Matrix3d rotation_from(const fs::path& path, const Line& line, const std::vector<double>& v, std::size_t first,
                              bool w_first) {
  const Eigen::Quaterniond q = w_first ? make_quaternion(path, line, v[first], v[first + 1], v[first + 2], v[first + 3])
                                       : make_quaternion(path, line, v[first + 3], v[first], v[first + 1], v[first + 2]);
  return q.toRotationMatrix();
}

Trajectory parse_tum(const fs::path& path, const std::vector<Line>& lines) {
  Trajectory trajectory;
  bool w_first = false;  // TUM order unless a header says otherwise
  for (const Line& line : lines) {
    if (is_comment_or_blank(line.text)) {
      if (trajectory.empty()) w_first = header_says_w_first(line.text).value_or(w_first);
      continue;
    }
    const auto tokens = split_tokens(line.text, false);
    const auto v = parse_numbers(path, line, tokens, 8, w_first ? "TUM: t x y z qw qx qy qz" : "TUM: t x y z qx qy qz qw");
    StampedPose pose;
    pose.timestamp = parse_stamp(path, line, tokens[0]);
    pose.T_world_cam.linear() = rotation_from(path, line, v, 4, w_first);
    pose.T_world_cam.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
    trajectory.push_back(pose);
  }
  return trajectory;
}

Trajectory parse_kitti(const fs::path& path, const std::vector<Line>& lines) {
  Trajectory trajectory;
  for (const Line& line : lines) {
    if (is_comment_or_blank(line.text)) continue;
    const auto tokens = split_tokens(line.text, false);
    if (tokens.size() != 12) {
      fail(path, line.number, "expected 12 numbers (KITTI: row-major 3x4 [R|t]), found " +
                                  std::to_string(tokens.size()));
    }
    const auto v = parse_numbers(path, line, tokens, 12, "KITTI: row-major 3x4 [R|t]");
    Eigen::Matrix3d R;
    R << v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10];
    // KITTI files round R to 6-9 digits; re-project onto SO(3) via a unit quaternion.
    Eigen::Quaterniond q(R);
    if (!(q.norm() > 1e-6)) fail(path, line.number, "rotation part is not a rotation matrix");
    StampedPose pose;
    pose.timestamp = static_cast<double>(trajectory.size());
    pose.T_world_cam.linear() = q.normalized().toRotationMatrix();
    pose.T_world_cam.translation() = Eigen::Vector3d(v[3], v[7], v[11]);
    trajectory.push_back(pose);
  }
  return trajectory;
}

// EuRoC stamps are nanoseconds. A stamp with a real fractional part below
// 1e12 can only be seconds (someone's csv export), so it is kept as is.
double parse_euroc_stamp(const fs::path& path, const Line& line, const std::string& token) {
  const auto value = parse_finite_number(token);
  if (!value) fail(path, line.number, "timestamp '" + token + "' is not a finite number");
  if (*value < kNanosecondStampThreshold && *value != std::floor(*value)) return *value;
  return *parse_nanoseconds_as_seconds(token);
}

Trajectory parse_euroc(const fs::path& path, const std::vector<Line>& lines) {
  Trajectory trajectory;
  bool w_first = true;  // EuRoC order unless a header says otherwise
  for (const Line& line : lines) {
    const bool header = is_comment_or_blank(line.text) || (trajectory.empty() && !starts_with_number(line.text, true));
    if (header) {
      // A header without '#' ("timestamp,p_x,...") is allowed before the first pose.
      if (trajectory.empty()) w_first = header_says_w_first(line.text).value_or(w_first);
      continue;
    }
    const auto tokens = split_tokens(line.text, true);
    const auto v = parse_numbers(path, line, tokens, 8,
                                 w_first ? "EuRoC csv: timestamp[ns], p_x, p_y, p_z, q_w, q_x, q_y, q_z"
                                         : "csv: timestamp[ns], p_x, p_y, p_z, q_x, q_y, q_z, q_w");
    StampedPose pose;
    pose.timestamp = parse_euroc_stamp(path, line, tokens[0]);
    pose.T_world_cam.linear() = rotation_from(path, line, v, 4, w_first);
    pose.T_world_cam.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
    trajectory.push_back(pose);
  }
  return trajectory;
}

TrajectoryFormat detect_from_lines(const fs::path& path, const std::vector<Line>& lines) {
  for (const Line& line : lines) {
    if (is_comment_or_blank(line.text)) continue;
    if (line.text.find(',') != std::string::npos) {
      if (!starts_with_number(line.text, true)) continue;  // csv header without '#'
      return TrajectoryFormat::Euroc;
    }
    const auto tokens = split_tokens(line.text, false);
    if (tokens.size() == 12) return TrajectoryFormat::Kitti;
    if (tokens.size() >= 8) return TrajectoryFormat::Tum;
    fail(path, line.number,
         "cannot tell the trajectory format: expected 8 numbers (TUM), 12 (KITTI) or a csv line (EuRoC), found " +
             std::to_string(tokens.size()) + " fields");
  }
  throw Error("trajectory file " + path.string() + " contains no poses; check that the run wrote its trajectory");
}

std::string format_number(double value) {
  // Shortest text that reads back to the identical double.
  char buffer[64];
  const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return ec == std::errc() ? std::string(buffer, ptr) : std::string("nan");
}

}  // namespace

TrajectoryFormat parse_trajectory_format(const std::string& name) {
  const std::string n = lower(name);
  if (n == "tum") return TrajectoryFormat::Tum;
  if (n == "kitti") return TrajectoryFormat::Kitti;
  if (n == "euroc") return TrajectoryFormat::Euroc;
  throw Error("unknown trajectory format '" + name + "'; use tum, kitti or euroc");
}

std::string to_string(TrajectoryFormat format) {
  switch (format) {
    case TrajectoryFormat::Tum: return "tum";
    case TrajectoryFormat::Kitti: return "kitti";
    case TrajectoryFormat::Euroc: return "euroc";
  }
  return "tum";
}

TrajectoryFormat detect_trajectory_format(const fs::path& path) { return detect_from_lines(path, read_lines(path)); }

Trajectory read_trajectory(const fs::path& path, std::optional<TrajectoryFormat> format) {
  const auto lines = read_lines(path);
  const TrajectoryFormat chosen = format ? *format : detect_from_lines(path, lines);
  Trajectory trajectory;
  switch (chosen) {
    case TrajectoryFormat::Tum: trajectory = parse_tum(path, lines); break;
    case TrajectoryFormat::Kitti: trajectory = parse_kitti(path, lines); break;
    case TrajectoryFormat::Euroc: trajectory = parse_euroc(path, lines); break;
  }
  if (trajectory.empty()) {
    throw Error("trajectory file " + path.string() + " contains no poses; check that the run wrote its trajectory");
  }
  return trajectory;
}

Trajectory read_kitti_trajectory(const fs::path& path, const fs::path& times_path) {
  Trajectory trajectory = read_trajectory(path, TrajectoryFormat::Kitti);
  std::vector<double> times;
  for (const Line& line : read_lines(times_path)) {
    if (is_comment_or_blank(line.text)) continue;
    const auto tokens = split_tokens(line.text, false);
    if (tokens.size() != 1) fail(times_path, line.number, "expected one timestamp per line");
    times.push_back(parse_stamp(times_path, line, tokens[0]));
  }
  if (times.size() != trajectory.size()) {
    throw Error("KITTI times file " + times_path.string() + " has " + std::to_string(times.size()) +
                " stamps but " + path.string() + " has " + std::to_string(trajectory.size()) +
                " poses; pass the times file of the same sequence");
  }
  for (std::size_t i = 0; i < times.size(); ++i) trajectory[i].timestamp = times[i];
  return trajectory;
}

std::string format_trajectory_line(const StampedPose& pose, TrajectoryFormat format) {
  const Eigen::Vector3d t = pose.T_world_cam.translation();
  const Eigen::Matrix3d R = pose.T_world_cam.linear();
  std::string line;
  auto add = [&line](const std::string& field, const char* separator) {
    if (!line.empty()) line += separator;
    line += field;
  };
  switch (format) {
    case TrajectoryFormat::Tum: {
      const Eigen::Quaterniond q(R);
      for (double v : {pose.timestamp, t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()}) add(format_number(v), " ");
      break;
    }
    case TrajectoryFormat::Kitti:
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) add(format_number(R(r, c)), " ");
        add(format_number(t[r]), " ");
      }
      break;
    case TrajectoryFormat::Euroc: {
      const Eigen::Quaterniond q(R);
      add(std::to_string(std::llround(pose.timestamp * 1e9)), ",");
      for (double v : {t.x(), t.y(), t.z(), q.w(), q.x(), q.y(), q.z()}) add(format_number(v), ",");
      break;
    }
  }
  return line;
}

namespace {
constexpr const char* kEurocHeader = "#timestamp [ns],p_x [m],p_y [m],p_z [m],q_w [],q_x [],q_y [],q_z []";
}

void write_trajectory(const fs::path& path, const Trajectory& trajectory, TrajectoryFormat format) {
  std::string text;
  if (format == TrajectoryFormat::Euroc) text += std::string(kEurocHeader) + '\n';
  for (const StampedPose& pose : trajectory) text += format_trajectory_line(pose, format) + '\n';
  write_file_atomically(path, text, "trajectory file");
}

TrajectoryWriter::TrajectoryWriter(const fs::path& path, TrajectoryFormat format)
    : path_(path), format_(format), fd_(::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666)) {
  if (fd_ < 0) {
    throw Error("cannot write trajectory file " + path.string() + ": " + system_reason(errno) +
                "; check that its folder exists and is writable");
  }
  if (format_ == TrajectoryFormat::Euroc) append(std::string(kEurocHeader) + '\n');
}

TrajectoryWriter::~TrajectoryWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void TrajectoryWriter::write(const StampedPose& pose) {
  if (append(format_trajectory_line(pose, format_) + '\n')) ++count_;
}

bool TrajectoryWriter::append(const std::string& line) {
  if (failed_) return false;
  // One write() per line: a killed process leaves whole lines behind. Only
  // after a short write (disk full, file size limit) is the rest tried, which
  // gives the cause; a line that still fails is cut off again.
  std::size_t done = 0;
  int err = 0;
  while (done < line.size()) {
    const ssize_t n = ::write(fd_, line.data() + done, line.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      err = n < 0 ? errno : ENOSPC;
      break;
    }
    done += static_cast<std::size_t>(n);
  }
  if (done == line.size()) {
    size_ += line.size();
    return true;
  }
  if (done > 0 && ::ftruncate(fd_, static_cast<off_t>(size_)) == 0) ::lseek(fd_, static_cast<off_t>(size_), SEEK_SET);
  failed_ = true;
  spdlog::warn("writing trajectory file {} failed ({}); it stops after {} poses, the final trajectory is still "
               "written at the end",
               path_.string(), system_reason(err), count_);
  return false;
}

}  // namespace stillslam
