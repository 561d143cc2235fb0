// `stillslam bag-export BAG --topic T [--frames PARENT,CHILD] --out FILE`:
// the poses of an Odometry, PoseStamped or TF topic of a ROS 2 bag as a TUM
// trajectory (io/bag_trajectory.h), e.g. a robot's odometry for `stillslam eval`.
#include <iostream>

#include "commands.h"
#include "stillslam/core/error.h"
#include "stillslam/io/bag_reader.h"
#include "stillslam/io/bag_trajectory.h"
#include "stillslam/io/trajectory.h"

namespace stillslam::apps {
namespace {

struct BagExportArgs {
  std::string bag, topic, out;
  std::vector<std::string> frames;
};

void bag_export(const BagExportArgs& args) {
  BagTrajectoryOptions options;
  options.topic = args.topic;
  if (!args.frames.empty()) {
    if (args.frames.size() != 2) throw Error("--frames takes PARENT,CHILD (two frame names), e.g. --frames odom,base_link");
    options.frames = std::pair{args.frames[0], args.frames[1]};
  }
  const auto bag = open_bag(args.bag);
  const Trajectory trajectory = read_bag_trajectory(*bag, options);
  write_trajectory(args.out, trajectory, TrajectoryFormat::Tum);
  std::cout << "wrote " << trajectory.size() << " poses of " << args.topic << " to " << args.out << "\n";
}

}  // namespace

void add_bag_export_command(CLI::App& app) {
  auto args = std::make_shared<BagExportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "bag-export", "write the poses of a ROS 2 bag topic (Odometry, PoseStamped, TF frame pair) as a TUM trajectory");
  cmd->add_option("bag", args->bag, "ROS 2 bag: folder with metadata.yaml, or a .db3 / .mcap file")->required();
  cmd->add_option("--topic", args->topic, "nav_msgs/Odometry, geometry_msgs/PoseStamped or tf2_msgs/TFMessage topic")
      ->required();
  cmd->add_option("--frames", args->frames, "TF topics: PARENT,CHILD (the child's pose in the parent frame)")
      ->delimiter(',');
  cmd->add_option("--out", args->out, "TUM trajectory file to write")->required();
  cmd->callback([args] { bag_export(*args); });
}

}  // namespace stillslam::apps
