#include "stillslam/io/bag_trajectory.h"

#include <algorithm>
#include <set>

#include "stillslam/core/error.h"
#include "stillslam/io/ros2_message_codec.h"

namespace stillslam {
namespace {

StampedPose stamped(const ros2::Header& h, const ros2::Pose& p) {
  StampedPose s;
  s.timestamp = static_cast<double>(h.stamp_ns()) * 1e-9;
  const auto& q = p.orientation;  // x, y, z, w
  s.T_world_cam.linear() = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized().toRotationMatrix();
  s.T_world_cam.translation() = Eigen::Vector3d(p.position[0], p.position[1], p.position[2]);
  return s;
}

std::string pose_topics(const BagReader& bag) {
  std::string out;
  for (const BagTopic& t : bag.topics()) {
    if (t.type == ros2::kOdometryType || t.type == ros2::kPoseStampedType ||
        t.type == ros2::kPoseWithCovarianceStampedType || t.type == ros2::kTfMessageType) {
      out += (out.empty() ? "" : ", ") + t.name + " (" + t.type + ")";
    }
  }
  return out.empty() ? "none" : out;
}

}  // namespace

Trajectory read_bag_trajectory(const BagReader& bag, const BagTrajectoryOptions& options) {
  const auto id = bag.find_topic(options.topic);
  const std::string name = bag.file().string();
  if (!id) throw Error(name + ": topic '" + options.topic + "' is not in the bag; its pose topics: " + pose_topics(bag));
  const std::string& type = bag.topics()[*id].type;
  const bool tf = type == ros2::kTfMessageType;
  const bool stamped_pose = type == ros2::kPoseStampedType || type == ros2::kPoseWithCovarianceStampedType;
  if (type != ros2::kOdometryType && !stamped_pose && !tf) {
    throw Error(name + ": topic '" + options.topic + "' holds " + type + "; export needs " + ros2::kOdometryType +
                ", " + ros2::kPoseStampedType + ", " + ros2::kPoseWithCovarianceStampedType + " or " +
                ros2::kTfMessageType + " (pose topics: " + pose_topics(bag) + ")");
  }
  Trajectory out;
  std::set<std::string> pairs_seen;
  for (std::size_t i = 0; i < bag.messages().size(); ++i) {
    if (bag.messages()[i].topic != *id) continue;
    const std::string what = name + ": topic " + options.topic + " message " + std::to_string(i);
    const auto bytes = bag.read(i);
    if (type == ros2::kOdometryType) {
      const ros2::Odometry m = ros2::decode_odometry(bytes, what);
      out.push_back(stamped(m.header, m.pose));
    } else if (stamped_pose) {
      const ros2::PoseStamped m = ros2::decode_pose_stamped(bytes, what);
      out.push_back(stamped(m.header, m.pose));
    } else {
      for (const ros2::TransformStamped& t : ros2::decode_tf_message(bytes, what).transforms) {
        pairs_seen.insert(t.header.frame_id + "," + t.child_frame_id);
        if (options.frames && t.header.frame_id == options.frames->first && t.child_frame_id == options.frames->second) {
          out.push_back(stamped(t.header, t.transform));
        }
      }
    }
  }
  if (tf && out.empty()) {
    std::string list;
    for (const std::string& p : pairs_seen) list += (list.empty() ? "" : "; ") + p;
    throw Error(name + ": " + options.topic + ": " +
                (options.frames ? "no transform " + options.frames->first + " -> " + options.frames->second
                                : std::string("a TF topic needs --frames PARENT,CHILD")) +
                "; the frame pairs it holds (PARENT,CHILD): " + (list.empty() ? "none" : list));
  }
  if (out.empty()) throw Error(name + ": topic '" + options.topic + "' has no messages");
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.timestamp < b.timestamp; });
  out.erase(std::unique(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.timestamp == b.timestamp; }),
            out.end());
  return out;
}

}  // namespace stillslam
