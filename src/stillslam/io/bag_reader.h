#pragma once
// Read access to a ROS 2 bag, whatever its storage (sqlite3 .db3 or MCAP).
// Opening indexes every message (topic, log time, where it is stored) without
// decoding it; read(i) fetches message i's CDR bytes (safe from several
// threads). A bag damaged part-way (truncated file, corrupt record or page)
// keeps the messages read before the damage: damage() says where it is and a
// warning names the file and offset; damage before the first message is an
// Error naming them.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace stillslam {

struct BagTopic {
  std::string name;  // "/cam0/image_raw"
  std::string type;  // "sensor_msgs/msg/Image"
  std::string serialization = "cdr";
  std::size_t message_count = 0;  // messages indexed
};

struct BagMessageInfo {
  std::uint32_t topic = 0;  // index into topics()
  std::int64_t log_time_ns = 0;
};

class BagReader {
 public:
  virtual ~BagReader() = default;
  virtual std::string storage() const = 0;  // "sqlite3", "mcap"
  const std::filesystem::path& file() const { return file_; }
  const std::vector<BagTopic>& topics() const { return topics_; }
  // Every message of the bag in storage order.
  const std::vector<BagMessageInfo>& messages() const { return messages_; }
  // Message i's serialized bytes (CDR for ROS 2).
  virtual std::vector<std::uint8_t> read(std::size_t i) const = 0;
  // At most the first `n` bytes of message i (enough for a header stamp,
  // without reading a whole image where the storage allows).
  virtual std::vector<std::uint8_t> read_prefix(std::size_t i, std::size_t n) const;
  // Where reading stopped early ("FILE: at byte N: why"), empty for an intact bag.
  const std::string& damage() const { return damage_; }

  std::optional<std::uint32_t> find_topic(const std::string& name) const;
  // "/a (sensor_msgs/msg/Image, 10 messages), /b (...)" for error messages.
  std::string topic_list() const;

 protected:
  explicit BagReader(std::filesystem::path file) : file_(std::move(file)) {}
  // Records the damage (warning) or, when no message was read, throws it.
  void stop_at_damage(const std::string& detail);
  std::uint32_t add_topic(BagTopic topic);

  std::filesystem::path file_;
  std::vector<BagTopic> topics_;
  std::vector<BagMessageInfo> messages_;
  std::string damage_;
};

// A bag folder (metadata.yaml + .db3 or .mcap files), or a bare .db3 / .mcap
// file. A folder of several files is read as one bag (messages concatenated
// in the order metadata.yaml lists the files). Error naming the path when it
// is not a bag.
std::unique_ptr<BagReader> open_bag(const std::filesystem::path& path);
// A warning per topic whose message count differs from what `source`
// (metadata.yaml, the MCAP summary) lists.
void warn_on_count_mismatch(const BagReader& bag, const std::vector<BagTopic>& expected, const std::string& source);
// Whether `path` looks like a bag (for open_dataset's layout detection).
bool is_bag_path(const std::filesystem::path& path);

}  // namespace stillslam
