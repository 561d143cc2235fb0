#include "stillslam/io/bag_dataset.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>
#include <spdlog/spdlog.h>

#include "stillslam/core/error.h"
#include "stillslam/io/ros2_image_convert.h"
#include "stillslam/io/ros2_message_codec.h"
#include "stillslam/io/timestamp_association.h"

namespace stillslam {
namespace {

constexpr std::size_t kStampBytes = 12;  // encapsulation + builtin_interfaces/Time

bool is_depth(const cv::Mat& image) { return image.type() == CV_16UC1 || image.type() == CV_32FC1; }

cv::Mat to_gray(const cv::Mat& image) {
  if (image.channels() == 1) return image;
  cv::Mat gray;
  cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

std::string size_text(const cv::Size& s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }

}  // namespace

std::uint32_t BagDataset::require_image_topic(const std::string& name) const {
  const auto topic = bag_->find_topic(name);
  if (!topic) {
    throw Error(bag_->file().string() + ": topic '" + name + "' is not in the bag; it has: " + bag_->topic_list());
  }
  const std::string& type = bag_->topics()[*topic].type;
  if (type != ros2::kImageType && type != ros2::kCompressedImageType) {
    throw Error(bag_->file().string() + ": topic '" + name + "' holds " + type + ", not images (" +
                ros2::kImageType + " or " + ros2::kCompressedImageType + "); the bag has: " + bag_->topic_list());
  }
  const std::string& serialization = bag_->topics()[*topic].serialization;
  if (!serialization.empty() && serialization != "cdr") {
    throw Error(bag_->file().string() + ": topic '" + name + "' is serialized as '" + serialization +
                "'; only CDR (ROS 2's rmw serialization) is read");
  }
  if (bag_->topics()[*topic].message_count == 0) {
    throw Error(bag_->file().string() + ": topic '" + name + "' has no messages" +
                (bag_->damage().empty() ? std::string() : " before the damage (" + bag_->damage() + ")"));
  }
  return *topic;
}

BagDataset::BagDataset(const std::filesystem::path& path, const CameraSettings& settings,
                       const DatasetOptions& options)
    : FileDataset(options.skip_bad_frames), bag_(open_bag(path)), topics_(options.topics),
      side_by_side_(options.side_by_side) {
  const std::string bag_name = path.string();
  if (topics_.empty()) {
    throw Error(bag_name + ": a ROS 2 bag needs its image topics: --topics LEFT,RIGHT (stereo) or RGB,DEPTH "
                           "(RGB-D), or --topics TOPIC --side-by-side; the bag has: " + bag_->topic_list());
  }
  if (side_by_side_ && topics_.size() != 1) {
    throw Error(bag_name + ": --side-by-side takes one topic holding left|right images (got " +
                std::to_string(topics_.size()) + ")");
  }
  if (!side_by_side_ && topics_.size() != 2) {
    throw Error(bag_name + ": " + std::to_string(topics_.size()) + " image topic(s) given (" + topics_.front() +
                (topics_.size() > 1 ? ", ..." : "") +
                "): stereo needs two, --topics LEFT,RIGHT; RGB-D needs --topics RGB,DEPTH; one topic with left|right "
                "side by side needs --side-by-side. The bag has: " + bag_->topic_list());
  }
  std::vector<std::uint32_t> ids;
  for (const std::string& t : topics_) ids.push_back(require_image_topic(t));
  // An encoding not supported fails here, before the run, rather than at the first frame.
  for (const std::uint32_t id : ids) {
    const auto first = std::find_if(bag_->messages().begin(), bag_->messages().end(),
                                    [&](const BagMessageInfo& m) { return m.topic == id; });
    const BagTopic& topic = bag_->topics()[id];
    std::optional<std::string> unsupported;
    try {
      const auto bytes = bag_->read(static_cast<std::size_t>(first - bag_->messages().begin()));
      unsupported = topic.type == ros2::kImageType
                        ? ros2::unsupported(ros2::decode_image(bytes, topic.name), topic.name)
                        : ros2::unsupported(ros2::decode_compressed_image(bytes, topic.name), topic.name);
    } catch (const Error&) {
      // A message that does not decode is load()'s to report (or skip); only the encoding is checked here.
    }
    if (unsupported) throw Error(bag_name + ": " + *unsupported + ". The bag has: " + bag_->topic_list());
  }

  // Header stamps per topic, sorted; duplicates dropped.
  std::vector<std::vector<std::pair<std::int64_t, std::size_t>>> stamped(ids.size());
  for (std::size_t i = 0; i < bag_->messages().size(); ++i) {
    for (std::size_t k = 0; k < ids.size(); ++k) {
      if (bag_->messages()[i].topic != ids[k]) continue;
      const auto prefix = bag_->read_prefix(i, kStampBytes);
      stamped[k].emplace_back(ros2::decode_stamp_ns(prefix, "topic " + topics_[k] + " message " + std::to_string(i)), i);
    }
  }
  for (std::size_t k = 0; k < ids.size(); ++k) {
    auto& list = stamped[k];
    if (std::all_of(list.begin(), list.end(), [](const auto& s) { return s.first == 0; })) {
      spdlog::warn("{}: topic {} has no header stamps (all zero): using the bag's receive times", bag_name, topics_[k]);
      for (auto& s : list) s.first = bag_->messages()[s.second].log_time_ns;
    }
    std::stable_sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    const std::size_t before = list.size();
    list.erase(std::unique(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
               list.end());
    if (list.size() < before) {
      spdlog::warn("{}: topic {} has {} messages with a header stamp seen before: the first of each is used", bag_name,
                   topics_[k], before - list.size());
    }
  }

  // Which camera: the settings say, else the second topic's encoding does.
  if (side_by_side_ || settings.stereo) {
    sensor_ = SensorType::Stereo;
  } else if (settings.rgbd) {
    sensor_ = SensorType::Rgbd;
  } else {
    sensor_ = is_depth(decode(stamped[1].front().second)) ? SensorType::Rgbd : SensorType::Stereo;
  }
  const std::string settings_name = settings.file.empty() ? "the settings" : settings.file.string();
  if (sensor_ == SensorType::Stereo && !settings.stereo) {
    throw Error(bag_name + ": stereo topics, but " + settings_name +
                " describe no stereo pair: give stereo settings (Camera2.* with Stereo.T_c1_c2, or Camera.bf / "
                "Stereo.b), or --camera-info-from-bag to take the calibration from the bag's CameraInfo");
  }
  if (sensor_ == SensorType::Rgbd && settings.stereo) {
    throw Error(bag_name + ": RGB-D topics, but " + settings_name + " describe a stereo pair: use RGB-D settings");
  }

  const auto seconds = [](std::int64_t ns) { return static_cast<double>(ns) * 1e-9; };
  if (side_by_side_) {
    for (const auto& [ns, message] : stamped[0]) frames_.push_back({seconds(ns), message, message});
  } else {
    std::vector<double> a, b;
    for (const auto& s : stamped[0]) a.push_back(seconds(s.first));
    for (const auto& s : stamped[1]) b.push_back(seconds(s.first));
    for (const auto& [ia, ib] : associate_timestamps(a, b, options.max_dt)) {
      frames_.push_back({a[ia], stamped[0][ia].second, stamped[1][ib].second});
    }
    unpaired_first_ = a.size() - frames_.size();
    unpaired_second_ = b.size() - frames_.size();
    if (unpaired_first_ > 0 || unpaired_second_ > 0) {
      spdlog::warn("{}: {} messages on {} and {} on {}: {} pairs within {} s; {} of {} and {} of {} have no partner "
                   "and are dropped",
                   bag_name, a.size(), topics_[0], b.size(), topics_[1], frames_.size(), options.max_dt,
                   unpaired_first_, topics_[0], unpaired_second_, topics_[1]);
    }
  }
  if (frames_.empty()) {
    throw Error(bag_name + ": no frames: no message of " + topics_[0] + " has a partner on " + topics_.back() +
                " within " + std::to_string(options.max_dt) + " s (check the topics, or widen --pair-tolerance)");
  }

  if (sensor_ == SensorType::Stereo) {
    if (settings.stereo->rectified) {
      stereo_ = settings.stereo;
      expected_size_ = cv::Size(settings.camera.width, settings.camera.height);
    } else {
      cv::Size size(settings.stereo->left.width, settings.stereo->left.height);
      if (size.width <= 0 || size.height <= 0) size = cv::Size(settings.camera.width, settings.camera.height);
      if (size.width <= 0 || size.height <= 0) {
        cv::Mat first = decode(frames_.front().first);
        size = side_by_side_ ? cv::Size(first.cols / 2, first.rows) : first.size();
      }
      rectifier_ = std::make_unique<StereoRectifier>(*settings.stereo, size);
      expected_size_ = size;
    }
  } else {
    expected_size_ = cv::Size(settings.camera.width, settings.camera.height);
  }
}

std::optional<StereoCalibration> BagDataset::rectified_stereo() const {
  if (rectifier_) return rectifier_->rectified();
  return stereo_;
}

std::string BagDataset::frame_name(std::size_t i) const {
  return topics_[0] + " @ " + std::to_string(frames_.at(i).timestamp);
}

cv::Mat BagDataset::decode(std::size_t message) const {
  const BagTopic& topic = bag_->topics()[bag_->messages()[message].topic];
  const std::string what = bag_->file().string() + ": topic " + topic.name + " message " + std::to_string(message);
  const auto bytes = bag_->read(message);
  if (topic.type == ros2::kImageType) return ros2::image_to_mat(ros2::decode_image(bytes, what), topic.name);
  return ros2::compressed_image_to_mat(ros2::decode_compressed_image(bytes, what), topic.name);
}

SensorFrame BagDataset::read_frame(std::size_t i) const {
  const Pair& p = frames_[i];
  SensorFrame frame;
  frame.name = frame_name(i);
  const auto check_size = [&](const cv::Mat& image, const std::string& topic) {
    if (expected_size_.width > 0 && expected_size_.height > 0 && image.size() != expected_size_) {
      throw Error(bag_->file().string() + ": topic " + topic + " image at " + std::to_string(p.timestamp) + " is " +
                  size_text(image.size()) + " but the calibration expects " + size_text(expected_size_) +
                  (side_by_side_ ? " per side (the side-by-side image is split in two halves)" : "") +
                  " (use the settings made for this camera, or --camera-info-from-bag)");
    }
  };
  if (sensor_ == SensorType::Rgbd) {
    const cv::Mat color = decode(p.first);
    if (is_depth(color)) {
      throw Error("topic " + topics_[0] + " holds depth images: give the colour topic first, --topics RGB,DEPTH");
    }
    if (color.channels() == 1) {
      frame.gray = color;
      cv::cvtColor(color, frame.color, cv::COLOR_GRAY2BGR);
    } else {
      frame.color = color;
      cv::cvtColor(color, frame.gray, cv::COLOR_BGR2GRAY);
    }
    check_size(frame.color, topics_[0]);
    const cv::Mat depth = decode(p.second);
    if (depth.type() == CV_16UC1) {
      depth.convertTo(frame.depth, CV_32F, 1e-3);  // millimetres (REP 118)
    } else if (depth.type() == CV_32FC1) {
      frame.depth = depth.clone();
      cv::patchNaNs(frame.depth, 0);
    } else {
      throw Error("topic " + topics_[1] + " is not a depth image (" + std::to_string(depth.channels()) +
                  " channel(s) of 8-bit data; expected 16UC1 millimetres or 32FC1 metres)");
    }
    if (frame.depth.size() != frame.color.size()) {
      throw Error("topic " + topics_[1] + ": depth image is " + size_text(frame.depth.size()) + " but the colour image is " +
                  size_text(frame.color.size()) + " (depth must be registered to the colour camera)");
    }
    return frame;
  }
  cv::Mat left_as_stored, right_as_stored;
  if (side_by_side_) {
    const cv::Mat both = decode(p.first);
    if (both.cols % 2 != 0) {
      throw Error("topic " + topics_[0] + ": side-by-side image is " + size_text(both.size()) +
                  ", an odd width cannot split into left|right halves");
    }
    left_as_stored = both.colRange(0, both.cols / 2).clone();
    right_as_stored = both.colRange(both.cols / 2, both.cols).clone();
  } else {
    left_as_stored = decode(p.first);
    right_as_stored = decode(p.second);
  }
  for (const auto& [image, topic] : {std::pair{&left_as_stored, topics_[0]}, std::pair{&right_as_stored, topics_.back()}}) {
    if (is_depth(*image)) throw Error("topic " + topic + " holds depth images, not a stereo camera's");
    check_size(*image, topic);
  }
  const cv::Mat left = to_gray(left_as_stored);
  const cv::Mat right = to_gray(right_as_stored);
  if (rectifier_) {
    frame.gray = rectifier_->rectify_left(left);
    frame.right = rectifier_->rectify_right(right);
    if (left_as_stored.channels() == 3) frame.color = rectifier_->rectify_left(left_as_stored);
  } else {
    frame.gray = left;
    frame.right = right;
    if (left_as_stored.channels() == 3) frame.color = left_as_stored;
  }
  if (frame.color.empty()) cv::cvtColor(frame.gray, frame.color, cv::COLOR_GRAY2BGR);
  return frame;
}

}  // namespace stillslam
