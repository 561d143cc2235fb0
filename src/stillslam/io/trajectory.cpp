#include "stillslam/io/trajectory.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <numeric>

#include <spdlog/spdlog.h>

#include <fcntl.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include "stillslam/core/atomic_file.h"
#include "stillslam/core/error.h"
#include "stillslam/core/text.h"
#include "stillslam/io/input_file.h"

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

// Values no real trajectory holds: they come from a damaged file, and would
// reach the statistics as inf or NaN.
// Metres: georeferenced files (UTM northings up to 1e7 m, ECEF 6.4e6 m) stay inside.
constexpr double kMaxAbsPosition = 1e8;
constexpr double kMaxAbsStamp = 1e10;        // seconds (year 2286)
constexpr double kQuaternionNormTolerance = 1e-2;  // files round to 4+ digits
constexpr double kRotationTolerance = 1e-2;        // KITTI rounds R to 6-9 digits

std::string format_number(double value) {
  // Shortest text that reads back to the identical double.
  char buffer[64];
  const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return ec == std::errc() ? std::string(buffer, ptr) : std::string("nan");
}

// Every field of a data line as a finite number.
std::vector<double> parse_numbers(const fs::path& path, const Line& line, const std::vector<std::string>& tokens,
                                  const std::string& layout) {
  std::vector<double> values(tokens.size());
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const auto value = parse_finite_number(tokens[i]);
    if (!value) fail(path, line.number, "'" + tokens[i] + "' is not a finite number (" + layout + ")");
    values[i] = *value;
  }
  return values;
}

std::vector<Line> read_lines(const fs::path& path, const std::string& what = "trajectory file") {
  std::ifstream in = open_input_file(path, what);  // skips a UTF-8 BOM
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

// True when the first field reads as a number, finite or not ("nan" and "inf"
// too, so a first pose line holding them is an error, not a header skipped).
bool starts_with_number(const std::string& text, bool commas) {
  const auto tokens = split_tokens(trim(text), commas);
  if (tokens.empty()) return false;
  const std::string& token = tokens.front();
  const char* begin = token.data() + (token.front() == '+' ? 1 : 0);
  double value = 0;
  const auto [ptr, ec] = std::from_chars(begin, token.data() + token.size(), value);
  return ptr == token.data() + token.size() && (ec == std::errc() || ec == std::errc::result_out_of_range);
}

double checked_stamp(const fs::path& path, const Line& line, const std::string& token, double seconds) {
  if (!(std::abs(seconds) <= kMaxAbsStamp)) {
    fail(path, line.number, "timestamp '" + token + "' is beyond " + format_number(kMaxAbsStamp) +
                                " s (year 2286; stamps above 1e12 are read as nanoseconds); fix the value");
  }
  return seconds;
}

double parse_stamp(const fs::path& path, const Line& line, const std::string& token) {
  const auto value = parse_finite_number(token);
  if (!value) fail(path, line.number, "timestamp '" + token + "' is not a finite number");
  if (std::abs(*value) > kNanosecondStampThreshold) {
    return checked_stamp(path, line, token, *parse_nanoseconds_as_seconds(token));
  }
  return checked_stamp(path, line, token, *value);
}

Eigen::Vector3d checked_position(const fs::path& path, const Line& line, double x, double y, double z) {
  const Eigen::Vector3d p(x, y, z);
  if (!(p.cwiseAbs().maxCoeff() <= kMaxAbsPosition)) {
    fail(path, line.number, "position (" + format_number(x) + ", " + format_number(y) + ", " + format_number(z) +
                                ") is beyond " + format_number(kMaxAbsPosition) + " m; fix the value");
  }
  return p;
}

Eigen::Quaterniond make_quaternion(const fs::path& path, const Line& line, double w, double x, double y, double z) {
  Eigen::Quaterniond q(w, x, y, z);
  const double norm = q.coeffs().stableNorm();  // no overflow to inf for 1e300
  if (!(std::abs(norm - 1.0) <= kQuaternionNormTolerance)) {
    fail(path, line.number, "quaternion (w " + format_number(w) + ", x " + format_number(x) + ", y " +
                                format_number(y) + ", z " + format_number(z) + ") has length " + format_number(norm) +
                                ", expected 1; check the columns and the values");
  }
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

// A pose and the line it came from, for messages about repeated stamps.
struct ParsedPose {
  StampedPose pose;
  std::size_t line = 0;
};

// EuRoC stamps are nanoseconds. A stamp with a real fractional part below
// 1e12 can only be seconds (someone's csv export), so it is kept as is.
double parse_euroc_stamp(const fs::path& path, const Line& line, const std::string& token) {
  const auto value = parse_finite_number(token);
  if (!value) fail(path, line.number, "timestamp '" + token + "' is not a finite number");
  if (*value < kNanosecondStampThreshold && *value != std::floor(*value)) return checked_stamp(path, line, token, *value);
  return checked_stamp(path, line, token, *parse_nanoseconds_as_seconds(token));
}

// TUM (blanks or commas; 8 columns, 9 in pyslam's files) and EuRoC csv (8 or
// more columns, the same number on every line) share a layout: a stamp, a
// position and a quaternion whose order a header before the first pose may set.
std::vector<ParsedPose> parse_stamped(const fs::path& path, const std::vector<Line>& lines, bool euroc) {
  std::vector<ParsedPose> poses;
  bool w_first = euroc;  // EuRoC stores q_w first, TUM last, unless a header says otherwise
  std::size_t columns = 0;  // of the first pose line (EuRoC)
  for (const Line& line : lines) {
    const bool header = is_comment_or_blank(line.text) || (poses.empty() && !starts_with_number(line.text, true));
    if (header) {
      // A header without '#' ("timestamp,p_x,...") is allowed before the first pose.
      if (poses.empty()) w_first = header_says_w_first(line.text).value_or(w_first);
      continue;
    }
    const std::string layout = euroc ? (w_first ? "EuRoC csv: timestamp[ns], p_x, p_y, p_z, q_w, q_x, q_y, q_z, ..."
                                                : "csv: timestamp[ns], p_x, p_y, p_z, q_x, q_y, q_z, q_w, ...")
                                     : (w_first ? "TUM: t x y z qw qx qy qz" : "TUM: t x y z qx qy qz qw");
    const auto tokens = split_tokens(line.text, true);
    if (columns == 0) columns = tokens.size();
    const bool count_ok = euroc ? tokens.size() >= 8 && tokens.size() == columns
                                : tokens.size() == 8 || tokens.size() == 9;
    if (!count_ok) {
      const std::string expected = euroc ? (columns >= 8 ? std::to_string(columns) + " (as the first pose line)"
                                                         : std::string("8 or more"))
                                         : std::string("8 (9 in pyslam's files)");
      fail(path, line.number,
           "expected " + expected + " numbers (" + layout + "), found " + std::to_string(tokens.size()) +
               "; fix the line, or pass the file's format explicitly if it is not " + (euroc ? "EuRoC" : "TUM"));
    }
    const auto v = parse_numbers(path, line, tokens, layout);
    ParsedPose parsed;
    parsed.line = line.number;
    parsed.pose.timestamp = euroc ? parse_euroc_stamp(path, line, tokens[0]) : parse_stamp(path, line, tokens[0]);
    parsed.pose.T_world_cam.linear() = rotation_from(path, line, v, 4, w_first);
    parsed.pose.T_world_cam.translation() = checked_position(path, line, v[1], v[2], v[3]);
    poses.push_back(parsed);
  }
  return poses;
}

std::vector<ParsedPose> parse_kitti(const fs::path& path, const std::vector<Line>& lines) {
  const std::string layout = "KITTI: row-major 3x4 [R|t]";
  std::vector<ParsedPose> poses;
  for (const Line& line : lines) {
    if (is_comment_or_blank(line.text)) continue;
    const auto tokens = split_tokens(line.text, false);
    if (tokens.size() != 12) {
      fail(path, line.number, "expected 12 numbers (" + layout + "), found " + std::to_string(tokens.size()) +
                                  "; fix the line, or pass the file's format explicitly if it is not KITTI");
    }
    const auto v = parse_numbers(path, line, tokens, layout);
    Eigen::Matrix3d R;
    R << v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10];
    const double off = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (!(off <= kRotationTolerance) || !(R.determinant() > 0)) {
      fail(path, line.number, "the 3x3 part is not a rotation matrix (R^T R differs from I by " + format_number(off) +
                                  ", det " + format_number(R.determinant()) + "); check the values and the format");
    }
    // KITTI files round R to 6-9 digits; re-project onto SO(3) via a unit quaternion.
    const Eigen::Quaterniond q(R);
    ParsedPose parsed;
    parsed.line = line.number;
    parsed.pose.timestamp = static_cast<double>(poses.size());
    parsed.pose.T_world_cam.linear() = q.normalized().toRotationMatrix();
    parsed.pose.T_world_cam.translation() = checked_position(path, line, v[3], v[7], v[11]);
    poses.push_back(parsed);
  }
  return poses;
}

// One pose per stamp: a stamp repeated with the same pose is a harmless
// duplicate (warned, the first line kept); with a different pose the file
// contradicts itself: an Error, or with KeepLast the later line wins (warned).
// `source` names the file in messages ("trajectory file <path>").
Trajectory without_repeated_stamps(const std::string& source, const std::vector<ParsedPose>& poses,
                                   DuplicateStamps duplicates) {
  std::vector<std::size_t> order(poses.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return poses[a].pose.timestamp < poses[b].pose.timestamp; });
  std::vector<bool> dropped(poses.size(), false);
  std::size_t same = 0, conflicting = 0;
  std::pair<std::size_t, std::size_t> first_same, first_conflict;  // (kept line, dropped line)
  std::size_t kept_index = 0;  // the pose kept so far for the current run of equal stamps
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k == 0 || poses[order[k]].pose.timestamp != poses[kept_index].pose.timestamp) {
      kept_index = order[k];
      continue;
    }
    const ParsedPose& kept = poses[kept_index];
    const ParsedPose& repeat = poses[order[k]];
    const double difference =
        (kept.pose.T_world_cam.matrix() - repeat.pose.T_world_cam.matrix()).cwiseAbs().maxCoeff();
    if (difference <= 1e-9) {
      if (same++ == 0) first_same = {kept.line, repeat.line};
      dropped[order[k]] = true;
      continue;
    }
    if (duplicates == DuplicateStamps::Error) {
      throw Error(source + ", lines " + std::to_string(kept.line) + " and " + std::to_string(repeat.line) +
                  ": the same timestamp " + format_number(kept.pose.timestamp) +
                  " s with different poses; keep one pose per timestamp, or keep the last one as TUM's associate.py "
                  "does (stillslam eval --duplicate-stamps last)");
    }
    if (conflicting++ == 0) first_conflict = {repeat.line, kept.line};
    dropped[kept_index] = true;  // the later line wins
    kept_index = order[k];
  }
  if (same > 0) {
    spdlog::warn("{}: {} line(s) repeat the timestamp and pose of an earlier line (first: line {} repeats line {}); "
                 "kept one pose per timestamp",
                 source, same, first_same.second, first_same.first);
  }
  if (conflicting > 0) {
    spdlog::warn("{}: {} timestamp(s) repeat with a different pose (first: lines {} and {}); kept the last line of "
                 "each, as TUM's associate.py does",
                 source, conflicting, first_conflict.second, first_conflict.first);
  }
  Trajectory trajectory;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (!dropped[i]) trajectory.push_back(poses[i].pose);
  }
  return trajectory;
}

// The format of the first pose line, from its column count, separator and the
// header before it. A csv line whose quaternion order no header names is
// ambiguous (EuRoC puts q_w first, TUM last): an Error asks for the format.
TrajectoryFormat detect_from_lines(const fs::path& path, const std::vector<Line>& lines) {
  std::optional<bool> w_first;
  for (const Line& line : lines) {
    const bool csv = line.text.find(',') != std::string::npos;
    if (is_comment_or_blank(line.text) || (csv && !starts_with_number(line.text, true))) {
      if (const auto order = header_says_w_first(line.text)) w_first = order;  // '#'-less csv header too
      continue;
    }
    const auto tokens = split_tokens(line.text, csv);
    if (csv) {
      if (tokens.size() < 8) {
        fail(path, line.number, "a csv line with " + std::to_string(tokens.size()) +
                                    " fields; expected 8 or more (timestamp, position, quaternion, ...)");
      }
      if (!w_first) {
        fail(path, line.number,
             "comma-separated, but no header names the quaternion columns (EuRoC csv has q_w first, TUM q_w "
             "last), so the order is unknown; add a header such as '#timestamp,p_x,p_y,p_z,q_w,q_x,q_y,q_z' or "
             "pass the format (stillslam eval --gt-format / --est-format euroc or tum)");
      }
      return *w_first ? TrajectoryFormat::Euroc : TrajectoryFormat::Tum;
    }
    if (tokens.size() == 12) return TrajectoryFormat::Kitti;
    if (tokens.size() == 8 || tokens.size() == 9) return TrajectoryFormat::Tum;
    fail(path, line.number,
         "cannot tell the trajectory format: found " + std::to_string(tokens.size()) +
             " fields, expected 8 (TUM: t x y z qx qy qz qw; 9 in pyslam's files), 12 (KITTI: row-major 3x4 [R|t]) "
             "or a csv line of 8 or more (EuRoC); fix the file or pass its format (--gt-format / --est-format)");
  }
  throw Error("trajectory file " + path.string() + " contains no poses; check that the run wrote its trajectory");
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

namespace {

std::vector<ParsedPose> parse_trajectory(const fs::path& path, std::optional<TrajectoryFormat> format) {
  const auto lines = read_lines(path);
  const TrajectoryFormat chosen = format ? *format : detect_from_lines(path, lines);
  std::vector<ParsedPose> poses;
  switch (chosen) {
    case TrajectoryFormat::Tum: poses = parse_stamped(path, lines, false); break;
    case TrajectoryFormat::Kitti: poses = parse_kitti(path, lines); break;
    case TrajectoryFormat::Euroc: poses = parse_stamped(path, lines, true); break;
  }
  if (poses.empty()) {
    throw Error("trajectory file " + path.string() + " contains no poses; check that the run wrote its trajectory");
  }
  return poses;
}

}  // namespace

Trajectory read_trajectory(const fs::path& path, std::optional<TrajectoryFormat> format, DuplicateStamps duplicates) {
  return without_repeated_stamps("trajectory file " + path.string(), parse_trajectory(path, format), duplicates);
}

Trajectory read_kitti_trajectory(const fs::path& path, const fs::path& times_path, DuplicateStamps duplicates) {
  std::vector<ParsedPose> poses = parse_trajectory(path, TrajectoryFormat::Kitti);
  std::vector<std::pair<double, std::size_t>> times;  // stamp, line
  for (const Line& line : read_lines(times_path, "KITTI times file")) {
    if (is_comment_or_blank(line.text)) continue;
    const auto tokens = split_tokens(line.text, false);
    if (tokens.size() != 1) fail(times_path, line.number, "expected one timestamp per line");
    times.emplace_back(parse_stamp(times_path, line, tokens[0]), line.number);
  }
  if (times.size() != poses.size()) {
    throw Error("KITTI times file " + times_path.string() + " has " + std::to_string(times.size()) +
                " stamps but " + path.string() + " has " + std::to_string(poses.size()) +
                " poses; pass the times file of the same sequence");
  }
  for (std::size_t i = 0; i < times.size(); ++i) {
    poses[i].pose.timestamp = times[i].first;
    poses[i].line = times[i].second;
  }
  return without_repeated_stamps("KITTI times file " + times_path.string() + " (poses " + path.string() + ")", poses,
                                 duplicates);
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
