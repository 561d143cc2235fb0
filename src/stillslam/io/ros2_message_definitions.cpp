#include "stillslam/io/ros2_message_definitions.h"

#include <map>
#include <set>
#include <vector>

namespace stillslam::ros2 {
namespace {

struct Definition {
  const char* fields;
  std::vector<const char*> nested;  // types the fields use, "pkg/msg/Type"
};

// Field lists of the public ROS 2 interfaces (comments left out).
const std::map<std::string, Definition>& definitions() {
  static const std::map<std::string, Definition> table = {
      {"builtin_interfaces/msg/Time", {"int32 sec\nuint32 nanosec\n", {}}},
      {"std_msgs/msg/Header", {"builtin_interfaces/Time stamp\nstring frame_id\n", {"builtin_interfaces/msg/Time"}}},
      {"sensor_msgs/msg/Image",
       {"std_msgs/Header header\nuint32 height\nuint32 width\nstring encoding\nuint8 is_bigendian\nuint32 step\n"
        "uint8[] data\n",
        {"std_msgs/msg/Header"}}},
      {"sensor_msgs/msg/CompressedImage", {"std_msgs/Header header\nstring format\nuint8[] data\n", {"std_msgs/msg/Header"}}},
      {"sensor_msgs/msg/RegionOfInterest",
       {"uint32 x_offset\nuint32 y_offset\nuint32 height\nuint32 width\nbool do_rectify\n", {}}},
      {"sensor_msgs/msg/CameraInfo",
       {"std_msgs/Header header\nuint32 height\nuint32 width\nstring distortion_model\nfloat64[] d\nfloat64[9] k\n"
        "float64[9] r\nfloat64[12] p\nuint32 binning_x\nuint32 binning_y\nRegionOfInterest roi\n",
        {"std_msgs/msg/Header", "sensor_msgs/msg/RegionOfInterest"}}},
      {"geometry_msgs/msg/Point", {"float64 x\nfloat64 y\nfloat64 z\n", {}}},
      {"geometry_msgs/msg/Vector3", {"float64 x\nfloat64 y\nfloat64 z\n", {}}},
      {"geometry_msgs/msg/Quaternion", {"float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n", {}}},
      {"geometry_msgs/msg/Pose",
       {"Point position\nQuaternion orientation\n", {"geometry_msgs/msg/Point", "geometry_msgs/msg/Quaternion"}}},
      {"geometry_msgs/msg/PoseStamped", {"std_msgs/Header header\nPose pose\n", {"std_msgs/msg/Header", "geometry_msgs/msg/Pose"}}},
      {"geometry_msgs/msg/PoseWithCovariance", {"Pose pose\nfloat64[36] covariance\n", {"geometry_msgs/msg/Pose"}}},
      {"geometry_msgs/msg/Twist", {"Vector3 linear\nVector3 angular\n", {"geometry_msgs/msg/Vector3"}}},
      {"geometry_msgs/msg/TwistWithCovariance", {"Twist twist\nfloat64[36] covariance\n", {"geometry_msgs/msg/Twist"}}},
      {"geometry_msgs/msg/Transform",
       {"Vector3 translation\nQuaternion rotation\n", {"geometry_msgs/msg/Vector3", "geometry_msgs/msg/Quaternion"}}},
      {"geometry_msgs/msg/TransformStamped",
       {"std_msgs/Header header\nstring child_frame_id\nTransform transform\n",
        {"std_msgs/msg/Header", "geometry_msgs/msg/Transform"}}},
      {"nav_msgs/msg/Odometry",
       {"std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n"
        "geometry_msgs/TwistWithCovariance twist\n",
        {"std_msgs/msg/Header", "geometry_msgs/msg/PoseWithCovariance", "geometry_msgs/msg/TwistWithCovariance"}}},
      {"tf2_msgs/msg/TFMessage",
       {"geometry_msgs/TransformStamped[] transforms\n", {"geometry_msgs/msg/TransformStamped"}}},
  };
  return table;
}

// "geometry_msgs/msg/Pose" -> "geometry_msgs/Pose".
std::string short_name(const std::string& type) {
  const auto p = type.find("/msg/");
  return p == std::string::npos ? type : type.substr(0, p) + "/" + type.substr(p + 5);
}

void add_nested(const std::string& type, std::set<std::string>& done, std::string& out) {
  for (const char* nested : definitions().at(type).nested) {
    if (!done.insert(nested).second) continue;
    out += std::string(80, '=') + "\nMSG: " + short_name(nested) + "\n" + definitions().at(nested).fields;
    add_nested(nested, done, out);
  }
}

}  // namespace

std::string message_definition(const std::string& type) {
  const auto it = definitions().find(type);
  if (it == definitions().end()) return {};
  std::string out = it->second.fields;
  std::set<std::string> done{type};
  add_nested(type, done, out);
  return out;
}

}  // namespace stillslam::ros2
