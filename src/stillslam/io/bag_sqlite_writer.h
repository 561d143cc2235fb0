#pragma once
// rosbag2 sqlite3 storage: tables topics and messages as ROS 2 Humble
// writes them, all rows in one transaction committed by close().
#include <memory>

#include "stillslam/io/bag_writer.h"

struct sqlite3;
struct sqlite3_stmt;

namespace stillslam {

class SqliteBagWriter : public BagWriter {
 public:
  SqliteBagWriter(const std::filesystem::path& db3, const std::filesystem::path& folder);
  ~SqliteBagWriter() override;

 protected:
  void on_topic(std::uint32_t topic, const BagTopic& t) override;
  void on_message(std::uint32_t topic, std::int64_t log_time_ns, const std::vector<std::uint8_t>& cdr) override;
  void on_close() override;
  std::string storage() const override { return "sqlite3"; }

 private:
  void exec(const char* sql);
  [[noreturn]] void fail(const std::string& what) const;
  struct Close {
    void operator()(sqlite3* db) const;
  };
  std::unique_ptr<sqlite3, Close> db_;
  sqlite3_stmt* insert_ = nullptr;
};

}  // namespace stillslam
