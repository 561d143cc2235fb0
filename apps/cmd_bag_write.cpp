// `stillslam bag-write FOLDER --out BAG`: a dataset folder (EuRoC stereo,
// TUM RGB-D) as a ROS 2 bag (io/bag_folder_writer.h), so bags can be made
// without ROS; prints the --topics to run it with.
#include <iostream>

#include "commands.h"
#include "stillslam/io/bag_folder_writer.h"

namespace stillslam::apps {
namespace {

struct BagWriteArgs {
  std::string folder, out;
  BagFolderWriteOptions options;
  bool no_summary = false, no_chunks = false;
};

void bag_write(BagWriteArgs args) {
  args.options.bag.summary = !args.no_summary;
  args.options.bag.chunked = !args.no_chunks;
  const BagFolderWriteResult r = write_folder_as_bag(args.folder, args.out, args.options);
  std::cout << "wrote " << args.out << ": " << r.layout << ", " << r.frames << " frames, " << r.messages
            << " messages; run it with --topics " << r.image_topics[0] << "," << r.image_topics[1] << "\n";
}

}  // namespace

void add_bag_write_command(CLI::App& app) {
  auto args = std::make_shared<BagWriteArgs>();
  CLI::App* cmd = app.add_subcommand("bag-write", "write a dataset folder (EuRoC, TUM RGB-D) as a ROS 2 bag");
  cmd->add_option("folder", args->folder, "dataset folder (EuRoC mav0/cam0 + cam1, or TUM rgb.txt + depth.txt)")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--out", args->out,
                  "bag to write: a folder (metadata.yaml + <name>_0.db3 / .mcap), or a bare FILE.mcap / FILE.db3")
      ->required();
  cmd->add_option("--format", args->options.bag.format, "db3 or mcap (default mcap; a .db3 / .mcap --out decides)")
      ->check(CLI::IsMember({"db3", "mcap"}));
  cmd->add_option("--compression", args->options.bag.compression, "MCAP chunk compression: zstd (default), lz4, none")
      ->check(CLI::IsMember({"zstd", "lz4", "none"}));
  cmd->add_option("--images", args->options.images,
                  "raw (sensor_msgs/Image, default) or png (sensor_msgs/CompressedImage; depth as compressedDepth png)")
      ->check(CLI::IsMember({"raw", "png"}));
  cmd->add_flag("--no-summary", args->no_summary, "MCAP: leave out the summary section (readers must scan)");
  cmd->add_flag("--no-chunks", args->no_chunks, "MCAP: plain message records instead of chunks");
  cmd->add_option("--depth-map-factor", args->options.depth_map_factor,
                  "TUM: depth PNG units per metre (default 5000); bags store 16UC1 depth in millimetres");
  cmd->add_option("--max-frames", args->options.max_frames, "write at most N frames per camera");
  cmd->callback([args] { bag_write(*args); });
}

}  // namespace stillslam::apps
