// `stillslam bag-info BAG`: what a ROS 2 bag holds (storage, topics with
// types and message counts, time span), to choose --topics without ROS.
#include <algorithm>
#include <iomanip>
#include <iostream>

#include "commands.h"
#include "stillslam/io/bag_reader.h"

namespace stillslam::apps {
namespace {

void bag_info(const std::string& path) {
  const auto bag = open_bag(path);
  std::cout << path << ": " << bag->storage() << ", " << bag->messages().size() << " messages";
  if (!bag->messages().empty()) {
    const auto [lo, hi] = std::minmax_element(bag->messages().begin(), bag->messages().end(),
                                              [](const auto& a, const auto& b) { return a.log_time_ns < b.log_time_ns; });
    std::cout << std::fixed << std::setprecision(3) << ", " << static_cast<double>(hi->log_time_ns - lo->log_time_ns) * 1e-9
              << " s from " << static_cast<double>(lo->log_time_ns) * 1e-9;
  }
  std::cout << "\n";
  for (const BagTopic& t : bag->topics()) {
    std::cout << "  " << t.name << "  " << t.type << "  " << t.message_count << " messages ("
              << t.serialization << ")\n";
  }
  if (!bag->damage().empty()) std::cout << "damaged: " << bag->damage() << "\n";
}

}  // namespace

void add_bag_info_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("bag-info", "list a ROS 2 bag's topics, types and message counts");
  cmd->add_option("bag", *path, "ROS 2 bag: folder with metadata.yaml, or a .db3 / .mcap file")->required();
  cmd->callback([path] { bag_info(*path); });
}

}  // namespace stillslam::apps
