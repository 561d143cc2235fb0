#pragma once
// The parts of a rosbag2 metadata.yaml that stillslam uses: the storage
// (sqlite3 / mcap), the relative file paths and the per-topic message counts.
// Read line by line (the file is rosbag2's fixed block layout), written in
// the same layout so `ros2 bag info` and rosbags read our bags.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "stillslam/io/bag_reader.h"

namespace stillslam {

struct BagMetadata {
  std::string storage_identifier;  // "sqlite3", "mcap"
  std::vector<std::string> relative_file_paths;
  std::vector<BagTopic> topics;  // name, type, serialization, message_count
  std::int64_t starting_time_ns = 0;
  std::int64_t duration_ns = 0;
  std::size_t message_count() const;
};

// Error naming the file when it is missing or lists no file.
BagMetadata read_bag_metadata(const std::filesystem::path& metadata_yaml);
void write_bag_metadata(const std::filesystem::path& metadata_yaml, const BagMetadata& metadata);

}  // namespace stillslam
