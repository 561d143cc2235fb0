#pragma once
// The ROS 2 interface definitions (.msg field lists) of the messages stillslam
// writes, for the "ros2msg" schemas of MCAP files: the type's own fields, then
// each nested type once, separated by a line of 80 '=' and "MSG: pkg/Type", as
// the MCAP ros2 profile expects. Empty for a type not listed here.
#include <string>

namespace stillslam::ros2 {

std::string message_definition(const std::string& type);

}  // namespace stillslam::ros2
