#include "stillslam/io/tum_dataset.h"

#include <opencv2/imgproc.hpp>
#include <spdlog/spdlog.h>

#include "stillslam/core/error.h"
#include "stillslam/io/image_io.h"
#include "stillslam/io/text_table.h"
#include "stillslam/io/timestamp_association.h"
#include "stillslam/io/timestamp_check.h"

namespace stillslam {
namespace {

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

struct TimedFile {
  double time;
  std::string file;
};

std::vector<TimedFile> read_tum_list(const std::filesystem::path& list) {
  std::vector<TimedFile> out;
  TimestampCheck stamps(list);
  for (const TextRow& row : read_text_table(list)) {
    if (row.fields.size() < 2) {
      throw Error(list.string() + ":" + std::to_string(row.line) +
                  ": expected 'timestamp file' (TUM rgb.txt / depth.txt format)");
    }
    out.push_back({parse_double(row.fields[0], list, row.line), row.fields[1]});
    stamps.add(out.back().time, row.fields[0], row.line);
  }
  return out;
}

}  // namespace

std::vector<TumPair> read_tum_associations(const std::filesystem::path& file) {
  std::vector<TumPair> pairs;
  // The rgb stamps become the trajectory's: sorted and unique. The depth
  // stamps only pick files, but must still be real times.
  TimestampCheck rgb_stamps(file, "rgb timestamp");
  for (const TextRow& row : read_text_table(file)) {
    if (row.fields.size() < 4) {
      throw Error(file.string() + ":" + std::to_string(row.line) +
                  ": expected 't_rgb rgb/x.png t_depth depth/y.png' (TUM association format)");
    }
    TumPair p{parse_double(row.fields[0], file, row.line), row.fields[1],
              parse_double(row.fields[2], file, row.line), row.fields[3]};
    // Some tools write depth first; the folder names tell the order.
    const bool depth_first = starts_with(p.rgb_file, "depth") && starts_with(p.depth_file, "rgb");
    if (depth_first) {
      std::swap(p.rgb_time, p.depth_time);
      std::swap(p.rgb_file, p.depth_file);
    }
    rgb_stamps.add(p.rgb_time, row.fields[depth_first ? 2 : 0], row.line);
    TimestampCheck(file, "depth timestamp").add(p.depth_time, row.fields[depth_first ? 0 : 2], row.line);
    pairs.push_back(std::move(p));
  }
  return pairs;
}

std::vector<TumPair> associate_tum_lists(const std::filesystem::path& rgb_list,
                                         const std::filesystem::path& depth_list, double max_dt) {
  const auto rgb = read_tum_list(rgb_list);
  const auto depth = read_tum_list(depth_list);
  std::vector<double> rgb_times, depth_times;
  for (const auto& r : rgb) rgb_times.push_back(r.time);
  for (const auto& d : depth) depth_times.push_back(d.time);
  std::vector<TumPair> pairs;
  for (const auto& [ir, id] : associate_timestamps(rgb_times, depth_times, max_dt)) {
    pairs.push_back({rgb[ir].time, rgb[ir].file, depth[id].time, depth[id].file});
  }
  // As associate.py, frames are the pairs found; the images left out are said.
  if (!pairs.empty() && pairs.size() < rgb.size()) {
    spdlog::warn("{} lists {} images and {} lists {}: {} rgb/depth pairs within {} s, {} rgb images without a "
                 "depth partner are dropped",
                 rgb_list.string(), rgb.size(), depth_list.string(), depth.size(), pairs.size(), max_dt,
                 rgb.size() - pairs.size());
  }
  return pairs;
}

TumDataset::TumDataset(const std::filesystem::path& folder, const CameraSettings& settings,
                       const DatasetOptions& options)
    : FileDataset(options.skip_bad_frames),
      folder_(folder),
      depth_map_factor_(settings.depth_map_factor),
      expected_size_(settings.camera.width, settings.camera.height) {
  std::error_code ec;
  if (options.association_file) {
    source_ = *options.association_file;
    if (source_.is_relative() && !std::filesystem::exists(source_, ec)) source_ = folder / source_;
    if (!std::filesystem::is_regular_file(source_, ec)) {
      throw Error(options.association_file->string() + ": association file not found");
    }
    pairs_ = read_tum_associations(source_);
  } else if (std::filesystem::is_regular_file(folder / "associations.txt", ec)) {
    source_ = folder / "associations.txt";
    pairs_ = read_tum_associations(source_);
  } else if (std::filesystem::is_regular_file(folder / "associate.txt", ec)) {
    source_ = folder / "associate.txt";
    pairs_ = read_tum_associations(source_);
  } else {
    source_ = folder / "rgb.txt";
    if (!std::filesystem::is_regular_file(folder / "depth.txt", ec)) {
      throw Error((folder / "depth.txt").string() +
                  ": missing; a TUM RGB-D folder needs rgb.txt and depth.txt, or an associations.txt");
    }
    if (options.max_dt <= 0) throw Error("TUM association: max_dt must be positive");
    pairs_ = associate_tum_lists(source_, folder / "depth.txt", options.max_dt);
  }
  if (pairs_.empty()) {
    throw Error(source_.string() + ": no frames (empty list, or no rgb/depth pair within " +
                std::to_string(options.max_dt) + " s)");
  }
}

SensorFrame TumDataset::read_frame(std::size_t i) const {
  const TumPair& p = pairs_[i];
  SensorFrame frame;
  frame.name = p.rgb_file;
  frame.color = read_color_image(folder_ / p.rgb_file);
  // The RGB-D pipeline uses the settings' intrinsics as they are: images of
  // another size mean the wrong settings file.
  if (expected_size_.width > 0 && expected_size_.height > 0 && frame.color.size() != expected_size_) {
    throw Error((folder_ / p.rgb_file).string() + ": image is " + std::to_string(frame.color.cols) + "x" +
                std::to_string(frame.color.rows) + " but the settings say Camera.width/height " +
                std::to_string(expected_size_.width) + "x" + std::to_string(expected_size_.height) +
                " (use the settings file made for this camera)");
  }
  cv::cvtColor(frame.color, frame.gray, cv::COLOR_BGR2GRAY);
  frame.depth = read_depth_image(folder_ / p.depth_file, depth_map_factor_);
  if (frame.depth.size() != frame.color.size()) {
    throw Error((folder_ / p.depth_file).string() + ": depth image is " + std::to_string(frame.depth.cols) +
                "x" + std::to_string(frame.depth.rows) + " but the colour image " + p.rgb_file + " is " +
                std::to_string(frame.color.cols) + "x" + std::to_string(frame.color.rows) +
                " (depth must be registered to the colour camera)");
  }
  return frame;
}

}  // namespace stillslam
