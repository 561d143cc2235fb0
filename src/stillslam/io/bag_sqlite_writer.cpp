#include "stillslam/io/bag_sqlite_writer.h"

#include <sqlite3.h>

#include "stillslam/core/error.h"

namespace stillslam {

void SqliteBagWriter::Close::operator()(sqlite3* db) const { sqlite3_close(db); }

void SqliteBagWriter::fail(const std::string& what) const {
  throw Error(path_.string() + ": " + what + ": " + (db_ ? sqlite3_errmsg(db_.get()) : "cannot create"));
}

void SqliteBagWriter::exec(const char* sql) {
  if (sqlite3_exec(db_.get(), sql, nullptr, nullptr, nullptr) != SQLITE_OK) fail(std::string("cannot run ") + sql);
}

SqliteBagWriter::SqliteBagWriter(const std::filesystem::path& db3, const std::filesystem::path& folder)
    : BagWriter(db3, folder) {
  sqlite3* db = nullptr;
  const int rc = sqlite3_open_v2(db3.string().c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr);
  db_.reset(db);
  if (rc != SQLITE_OK) fail("cannot create the bag file");
  exec("CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
       "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL)");
  exec("CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL, "
       "data BLOB NOT NULL)");
  exec("CREATE INDEX timestamp_idx ON messages (timestamp ASC)");
  exec("BEGIN TRANSACTION");
  if (sqlite3_prepare_v2(db_.get(), "INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)", -1,
                         &insert_, nullptr) != SQLITE_OK) {
    fail("cannot prepare the message insert");
  }
}

SqliteBagWriter::~SqliteBagWriter() {
  try {
    close();
  } catch (const Error&) {
    // close() reports errors to callers that call it; a destructor must not throw.
  }
  sqlite3_finalize(insert_);
}

void SqliteBagWriter::on_topic(std::uint32_t topic, const BagTopic& t) {
  sqlite3_stmt* st = nullptr;
  if (sqlite3_prepare_v2(db_.get(),
                         "INSERT INTO topics (id, name, type, serialization_format, offered_qos_profiles) "
                         "VALUES (?, ?, ?, 'cdr', '')",
                         -1, &st, nullptr) != SQLITE_OK) {
    fail("cannot add topic " + t.name);
  }
  sqlite3_bind_int64(st, 1, topic + 1);
  sqlite3_bind_text(st, 2, t.name.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(st, 3, t.type.c_str(), -1, SQLITE_TRANSIENT);
  const int rc = sqlite3_step(st);
  sqlite3_finalize(st);
  if (rc != SQLITE_DONE) fail("cannot add topic " + t.name);
}

void SqliteBagWriter::on_message(std::uint32_t topic, std::int64_t log_time_ns, const std::vector<std::uint8_t>& cdr) {
  sqlite3_reset(insert_);
  sqlite3_bind_int64(insert_, 1, topic + 1);
  sqlite3_bind_int64(insert_, 2, log_time_ns);
  sqlite3_bind_blob64(insert_, 3, cdr.data(), cdr.size(), SQLITE_STATIC);
  if (sqlite3_step(insert_) != SQLITE_DONE) fail("cannot write a message (disk full?)");
}

void SqliteBagWriter::on_close() { exec("COMMIT"); }

}  // namespace stillslam
