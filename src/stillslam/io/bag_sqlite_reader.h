#pragma once
// rosbag2's sqlite3 storage (.db3, ROS 2 Humble's default): table `topics`
// (id, name, type, serialization_format) and table `messages` (id,
// topic_id, timestamp, data). Opening reads ids and timestamps in storage
// order; read(i) selects one row's data by its id.
#include <memory>
#include <mutex>

#include "stillslam/io/bag_reader.h"

struct sqlite3;
struct sqlite3_stmt;

namespace stillslam {

class SqliteBagReader : public BagReader {
 public:
  explicit SqliteBagReader(const std::filesystem::path& db3);
  ~SqliteBagReader() override;
  std::string storage() const override { return "sqlite3"; }
  std::vector<std::uint8_t> read(std::size_t i) const override;
  std::vector<std::uint8_t> read_prefix(std::size_t i, std::size_t n) const override;  // incremental blob I/O

 private:
  [[noreturn]] void fail(const std::string& what) const;
  struct Close {
    void operator()(sqlite3* db) const;
  };
  std::unique_ptr<sqlite3, Close> db_;  // closed even when the constructor throws
  sqlite3_stmt* select_data_ = nullptr;
  std::vector<std::int64_t> row_ids_;  // per message
  mutable std::mutex mutex_;           // one statement, shared by read() callers
};

}  // namespace stillslam
