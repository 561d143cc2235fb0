#include "image_receiver.h"

#include <spdlog/spdlog.h>

#include "camera_info_message.h"
#include "image_message.h"
#include "live_node.h"
#include "ros_time.h"
#include "stillslam/core/error.h"

namespace stillslam::ros2 {

ImageReceiver::ImageReceiver(const DdsParticipant& participant, const LiveNodeOptions& options,
                             const FrameAssembler& assembler, Mailbox<SensorFrame>& mailbox, FrameStamps& stamps,
                             const std::atomic<bool>& external_stop)
    : options_(options),
      assembler_(assembler),
      mailbox_(mailbox),
      stamps_(stamps),
      external_stop_(external_stop),
      first_(participant, sensor_msgs_msg_dds__Image__desc, options.topics.first, options.input_qos),
      second_(participant, sensor_msgs_msg_dds__Image__desc, options.topics.second, options.input_qos),
      waiter_(participant),
      pairer_(options.pairing) {
  waiter_.add(first_);
  waiter_.add(second_);
  if (!options.topics.camera_info.empty()) {
    camera_info_.emplace(participant, sensor_msgs_msg_dds__CameraInfo__desc, options.topics.camera_info,
                         options.input_qos);
    waiter_.add(*camera_info_);
  }
  thread_ = std::thread([this] { loop(); });
}

ImageReceiver::~ImageReceiver() { stop(); }

void ImageReceiver::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

std::optional<std::string> ImageReceiver::error() const {
  std::lock_guard lock(error_mutex_);
  return error_;
}

void ImageReceiver::loop() {
  try {
    while (!stop_ && !external_stop_) {
      if (waiter_.wait(std::chrono::milliseconds(100))) receive();
    }
  } catch (const Error& e) {
    std::lock_guard lock(error_mutex_);
    error_ = e.what();
  }
  mailbox_.stop();
}

void ImageReceiver::receive() {
  first_.take([this](const sensor_msgs_msg_dds__Image_& m) { on_image(m, 0); });
  second_.take([this](const sensor_msgs_msg_dds__Image_& m) { on_image(m, 1); });
  if (camera_info_) camera_info_->take([this](const sensor_msgs_msg_dds__CameraInfo_& m) { on_camera_info(m); });
}

void ImageReceiver::on_image(const sensor_msgs_msg_dds__Image_& message, int side) {
  ++received_[side];
  const std::string& topic = side == 0 ? first_.name() : second_.name();
  StampedImage image{stamp_nanoseconds(message.header.stamp), image_from_message(message, topic)};
  std::optional<ImagePair> pair = side == 0 ? pairer_.add_first(std::move(image)) : pairer_.add_second(std::move(image));
  if (!pair) return;
  SensorFrame frame = assembler_.assemble(*pair, next_index_, first_.name(), second_.name());
  stamps_.record(next_index_, pair->first.stamp_ns);
  ++next_index_;
  mailbox_.put(std::move(frame));
}

void ImageReceiver::on_camera_info(const sensor_msgs_msg_dds__CameraInfo_& message) {
  ++camera_infos_;
  if (camera_info_checked_) return;
  camera_info_checked_ = true;
  if (const auto why = camera_info_mismatch(message, assembler_.camera())) {
    spdlog::warn("ros2: {} on {} (the settings file is used as it is)", *why, camera_info_->name());
  } else {
    spdlog::info("ros2: CameraInfo on {} agrees with the settings", camera_info_->name());
  }
}

}  // namespace stillslam::ros2
