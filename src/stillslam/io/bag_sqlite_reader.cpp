#include "stillslam/io/bag_sqlite_reader.h"

#include <sqlite3.h>

#include <map>

#include "stillslam/core/error.h"

namespace stillslam {

void SqliteBagReader::fail(const std::string& what) const {
  throw Error(file_.string() + ": " + what + ": " + (db_ ? sqlite3_errmsg(db_.get()) : "cannot open") +
              " (not a rosbag2 sqlite3 bag, or a damaged one)");
}

SqliteBagReader::SqliteBagReader(const std::filesystem::path& db3) : BagReader(db3) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(db3, ec)) throw Error(db3.string() + ": bag file not found");
  // immutable=1: no locks, no -wal/-shm files next to a bag that may be read-only.
  std::string uri = "file:";
  for (const char ch : db3.string()) {
    if (ch == '%' || ch == '?' || ch == '#') {
      static constexpr char kHex[] = "0123456789ABCDEF";
      uri += '%';
      uri += kHex[(static_cast<unsigned char>(ch) >> 4) & 0xF];
      uri += kHex[static_cast<unsigned char>(ch) & 0xF];
    } else {
      uri += ch;
    }
  }
  uri += "?immutable=1";
  sqlite3* db = nullptr;
  const int open_rc =
      sqlite3_open_v2(uri.c_str(), &db, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI | SQLITE_OPEN_NOMUTEX, nullptr);
  db_.reset(db);
  if (open_rc != SQLITE_OK) fail("cannot open");
  sqlite3_stmt* st = nullptr;
  if (sqlite3_prepare_v2(db_.get(), "SELECT id, name, type, serialization_format FROM topics ORDER BY id", -1, &st,
                         nullptr) != SQLITE_OK) {
    fail("cannot read table 'topics'");
  }
  std::map<std::int64_t, std::uint32_t> topic_of_id;
  int rc;
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    BagTopic t;
    const auto text = [&](int col) {
      const unsigned char* s = sqlite3_column_text(st, col);
      return s ? std::string(reinterpret_cast<const char*>(s)) : std::string();
    };
    t.name = text(1);
    t.type = text(2);
    t.serialization = text(3);
    topic_of_id[sqlite3_column_int64(st, 0)] = add_topic(std::move(t));
  }
  sqlite3_finalize(st);
  if (rc != SQLITE_DONE) fail("cannot read table 'topics'");

  if (sqlite3_prepare_v2(db_.get(), "SELECT id, topic_id, timestamp FROM messages ORDER BY id", -1, &st, nullptr) !=
      SQLITE_OK) {
    fail("cannot read table 'messages'");
  }
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    const auto it = topic_of_id.find(sqlite3_column_int64(st, 1));
    if (it == topic_of_id.end()) continue;  // a message of a topic not in `topics`: rosbag2 ignores it too
    row_ids_.push_back(sqlite3_column_int64(st, 0));
    messages_.push_back({it->second, sqlite3_column_int64(st, 2)});
    ++topics_[it->second].message_count;
  }
  const std::string why = rc == SQLITE_DONE ? std::string() : sqlite3_errmsg(db_.get());
  sqlite3_finalize(st);
  if (!why.empty()) {
    stop_at_damage("after message row " + std::to_string(row_ids_.empty() ? 0 : row_ids_.back()) + ": " + why);
  }
  if (sqlite3_prepare_v2(db_.get(), "SELECT data FROM messages WHERE id = ?", -1, &select_data_, nullptr) != SQLITE_OK) {
    fail("cannot read table 'messages'");
  }
}

void SqliteBagReader::Close::operator()(sqlite3* db) const { sqlite3_close(db); }

SqliteBagReader::~SqliteBagReader() { sqlite3_finalize(select_data_); }

std::vector<std::uint8_t> SqliteBagReader::read(std::size_t i) const {
  const std::lock_guard lock(mutex_);
  sqlite3_reset(select_data_);
  sqlite3_bind_int64(select_data_, 1, row_ids_.at(i));
  if (sqlite3_step(select_data_) != SQLITE_ROW) {
    throw Error(file_.string() + ": message row " + std::to_string(row_ids_[i]) +
                " cannot be read: " + sqlite3_errmsg(db_.get()) + " (damaged bag)");
  }
  const auto* p = static_cast<const std::uint8_t*>(sqlite3_column_blob(select_data_, 0));
  const auto n = static_cast<std::size_t>(sqlite3_column_bytes(select_data_, 0));
  std::vector<std::uint8_t> out(p, p + n);
  sqlite3_reset(select_data_);
  return out;
}

std::vector<std::uint8_t> SqliteBagReader::read_prefix(std::size_t i, std::size_t n) const {
  const std::lock_guard lock(mutex_);
  sqlite3_blob* blob = nullptr;
  if (sqlite3_blob_open(db_.get(), "main", "messages", "data", row_ids_.at(i), 0, &blob) != SQLITE_OK) {
    sqlite3_blob_close(blob);
    throw Error(file_.string() + ": message row " + std::to_string(row_ids_[i]) +
                " cannot be read: " + sqlite3_errmsg(db_.get()) + " (damaged bag)");
  }
  std::vector<std::uint8_t> out(std::min<std::size_t>(n, static_cast<std::size_t>(sqlite3_blob_bytes(blob))));
  const int rc = sqlite3_blob_read(blob, out.data(), static_cast<int>(out.size()), 0);
  sqlite3_blob_close(blob);
  if (rc != SQLITE_OK) {
    throw Error(file_.string() + ": message row " + std::to_string(row_ids_[i]) + " cannot be read (damaged bag)");
  }
  return out;
}

}  // namespace stillslam
