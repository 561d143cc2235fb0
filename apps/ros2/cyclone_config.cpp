#include "cyclone_config.h"

#include "stillslam/core/error.h"

namespace stillslam::ros2 {

void DdsNetworkOptions::check() const {
  if (domain < 0 || domain > 232) {
    throw Error("--domain " + std::to_string(domain) + " is out of range: DDS domain ids are 0..232 (ROS 2's default is 0)");
  }
  if (max_participants < 2 || max_participants > 120) {
    throw Error("DDS max_participants " + std::to_string(max_participants) + " is out of range 2..120");
  }
}

std::optional<std::string> cyclone_config_xml(const DdsNetworkOptions& options) {
  options.check();
  if (!options.loopback_only) return std::nullopt;
  // Participant indices are what unicast discovery probes (no multicast to
  // announce them); the peer list names only this machine.
  return "<CycloneDDS><Domain Id=\"any\">"
         "<General><Interfaces><NetworkInterface address=\"127.0.0.1\"/></Interfaces>"
         "<AllowMulticast>false</AllowMulticast></General>"
         "<Discovery><ParticipantIndex>auto</ParticipantIndex>"
         "<MaxAutoParticipantIndex>" +
         std::to_string(options.max_participants - 1) +
         "</MaxAutoParticipantIndex>"
         "<Peers><Peer address=\"127.0.0.1\"/></Peers></Discovery>"
         "</Domain></CycloneDDS>";
}

}  // namespace stillslam::ros2
