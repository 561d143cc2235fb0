#include "dds.h"

#include <thread>
#include <vector>

#include "stillslam/core/error.h"

namespace stillslam::ros2 {

namespace {

std::string dds_error(dds_return_t code) { return dds_strretcode(code); }

struct Qos {
  explicit Qos(QosProfile profile) : qos(dds_create_qos()) {
    const bool sensor = profile == QosProfile::SensorData;
    dds_qset_reliability(qos, sensor ? DDS_RELIABILITY_BEST_EFFORT : DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
    dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, sensor ? 5 : 10);
    dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);
  }
  ~Qos() { dds_delete_qos(qos); }
  Qos(const Qos&) = delete;
  Qos& operator=(const Qos&) = delete;
  dds_qos_t* qos;
};

}  // namespace

QosProfile parse_qos_profile(const std::string& text, const std::string& option) {
  if (text == "default") return QosProfile::Default;
  if (text == "sensor_data") return QosProfile::SensorData;
  throw Error(option + " '" + text + "' is not a QoS profile: use default (reliable, keep last 10) or sensor_data "
              "(best effort, keep last 5)");
}

std::string dds_topic_name(const std::string& ros_name) {
  std::size_t start = 0;
  while (start < ros_name.size() && ros_name[start] == '/') ++start;
  if (start == ros_name.size()) throw Error("empty ROS 2 topic name '" + ros_name + "'");
  return "rt/" + ros_name.substr(start);
}

std::string camera_info_topic(const std::string& image_topic) {
  const std::size_t slash = image_topic.rfind('/');
  return (slash == std::string::npos ? std::string() : image_topic.substr(0, slash + 1)) + "camera_info";
}

DdsParticipant::DdsParticipant(const DdsNetworkOptions& options) {
  const auto xml = cyclone_config_xml(options);
  const auto domain = static_cast<dds_domainid_t>(options.domain);
  if (xml) {
    domain_ = dds_create_domain(domain, xml->c_str());
    if (domain_ < 0) throw Error("cannot create DDS domain " + std::to_string(domain) + " on 127.0.0.1: " + dds_error(domain_));
  }
  participant_ = dds_create_participant(domain, nullptr, nullptr);
  if (participant_ < 0) {
    const std::string why = dds_error(participant_);
    if (domain_ > 0) dds_delete(domain_);
    throw Error("cannot create a DDS participant on domain " + std::to_string(domain) + ": " + why);
  }
}

DdsParticipant::~DdsParticipant() {
  dds_delete(participant_);
  if (domain_ > 0) dds_delete(domain_);
}

DdsEndpoint::DdsEndpoint(const DdsParticipant& participant, const dds_topic_descriptor_t& type,
                         const std::string& ros_name, QosProfile qos, bool writer)
    : name_(dds_topic_name(ros_name)), writer_(writer) {
  const Qos q(qos);
  topic_ = dds_create_topic(participant.handle(), &type, name_.c_str(), q.qos, nullptr);
  if (topic_ < 0) {
    throw Error("cannot create DDS topic " + name_ + " (" + type.m_typename + "): " + dds_error(topic_) +
                " (one topic name carries one message type)");
  }
  endpoint_ = writer ? dds_create_writer(participant.handle(), topic_, q.qos, nullptr)
                     : dds_create_reader(participant.handle(), topic_, q.qos, nullptr);
  if (endpoint_ < 0) {
    const std::string why = dds_error(endpoint_);
    dds_delete(topic_);
    throw Error(std::string("cannot create a DDS ") + (writer ? "writer" : "reader") + " on " + name_ + ": " + why);
  }
}

DdsEndpoint::~DdsEndpoint() {
  dds_delete(endpoint_);
  dds_delete(topic_);
}

std::uint32_t DdsEndpoint::matched() const {
  if (writer_) {
    dds_publication_matched_status_t s{};
    return dds_get_publication_matched_status(endpoint_, &s) == DDS_RETCODE_OK ? s.current_count : 0;
  }
  dds_subscription_matched_status_t s{};
  return dds_get_subscription_matched_status(endpoint_, &s) == DDS_RETCODE_OK ? s.current_count : 0;
}

bool DdsEndpoint::wait_matched(std::uint32_t count, std::chrono::milliseconds timeout) const {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (matched() < count) {
    if (std::chrono::steady_clock::now() >= end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

bool DdsEndpoint::wait_for_acks(std::chrono::milliseconds timeout) const {
  return dds_wait_for_acks(endpoint_, DDS_MSECS(timeout.count())) == DDS_RETCODE_OK;
}

void DdsEndpoint::write_sample(const void* sample) const {
  const dds_return_t rc = dds_write(endpoint_, sample);
  if (rc != DDS_RETCODE_OK) throw Error("cannot write on DDS topic " + name_ + ": " + dds_error(rc));
}

std::size_t DdsEndpoint::take_samples(const std::function<void(const void*)>& on_sample) const {
  constexpr std::size_t kBatch = 16;
  std::size_t seen = 0;
  for (;;) {
    void* samples[kBatch] = {};
    dds_sample_info_t infos[kBatch];
    const dds_return_t n = dds_take(endpoint_, samples, infos, kBatch, kBatch);
    if (n < 0) throw Error("cannot take from DDS topic " + name_ + ": " + dds_error(n));
    if (n == 0) return seen;
    try {
      for (dds_return_t i = 0; i < n; ++i) {
        if (!infos[i].valid_data) continue;
        on_sample(samples[i]);
        ++seen;
      }
    } catch (...) {
      dds_return_loan(endpoint_, samples, n);
      throw;
    }
    dds_return_loan(endpoint_, samples, n);
  }
}

DdsWaiter::DdsWaiter(const DdsParticipant& participant) : waitset_(dds_create_waitset(participant.handle())) {
  if (waitset_ < 0) throw Error("cannot create a DDS waitset: " + dds_error(waitset_));
}

DdsWaiter::~DdsWaiter() { dds_delete(waitset_); }

void DdsWaiter::add(const DdsEndpoint& reader) {
  const dds_entity_t condition = dds_create_readcondition(reader.handle(), DDS_ANY_STATE);
  if (condition < 0) throw Error("cannot wait on " + reader.name() + ": " + dds_error(condition));
  const dds_return_t rc = dds_waitset_attach(waitset_, condition, 0);
  if (rc != DDS_RETCODE_OK) throw Error("cannot wait on " + reader.name() + ": " + dds_error(rc));
}

bool DdsWaiter::wait(std::chrono::milliseconds timeout) const {
  return dds_waitset_wait(waitset_, nullptr, 0, DDS_MSECS(timeout.count())) > 0;
}

}  // namespace stillslam::ros2
