// Bag storage round trips (sqlite3, MCAP zstd / lz4 / none, with and without
// summary and chunks) and damaged files: truncated, corrupt in the middle.
#include <gtest/gtest.h>

#include <fstream>

#include "common/log_capture.h"
#include "io/temp_dir.h"
#include "stillslam/core/error.h"
#include "stillslam/io/bag_metadata.h"
#include "stillslam/io/bag_reader.h"
#include "stillslam/io/bag_writer.h"
#include "stillslam/io/mcap_reader.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

// Message k of topic t: 3000 bytes that name both (so a mix-up shows).
std::vector<std::uint8_t> payload(int t, int k) {
  std::vector<std::uint8_t> b(3000);
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = static_cast<std::uint8_t>(t * 31 + k * 7 + i % 13);
  return b;
}

constexpr int kMessages = 40;

void write_bag(const fs::path& path, const BagWriterOptions& options) {
  auto bag = open_bag_writer(path, options);
  const auto a = bag->add_topic("/a", "sensor_msgs/msg/Image");
  const auto b = bag->add_topic("/b", "nav_msgs/msg/Odometry");
  for (int k = 0; k < kMessages; ++k) {
    bag->write(a, 1000 + k * 10, payload(0, k));
    if (k % 2 == 0) bag->write(b, 1005 + k * 10, payload(1, k));
  }
  bag->close();
}

void expect_all_messages(const BagReader& bag) {
  ASSERT_EQ(bag.topics().size(), 2u);
  EXPECT_EQ(bag.topics()[0].name, "/a");
  EXPECT_EQ(bag.topics()[0].type, "sensor_msgs/msg/Image");
  EXPECT_EQ(bag.topics()[0].message_count, static_cast<std::size_t>(kMessages));
  EXPECT_EQ(bag.topics()[1].message_count, static_cast<std::size_t>(kMessages / 2));
  ASSERT_EQ(bag.messages().size(), static_cast<std::size_t>(kMessages + kMessages / 2));
  int k_a = 0, k_b = 0;
  for (std::size_t i = 0; i < bag.messages().size(); ++i) {
    const auto& m = bag.messages()[i];
    const int k = m.topic == 0 ? k_a++ : 2 * k_b++;
    EXPECT_EQ(bag.read(i), payload(static_cast<int>(m.topic), k)) << i;
    EXPECT_EQ(m.log_time_ns, (m.topic == 0 ? 1000 : 1005) + k * 10);
  }
  EXPECT_TRUE(bag.damage().empty());
}

struct Variant {
  const char* name;
  BagWriterOptions options;
  const char* out;
};

TEST(BagStorage, EveryFormatRoundTrips) {
  test::TempDir dir;
  const auto opts = [](std::string format, std::string compression, bool chunked, bool summary) {
    BagWriterOptions o;
    o.format = format;
    o.compression = compression;
    o.chunked = chunked;
    o.summary = summary;
    o.chunk_size = 20000;  // several chunks
    return o;
  };
  const std::vector<Variant> variants = {
      {"db3 folder", opts("db3", "none", true, true), "db3_bag"},
      {"bare db3", opts("db3", "none", true, true), "bare.db3"},
      {"mcap zstd", opts("mcap", "zstd", true, true), "zstd_bag"},
      {"mcap lz4", opts("mcap", "lz4", true, true), "lz4.mcap"},
      {"mcap none", opts("mcap", "none", true, true), "none.mcap"},
      {"mcap zstd no summary", opts("mcap", "zstd", true, false), "nosummary.mcap"},
      {"mcap no chunks", opts("mcap", "none", false, false), "nochunks.mcap"},
  };
  for (const Variant& v : variants) {
    SCOPED_TRACE(v.name);
    write_bag(dir.path() / v.out, v.options);
    const auto bag = open_bag(dir.path() / v.out);
    EXPECT_EQ(bag->storage(), v.options.format == "db3" ? "sqlite3" : "mcap");
    expect_all_messages(*bag);
    if (fs::is_directory(dir.path() / v.out)) {
      const BagMetadata m = read_bag_metadata(dir.path() / v.out / "metadata.yaml");
      ASSERT_EQ(m.topics.size(), 2u);
      EXPECT_EQ(m.topics[1].message_count, static_cast<std::size_t>(kMessages / 2));
      EXPECT_EQ(m.topics[1].name, "/b");
      EXPECT_EQ(m.starting_time_ns, 1000);
    }
  }
  const McapReader with_summary(dir.path() / "lz4.mcap");
  ASSERT_TRUE(with_summary.summary_counts());
  EXPECT_EQ(with_summary.summary_counts()->at("/a"), static_cast<std::uint64_t>(kMessages));
  EXPECT_GT(with_summary.chunk_count(), 3u);
  EXPECT_FALSE(McapReader(dir.path() / "nosummary.mcap").summary_counts());
}

TEST(BagStorage, CountsBelowMetadataAreAWarning) {
  test::TempDir dir;
  BagWriterOptions o;
  o.format = "db3";
  write_bag(dir.path() / "bag", o);
  BagMetadata m = read_bag_metadata(dir.path() / "bag" / "metadata.yaml");
  m.topics[1].message_count = 25;  // as if the recording had more than the file kept
  write_bag_metadata(dir.path() / "bag" / "metadata.yaml", m);
  test::LogCapture log;
  const auto bag = open_bag(dir.path() / "bag");
  EXPECT_EQ(bag->topics()[1].message_count, 20u);
  EXPECT_NE(log.text().find("lists 25 messages on /b, the bag holds 20"), std::string::npos) << log.text();
}

TEST(BagStorage, Db3PathWithUriCharacters) {
  test::TempDir dir;
  BagWriterOptions o;
  o.format = "db3";
  const fs::path file = dir.path() / "odd name ?#%20.db3";
  write_bag(file, o);
  expect_all_messages(*open_bag(file));
}

TEST(BagStorage, FolderOfSeveralFilesReadsAsOneBag) {
  test::TempDir dir;
  const fs::path folder = dir.path() / "split";
  fs::create_directories(folder);
  for (int part = 0; part < 2; ++part) {
    BagWriterOptions o;
    o.format = part == 0 ? "db3" : "mcap";
    auto bag = open_bag_writer(folder / ("split_" + std::to_string(part) + (part == 0 ? ".db3" : ".mcap")), o);
    // The second file lists the topics in the other order.
    const auto b = part == 1 ? bag->add_topic("/b", "nav_msgs/msg/Odometry") : 0;
    const auto a = bag->add_topic("/a", "sensor_msgs/msg/Image");
    for (int k = 0; k < 3; ++k) bag->write(a, 100 * part + k, payload(0, 3 * part + k));
    if (part == 1) bag->write(b, 150, payload(1, 0));
    bag->close();
  }
  BagMetadata m;
  m.storage_identifier = "mixed";
  m.relative_file_paths = {"split_0.db3", "split_1.mcap"};
  write_bag_metadata(folder / "metadata.yaml", m);
  const auto bag = open_bag(folder);
  ASSERT_EQ(bag->topics().size(), 2u);
  EXPECT_EQ(bag->topics()[0].name, "/a");
  EXPECT_EQ(bag->topics()[0].message_count, 6u);
  EXPECT_EQ(bag->topics()[1].message_count, 1u);
  ASSERT_EQ(bag->messages().size(), 7u);
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(bag->messages()[i].topic, 0u);
    EXPECT_EQ(bag->read(i), payload(0, static_cast<int>(i)));
  }
  EXPECT_EQ(bag->messages()[6].topic, 1u);
}

void truncate_file(const fs::path& file, std::uintmax_t size) { fs::resize_file(file, size); }

void corrupt(const fs::path& file, std::uintmax_t at, std::size_t n) {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(static_cast<std::streamoff>(at));
  const std::string junk(n, '\xA5');
  f.write(junk.data(), static_cast<std::streamsize>(junk.size()));
}

TEST(BagStorage, TruncatedMcapKeepsTheWholeChunksBeforeTheCut) {
  test::TempDir dir;
  BagWriterOptions o;
  o.chunk_size = 20000;
  const fs::path file = dir.path() / "t.mcap";
  write_bag(file, o);
  truncate_file(file, fs::file_size(file) / 2);
  const McapReader bag(file);
  EXPECT_GT(bag.messages().size(), 5u);
  EXPECT_LT(bag.messages().size(), static_cast<std::size_t>(kMessages));
  EXPECT_NE(bag.damage().find(file.string()), std::string::npos) << bag.damage();
  EXPECT_NE(bag.damage().find("at byte"), std::string::npos) << bag.damage();
  for (std::size_t i = 0; i < bag.messages().size(); ++i) EXPECT_EQ(bag.read(i).size(), 3000u);
  // Cut inside the first chunk: nothing to read is an Error naming the file and offset.
  truncate_file(file, 200);
  try {
    McapReader again(file);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("byte"), std::string::npos) << e.what();
  }
  truncate_file(file, 3);
  EXPECT_THROW(McapReader{file}, Error);
}

TEST(BagStorage, McapCorruptInTheMiddleKeepsTheMessagesBefore) {
  test::TempDir dir;
  for (const std::string compression : {"zstd", "lz4", "none"}) {
    SCOPED_TRACE(compression);
    BagWriterOptions o;
    o.compression = compression;
    o.chunk_size = 20000;
    o.summary = false;
    const fs::path file = dir.path() / (compression + ".mcap");
    write_bag(file, o);
    // Overwrite a record header (length field) in the middle: the scan stops there.
    const std::uintmax_t middle = fs::file_size(file) / 2;
    corrupt(file, middle, 64);
    const McapReader bag(file);
    EXPECT_GT(bag.messages().size(), 5u);
    EXPECT_LT(bag.messages().size(), static_cast<std::size_t>(kMessages + kMessages / 2));
    EXPECT_FALSE(bag.damage().empty());
    for (std::size_t i = 0; i < bag.messages().size(); ++i) {
      // Messages before the damage are intact.
      EXPECT_EQ(bag.read(i).size(), 3000u);
    }
  }
}

TEST(BagStorage, Db3DamagedOrNotABag) {
  test::TempDir dir;
  BagWriterOptions o;
  o.format = "db3";
  const fs::path file = dir.path() / "d.db3";
  write_bag(file, o);
  truncate_file(file, fs::file_size(file) / 2);
  // sqlite reports the lost pages when the scan reaches them; either the
  // messages before them are kept with the damage named, or (a cut inside the
  // schema) an Error names the file.
  try {
    const auto bag = open_bag(file);
    EXPECT_LT(bag->messages().size(), static_cast<std::size_t>(kMessages + kMessages / 2));
    EXPECT_NE(bag->damage().find(file.string()), std::string::npos) << bag->damage();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  std::ofstream(dir.path() / "junk.db3") << "not a database at all, just text that is long enough for a header....";
  EXPECT_THROW(open_bag(dir.path() / "junk.db3"), Error);
  std::ofstream(dir.path() / "junk.mcap") << "not an mcap";
  EXPECT_THROW(open_bag(dir.path() / "junk.mcap"), Error);
  EXPECT_THROW(open_bag(dir.path() / "missing"), Error);
}

}  // namespace
}  // namespace stillslam
