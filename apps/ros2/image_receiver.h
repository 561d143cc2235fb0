#pragma once
// The node's input thread: waits on the image (and CameraInfo) readers,
// pairs the images by stamp, builds SensorFrames and leaves each in the
// mailbox for the System (a newer frame replaces one not yet taken). Ends on
// stop(), on the external stop flag, or at the first bad message (error()),
// and then stops the mailbox so the consumer's take() returns.
#include <atomic>
#include <cstddef>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "dds.h"
#include "frame_assembler.h"
#include "frame_stamps.h"
#include "sensor_msgs/msg/CameraInfo.h"
#include "sensor_msgs/msg/Image.h"
#include "stamp_pairer.h"
#include "stillslam/core/mailbox.h"

namespace stillslam::ros2 {

struct LiveNodeOptions;

class ImageReceiver {
 public:
  ImageReceiver(const DdsParticipant& participant, const LiveNodeOptions& options, const FrameAssembler& assembler,
                Mailbox<SensorFrame>& mailbox, FrameStamps& stamps, const std::atomic<bool>& external_stop);
  ~ImageReceiver();  // stop()
  ImageReceiver(const ImageReceiver&) = delete;
  ImageReceiver& operator=(const ImageReceiver&) = delete;
  void stop();

  std::size_t received_first() const { return received_[0]; }
  std::size_t received_second() const { return received_[1]; }
  std::size_t camera_infos() const { return camera_infos_; }
  // Pairing counts; read after stop().
  const StampPairer& pairer() const { return pairer_; }
  std::optional<std::string> error() const;

 private:
  void loop();
  void receive();
  void on_image(const sensor_msgs_msg_dds__Image_& message, int side);
  void on_camera_info(const sensor_msgs_msg_dds__CameraInfo_& message);

  const LiveNodeOptions& options_;
  const FrameAssembler& assembler_;
  Mailbox<SensorFrame>& mailbox_;
  FrameStamps& stamps_;
  const std::atomic<bool>& external_stop_;
  DdsReader<sensor_msgs_msg_dds__Image_> first_, second_;
  std::optional<DdsReader<sensor_msgs_msg_dds__CameraInfo_>> camera_info_;
  DdsWaiter waiter_;
  StampPairer pairer_;
  std::size_t next_index_ = 0;
  std::atomic<std::size_t> received_[2] = {0, 0};
  std::atomic<std::size_t> camera_infos_{0};
  bool camera_info_checked_ = false;
  mutable std::mutex error_mutex_;
  std::optional<std::string> error_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace stillslam::ros2
