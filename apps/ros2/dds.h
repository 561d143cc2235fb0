#pragma once
// Thin owners of Cyclone DDS entities (C API) for the node: a participant on
// a configured domain, typed topics with ROS 2's QoS profiles, readers and
// writers of the idlc-generated message structs. Every entity is deleted
// with its owner; an error of the C API becomes a stillslam::Error naming the
// topic.
#include <dds/dds.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "cyclone_config.h"

namespace stillslam::ros2 {

// ROS 2's QoS profiles (rmw_qos_profile_default and _sensor_data), both
// volatile.
enum class QosProfile {
  Default,     // reliable, keep last 10
  SensorData,  // best effort, keep last 5
};
// "default" / "sensor_data"; Error naming `option` otherwise.
QosProfile parse_qos_profile(const std::string& text, const std::string& option);

// ROS 2's topic name on DDS: "rt/" + the name without its leading '/'.
std::string dds_topic_name(const std::string& ros_name);
// The CameraInfo beside an image topic, as ROS 2 camera drivers name it:
// "camera/left/image_raw" -> "camera/left/camera_info".
std::string camera_info_topic(const std::string& image_topic);

class DdsParticipant {
 public:
  explicit DdsParticipant(const DdsNetworkOptions& options);
  ~DdsParticipant();
  DdsParticipant(const DdsParticipant&) = delete;
  DdsParticipant& operator=(const DdsParticipant&) = delete;
  dds_entity_t handle() const { return participant_; }

 private:
  dds_entity_t domain_ = 0;  // only for a loopback configuration
  dds_entity_t participant_ = 0;
};

// A reader or writer with its topic; the base of the typed ones below.
class DdsEndpoint {
 public:
  DdsEndpoint(const DdsParticipant& participant, const dds_topic_descriptor_t& type, const std::string& ros_name,
              QosProfile qos, bool writer);
  ~DdsEndpoint();
  DdsEndpoint(const DdsEndpoint&) = delete;
  DdsEndpoint& operator=(const DdsEndpoint&) = delete;
  dds_entity_t handle() const { return endpoint_; }
  const std::string& name() const { return name_; }  // the DDS topic, "rt/..."
  // Readers (writers) on the other side that match this endpoint now.
  std::uint32_t matched() const;
  // Waits until at least `count` endpoints match; false after `timeout`.
  bool wait_matched(std::uint32_t count, std::chrono::milliseconds timeout) const;
  // Writers: waits until every matched reader acknowledged what was written
  // (reliable QoS); false after `timeout`.
  bool wait_for_acks(std::chrono::milliseconds timeout) const;

 protected:
  void write_sample(const void* sample) const;
  // Takes every waiting sample; `on_sample` sees the valid ones (loaned
  // memory, valid during the call). Returns how many it saw.
  std::size_t take_samples(const std::function<void(const void*)>& on_sample) const;

 private:
  std::string name_;
  bool writer_;
  dds_entity_t topic_ = 0;
  dds_entity_t endpoint_ = 0;
};

template <class Message>
class DdsWriter : public DdsEndpoint {
 public:
  DdsWriter(const DdsParticipant& p, const dds_topic_descriptor_t& type, const std::string& ros_name,
            QosProfile qos = QosProfile::Default)
      : DdsEndpoint(p, type, ros_name, qos, true) {}
  void write(const Message& message) const { write_sample(&message); }
};

template <class Message>
class DdsReader : public DdsEndpoint {
 public:
  DdsReader(const DdsParticipant& p, const dds_topic_descriptor_t& type, const std::string& ros_name,
            QosProfile qos = QosProfile::Default)
      : DdsEndpoint(p, type, ros_name, qos, false) {}
  std::size_t take(const std::function<void(const Message&)>& on_message) const {
    return take_samples([&](const void* s) { on_message(*static_cast<const Message*>(s)); });
  }
};

// Waits for data on any of a set of readers (a DDS waitset).
class DdsWaiter {
 public:
  explicit DdsWaiter(const DdsParticipant& participant);
  ~DdsWaiter();
  DdsWaiter(const DdsWaiter&) = delete;
  DdsWaiter& operator=(const DdsWaiter&) = delete;
  void add(const DdsEndpoint& reader);
  // True when some reader has data; false after `timeout`.
  bool wait(std::chrono::milliseconds timeout) const;

 private:
  dds_entity_t waitset_ = 0;
};

}  // namespace stillslam::ros2
