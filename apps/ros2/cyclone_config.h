#pragma once
// Where the node's DDS traffic may go. Loopback only (the default) is a
// Cyclone DDS configuration bound to 127.0.0.1 with multicast off and
// 127.0.0.1 as the only discovery peer: a container's lo often has no
// multicast, and nothing leaves the machine. Open: Cyclone's own defaults
// (CYCLONEDDS_URI, multicast discovery on every interface), as ROS 2 nodes on
// rmw_cyclonedds use them.
#include <optional>
#include <string>

namespace stillslam::ros2 {

struct DdsNetworkOptions {
  int domain = 0;             // ROS_DOMAIN_ID; 0..232 (DDS port arithmetic)
  bool loopback_only = true;  // false: `--network`, every interface
  // Loopback discovery probes the ports of participant indices 0..this: the
  // most DDS participants (processes) on the machine that find each other.
  int max_participants = 32;
  void check() const;
};

// The CYCLONEDDS_URI-style XML configuration for loopback only; nullopt when
// the options leave the network open (Cyclone's defaults apply).
std::optional<std::string> cyclone_config_xml(const DdsNetworkOptions& options);

}  // namespace stillslam::ros2
